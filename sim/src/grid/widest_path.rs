//! Passage clearance: the widest (maximin, bottleneck) path on an 8-connected grid.
//!
//! [`widest_path`] answers "at what uncertainty radius does the route close?". With
//! `clearance` the distance from each cell to the nearest hazard, a path whose cells all have
//! clearance `> r` exists **iff** `r <` the returned value: the returned value is the largest,
//! over all paths, of the smallest clearance along the path.
//!
//! # Move model
//! The same as [`crate::grid::astar`]: 8-connected, and a diagonal move is allowed only if both
//! orthogonal cells it passes between are passable (no corner cutting). "Passable" means
//! `passable(i)` is true, `clearance[i]` is not NaN and the cell lies in the search window.
//!
//! At threshold `r` the cells with clearance `≤ r` are blocked, and a blocked corner cell forbids
//! the diagonal next to it. So a diagonal move's bottleneck also includes the clearance of its
//! two corner cells: that is what makes the "iff" above exact for A* run on the thresholded
//! grid. (Counting only the cells on the path would overstate the value whenever a path squeezes
//! diagonally past a low-clearance corner.)
//!
//! # Algorithm
//! Dijkstra's algorithm in the (max, min) semiring: a max-heap of bottleneck values, each cell's
//! value the best bottleneck known so far, relaxed as `min(value(cur), clearance(nb))`. Values
//! only decrease along a path, so the first time a cell is popped its value is final; the
//! search stops when the goal is popped. Ties are popped roomiest cell first, then in increasing
//! cell index, so the work done is deterministic (the returned value is unique anyway).
//!
//! ## References
//! - M. Pollack, "The Maximum Capacity Through a Network", *Operations Research* 8(5) (1960)
//!   733–736 (the bottleneck path problem).
//! - E. W. Dijkstra, "A Note on Two Problems in Connexion with Graphs", *Numerische Mathematik*
//!   1 (1959) 269–271.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// One open-set entry: bottleneck value so far, the cell's own clearance and its window-local
/// index. Among equal bottlenecks the roomier cell pops first, so the search tree (and the
/// bottleneck's reported place) does not hug obstacles past a pinch; then the lower index.
/// Both clearances are packed into one integer in the order of `f32::total_cmp`, so the heap
/// compares once where it compared twice (the heap is most of the search's time).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Open {
    /// `ordered(value) << 32 | ordered(own)`.
    key: u64,
    local: u32,
}

impl Open {
    fn new(value: f32, own: f32, local: u32) -> Self {
        Self {
            key: (u64::from(ordered(value)) << 32) | u64::from(ordered(own)),
            local,
        }
    }

    /// The bottleneck value.
    fn value(self) -> f32 {
        from_ordered((self.key >> 32) as u32)
    }
}

/// `f32` bits as an unsigned integer in the order of `f32::total_cmp`.
fn ordered(v: f32) -> u32 {
    let b = v.to_bits();
    if b >> 31 == 1 { !b } else { b | 0x8000_0000 }
}

/// The inverse of [`ordered`].
fn from_ordered(o: u32) -> f32 {
    f32::from_bits(if o >> 31 == 1 { o & 0x7fff_ffff } else { !o })
}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Open {
    /// Larger value pops first, then the roomier cell, then lower index.
    fn cmp(&self, other: &Self) -> Ordering {
        self.key
            .cmp(&other.key)
            .then_with(|| other.local.cmp(&self.local))
    }
}

/// A widest path's bottleneck: its value and where it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bottleneck {
    /// The largest bottleneck clearance over all paths (see [`widest_path`]).
    pub clearance: f32,
    /// The cell (row-major index) nearest the goal, along one widest path, that sets the
    /// bottleneck: past it, the rest of that path to the goal stays open at a larger radius.
    pub narrowest_cell: usize,
}

/// The largest bottleneck clearance over all 8-connected paths from `start` to `goal`, or
/// `None` if no path joins them.
///
/// A path's bottleneck is the minimum of `clearance` over its cells, `start` and `goal`
/// included, and over the two corner cells of each diagonal move (see the module docs: a
/// diagonal is only open while both corners are). Only cells with `passable(i)` true and a non-NaN clearance, inside `window`, are
/// used; diagonal moves need both orthogonal neighbours usable (no corner cutting).
/// `start == goal` gives `clearance[start]` when that cell is usable.
///
/// Indices are row-major (`i = row * width + col`). `window = Some((col0, row0, col1, row1))`
/// restricts the search to those inclusive bounds, clipped to the grid; an empty window, or a
/// start or goal outside it, gives `None`. `None` searches the whole grid.
///
/// # Units
/// The result is in the units of `clearance` (metres for a clearance map in metres).
///
/// # Panics
/// If `clearance.len() != width * height`, or `start` or `goal` is outside the grid.
#[must_use]
pub fn widest_path(
    width: usize,
    height: usize,
    clearance: &[f32],
    passable: impl Fn(usize) -> bool,
    start: usize,
    goal: usize,
    window: Option<(usize, usize, usize, usize)>,
) -> Option<f32> {
    widest_path_bottleneck(width, height, clearance, passable, start, goal, window)
        .map(|b| b.clearance)
}

/// [`widest_path`] with where its bottleneck lies: the cell nearest `goal`, along one widest
/// path, whose clearance (or a diagonal move's corner clearance) equals the bottleneck. A rover
/// on that path must keep its uncertainty radius below the value until it is past that cell
/// (the passage-aware planning of [`crate::operations::policy`] uses it).
///
/// The answer can never exceed the goal's own clearance. When the start is at least as roomy
/// as the goal and a path stays at or above the goal's clearance, the goal is the bottleneck
/// and the search returns it as soon as a goal-directed walk over those cells arrives (in open
/// ground, about the leg's length in cells) instead of expanding every cell that ties with
/// it: the same answer, cell included, as the full search ([`dijkstra_bottleneck`], the
/// reference the tests hold it to), which runs otherwise.
///
/// # Panics
/// As [`widest_path`].
#[must_use]
pub fn widest_path_bottleneck(
    width: usize,
    height: usize,
    clearance: &[f32],
    passable: impl Fn(usize) -> bool,
    start: usize,
    goal: usize,
    window: Option<(usize, usize, usize, usize)>,
) -> Option<Bottleneck> {
    let passable = &passable;
    if let Some(w) = Window::new(width, height, clearance, start, goal, window)
        && !clearance[goal].is_nan()
        && clearance[goal] <= clearance[start]
        && reachable_at(&w, clearance, passable, start, goal, clearance[goal])
    {
        return Some(Bottleneck {
            clearance: clearance[goal],
            narrowest_cell: goal,
        });
    }
    dijkstra_bottleneck(width, height, clearance, passable, start, goal, window)
}

/// The search window of [`widest_path_bottleneck`], clipped to the grid, holding both ends.
struct Window {
    width: usize,
    col0: usize,
    row0: usize,
    win_w: usize,
    win_h: usize,
}

impl Window {
    /// `None` for an empty window or one without `start` and `goal`.
    ///
    /// # Panics
    /// As [`widest_path`].
    fn new(
        width: usize,
        height: usize,
        clearance: &[f32],
        start: usize,
        goal: usize,
        window: Option<(usize, usize, usize, usize)>,
    ) -> Option<Self> {
        assert_eq!(
            clearance.len(),
            width * height,
            "clearance length must be width * height ({width} * {height})"
        );
        assert!(
            start < clearance.len() && goal < clearance.len(),
            "start {start} or goal {goal} outside the {width}×{height} grid"
        );
        let (col0, row0, col1, row1) = match window {
            None => (0, 0, width - 1, height - 1),
            Some((c0, r0, c1, r1)) => (c0, r0, c1.min(width - 1), r1.min(height - 1)),
        };
        if col0 > col1 || row0 > row1 {
            return None;
        }
        let inside = |i: usize| {
            let (r, c) = (i / width, i % width);
            (row0..=row1).contains(&r) && (col0..=col1).contains(&c)
        };
        (inside(start) && inside(goal)).then_some(Self {
            width,
            col0,
            row0,
            win_w: col1 - col0 + 1,
            win_h: row1 - row0 + 1,
        })
    }

    /// Window-local index of grid cell `i` (inside the window).
    fn local(&self, i: usize) -> usize {
        (i / self.width - self.row0) * self.win_w + (i % self.width - self.col0)
    }

    /// Grid index of window-local cell `l`.
    fn global(&self, l: usize) -> usize {
        (self.row0 + l / self.win_w) * self.width + self.col0 + l % self.win_w
    }
}

/// Whether a path of moves whose bottleneck is at least `t` (cells, and a diagonal's two
/// corners, of clearance `≥ t`, usable, in the window) joins `start` to `goal`: a depth-first
/// walk that tries the neighbour nearest the goal first, so in open ground it goes about
/// straight there.
fn reachable_at(
    w: &Window,
    clearance: &[f32],
    passable: &impl Fn(usize) -> bool,
    start: usize,
    goal: usize,
    t: f32,
) -> bool {
    let open = |l: usize| {
        let i = w.global(l);
        clearance[i] >= t && passable(i)
    };
    if !open(w.local(start)) || !open(w.local(goal)) {
        return false;
    }
    let goal_l = w.local(goal);
    let (goal_r, goal_c) = ((goal_l / w.win_w) as i64, (goal_l % w.win_w) as i64);
    let mut seen = vec![false; w.win_w * w.win_h];
    let mut stack = vec![w.local(start)];
    seen[w.local(start)] = true;
    let mut next: Vec<(i64, usize)> = Vec::with_capacity(8);
    while let Some(cur) = stack.pop() {
        if cur == goal_l {
            return true;
        }
        let (r, c) = ((cur / w.win_w) as i64, (cur % w.win_w) as i64);
        let at = |dr: i64, dc: i64| -> Option<usize> {
            let (rr, cc) = (r + dr, c + dc);
            (rr >= 0 && cc >= 0 && rr < w.win_h as i64 && cc < w.win_w as i64)
                .then(|| rr as usize * w.win_w + cc as usize)
                .filter(|&l| open(l))
        };
        let (up, down, left, right) = (at(-1, 0), at(1, 0), at(0, -1), at(0, 1));
        next.clear();
        for (dr, dc, cell) in [
            (-1, 0, up),
            (1, 0, down),
            (0, -1, left),
            (0, 1, right),
            (-1, -1, up.and(left).and_then(|_| at(-1, -1))),
            (-1, 1, up.and(right).and_then(|_| at(-1, 1))),
            (1, -1, down.and(left).and_then(|_| at(1, -1))),
            (1, 1, down.and(right).and_then(|_| at(1, 1))),
        ] {
            if let Some(l) = cell
                && !seen[l]
            {
                let (dy, dx) = ((r + dr - goal_r).abs(), (c + dc - goal_c).abs());
                next.push((dy.max(dx) * 3 + dy.min(dx), l));
            }
        }
        // Farthest pushed first, so the nearest is tried next.
        next.sort_unstable_by(|a, b| b.cmp(a));
        for &(_, l) in &next {
            seen[l] = true;
            stack.push(l);
        }
    }
    false
}

/// [`widest_path_bottleneck`] by Dijkstra's search alone (module docs): the reference.
///
/// # Panics
/// As [`widest_path`].
#[must_use]
pub fn dijkstra_bottleneck(
    width: usize,
    height: usize,
    clearance: &[f32],
    passable: impl Fn(usize) -> bool,
    start: usize,
    goal: usize,
    window: Option<(usize, usize, usize, usize)>,
) -> Option<Bottleneck> {
    let w = Window::new(width, height, clearance, start, goal, window)?;
    let (win_w, win_h) = (w.win_w, w.win_h);
    let global = |l: usize| w.global(l);
    let usable = |i: usize| !clearance[i].is_nan() && passable(i);
    if !usable(start) || !usable(goal) {
        return None;
    }
    let (start_l, goal_l) = (w.local(start), w.local(goal));

    // Cell states; `best` is meaningful from REACHED on.
    const UNSEEN: u8 = 0;
    const BLOCKED: u8 = 1;
    const USABLE: u8 = 2;
    const REACHED: u8 = 3;
    const CLOSED: u8 = 4;
    let mut state = vec![UNSEEN; win_w * win_h];
    let mut best = vec![f32::NEG_INFINITY; win_w * win_h];
    // How each reached cell was reached: its parent (window-local) and the move's own
    // bottleneck (the cell's clearance, or a diagonal's corner clearance if lower).
    let mut parent = vec![u32::MAX; win_w * win_h];
    let mut via = vec![f32::INFINITY; win_w * win_h];
    // Passability is asked at most once per cell.
    let probe = |state: &mut [u8], l: usize| -> bool {
        if state[l] == UNSEEN {
            state[l] = if usable(global(l)) { USABLE } else { BLOCKED };
        }
        state[l] != BLOCKED
    };

    let mut heap = BinaryHeap::new();
    best[start_l] = clearance[start];
    state[start_l] = REACHED;
    heap.push(Open::new(
        clearance[start],
        clearance[start],
        start_l as u32,
    ));
    while let Some(open) = heap.pop() {
        let (value, cur) = (open.value(), open.local as usize);
        if state[cur] == CLOSED {
            continue;
        }
        state[cur] = CLOSED;
        if cur == goal_l {
            // Walk back from the goal to the first move (or the start) that sets the value.
            let mut at = cur;
            while parent[at] != u32::MAX && via[at] > value {
                at = parent[at] as usize;
            }
            return Some(Bottleneck {
                clearance: value,
                narrowest_cell: global(at),
            });
        }
        let (r, c) = (cur / win_w, cur % win_w);
        let up = r > 0 && probe(&mut state, cur - win_w);
        let down = r + 1 < win_h && probe(&mut state, cur + win_w);
        let left = c > 0 && probe(&mut state, cur - 1);
        let right = c + 1 < win_w && probe(&mut state, cur + 1);
        let value_of = |ok: bool, l: usize| {
            if ok {
                clearance[global(l)]
            } else {
                f32::NEG_INFINITY
            }
        };
        let (vu, vd, vl, vr) = (
            value_of(up, cur.wrapping_sub(win_w)),
            value_of(down, cur + win_w),
            value_of(left, cur.wrapping_sub(1)),
            value_of(right, cur + 1),
        );
        // A diagonal move needs both corner cells open at the threshold too, so their
        // clearance bounds the move (as it would for A* on the grid thresholded at r).
        let candidates = [
            (up, cur.wrapping_sub(win_w), f32::INFINITY),
            (down, cur + win_w, f32::INFINITY),
            (left, cur.wrapping_sub(1), f32::INFINITY),
            (right, cur + 1, f32::INFINITY),
            (up && left, cur.wrapping_sub(win_w + 1), vu.min(vl)),
            (
                up && right,
                cur.wrapping_sub(win_w).wrapping_add(1),
                vu.min(vr),
            ),
            (down && left, (cur + win_w).wrapping_sub(1), vd.min(vl)),
            (down && right, cur + win_w + 1, vd.min(vr)),
        ];
        for (ok, nb, corner) in candidates {
            if !ok || !probe(&mut state, nb) || state[nb] == CLOSED {
                continue;
            }
            let step = clearance[global(nb)].min(corner);
            let v = value.min(step);
            if state[nb] == USABLE || v > best[nb] {
                state[nb] = REACHED;
                best[nb] = v;
                parent[nb] = cur as u32;
                via[nb] = step;
                heap.push(Open::new(v, clearance[global(nb)], nb as u32));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::collections::VecDeque;

    /// Is there a path using only usable cells with clearance ≥ `t`? (BFS, same move model.)
    fn connected_at(
        width: usize,
        height: usize,
        usable: &dyn Fn(usize) -> bool,
        start: usize,
        goal: usize,
    ) -> bool {
        if !usable(start) || !usable(goal) {
            return false;
        }
        let ok = |r: i64, c: i64| {
            r >= 0
                && c >= 0
                && r < height as i64
                && c < width as i64
                && usable(r as usize * width + c as usize)
        };
        let mut seen = vec![false; width * height];
        let mut queue = VecDeque::from([start]);
        seen[start] = true;
        while let Some(u) = queue.pop_front() {
            if u == goal {
                return true;
            }
            let (r, c) = ((u / width) as i64, (u % width) as i64);
            for dr in -1..=1_i64 {
                for dc in -1..=1_i64 {
                    if (dr, dc) == (0, 0) || !ok(r + dr, c + dc) {
                        continue;
                    }
                    if dr != 0 && dc != 0 && !(ok(r + dr, c) && ok(r, c + dc)) {
                        continue;
                    }
                    let v = (r + dr) as usize * width + (c + dc) as usize;
                    if !seen[v] {
                        seen[v] = true;
                        queue.push_back(v);
                    }
                }
            }
        }
        false
    }

    /// Binary search over the distinct clearance values for the largest threshold that still
    /// connects start and goal.
    #[allow(clippy::too_many_arguments)]
    fn brute_force(
        width: usize,
        height: usize,
        clearance: &[f32],
        passable: &[bool],
        start: usize,
        goal: usize,
        window: Option<(usize, usize, usize, usize)>,
    ) -> Option<f32> {
        let (c0, r0, c1, r1) = window.unwrap_or((0, 0, width - 1, height - 1));
        let inside = |i: usize| {
            let (r, c) = (i / width, i % width);
            r >= r0 && r <= r1 && c >= c0 && c <= c1
        };
        let mut values: Vec<f32> = clearance.to_vec();
        values.sort_by(f32::total_cmp);
        values.dedup();
        let at = |t: f32| {
            let usable = |i: usize| passable[i] && inside(i) && clearance[i] >= t;
            connected_at(width, height, &usable, start, goal)
        };
        if values.is_empty() || !at(values[0]) {
            return None;
        }
        // Invariant: at(values[lo]) holds; find the last index where it does.
        let (mut lo, mut hi) = (0, values.len());
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if at(values[mid]) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(values[lo])
    }

    #[test]
    fn matches_brute_force_on_random_grids() {
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        let mut found = 0;
        for trial in 0..500 {
            let width = rng.random_range(1..=20);
            let height = rng.random_range(1..=20);
            let n = width * height;
            // Few distinct values (many ties) or continuous ones.
            let discrete = rng.random_bool(0.5);
            let clearance: Vec<f32> = (0..n)
                .map(|_| {
                    if discrete {
                        rng.random_range(0..5) as f32
                    } else {
                        rng.random_range(-1.0..10.0)
                    }
                })
                .collect();
            let blocked = rng.random_range(0.0..0.35);
            let passable: Vec<bool> = (0..n).map(|_| !rng.random_bool(blocked)).collect();
            let window = if rng.random_bool(0.3) {
                let (ca, cb) = (rng.random_range(0..width), rng.random_range(0..width));
                let (ra, rb) = (rng.random_range(0..height), rng.random_range(0..height));
                Some((ca.min(cb), ra.min(rb), ca.max(cb), ra.max(rb)))
            } else {
                None
            };
            let start = rng.random_range(0..n);
            let goal = rng.random_range(0..n);
            let got = widest_path(
                width,
                height,
                &clearance,
                |i| passable[i],
                start,
                goal,
                window,
            );
            let want = brute_force(width, height, &clearance, &passable, start, goal, window);
            assert_eq!(got, want, "trial {trial}");
            found += usize::from(got.is_some());
        }
        assert!(found > 100, "too few connected cases: {found}");
    }

    #[test]
    fn the_goal_directed_shortcut_gives_the_reference_answer_and_cell() {
        let mut rng = ChaCha8Rng::seed_from_u64(26);
        let mut shortcut = 0;
        for trial in 0..3000 {
            let width = rng.random_range(1..=24);
            let height = rng.random_range(1..=24);
            let n = width * height;
            // Few distinct values (ties everywhere, as on a planning grid) or continuous ones.
            let levels = rng.random_range(1..6);
            let discrete = rng.random_bool(0.7);
            let clearance: Vec<f32> = (0..n)
                .map(|_| {
                    if discrete {
                        rng.random_range(0..levels) as f32
                    } else {
                        rng.random_range(-1.0..10.0)
                    }
                })
                .collect();
            let blocked = rng.random_range(0.0..0.3);
            let passable: Vec<bool> = (0..n).map(|_| !rng.random_bool(blocked)).collect();
            let window = if rng.random_bool(0.3) {
                let (ca, cb) = (rng.random_range(0..width), rng.random_range(0..width));
                let (ra, rb) = (rng.random_range(0..height), rng.random_range(0..height));
                Some((ca.min(cb), ra.min(rb), ca.max(cb), ra.max(rb)))
            } else {
                None
            };
            let (start, goal) = (rng.random_range(0..n), rng.random_range(0..n));
            let open = |i: usize| passable[i];
            let got = widest_path_bottleneck(width, height, &clearance, open, start, goal, window);
            let want = dijkstra_bottleneck(width, height, &clearance, open, start, goal, window);
            assert_eq!(got, want, "trial {trial}");
            shortcut += usize::from(got.is_some_and(|b| b.narrowest_cell == goal));
        }
        assert!(shortcut > 500, "the shortcut case too rare: {shortcut}");
    }

    #[test]
    fn packed_keys_keep_the_order_of_total_cmp() {
        let values = [
            f32::NEG_INFINITY,
            -3.5,
            -0.0,
            0.0,
            1e-40,
            2.25,
            f32::INFINITY,
            f32::NAN,
        ];
        for a in values {
            assert_eq!(from_ordered(ordered(a)).to_bits(), a.to_bits());
            for b in values {
                assert_eq!(ordered(a).cmp(&ordered(b)), a.total_cmp(&b), "{a} {b}");
            }
        }
    }

    #[test]
    fn threshold_semantics() {
        // A corridor whose narrowest cell has clearance 1.5.
        let clearance = [3.0, 2.0, 1.5, 2.5, 4.0];
        let v = widest_path(5, 1, &clearance, |_| true, 0, 4, None);
        assert_eq!(v, Some(1.5));
        // A detour through a wider row wins.
        let clearance = [3.0, 0.5, 3.0, 3.0, 2.0, 3.0];
        assert_eq!(
            widest_path(3, 2, &clearance, |_| true, 0, 2, None),
            Some(2.0)
        );
    }

    #[test]
    fn bottleneck_is_the_narrowest_cell_nearest_the_goal() {
        // Two equal pinches (cells 2 and 5); the one nearer the goal is reported, so a rover
        // must keep r below 1.5 until it is past cell 5.
        let clearance = [3.0, 2.0, 1.5, 2.5, 4.0, 1.5, 3.0, 3.0];
        let b = widest_path_bottleneck(8, 1, &clearance, |_| true, 0, 7, None).expect("a path");
        assert_eq!((b.clearance, b.narrowest_cell), (1.5, 5));
        // Reversed, the pinch nearer the new goal (cell 0's side) is cell 2.
        let b = widest_path_bottleneck(8, 1, &clearance, |_| true, 7, 0, None).expect("a path");
        assert_eq!((b.clearance, b.narrowest_cell), (1.5, 2));
        // The start itself may be the bottleneck.
        let clearance = [0.5, 2.0, 3.0];
        let b = widest_path_bottleneck(3, 1, &clearance, |_| true, 0, 2, None).expect("a path");
        assert_eq!((b.clearance, b.narrowest_cell), (0.5, 0));
        // A pinch in a 2-D corridor: a 5×3 grid whose middle column narrows to one cell.
        #[rustfmt::skip]
        let clearance = [
            4.0, 4.0, 0.2, 4.0, 4.0,
            4.0, 4.0, 1.0, 4.0, 4.0,
            4.0, 4.0, 0.2, 4.0, 4.0,
        ];
        let b = widest_path_bottleneck(5, 3, &clearance, |_| true, 5, 9, None).expect("a path");
        assert_eq!((b.clearance, b.narrowest_cell), (1.0, 7));
    }

    #[test]
    fn diagonal_corners_bound_the_move() {
        // 0 → 3 diagonally squeezes past corner 1 (clearance 0.5); 0 → 2 → 3 does not.
        let clearance = [5.0, 0.5, 5.0, 5.0];
        assert_eq!(
            widest_path(2, 2, &clearance, |_| true, 0, 3, None),
            Some(5.0)
        );
        let clearance = [5.0, 0.5, 0.5, 5.0];
        assert_eq!(
            widest_path(2, 2, &clearance, |_| true, 0, 3, None),
            Some(0.5)
        );
    }

    #[test]
    fn no_corner_cutting_and_walls() {
        let clearance = [1.0; 4];
        let open = [true, false, false, true];
        assert_eq!(widest_path(2, 2, &clearance, |i| open[i], 0, 3, None), None);
        let open = [true, true, false, true];
        assert_eq!(
            widest_path(2, 2, &clearance, |i| open[i], 0, 3, None),
            Some(1.0)
        );
    }

    #[test]
    fn window_restricts_the_search() {
        // 3×3 with the middle row blocked except at col 2; a window of cols 0..=1 cuts it.
        let clearance = [1.0; 9];
        let open = [true, true, true, false, false, true, true, true, true];
        assert_eq!(
            widest_path(3, 3, &clearance, |i| open[i], 0, 6, None),
            Some(1.0)
        );
        assert_eq!(
            widest_path(3, 3, &clearance, |i| open[i], 0, 6, Some((0, 0, 1, 2))),
            None
        );
        // Start outside the window, an empty window, and bounds past the grid (clipped).
        assert_eq!(
            widest_path(3, 3, &clearance, |_| true, 2, 6, Some((0, 0, 1, 2))),
            None
        );
        assert_eq!(
            widest_path(3, 3, &clearance, |_| true, 0, 0, Some((2, 0, 1, 2))),
            None
        );
        assert_eq!(
            widest_path(3, 3, &clearance, |_| true, 0, 8, Some((0, 0, 9, 9))),
            Some(1.0)
        );
    }

    #[test]
    fn degenerate_inputs() {
        assert_eq!(widest_path(1, 1, &[2.5], |_| true, 0, 0, None), Some(2.5));
        assert_eq!(widest_path(1, 1, &[2.5], |_| false, 0, 0, None), None);
        assert_eq!(widest_path(1, 1, &[f32::NAN], |_| true, 0, 0, None), None);
        let inf = [f32::INFINITY; 3];
        assert_eq!(
            widest_path(1, 3, &inf, |_| true, 0, 2, None),
            Some(f32::INFINITY)
        );
        let neg = [f32::NEG_INFINITY; 3];
        assert_eq!(
            widest_path(3, 1, &neg, |_| true, 0, 2, None),
            Some(f32::NEG_INFINITY)
        );
    }
}
