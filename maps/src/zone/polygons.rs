//! Flat storage for the validated polygons of one zone kind: every ring's vertices in one `Vec`,
//! each polygon with its bounding box, so point location prunes by box and then walks contiguous
//! memory.

use super::geometry::{Aabb, Location, P, locate_in_ring};

/// Index range of one ring in [`Polygons::vertices`].
#[derive(Clone, Copy, Debug)]
struct RingSpan {
    start: u32,
    len: u32,
}

/// One polygon: its rings (the first is the shell) and its bounding box.
#[derive(Clone, Debug)]
pub(super) struct PolygonEntry {
    /// Range of this polygon's rings in the ring table.
    rings: std::ops::Range<u32>,
    /// Box around the shell.
    pub aabb: Aabb,
    /// Box around each ring, in ring order (shell first).
    ring_aabbs: Vec<Aabb>,
}

/// Polygons with holes, orientation normalised: shells counter-clockwise, holes clockwise, so the
/// polygon's interior is always on the left of every directed edge.
#[derive(Clone, Debug, Default)]
pub(super) struct Polygons {
    vertices: Vec<P>,
    rings: Vec<RingSpan>,
    polygons: Vec<PolygonEntry>,
}

impl Polygons {
    /// Add a polygon given as open rings (no repeated closing vertex), shell first, already
    /// validated and oriented.
    pub fn push(&mut self, rings: &[Vec<P>]) {
        let first_ring = self.rings.len() as u32;
        let mut ring_aabbs = Vec::with_capacity(rings.len());
        for ring in rings {
            self.rings.push(RingSpan {
                start: self.vertices.len() as u32,
                len: ring.len() as u32,
            });
            self.vertices.extend_from_slice(ring);
            ring_aabbs.push(Aabb::of_points(ring));
        }
        let aabb = ring_aabbs.first().copied().unwrap_or(Aabb::EMPTY);
        self.polygons.push(PolygonEntry {
            rings: first_ring..self.rings.len() as u32,
            aabb,
            ring_aabbs,
        });
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.polygons.len()
    }

    /// Whether there are no polygons.
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
    }

    /// The polygons.
    pub fn entries(&self) -> &[PolygonEntry] {
        &self.polygons
    }

    /// The rings of polygon `index` (shell first), each as open vertices.
    pub fn rings(&self, index: usize) -> impl Iterator<Item = &[P]> + '_ {
        let span = self.polygons[index].rings.clone();
        self.rings[span.start as usize..span.end as usize]
            .iter()
            .map(|r| &self.vertices[r.start as usize..(r.start + r.len) as usize])
    }

    /// Every directed edge `(a, b)` of polygon `index`, interior on the left.
    pub fn edges(&self, index: usize) -> impl Iterator<Item = (P, P)> + '_ {
        self.rings(index).flat_map(ring_edges)
    }

    /// Every edge of every polygon.
    pub fn all_edges(&self) -> Vec<[P; 2]> {
        (0..self.len())
            .flat_map(|i| self.edges(i).map(|(a, b)| [a, b]))
            .collect()
    }

    /// Locate `p` relative to polygon `index` (closed, holes excluded).
    pub fn locate(&self, index: usize, p: P) -> Location {
        let entry = &self.polygons[index];
        if !entry.aabb.contains(p) {
            return Location::Outside;
        }
        let mut rings = self.rings(index).zip(&entry.ring_aabbs);
        let Some((shell, _)) = rings.next() else {
            return Location::Outside;
        };
        match locate_in_ring(p, shell) {
            Location::Inside => {}
            other => return other,
        }
        for (hole, aabb) in rings {
            if aabb.contains(p) {
                match locate_in_ring(p, hole) {
                    Location::Inside => return Location::Outside,
                    Location::Boundary => return Location::Boundary,
                    Location::Outside => {}
                }
            }
        }
        Location::Inside
    }

    /// Whether `p` lies in the closed union of all polygons.
    pub fn covers(&self, p: P) -> bool {
        (0..self.len()).any(|i| self.locate(i, p) != Location::Outside)
    }
}

/// The directed edges of an open ring, closing edge included.
pub(super) fn ring_edges(ring: &[P]) -> impl Iterator<Item = (P, P)> + '_ {
    let n = ring.len();
    (0..n).map(move |i| (ring[i], ring[(i + 1) % n]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, side: f64) -> Vec<P> {
        vec![
            [x0, y0],
            [x0 + side, y0],
            [x0 + side, y0 + side],
            [x0, y0 + side],
        ]
    }

    #[test]
    fn holes_are_outside() {
        let mut polys = Polygons::default();
        assert!(polys.is_empty());
        assert!(!polys.covers([0.0, 0.0]));
        let mut hole = square(3.0, 3.0, 4.0);
        hole.reverse();
        polys.push(&[square(0.0, 0.0, 10.0), hole]);
        assert_eq!(polys.len(), 1);
        assert_eq!(polys.locate(0, [1.0, 1.0]), Location::Inside);
        assert_eq!(polys.locate(0, [5.0, 5.0]), Location::Outside);
        assert_eq!(polys.locate(0, [3.0, 5.0]), Location::Boundary);
        assert_eq!(polys.locate(0, [10.0, 5.0]), Location::Boundary);
        assert_eq!(polys.locate(0, [11.0, 5.0]), Location::Outside);
        assert_eq!(polys.edges(0).count(), 8);
        assert!(polys.covers([3.0, 3.0]));
        assert!(!polys.covers([4.0, 4.0]));
    }
}
