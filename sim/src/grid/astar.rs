//! A* on an 8-connected grid, with flat arrays and scratch reused across calls.
//!
//! [`AStar`] finds a cheapest path between two cells of a `width × height` row-major grid
//! (`i = row * width + col`). The caller describes the terrain with a closure giving the cost
//! multiplier of *entering* each cell, or `f32::INFINITY` for a blocked cell.
//!
//! # Move model
//! - A move to one of the 4 orthogonal neighbours costs `1 × cell_cost(neighbour)`; a move to one
//!   of the 4 diagonal neighbours costs `√2 × cell_cost(neighbour)`.
//! - A diagonal move is allowed only if both orthogonal cells it passes between are passable
//!   (no corner cutting), so a path never slips between two blocked cells touching at a corner.
//! - The cost of the start cell is never charged; a path's cost is the sum of its move costs,
//!   in cells (multiply by the resolution for metres).
//!
//! # Search
//! Textbook A* (Hart, Nilsson & Raphael 1968) with the octile-distance heuristic
//! `min_cost × (max(Δr, Δc) + (√2 − 1) · min(Δr, Δc))`. It is consistent when every passable
//! cell costs at least `min_cost`, so each cell is expanded at most once and the returned path
//! is optimal. Improved cells are pushed again (lazy deletion); stale entries are skipped when
//! popped. A closed neighbour is known to be passable, so its cost is not even looked up.
//!
//! The open set is an exact *banded* priority queue (Dial-style buckets over a coarse `f`, the
//! current band sorted; see `OpenSet`): A* pops `f` almost monotonically, so most pushes are
//! appends, and it pops exactly what a binary heap would — about 1.35× faster than the 4-ary
//! heap it replaced on the B4 grids (BENCHMARKS.md).
//!
//! Costs `g` are accumulated in `f64`: sums of millions of `f32` costs stay exact to far below
//! the 1e-6 relative tolerance the tests demand.
//!
//! **Determinism.** Open-set keys are totally ordered: lower `f` first, then larger `g`
//! (compared as `f32`; deeper nodes first, which cuts expansions on plateaus of equal `f`), then
//! lower cell index. The same input therefore always gives the same path. Equal `f` means
//! bit-equal `f64`: on uniform-cost maps, sums that are equal in exact arithmetic may round
//! differently, and those are ordered by their rounded values.
//!
//! **No path, found early.** A search that runs past [`REACH_CHECK_AFTER`] expansions checks
//! once, by a bidirectional flood fill over the passable cells, whether the goal can be reached
//! at all, and stops if it cannot; otherwise it carries on unchanged, so the paths are exactly
//! those of the plain search (tested).
//!
//! **No per-call reset.** Each cell's state carries a generation stamp; a cell whose stamp is
//! not the current call's is "unseen", so a call costs time proportional to the cells it
//! touches, not to the grid size (16 bytes of state per cell, allocated once in
//! [`AStar::new`]).
//!
//! ## References
//! - P. E. Hart, N. J. Nilsson and B. Raphael, "A Formal Basis for the Heuristic Determination
//!   of Minimum Cost Paths", *IEEE Transactions on Systems Science and Cybernetics* 4(2) (1968)
//!   100–107.

mod open_set;

use open_set::{BANDS_PER_UNIT, OpenSet, key_cell, open_key};

/// √2 − 1, the extra octile cost of a diagonal step over an orthogonal one.
const SQRT2_MINUS_1: f64 = std::f64::consts::SQRT_2 - 1.0;

/// A path found by [`AStar::plan`].
#[derive(Debug, Clone, PartialEq)]
pub struct GridPath {
    /// Row-major cell indices from the start to the goal, both included.
    pub cells: Vec<usize>,
    /// Total move cost.
    ///
    /// # Units
    /// Cells (step length in cell widths × cost multiplier), summed in `f64`.
    pub cost: f64,
}

/// Per-cell search state, kept together so one cache line serves a relaxation.
#[derive(Debug, Clone, Copy, Default)]
struct CellState {
    /// Best known cost from the start (valid only when the stamp is current).
    g: f64,
    /// Predecessor on the best known path.
    parent: u32,
    /// `2·generation` = open (seen) in the current call, `2·generation + 1` = closed; any other
    /// value = not seen in the current call.
    stamp: u32,
}

/// A* planner for one grid size, owning the scratch memory reused by every [`AStar::plan`].
///
/// Memory: 16 bytes per cell plus the open set, and 2 bits per cell plus a frontier for the
/// reachability check of a long search ([`REACH_CHECK_AFTER`]).
#[derive(Debug, Clone)]
pub struct AStar {
    width: usize,
    height: usize,
    cells: Vec<CellState>,
    heap: OpenSet,
    generation: u32,
    expansions: usize,
    /// Scratch of the reachability check ([`REACH_CHECK_AFTER`]).
    reach: Reach,
    /// Expansions after which a search checks that the goal is reachable at all.
    reach_check_after: usize,
}

/// A search still running after this many expansions first checks, by a bidirectional flood
/// fill, that the goal is reachable at all, and gives up at once if it is not. Without a path
/// A* closes every cell it can reach (a NO_PATH fault on a large map: most of a traverse's
/// planning time); the flood fill proves the same an order of magnitude faster. With a path it
/// changes nothing but the time: the search then goes on as it was.
pub const REACH_CHECK_AFTER: usize = 16_384;

impl AStar {
    /// A planner for `width × height` grids.
    ///
    /// # Panics
    /// If `width * height` overflows or exceeds `u32::MAX` cells.
    #[must_use]
    pub fn new(width: usize, height: usize) -> Self {
        let n = width
            .checked_mul(height)
            .filter(|&n| n <= u32::MAX as usize)
            .unwrap_or_else(|| panic!("grid {width}×{height} exceeds u32::MAX cells"));
        Self {
            width,
            height,
            cells: vec![CellState::default(); n],
            heap: OpenSet::default(),
            generation: 0,
            expansions: 0,
            reach: Reach::default(),
            reach_check_after: REACH_CHECK_AFTER,
        }
    }

    /// This planner with the reachability check after `expansions` expansions instead of
    /// [`REACH_CHECK_AFTER`] (`usize::MAX`: never). For tests and benchmarks: the paths are the
    /// same for any value.
    #[must_use]
    pub fn with_reach_check_after(mut self, expansions: usize) -> Self {
        self.reach_check_after = expansions;
        self
    }

    /// Grid width in cells.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Grid height in cells.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// Nodes expanded by the last call of [`AStar::plan`]: the cells taken from the open set and
    /// closed, the start and the goal included (0 when the call returned before searching).
    #[must_use]
    pub fn expansions(&self) -> usize {
        self.expansions
    }

    /// Cheapest path from `start` to `goal` (row-major indices), or `None` if there is none.
    ///
    /// `cell_cost(i)` is the cost multiplier (normally ≥ 1.0) of entering cell `i`, or
    /// `f32::INFINITY` (or NaN) if the cell is blocked; it is only called on cells inside the
    /// grid. `min_cost` scales the octile heuristic and must not exceed any passable cell's cost
    /// for the result to be optimal (normally 1.0); a value ≤ 0, infinite or NaN turns the
    /// search into Dijkstra's. Costs must be ≥ 0 (a negative cost gives an unspecified path).
    /// A blocked start or goal gives `None`; `start == goal` gives the one-cell path of cost 0.
    ///
    /// # Panics
    /// If `start` or `goal` is outside the grid.
    pub fn plan<F: Fn(usize) -> f32>(
        &mut self,
        start: usize,
        goal: usize,
        min_cost: f32,
        cell_cost: F,
    ) -> Option<GridPath> {
        self.plan_edges(start, goal, min_cost, |_, to| cell_cost(to))
    }

    /// [`AStar::plan`] with a cost that depends on the move: `move_cost(from, to)` is the cost
    /// multiplier of moving from cell `from` to its neighbour `to` (the direction of travel
    /// matters: uphill on sand is not downhill on sand), `f32::INFINITY` if that move is
    /// blocked. `move_cost(i, i)` says whether cell `i` can be occupied at all: it decides the
    /// start and goal, and the early unreachability check counts a cell passable when it is
    /// finite. A diagonal move is allowed when both orthogonal moves from `from` beside it are.
    /// The heuristic stays admissible when no finite move costs less than `min_cost`.
    ///
    /// # Panics
    /// If `start` or `goal` is outside the grid.
    pub fn plan_edges<F: Fn(usize, usize) -> f32>(
        &mut self,
        start: usize,
        goal: usize,
        min_cost: f32,
        move_cost: F,
    ) -> Option<GridPath> {
        let cell_cost = |i: usize| move_cost(i, i);
        let n = self.cells.len();
        assert!(
            start < n && goal < n,
            "start {start} or goal {goal} outside the {}×{} grid",
            self.width,
            self.height
        );
        self.expansions = 0;
        let passable = |c: f32| c < f32::INFINITY;
        if !passable(cell_cost(start)) || !passable(cell_cost(goal)) {
            return None;
        }
        if start == goal {
            return Some(GridPath {
                cells: vec![start],
                cost: 0.0,
            });
        }
        let open_stamp = self.next_generation();
        let width = self.width;
        let height = self.height;
        let reach_check_after = self.reach_check_after;
        let reach = &mut self.reach;
        let mut search = Search {
            cells: &mut self.cells,
            heap: &mut self.heap,
            open_stamp,
            closed_stamp: open_stamp + 1,
            width,
            goal_row: goal / width,
            goal_col: goal % width,
            h_scale: if min_cost > 0.0 && min_cost.is_finite() {
                f64::from(min_cost)
            } else {
                0.0
            },
        };
        // Bands a fraction of the cheapest step wide.
        let cost_unit = if search.h_scale > 0.0 {
            search.h_scale
        } else {
            1.0
        };
        search.heap.reset(BANDS_PER_UNIT / cost_unit);
        search.cells[start] = CellState {
            g: 0.0,
            parent: start as u32,
            stamp: open_stamp,
        };
        let f_start = search.heuristic(start / width, start % width);
        search.heap.push(open_key(f_start, 0.0, start as u32));

        let sqrt2 = std::f64::consts::SQRT_2;
        let mut expansions = 0_usize;
        let mut found = false;
        while let Some(key) = search.heap.pop() {
            let cell = key_cell(key);
            let cur = cell as usize;
            // Lazy deletion: with a consistent heuristic the first pop of a cell carries its
            // best g, so any later pop of the same cell is stale.
            let state = &mut search.cells[cur];
            if state.stamp == search.closed_stamp {
                continue;
            }
            state.stamp = search.closed_stamp;
            let g = state.g;
            expansions += 1;
            if cur == goal {
                found = true;
                break;
            }
            if expansions == reach_check_after
                && !reach.connected(width, height, start, goal, |i| cell_cost(i) < f32::INFINITY)
            {
                break;
            }
            let (row, col) = (cur / width, cur % width);
            // A closed cell was entered, so it is passable: its cost is not needed, and it
            // needs no relaxation. About half the neighbours are closed.
            let mut orthogonal = |inside: bool, r: usize, c: usize| -> bool {
                if !inside {
                    return false;
                }
                if search.is_closed(r, c) {
                    return true;
                }
                let cost = f64::from(move_cost(cur, r * width + c));
                // `x < ∞` is false for ∞ and NaN alike: both are blocked.
                let open = cost < f64::INFINITY;
                if open {
                    search.relax_unclosed(cell, g, r, c, cost);
                }
                open
            };
            let pu = orthogonal(row > 0, row.wrapping_sub(1), col);
            let pd = orthogonal(row + 1 < height, row + 1, col);
            let pl = orthogonal(col > 0, row, col.wrapping_sub(1));
            let pr = orthogonal(col + 1 < width, row, col + 1);
            // Out-of-grid diagonals are excluded by their orthogonal flags, so the wrapping
            // subtractions are never used.
            for (ok, r, c) in [
                (pu && pl, row.wrapping_sub(1), col.wrapping_sub(1)),
                (pu && pr, row.wrapping_sub(1), col + 1),
                (pd && pl, row + 1, col.wrapping_sub(1)),
                (pd && pr, row + 1, col + 1),
            ] {
                if ok && !search.is_closed(r, c) {
                    let cost = f64::from(move_cost(cur, r * width + c));
                    if cost < f64::INFINITY {
                        search.relax_unclosed(cell, g, r, c, sqrt2 * cost);
                    }
                }
            }
        }
        self.expansions = expansions;
        if !found {
            return None;
        }
        let cost = self.cells[goal].g;
        let mut path = vec![goal];
        let mut cur = goal;
        while cur != start {
            cur = self.cells[cur].parent as usize;
            path.push(cur);
        }
        path.reverse();
        Some(GridPath { cells: path, cost })
    }

    /// Advances the generation and returns its "open" stamp, resetting the stamps when they
    /// would wrap (once every 2³¹ calls).
    fn next_generation(&mut self) -> u32 {
        if self.generation >= u32::MAX / 2 - 1 {
            for c in &mut self.cells {
                c.stamp = 0;
            }
            self.generation = 0;
        }
        self.generation += 1;
        2 * self.generation
    }
}

/// Scratch of [`Reach::connected`]: the cells each side has reached (bit sets) and its queue.
#[derive(Debug, Clone, Default)]
struct Reach {
    seen: [Vec<u64>; 2],
    queue: [std::collections::VecDeque<u32>; 2],
}

impl Reach {
    /// Whether `goal` can be reached from `start` (both passable) on the `width × height` grid
    /// through cells that are `passable`. A* moves diagonally only between two passable
    /// orthogonal cells, so its reachable set is the 4-connected one. Breadth-first from both
    /// ends, one cell of each in turn: the answer is known when the two meet, or when one side
    /// has run out of cells (its component, without the other end), so the work is about twice
    /// the smaller component, not the start's whole component.
    fn connected(
        &mut self,
        width: usize,
        height: usize,
        start: usize,
        goal: usize,
        passable: impl Fn(usize) -> bool,
    ) -> bool {
        let words = (width * height).div_ceil(64);
        for (seen, queue) in self.seen.iter_mut().zip(&mut self.queue) {
            seen.clear();
            seen.resize(words, 0);
            queue.clear();
        }
        let mark = |seen: &mut [u64], i: usize| seen[i / 64] |= 1 << (i % 64);
        let marked = |seen: &[u64], i: usize| seen[i / 64] & (1 << (i % 64)) != 0;
        for (side, end) in [start, goal].into_iter().enumerate() {
            mark(&mut self.seen[side], end);
            self.queue[side].push_back(end as u32);
        }
        if start == goal {
            return true;
        }
        loop {
            for side in 0..2 {
                let Some(cell) = self.queue[side].pop_front() else {
                    return false;
                };
                let cur = cell as usize;
                let (row, col) = (cur / width, cur % width);
                for (inside, nb) in [
                    (row > 0, cur.wrapping_sub(width)),
                    (row + 1 < height, cur + width),
                    (col > 0, cur.wrapping_sub(1)),
                    (col + 1 < width, cur + 1),
                ] {
                    if !inside || marked(&self.seen[side], nb) {
                        continue;
                    }
                    if marked(&self.seen[1 - side], nb) {
                        return true;
                    }
                    if passable(nb) {
                        mark(&mut self.seen[side], nb);
                        self.queue[side].push_back(nb as u32);
                    }
                }
            }
        }
    }
}

/// [`AStar`] planners kept for reuse, so that a traverse does not allocate (and the kernel
/// does not zero) 16 bytes per grid cell for every run: on a 4.8-million-cell grid that was
/// most of a statistical-localizer run's time.
///
/// A reused planner gives exactly the paths a new one would ([`AStar::plan`] resets nothing
/// per call and depends on no earlier call). The pool holds at most as many planners as runs
/// were in progress at once; a planner of another size is never handed out.
#[derive(Debug, Default)]
pub struct AStarPool {
    free: std::sync::Mutex<Vec<AStar>>,
}

impl AStarPool {
    /// A planner for `width × height` grids: a free one of that size, or a new one.
    ///
    /// # Panics
    /// As [`AStar::new`], if a new planner is needed and `width * height` is too large.
    #[must_use]
    pub fn take(&self, width: usize, height: usize) -> PooledAStar<'_> {
        let reused = self.free.lock().ok().and_then(|mut free| {
            let i = free
                .iter()
                .rposition(|a| a.width == width && a.height == height)?;
            Some(free.swap_remove(i))
        });
        PooledAStar {
            pool: self,
            astar: Some(reused.unwrap_or_else(|| AStar::new(width, height))),
        }
    }

    /// Planners free for reuse now.
    #[must_use]
    pub fn free_len(&self) -> usize {
        self.free.lock().map_or(0, |free| free.len())
    }
}

/// A clone is an empty pool: planners are scratch, not state.
impl Clone for AStarPool {
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// A planner taken from an [`AStarPool`]; it goes back to the pool when dropped.
#[derive(Debug)]
pub struct PooledAStar<'a> {
    pool: &'a AStarPool,
    astar: Option<AStar>,
}

impl std::ops::Deref for PooledAStar<'_> {
    type Target = AStar;
    fn deref(&self) -> &AStar {
        self.astar
            .as_ref()
            .unwrap_or_else(|| unreachable!("taken only on drop"))
    }
}

impl std::ops::DerefMut for PooledAStar<'_> {
    fn deref_mut(&mut self) -> &mut AStar {
        self.astar
            .as_mut()
            .unwrap_or_else(|| unreachable!("taken only on drop"))
    }
}

impl Drop for PooledAStar<'_> {
    fn drop(&mut self) {
        if let (Some(astar), Ok(mut free)) = (self.astar.take(), self.pool.free.lock()) {
            free.push(astar);
        }
    }
}

/// The borrowed state of one [`AStar::plan`] call.
struct Search<'a> {
    cells: &'a mut [CellState],
    heap: &'a mut OpenSet,
    open_stamp: u32,
    closed_stamp: u32,
    width: usize,
    goal_row: usize,
    goal_col: usize,
    h_scale: f64,
}

impl Search<'_> {
    /// Octile distance to the goal × `min_cost`.
    #[inline(always)]
    fn heuristic(&self, row: usize, col: usize) -> f64 {
        let dr = row.abs_diff(self.goal_row) as f64;
        let dc = col.abs_diff(self.goal_col) as f64;
        self.h_scale * (dr.max(dc) + SQRT2_MINUS_1 * dr.min(dc))
    }

    #[inline(always)]
    fn is_closed(&self, row: usize, col: usize) -> bool {
        self.cells[row * self.width + col].stamp == self.closed_stamp
    }

    /// Relaxes the move from `cur` (best cost `g`) into the unclosed cell (`row`, `col`)
    /// costing `step`.
    #[inline(always)]
    fn relax_unclosed(&mut self, cur: u32, g: f64, row: usize, col: usize, step: f64) {
        let nb = row * self.width + col;
        let state = &mut self.cells[nb];
        let ng = g + step;
        if state.stamp != self.open_stamp || ng < state.g {
            *state = CellState {
                g: ng,
                parent: cur,
                stamp: self.open_stamp,
            };
            let f = ng + self.heuristic(row, col);
            self.heap.push(open_key(f, ng, nb as u32));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::cmp::Ordering;
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;

    /// A wall of column 5 that is cheap to cross westward and blocked eastward (sand uphill one
    /// way, downhill the other): going east the path detours around its end, going west it
    /// goes straight through; with the cell-cost closure the same wall is symmetric.
    #[test]
    fn move_costs_depend_on_the_direction() {
        let (w, h) = (11, 7);
        let wall = |i: usize| i % w == 5 && i / w < 6;
        let cost = |from: usize, to: usize| {
            if from != to && wall(to) && to % w > from % w {
                f32::INFINITY
            } else {
                1.0
            }
        };
        let mut a = AStar::new(w, h);
        let east = a
            .plan_edges(3 * w + 1, 3 * w + 9, 1.0, cost)
            .expect("a path east");
        assert!(
            east.cells.iter().any(|&c| c / w == 6),
            "detours below the wall: {east:?}"
        );
        let west = a
            .plan_edges(3 * w + 9, 3 * w + 1, 1.0, cost)
            .expect("a path west");
        assert_eq!(west.cells.len(), 9, "straight through: {west:?}");
        assert!((west.cost - 8.0).abs() < 1e-9);
        // The start and goal must be occupiable: `cost(i, i)` decides.
        assert!(
            a.plan_edges(0, 10, 1.0, |f, t| if f == t && t == 10 {
                f32::INFINITY
            } else {
                1.0
            })
            .is_none()
        );
    }

    /// Plain Dijkstra over the same move model, returning the optimal cost.
    fn dijkstra(
        width: usize,
        height: usize,
        cost: &[f32],
        start: usize,
        goal: usize,
    ) -> Option<f64> {
        #[derive(PartialEq)]
        struct Key(f64);
        impl Eq for Key {}
        impl PartialOrd for Key {
            fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
                Some(self.cmp(o))
            }
        }
        impl Ord for Key {
            fn cmp(&self, o: &Self) -> Ordering {
                self.0.total_cmp(&o.0)
            }
        }
        let ok = |r: i64, c: i64| {
            r >= 0
                && c >= 0
                && r < height as i64
                && c < width as i64
                && cost[r as usize * width + c as usize].is_finite()
        };
        if !cost[start].is_finite() || !cost[goal].is_finite() {
            return None;
        }
        let mut dist = vec![f64::INFINITY; width * height];
        let mut heap = BinaryHeap::new();
        dist[start] = 0.0;
        heap.push(Reverse((Key(0.0), start)));
        while let Some(Reverse((Key(d), u))) = heap.pop() {
            if d > dist[u] {
                continue;
            }
            if u == goal {
                return Some(d);
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
                    let step = if dr != 0 && dc != 0 {
                        std::f64::consts::SQRT_2
                    } else {
                        1.0
                    };
                    let nd = d + step * f64::from(cost[v]);
                    if nd < dist[v] {
                        dist[v] = nd;
                        heap.push(Reverse((Key(nd), v)));
                    }
                }
            }
        }
        None
    }

    fn random_grid(rng: &mut ChaCha8Rng, width: usize, height: usize, blocked: f64) -> Vec<f32> {
        random_grid_with(rng, width, height, blocked, 2.0)
    }

    /// Costs uniform in `[1, max_cost)`, `blocked` of the cells blocked.
    fn random_grid_with(
        rng: &mut ChaCha8Rng,
        width: usize,
        height: usize,
        blocked: f64,
        max_cost: f32,
    ) -> Vec<f32> {
        (0..width * height)
            .map(|_| {
                if rng.random_bool(blocked) {
                    f32::INFINITY
                } else {
                    rng.random_range(1.0..max_cost)
                }
            })
            .collect()
    }

    /// The path is connected, legal (no corner cutting, passable) and its cost is `cost`.
    fn check_path(width: usize, cost: &[f32], path: &GridPath, start: usize, goal: usize) {
        assert_eq!(path.cells.first(), Some(&start));
        assert_eq!(path.cells.last(), Some(&goal));
        let mut total = 0.0;
        for pair in path.cells.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let (ra, ca) = (a / width, a % width);
            let (rb, cb) = (b / width, b % width);
            let (dr, dc) = (ra.abs_diff(rb), ca.abs_diff(cb));
            assert!(dr <= 1 && dc <= 1 && dr + dc > 0, "not adjacent: {a} → {b}");
            assert!(cost[b].is_finite(), "blocked cell {b} on the path");
            if dr == 1 && dc == 1 {
                assert!(cost[ra * width + cb].is_finite() && cost[rb * width + ca].is_finite());
                total += std::f64::consts::SQRT_2 * f64::from(cost[b]);
            } else {
                total += f64::from(cost[b]);
            }
        }
        assert!((total - path.cost).abs() <= 1e-9 * total.max(1.0));
    }

    #[test]
    fn matches_dijkstra_on_random_grids() {
        let mut rng = ChaCha8Rng::seed_from_u64(42);
        let mut found = 0;
        for trial in 0..400 {
            let width = rng.random_range(1..=30);
            let height = rng.random_range(1..=30);
            let blocked = rng.random_range(0.0..0.3);
            let cost = random_grid(&mut rng, width, height, blocked);
            let mut astar = AStar::new(width, height);
            // Several queries on one planner also exercise the generation stamps.
            for _ in 0..5 {
                let start = rng.random_range(0..width * height);
                let goal = rng.random_range(0..width * height);
                let got = astar.plan(start, goal, 1.0, |i| cost[i]);
                let want = dijkstra(width, height, &cost, start, goal);
                match (&got, want) {
                    (Some(p), Some(w)) => {
                        assert!(
                            (p.cost - w).abs() <= 1e-6 * w.max(1.0),
                            "trial {trial}: A* {} vs Dijkstra {w}",
                            p.cost
                        );
                        check_path(width, &cost, p, start, goal);
                        found += 1;
                    }
                    (None, None) => {}
                    _ => panic!("trial {trial}: A* {got:?} vs Dijkstra {want:?}"),
                }
            }
        }
        assert!(found > 1000, "too few solvable cases: {found}");
    }

    /// Other cost models: a wide cost range (keys jump past the open set's band window),
    /// integer costs (many equal `f`), and `min_cost = 0` (Dijkstra).
    #[test]
    fn matches_dijkstra_with_wide_integer_and_zero_heuristic_costs() {
        let mut rng = ChaCha8Rng::seed_from_u64(43);
        for trial in 0..300 {
            let width = rng.random_range(1..=30);
            let height = rng.random_range(1..=30);
            let mut cost = random_grid_with(&mut rng, width, height, 0.15, 500.0);
            let model = trial % 3;
            if model == 1 {
                for c in cost.iter_mut().filter(|c| c.is_finite()) {
                    *c = (*c % 3.0).floor() + 1.0;
                }
            }
            let min_cost = if model == 2 { 0.0 } else { 1.0 };
            let mut astar = AStar::new(width, height);
            for _ in 0..3 {
                let start = rng.random_range(0..width * height);
                let goal = rng.random_range(0..width * height);
                let got = astar.plan(start, goal, min_cost, |i| cost[i]);
                let want = dijkstra(width, height, &cost, start, goal);
                match (&got, want) {
                    (Some(p), Some(w)) => {
                        assert!((p.cost - w).abs() <= 1e-6 * w.max(1.0), "trial {trial}");
                        check_path(width, &cost, p, start, goal);
                    }
                    (None, None) => {}
                    _ => panic!("trial {trial}: A* {got:?} vs Dijkstra {want:?}"),
                }
            }
        }
    }

    #[test]
    fn uniform_cost_straight_line_expands_only_the_line() {
        // Equal f everywhere on the line: preferring larger g dives straight to the goal.
        let mut astar = AStar::new(200, 1);
        let path = astar.plan(0, 199, 1.0, |_| 1.0).expect("path");
        assert_eq!(path.cost, 199.0);
        assert_eq!(astar.expansions(), 200);
        let mut astar = AStar::new(100, 100);
        let path = astar.plan(0, 99 * 100 + 99, 1.0, |_| 1.0).expect("path");
        assert_eq!(path.cells.len(), 100);
        assert!(
            astar.expansions() < 400,
            "{} expansions",
            astar.expansions()
        );
    }

    #[test]
    fn zero_min_cost_is_dijkstra_and_agrees() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let cost = random_grid(&mut rng, 25, 25, 0.15);
        let mut astar = AStar::new(25, 25);
        let a = astar.plan(0, 624, 1.0, |i| cost[i]).map(|p| p.cost);
        let a_expanded = astar.expansions();
        let d = astar.plan(0, 624, 0.0, |i| cost[i]).map(|p| p.cost);
        assert!(astar.expansions() >= a_expanded);
        for odd in [f32::NAN, f32::INFINITY, -1.0] {
            assert_eq!(astar.plan(0, 624, odd, |i| cost[i]).map(|p| p.cost), d);
        }
        match (a, d) {
            (Some(a), Some(d)) => assert!((a - d).abs() <= 1e-9 * d),
            (a, d) => assert_eq!(a, d),
        }
    }

    #[test]
    fn same_input_same_path() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        // Few distinct costs: many equal-cost paths, so tie-breaking decides.
        let cost: Vec<f32> = (0..40 * 40)
            .map(|_| {
                if rng.random_bool(0.1) {
                    f32::INFINITY
                } else {
                    1.0
                }
            })
            .collect();
        let first = AStar::new(40, 40).plan(41, 1558, 1.0, |i| cost[i]);
        let mut reused = AStar::new(40, 40);
        for _ in 0..3 {
            let _ = reused.plan(1558, 41, 1.0, |i| cost[i]);
            assert_eq!(reused.plan(41, 1558, 1.0, |i| cost[i]), first);
        }
    }

    #[test]
    fn pooled_planners_are_reused_and_plan_like_new_ones() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let cost = random_grid(&mut rng, 30, 20, 0.2);
        let pool = AStarPool::default();
        let want = AStar::new(30, 20).plan(5, 590, 1.0, |i| cost[i]);
        {
            let mut a = pool.take(30, 20);
            let _ = a.plan(590, 31, 1.0, |i| cost[i]);
            let b = pool.take(30, 20);
            assert_eq!(pool.free_len(), 0);
            drop(b);
        }
        assert_eq!(pool.free_len(), 2);
        assert_eq!(pool.take(30, 20).plan(5, 590, 1.0, |i| cost[i]), want);
        // Another size is never handed out.
        let other = pool.take(20, 30);
        assert_eq!(
            (other.width(), other.height(), pool.free_len()),
            (20, 30, 2)
        );
        assert_eq!(pool.clone().free_len(), 0);
    }

    #[test]
    fn reach_check_changes_no_path() {
        let mut rng = ChaCha8Rng::seed_from_u64(77);
        let (mut with_paths, mut without) = (0, 0);
        for trial in 0..300 {
            let (w, h) = (rng.random_range(1..=40), rng.random_range(1..=40));
            // Dense obstacles often cut the grid into components.
            let blocked = rng.random_range(0.0..0.55);
            let cost = random_grid(&mut rng, w, h, blocked);
            let mut never = AStar::new(w, h).with_reach_check_after(usize::MAX);
            let mut at_once = AStar::new(w, h).with_reach_check_after(1);
            let mut soon = AStar::new(w, h).with_reach_check_after(7);
            for _ in 0..4 {
                let (a, b) = (rng.random_range(0..w * h), rng.random_range(0..w * h));
                let want = never.plan(a, b, 1.0, |i| cost[i]);
                assert_eq!(at_once.plan(a, b, 1.0, |i| cost[i]), want, "trial {trial}");
                assert_eq!(soon.plan(a, b, 1.0, |i| cost[i]), want, "trial {trial}");
                match want {
                    Some(_) => with_paths += 1,
                    None => without += 1,
                }
            }
        }
        assert!(with_paths > 100 && without > 100, "{with_paths} {without}");
    }

    #[test]
    fn reach_check_stops_a_search_without_a_path_early() {
        // A 200 × 200 open grid whose goal is walled into a corner pocket.
        let (w, h) = (200, 200);
        let cost: Vec<f32> = (0..w * h)
            .map(|i| {
                let (r, c) = (i / w, i % w);
                if (r == 190 && c >= 190) || (c == 190 && r >= 190) {
                    f32::INFINITY
                } else {
                    1.0
                }
            })
            .collect();
        let mut astar = AStar::new(w, h).with_reach_check_after(1000);
        assert_eq!(astar.plan(0, w * h - 1, 1.0, |i| cost[i]), None);
        assert_eq!(astar.expansions(), 1000);
    }

    #[test]
    fn walled_off_goal_has_no_path() {
        // Column 3 fully blocked splits a 7×5 grid.
        let (w, h) = (7, 5);
        let cost: Vec<f32> = (0..w * h)
            .map(|i| if i % w == 3 { f32::INFINITY } else { 1.0 })
            .collect();
        let mut astar = AStar::new(w, h);
        assert_eq!(astar.plan(0, w * h - 1, 1.0, |i| cost[i]), None);
        assert!(astar.expansions() > 0);
    }

    #[test]
    fn no_corner_cutting() {
        // 2×2 with the anti-diagonal blocked: the diagonal move (0,0)→(1,1) is forbidden.
        let cost = [1.0, f32::INFINITY, f32::INFINITY, 1.0];
        assert_eq!(AStar::new(2, 2).plan(0, 3, 1.0, |i| cost[i]), None);
        // With one side open the path goes around it: 2 orthogonal moves, not 1 diagonal.
        let cost = [1.0, 1.0, f32::INFINITY, 1.0];
        let path = AStar::new(2, 2).plan(0, 3, 1.0, |i| cost[i]).expect("path");
        assert_eq!(path.cells, vec![0, 1, 3]);
        assert_eq!(path.cost, 2.0);
    }

    #[test]
    fn diagonal_costs_sqrt2() {
        let path = AStar::new(3, 3).plan(0, 8, 1.0, |_| 1.0).expect("path");
        assert_eq!(path.cells, vec![0, 4, 8]);
        assert_eq!(path.cost, 2.0 * std::f64::consts::SQRT_2);
    }

    #[test]
    fn start_equals_goal_and_one_cell_grid() {
        let mut astar = AStar::new(1, 1);
        let path = astar.plan(0, 0, 1.0, |_| 1.0).expect("path");
        assert_eq!(
            path,
            GridPath {
                cells: vec![0],
                cost: 0.0
            }
        );
        assert_eq!(astar.plan(0, 0, 1.0, |_| f32::INFINITY), None);
        let mut astar = AStar::new(4, 3);
        assert_eq!(
            astar.plan(5, 5, 1.0, |_| 1.5).map(|p| p.cells),
            Some(vec![5])
        );
    }

    #[test]
    fn blocked_start_or_goal_has_no_path() {
        let mut astar = AStar::new(5, 5);
        assert_eq!(
            astar.plan(0, 24, 1.0, |i| if i == 0 { f32::INFINITY } else { 1.0 }),
            None
        );
        assert_eq!(
            astar.plan(0, 24, 1.0, |i| if i == 24 { f32::NAN } else { 1.0 }),
            None
        );
        assert_eq!(astar.expansions(), 0);
    }

    #[test]
    fn single_row_and_column() {
        let mut astar = AStar::new(6, 1);
        let path = astar.plan(5, 0, 1.0, |_| 2.0).expect("path");
        assert_eq!(path.cells, vec![5, 4, 3, 2, 1, 0]);
        assert_eq!(path.cost, 10.0);
        let mut astar = AStar::new(1, 6);
        assert_eq!(
            astar.plan(0, 5, 1.0, |i| if i == 3 { f32::INFINITY } else { 1.0 }),
            None
        );
    }

    #[test]
    fn generation_wrap_resets_stamps() {
        let cost = [1.0_f32; 16];
        let mut astar = AStar::new(4, 4);
        let expected = astar.plan(0, 15, 1.0, |i| cost[i]);
        astar.generation = u32::MAX / 2 - 2;
        for _ in 0..4 {
            assert_eq!(astar.plan(0, 15, 1.0, |i| cost[i]), expected);
        }
        assert!(astar.generation < 10);
    }

    #[test]
    #[should_panic(expected = "outside")]
    fn start_outside_panics() {
        let _ = AStar::new(3, 3).plan(9, 0, 1.0, |_| 1.0);
    }
}
