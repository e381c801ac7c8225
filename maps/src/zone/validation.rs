//! Validation of one polygon's rings (OGC simple-feature rules, with the GeoJSON closing rule),
//! reporting *where* the problem is, and normalisation to open, oriented rings.
//!
//! Rules: every ring has at least 4 positions and ends where it starts; a ring encloses a non-zero
//! area; no ring crosses or touches itself; rings do not cross or share an edge, though they may
//! touch at isolated points; every hole lies inside the shell and no hole lies inside another.
//! Decisions use exact orientation predicates, so a valid polygon is never rejected because of
//! rounding; reported coordinates are computed in floating point.

use super::geometry::{
    Location, P, cross, lerp, locate_in_ring, orient, project, ring_double_area,
};
use super::polygons::ring_edges;
use geo::algorithm::kernels::Orientation;

/// The first problem found in a polygon. Ring indices count the shell as ring 0.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum PolygonProblem {
    /// The polygon has no rings at all.
    NoRings,
    /// A ring has fewer than 4 positions.
    TooFewPositions { ring: usize, positions: usize },
    /// A ring's last position differs from its first.
    NotClosed { ring: usize, first: P, last: P },
    /// A ring encloses no area (fewer than 3 distinct vertices, or all on one line).
    ZeroArea { ring: usize },
    /// A ring crosses, touches or doubles back on itself.
    SelfIntersection { ring: usize, at: P },
    /// Two rings cross, or share part of an edge.
    RingsCross { ring_a: usize, ring_b: usize, at: P },
    /// A hole reaches outside the shell.
    HoleOutsideShell { ring: usize },
    /// One hole lies inside another.
    HolesOverlap { ring_a: usize, ring_b: usize },
}

/// Validate a polygon given as GeoJSON rings (closed: last position = first) and return it as
/// open rings without repeated vertices, shell counter-clockwise and holes clockwise.
pub(super) fn validate_polygon(rings: &[Vec<P>]) -> Result<Vec<Vec<P>>, PolygonProblem> {
    if rings.is_empty() {
        return Err(PolygonProblem::NoRings);
    }
    let mut open = Vec::with_capacity(rings.len());
    for (r, ring) in rings.iter().enumerate() {
        let (Some(&first), Some(&last)) = (ring.first(), ring.last()) else {
            return Err(PolygonProblem::TooFewPositions {
                ring: r,
                positions: 0,
            });
        };
        if ring.len() < 4 {
            return Err(PolygonProblem::TooFewPositions {
                ring: r,
                positions: ring.len(),
            });
        }
        if first != last {
            return Err(PolygonProblem::NotClosed {
                ring: r,
                first,
                last,
            });
        }
        let mut v: Vec<P> = Vec::with_capacity(ring.len() - 1);
        for &p in &ring[..ring.len() - 1] {
            if v.last() != Some(&p) {
                v.push(p);
            }
        }
        while v.len() > 1 && v.last() == v.first() {
            v.pop();
        }
        if v.len() < 3
            || v.iter()
                .all(|&p| orient(v[0], v[1], p) == Orientation::Collinear)
        {
            return Err(PolygonProblem::ZeroArea { ring: r });
        }
        open.push(v);
    }
    let touches = check_crossings(&open)?;
    check_holes(&open, &touches)?;
    for (r, v) in open.iter_mut().enumerate() {
        // A simple ring off one line has non-zero area; this catches only rounding to zero.
        let area = ring_double_area(v);
        if area == 0.0 {
            return Err(PolygonProblem::ZeroArea { ring: r });
        }
        // Shell counter-clockwise, holes clockwise: the interior is left of every edge.
        if (r == 0) == (area < 0.0) {
            v.reverse();
        }
    }
    Ok(open)
}

/// One edge in the sweep.
struct Edge {
    ring: usize,
    index: usize,
    a: P,
    b: P,
}

/// How two closed segments meet.
enum Meeting {
    /// Not at all.
    Apart,
    /// At one point; `proper` when it is interior to both segments and they cross.
    Point { at: P, proper: bool },
    /// Along a piece of positive length starting at `at`.
    Overlap { at: P },
}

fn sign(o: Orientation) -> i8 {
    match o {
        Orientation::CounterClockwise => 1,
        Orientation::Clockwise => -1,
        Orientation::Collinear => 0,
    }
}

/// Exact classification of how segments `a b` and `c d` meet.
fn meet(a: P, b: P, c: P, d: P) -> Meeting {
    let (s1, s2) = (sign(orient(a, b, c)), sign(orient(a, b, d)));
    if s1 == 0 && s2 == 0 {
        // Collinear: compare the intervals along the dominant axis of a b.
        let k = usize::from((b[1] - a[1]).abs() > (b[0] - a[0]).abs());
        let (lo1, hi1) = (a[k].min(b[k]), a[k].max(b[k]));
        let (lo2, hi2) = (c[k].min(d[k]), c[k].max(d[k]));
        let (lo, hi) = (lo1.max(lo2), hi1.min(hi2));
        if lo > hi {
            return Meeting::Apart;
        }
        let at = [a, b, c, d].into_iter().find(|p| p[k] == lo).unwrap_or(a);
        return if lo == hi {
            Meeting::Point { at, proper: false }
        } else {
            Meeting::Overlap { at }
        };
    }
    let (s3, s4) = (sign(orient(c, d, a)), sign(orient(c, d, b)));
    if s1 * s2 > 0 || s3 * s4 > 0 {
        return Meeting::Apart;
    }
    let at = if s1 == 0 {
        c
    } else if s2 == 0 {
        d
    } else if s3 == 0 {
        a
    } else if s4 == 0 {
        b
    } else {
        let (ca, cb) = (cross(c, d, a), cross(c, d, b));
        return Meeting::Point {
            at: lerp(a, b, ca / (ca - cb)),
            proper: true,
        };
    };
    Meeting::Point { at, proper: false }
}

/// Find crossings between and within rings with a sweep along x. Returns, for every edge (indexed
/// per ring), the parameters at which other rings touch it.
fn check_crossings(rings: &[Vec<P>]) -> Result<Vec<Vec<Vec<f64>>>, PolygonProblem> {
    let mut edges: Vec<Edge> = rings
        .iter()
        .enumerate()
        .flat_map(|(ring, v)| {
            ring_edges(v)
                .enumerate()
                .map(move |(index, (a, b))| Edge { ring, index, a, b })
        })
        .collect();
    edges.sort_by(|e, f| e.a[0].min(e.b[0]).total_cmp(&f.a[0].min(f.b[0])));
    let mut touches: Vec<Vec<Vec<f64>>> = rings.iter().map(|v| vec![Vec::new(); v.len()]).collect();
    for (i, e) in edges.iter().enumerate() {
        let e_max_x = e.a[0].max(e.b[0]);
        let (e_min_y, e_max_y) = (e.a[1].min(e.b[1]), e.a[1].max(e.b[1]));
        for f in &edges[i + 1..] {
            if f.a[0].min(f.b[0]) > e_max_x {
                break;
            }
            if f.a[1].min(f.b[1]) > e_max_y || f.a[1].max(f.b[1]) < e_min_y {
                continue;
            }
            let meeting = meet(e.a, e.b, f.a, f.b);
            if e.ring == f.ring {
                let n = rings[e.ring].len();
                let adjacent = (e.index + 1) % n == f.index || (f.index + 1) % n == e.index;
                match meeting {
                    Meeting::Apart => {}
                    // Neighbours always share their common vertex; only doubling back is wrong.
                    Meeting::Point { .. } if adjacent => {}
                    Meeting::Point { at, .. } | Meeting::Overlap { at } => {
                        let at = if adjacent { shared_vertex(e, f) } else { at };
                        return Err(PolygonProblem::SelfIntersection { ring: e.ring, at });
                    }
                }
            } else {
                match meeting {
                    Meeting::Apart => {}
                    Meeting::Point { at, proper: false } => {
                        touches[e.ring][e.index].push(project(e.a, e.b, at).clamp(0.0, 1.0));
                        touches[f.ring][f.index].push(project(f.a, f.b, at).clamp(0.0, 1.0));
                    }
                    Meeting::Point { at, proper: true } | Meeting::Overlap { at } => {
                        let (ring_a, ring_b) = (e.ring.max(f.ring), e.ring.min(f.ring));
                        return Err(PolygonProblem::RingsCross { ring_a, ring_b, at });
                    }
                }
            }
        }
    }
    Ok(touches)
}

/// The vertex two adjacent edges share.
fn shared_vertex(e: &Edge, f: &Edge) -> P {
    if e.b == f.a { e.b } else { e.a }
}

/// Midpoints of the pieces of `ring`'s edges between the points where other rings touch them.
/// With no crossings left, each piece lies entirely inside or entirely outside any other ring.
fn piece_midpoints<'a>(ring: &'a [P], touches: &'a [Vec<f64>]) -> impl Iterator<Item = P> + 'a {
    ring_edges(ring).zip(touches).flat_map(|((a, b), ts)| {
        let mut ts: Vec<f64> = ts.iter().copied().chain([0.0, 1.0]).collect();
        ts.sort_by(f64::total_cmp);
        ts.dedup();
        let mids: Vec<P> = ts
            .windows(2)
            .map(|w| lerp(a, b, 0.5 * (w[0] + w[1])))
            .collect();
        mids
    })
}

/// Every hole inside the shell, no hole inside another.
fn check_holes(rings: &[Vec<P>], touches: &[Vec<Vec<f64>>]) -> Result<(), PolygonProblem> {
    let shell = &rings[0];
    for (r, hole) in rings.iter().enumerate().skip(1) {
        if piece_midpoints(hole, &touches[r]).any(|m| locate_in_ring(m, shell) == Location::Outside)
        {
            return Err(PolygonProblem::HoleOutsideShell { ring: r });
        }
    }
    for (r1, h1) in rings.iter().enumerate().skip(1) {
        for (r2, h2) in rings.iter().enumerate().skip(1) {
            if r1 != r2
                && piece_midpoints(h2, &touches[r2])
                    .any(|m| locate_in_ring(m, h1) == Location::Inside)
            {
                let (ring_a, ring_b) = (r1.min(r2), r1.max(r2));
                return Err(PolygonProblem::HolesOverlap { ring_a, ring_b });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn closed(v: &[P]) -> Vec<P> {
        let mut v = v.to_vec();
        v.push(v[0]);
        v
    }

    const SQUARE: [P; 4] = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];

    #[test]
    fn normalises_orientation_and_duplicates() {
        let cw: Vec<P> = vec![
            [0.0, 0.0],
            [0.0, 10.0],
            [0.0, 10.0],
            [10.0, 10.0],
            [10.0, 0.0],
            [0.0, 0.0],
        ];
        let hole_ccw = closed(&[[2.0, 2.0], [4.0, 2.0], [4.0, 4.0]]);
        let out = validate_polygon(&[cw, hole_ccw]).expect("valid");
        assert_eq!(out[0].len(), 4);
        assert!(ring_double_area(&out[0]) > 0.0);
        assert!(ring_double_area(&out[1]) < 0.0);
    }

    #[test]
    fn rejects_each_problem() {
        use PolygonProblem::*;
        assert_eq!(validate_polygon(&[]), Err(NoRings));
        assert_eq!(
            validate_polygon(&[vec![[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]]),
            Err(TooFewPositions {
                ring: 0,
                positions: 3
            })
        );
        assert!(matches!(
            validate_polygon(&[SQUARE.to_vec()]),
            Err(NotClosed {
                ring: 0,
                first: [0.0, 0.0],
                last: [0.0, 10.0]
            })
        ));
        assert_eq!(
            validate_polygon(&[closed(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])]),
            Err(ZeroArea { ring: 0 })
        );
        // Bow-tie: crosses at (5, 5).
        let bowtie = closed(&[[0.0, 0.0], [10.0, 10.0], [10.0, 0.0], [0.0, 10.0]]);
        assert_eq!(
            validate_polygon(&[bowtie]),
            Err(SelfIntersection {
                ring: 0,
                at: [5.0, 5.0]
            })
        );
        // Spike doubling back along an edge.
        let spike = closed(&[
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [2.0, 4.0],
            [2.0, 6.0],
            [2.0, 4.0],
            [0.0, 4.0],
        ]);
        assert!(matches!(
            validate_polygon(&[spike]),
            Err(SelfIntersection { ring: 0, .. })
        ));
        // Figure eight touching itself at a vertex.
        let eight = closed(&[
            [0.0, 0.0],
            [2.0, 0.0],
            [1.0, 1.0],
            [2.0, 2.0],
            [0.0, 2.0],
            [1.0, 1.0],
        ]);
        assert_eq!(
            validate_polygon(&[eight]),
            Err(SelfIntersection {
                ring: 0,
                at: [1.0, 1.0]
            })
        );
        // A hole crossing the shell.
        let hole = closed(&[[5.0, 5.0], [15.0, 5.0], [15.0, 6.0], [5.0, 6.0]]);
        assert_eq!(
            validate_polygon(&[closed(&SQUARE), hole]),
            Err(RingsCross {
                ring_a: 1,
                ring_b: 0,
                at: [10.0, 5.0]
            })
        );
        // A hole entirely outside.
        let hole = closed(&[[20.0, 5.0], [25.0, 5.0], [25.0, 6.0]]);
        assert_eq!(
            validate_polygon(&[closed(&SQUARE), hole]),
            Err(HoleOutsideShell { ring: 1 })
        );
        // Nested holes.
        let h1 = closed(&[[1.0, 1.0], [9.0, 1.0], [9.0, 9.0], [1.0, 9.0]]);
        let h2 = closed(&[[2.0, 2.0], [8.0, 2.0], [8.0, 8.0], [2.0, 8.0]]);
        assert_eq!(
            validate_polygon(&[closed(&SQUARE), h1, h2]),
            Err(HolesOverlap {
                ring_a: 1,
                ring_b: 2
            })
        );
    }

    #[test]
    fn hole_touching_shell_at_a_point_is_valid() {
        let hole = closed(&[[0.0, 5.0], [5.0, 3.0], [5.0, 7.0]]);
        assert!(validate_polygon(&[closed(&SQUARE), hole]).is_ok());
    }

    #[test]
    fn hole_bridging_a_notch_is_outside() {
        // A C shape; the hole's edge from tip to tip spans the mouth, outside the shell.
        let c = closed(&[
            [0.0, 0.0],
            [10.0, 0.0],
            [10.0, 3.0],
            [3.0, 3.0],
            [3.0, 7.0],
            [10.0, 7.0],
            [10.0, 10.0],
            [0.0, 10.0],
        ]);
        // Every vertex is inside or on the shell, yet the edge (10,3)-(10,7) runs outside.
        let hole = closed(&[
            [10.0, 3.0],
            [10.0, 7.0],
            [9.0, 8.0],
            [1.0, 8.0],
            [1.0, 2.0],
            [9.0, 2.0],
        ]);
        assert!(matches!(
            validate_polygon(&[c, hole]),
            Err(PolygonProblem::HoleOutsideShell { ring: 1 })
        ));
    }
}
