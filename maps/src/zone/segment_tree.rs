//! A static bounding-volume hierarchy over line segments, answering "how far is the nearest
//! segment" by branch and bound.
//!
//! Built once (median split along the longer axis of the centres' box, four segments per leaf),
//! then queried read-only from any number of threads. The answer equals the brute-force minimum
//! over all segments bit for bit: boxes are only used to skip segments that provably cannot win.

use super::geometry::{Aabb, P, distance_point_segment};

/// Segments per leaf.
const LEAF_SIZE: usize = 4;

/// One node: a leaf owns `segments[first..first + count]`, an inner node (`count == 0`) has its
/// children at `first` and `first + 1`.
#[derive(Clone, Debug)]
struct Node {
    aabb: Aabb,
    first: u32,
    count: u32,
}

/// Segments with a bounding-volume hierarchy for nearest-distance queries.
#[derive(Clone, Debug, Default)]
pub(super) struct SegmentTree {
    segments: Vec<[P; 2]>,
    nodes: Vec<Node>,
}

impl SegmentTree {
    /// Build the tree over `segments` (their order is not kept).
    pub fn new(mut segments: Vec<[P; 2]>) -> Self {
        let mut nodes = Vec::with_capacity(2 * segments.len() / LEAF_SIZE + 1);
        if !segments.is_empty() {
            nodes.push(Node {
                aabb: Aabb::EMPTY,
                first: 0,
                count: 0,
            });
            build(&mut nodes, 0, &mut segments, 0);
        }
        Self { segments, nodes }
    }

    /// The segments, in tree order.
    #[cfg(test)]
    pub fn segments(&self) -> &[[P; 2]] {
        &self.segments
    }

    /// Euclidean distance from `p` to the nearest segment; `f64::INFINITY` when there are none.
    pub fn nearest_distance(&self, p: P) -> f64 {
        if self.nodes.is_empty() {
            return f64::INFINITY;
        }
        let mut best = f64::INFINITY;
        // Visit boxes nearest-first; skip a box only when it is clearly farther than `best` (the
        // slack keeps rounding in the box distance from skipping the true nearest segment).
        let mut stack: Vec<(f64, u32)> = Vec::with_capacity(64);
        stack.push((0.0, 0));
        while let Some((box_d2, index)) = stack.pop() {
            if box_d2 > best * best * (1.0 + 1e-9) {
                continue;
            }
            let node = &self.nodes[index as usize];
            if node.count > 0 {
                let first = node.first as usize;
                for s in &self.segments[first..first + node.count as usize] {
                    best = best.min(distance_point_segment(p, s[0], s[1]));
                }
            } else {
                let (l, r) = (node.first, node.first + 1);
                let dl = self.nodes[l as usize].aabb.distance_squared(p);
                let dr = self.nodes[r as usize].aabb.distance_squared(p);
                if dl <= dr {
                    stack.push((dr, r));
                    stack.push((dl, l));
                } else {
                    stack.push((dl, l));
                    stack.push((dr, r));
                }
            }
        }
        best
    }
}

/// Fill node `index` with `segments` (which start at `offset` in the tree's array), recursively.
fn build(nodes: &mut Vec<Node>, index: usize, segments: &mut [[P; 2]], offset: usize) {
    let aabb = segments
        .iter()
        .fold(Aabb::EMPTY, |bb, s| bb.union(Aabb::of_segment(s[0], s[1])));
    if segments.len() <= LEAF_SIZE {
        nodes[index] = Node {
            aabb,
            first: offset as u32,
            count: segments.len() as u32,
        };
        return;
    }
    let centres = segments.iter().fold(Aabb::EMPTY, |bb, s| {
        bb.union(Aabb {
            min: mid(s),
            max: mid(s),
        })
    });
    let axis = usize::from(centres.max[1] - centres.min[1] > centres.max[0] - centres.min[0]);
    let half = segments.len() / 2;
    segments.select_nth_unstable_by(half, |a, b| mid(a)[axis].total_cmp(&mid(b)[axis]));
    let first = nodes.len();
    nodes[index] = Node {
        aabb,
        first: first as u32,
        count: 0,
    };
    nodes.push(Node {
        aabb: Aabb::EMPTY,
        first: 0,
        count: 0,
    });
    nodes.push(Node {
        aabb: Aabb::EMPTY,
        first: 0,
        count: 0,
    });
    let (left, right) = segments.split_at_mut(half);
    build(nodes, first, left, offset);
    build(nodes, first + 1, right, offset + half);
}

/// Midpoint of a segment.
fn mid(s: &[P; 2]) -> P {
    Aabb::of_segment(s[0], s[1]).centre()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn empty_tree_is_infinitely_far() {
        assert_eq!(
            SegmentTree::new(Vec::new()).nearest_distance([0.0, 0.0]),
            f64::INFINITY
        );
    }

    #[test]
    fn equals_brute_force() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let pt = |rng: &mut ChaCha8Rng| {
            [
                rng.random_range(-100.0..100.0),
                rng.random_range(-100.0..100.0),
            ]
        };
        let segments: Vec<[P; 2]> = (0..500)
            .map(|_| {
                let a = pt(&mut rng);
                [
                    a,
                    [
                        a[0] + rng.random_range(-5.0..5.0),
                        a[1] + rng.random_range(-5.0..5.0),
                    ],
                ]
            })
            .collect();
        let tree = SegmentTree::new(segments.clone());
        assert_eq!(tree.segments().len(), 500);
        for _ in 0..2000 {
            let p = [
                rng.random_range(-150.0..150.0),
                rng.random_range(-150.0..150.0),
            ];
            let brute = segments
                .iter()
                .map(|s| distance_point_segment(p, s[0], s[1]))
                .fold(f64::INFINITY, f64::min);
            assert_eq!(tree.nearest_distance(p), brute);
        }
    }
}
