//! Planar primitives the zone code is built on: exact orientation, point location in rings and
//! polygons, point-to-segment distance and axis-aligned boxes.
//!
//! Orientation uses Shewchuk's adaptive-precision predicate (through geo's [`RobustKernel`]), so
//! "is this point on that edge" and "do these segments cross" are answered exactly for the given
//! floating-point coordinates. Distances are computed in ordinary floating point, a few ulps from
//! the true value.

use geo::Coord;
use geo::algorithm::kernels::{Kernel, Orientation, RobustKernel};

/// A point in map metres: `[x east, y north]`.
pub(super) type P = [f64; 2];

/// Exact orientation of `c` relative to the directed line `a → b`.
#[inline]
pub(super) fn orient(a: P, b: P, c: P) -> Orientation {
    let co = |p: P| Coord { x: p[0], y: p[1] };
    RobustKernel::orient2d(co(a), co(b), co(c))
}

/// `(b − a) × (c − a)` in floating point (twice the signed triangle area); only its magnitude is
/// used, for intersection parameters. Signs come from [`orient`].
#[inline]
pub(super) fn cross(a: P, b: P, c: P) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// `a + t (b − a)`, returning the endpoints themselves at `t = 0` and `t = 1`.
#[inline]
pub(super) fn lerp(a: P, b: P, t: f64) -> P {
    if t <= 0.0 {
        a
    } else if t >= 1.0 {
        b
    } else {
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    }
}

/// Parameter of the orthogonal projection of `p` on the line `a → b` (0 at `a`, 1 at `b`).
#[inline]
pub(super) fn project(a: P, b: P, p: P) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)
}

/// Euclidean distance from `p` to the closed segment `a b`, by parry's exact point projection
/// on a [`Segment`](parry2d_f64::shape::Segment) (the nearest point is an end or the orthogonal
/// foot; no polygonal approximation anywhere).
#[inline]
pub(super) fn distance_point_segment(p: P, a: P, b: P) -> f64 {
    use parry2d_f64::math::Vector;
    use parry2d_f64::query::PointQuery;
    use parry2d_f64::shape::Segment;
    Segment::new(Vector::new(a[0], a[1]), Vector::new(b[0], b[1]))
        .distance_to_local_point(Vector::new(p[0], p[1]), true)
}

/// Where a point lies relative to a closed region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Location {
    /// In the open interior.
    Inside,
    /// On an edge or a vertex.
    Boundary,
    /// Outside the closed region.
    Outside,
}

/// Locate `p` relative to the region bounded by the closed `ring` (vertices without the repeated
/// closing one; either orientation). Exact: uses [`orient`] for every decision that needs it.
pub(super) fn locate_in_ring(p: P, ring: &[P]) -> Location {
    let Some(&last) = ring.last() else {
        return Location::Outside;
    };
    let mut inside = false;
    let mut a = last;
    for &b in ring {
        let (min_x, max_x) = if a[0] <= b[0] {
            (a[0], b[0])
        } else {
            (b[0], a[0])
        };
        let (min_y, max_y) = if a[1] <= b[1] {
            (a[1], b[1])
        } else {
            (b[1], a[1])
        };
        let in_box = p[0] >= min_x && p[0] <= max_x && p[1] >= min_y && p[1] <= max_y;
        // Half-open rule: the edge counts when it straddles the horizontal line through p.
        let straddles = (a[1] > p[1]) != (b[1] > p[1]);
        if in_box {
            let o = orient(a, b, p);
            if o == Orientation::Collinear {
                return Location::Boundary;
            }
            if straddles && ((o == Orientation::CounterClockwise) == (b[1] > a[1])) {
                inside = !inside;
            }
        } else if straddles && p[0] < min_x {
            // Both ends lie east of p: the ray towards +x crosses the edge.
            inside = !inside;
        }
        // Otherwise the edge is entirely west of p, or does not straddle p's row.
        a = b;
    }
    if inside {
        Location::Inside
    } else {
        Location::Outside
    }
}

/// Twice the signed area of a ring given open or closed (positive when counter-clockwise): a fan
/// of triangles from the first vertex, which keeps the products small.
pub(super) fn ring_double_area(ring: &[P]) -> f64 {
    let Some(&o) = ring.first() else {
        return 0.0;
    };
    let mut sum = 0.0;
    for w in ring.windows(2) {
        sum += cross(o, w[0], w[1]);
    }
    sum
}

/// An axis-aligned box in map metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Aabb {
    /// South-west corner.
    pub min: P,
    /// North-east corner.
    pub max: P,
}

impl Aabb {
    /// The empty box (contains nothing; the identity of [`Aabb::union`]).
    pub const EMPTY: Aabb = Aabb {
        min: [f64::INFINITY; 2],
        max: [f64::NEG_INFINITY; 2],
    };

    /// The smallest box holding both ends of a segment.
    #[inline]
    pub fn of_segment(a: P, b: P) -> Aabb {
        Aabb {
            min: [a[0].min(b[0]), a[1].min(b[1])],
            max: [a[0].max(b[0]), a[1].max(b[1])],
        }
    }

    /// The smallest box holding all `points`.
    pub fn of_points(points: &[P]) -> Aabb {
        points
            .iter()
            .fold(Aabb::EMPTY, |bb, &p| bb.union(Aabb { min: p, max: p }))
    }

    /// The smallest box holding both boxes.
    #[inline]
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: [self.min[0].min(other.min[0]), self.min[1].min(other.min[1])],
            max: [self.max[0].max(other.max[0]), self.max[1].max(other.max[1])],
        }
    }

    /// Whether the closed boxes share a point.
    #[inline]
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min[0] <= other.max[0]
            && other.min[0] <= self.max[0]
            && self.min[1] <= other.max[1]
            && other.min[1] <= self.max[1]
    }

    /// Whether the closed box contains `p`.
    #[inline]
    pub fn contains(&self, p: P) -> bool {
        p[0] >= self.min[0] && p[0] <= self.max[0] && p[1] >= self.min[1] && p[1] <= self.max[1]
    }

    /// Squared distance from `p` to the closed box (0 inside).
    #[inline]
    pub fn distance_squared(&self, p: P) -> f64 {
        let dx = (self.min[0] - p[0]).max(p[0] - self.max[0]).max(0.0);
        let dy = (self.min[1] - p[1]).max(p[1] - self.max[1]).max(0.0);
        dx * dx + dy * dy
    }

    /// Centre of the box.
    #[inline]
    pub fn centre(&self) -> P {
        [
            0.5 * (self.min[0] + self.max[0]),
            0.5 * (self.min[1] + self.max[1]),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: [P; 4] = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];

    #[test]
    fn locate_square() {
        assert_eq!(locate_in_ring([2.0, 2.0], &SQUARE), Location::Inside);
        assert_eq!(locate_in_ring([5.0, 2.0], &SQUARE), Location::Outside);
        assert_eq!(locate_in_ring([-1.0, 0.0], &SQUARE), Location::Outside);
        assert_eq!(locate_in_ring([2.0, 0.0], &SQUARE), Location::Boundary);
        assert_eq!(locate_in_ring([4.0, 4.0], &SQUARE), Location::Boundary);
        assert_eq!(locate_in_ring([0.0, 2.0], &SQUARE), Location::Boundary);
        // Rows through vertices must not double count.
        assert_eq!(locate_in_ring([-1.0, 4.0], &SQUARE), Location::Outside);
        assert_eq!(
            locate_in_ring([2.0, 4.0 - 1e-12], &SQUARE),
            Location::Inside
        );
        let mut cw = SQUARE;
        cw.reverse();
        assert_eq!(locate_in_ring([2.0, 2.0], &cw), Location::Inside);
        assert_eq!(locate_in_ring([1.0, 4.0], &cw), Location::Boundary);
        assert_eq!(locate_in_ring([1.0, 1.0], &[]), Location::Outside);
    }

    #[test]
    fn locate_through_a_vertex_row() {
        // A diamond: the horizontal line through p passes through the east and west vertices.
        let diamond = [[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];
        assert_eq!(locate_in_ring([0.0, 0.0], &diamond), Location::Inside);
        assert_eq!(locate_in_ring([-2.0, 0.0], &diamond), Location::Outside);
        assert_eq!(locate_in_ring([2.0, 0.0], &diamond), Location::Outside);
        assert_eq!(locate_in_ring([0.5, 0.5], &diamond), Location::Boundary);
    }

    #[test]
    fn segment_distance() {
        let (a, b) = ([0.0, 0.0], [10.0, 0.0]);
        assert_eq!(distance_point_segment([5.0, 3.0], a, b), 3.0);
        assert_eq!(distance_point_segment([-3.0, 4.0], a, b), 5.0);
        assert_eq!(distance_point_segment([13.0, -4.0], a, b), 5.0);
        assert_eq!(distance_point_segment([7.0, 0.0], a, b), 0.0);
        assert_eq!(distance_point_segment([3.0, 4.0], a, a), 5.0);
    }

    #[test]
    fn areas_and_boxes() {
        let mut closed = SQUARE.to_vec();
        closed.push(SQUARE[0]);
        assert_eq!(ring_double_area(&closed), 32.0);
        closed.reverse();
        assert_eq!(ring_double_area(&closed), -32.0);
        let bb = Aabb::of_points(&SQUARE);
        assert_eq!(
            bb,
            Aabb {
                min: [0.0, 0.0],
                max: [4.0, 4.0]
            }
        );
        assert_eq!(bb.distance_squared([7.0, 8.0]), 25.0);
        assert_eq!(bb.distance_squared([1.0, 1.0]), 0.0);
        assert!(!Aabb::EMPTY.contains([0.0, 0.0]));
    }
}
