//! The time-indexed bound: the main timeline as a longest path over time slots, with every
//! candidate started inside its window, one task at a time, and the constraints a path cannot
//! see (each task at most once, each precondition with its successor) priced by Lagrange
//! multipliers.
//!
//! The knapsacks of [`knapsack`](super::knapsack) see how much time the candidates due by a
//! deadline (or released after a time) need, but not *when* they can run: two tasks whose
//! windows both hold 10:00–10:30 fit a one-hour prefix together although neither can move.
//! On a day oversubscribed by short windows that is most of the gap (B6 n = 160 seed 3: the
//! knapsacks give 114 points at the root against an optimum of 99). A path over slots sees
//! it exactly; what it does not see it pays for:
//!
//! * **Slots.** Time is cut into slots of `grain_s`; a task starting at `s` starts in slot
//!   `⌊s / g⌋` and holds `⌊d / g⌋` slots. Flooring keeps every real schedule a path:
//!   `⌊s₂/g⌋ ≥ ⌊(s₁ + d₁)/g⌋ ≥ ⌊s₁/g⌋ + ⌊d₁/g⌋`, and likewise for the end of the sol. A
//!   task that holds no slot (shorter than a slot, or on the HBS link alone) is free.
//! * **At most once.** A path may run a task again later in its window. For multipliers
//!   `λ ≥ 0`, `u·x ≤ (u − λ)·x + λ·1` on every completion (each `x_j ≤ 1`), so the path is
//!   valued with `u − λ` and `Σλ` is added back.
//! * **Preconditions.** For `μ ≥ 0` on a pair (successor `i`, precondition `q`, both
//!   candidates), `u·x ≤ u·x + μ·(x_q − x_i)`: `μ` moves from `i`'s utility to `q`'s.
//!   Windows tightened by precedence ([`candidates`](super::candidates)) also hold.
//! * **Mandatory tasks** are worth a bonus larger than everything else, subtracted again
//!   per remaining mandatory task: a path that cannot hold them all ends below the node's
//!   value, which prunes it.
//!
//! Energy, data and campaign caps are left to the knapsacks; the search takes the smaller
//! bound. The multipliers are tuned once, at the first node that needs this bound, by
//! subgradient steps toward the incumbent ([`Indexed::tune`]); any multipliers give a valid
//! bound, so every later node reuses them.
//!
//! ## References
//! Paper 003 §3.1 (optimistic plan quality for branch and bound). The time-indexed relaxation
//! of one-machine scheduling and its Lagrangian dual: Sousa & Wolsey, "A time indexed
//! formulation of non-preemptive single machine scheduling problems", Math. Programming 54
//! (1992); van den Akker, Hurkens & Savelsbergh, INFORMS J. Computing 12 (2000).

use super::candidates::Candidates;
use super::knapsack::main_time_s;
use crate::instance::{Instance, TaskId};
use crate::state::Cursor;
use std::time::Instant;

/// Most slots a sol is cut into; longer sols get longer slots.
const MAX_SLOTS: i64 = 1024;
/// Shortest slot, s: finer slots cost more and tighten little (durations are minutes).
const MIN_SLOT_S: i64 = 60;
/// Subgradient steps [`Indexed::tune`] takes at most ...
const TUNE_STEPS: usize = 150;
/// ... halving its step after this many in a row without a better bound ...
const TUNE_HALVE: usize = 4;
/// ... and stopping after this many.
const TUNE_STALL: usize = 20;

/// One candidate on the path: first and last start slot, slots held, value, candidate index.
#[derive(Clone, Copy)]
struct Item {
    first: u32,
    last: u32,
    slots: u32,
    value: f64,
    j: u32,
}

/// The multipliers of one tier and the buffers of the path.
pub(super) struct Indexed {
    tier: usize,
    /// The tier before, when this bound is for completions that tie it (see
    /// [`Indexed::new`]).
    coupled_to: Option<usize>,
    /// The coupling multiplier over `unit`: the tier-before utility is valued at
    /// `coupling / unit` per micro-point.
    coupling: f64,
    unit: f64,
    grain_s: i64,
    /// Bonus of a mandatory task, micro-points.
    bonus: f64,
    /// `λ` per task (by task index).
    lambda: Vec<f64>,
    /// `(successor, precondition)` task indices and their `μ`.
    pairs: Vec<(u32, u32)>,
    mu: Vec<f64>,
    tuned: bool,
    // Buffers.
    value: Vec<f64>,
    items: Vec<Item>,
    active: Vec<u32>,
    best: Vec<f64>,
    from: Vec<u32>,
    counts: Vec<f64>,
    /// The tasks of the last counted path, in start order (the free ones last).
    seq: Vec<TaskId>,
    /// The distinct paths the tuning walked, for the search's Lagrangian heuristic.
    paths: Vec<Vec<TaskId>>,
}

/// What a bound call aims at: `target`, the micro-points a completion must add to beat the
/// incumbent (it steers the tuning; `None` without an incumbent); `need`, the tier-before
/// gain a coupled bound assumes; `deadline`, when tuning must stop.
#[derive(Clone, Copy)]
pub(super) struct Goal {
    pub(super) target: Option<f64>,
    pub(super) need: f64,
    pub(super) deadline: Option<Instant>,
}

/// What one path gives: the bound (micro-points the completion adds to tier `tier`) and a
/// margin covering the rounding of its cancelling terms.
pub(super) struct PathBound {
    pub(super) bound: f64,
    pub(super) margin: f64,
}

impl Indexed {
    /// The bound of tier `tier`. With `coupled_to: Some(j)` it bounds only the completions
    /// that gain at least `need` in tier `j` (those that tie the incumbent there, when the
    /// bound of tier `j` cannot beat it): for `L ≥ 0`, their tier-`tier` gain is at most
    /// `max (u_tier + L·u_j)·x − L·need`, a Lagrangian relaxation of that requirement.
    pub(super) fn new(inst: &Instance, tier: usize, coupled_to: Option<usize>) -> Self {
        let p = inst.problem();
        let tasks = inst.tasks();
        let span = (p.end_s - p.start_s).max(1);
        let grain_s = MIN_SLOT_S.max((span + MAX_SLOTS - 1) / MAX_SLOTS);
        let total: f64 = tasks
            .iter()
            .map(|t| t.utility_micro.max(0) as f64)
            .sum::<f64>()
            + inst
                .campaigns()
                .iter()
                .map(|c| {
                    c.utility_micro
                        .iter()
                        .map(|&u| u.max(0) as f64)
                        .sum::<f64>()
                })
                .sum::<f64>();
        let pairs: Vec<(u32, u32)> = tasks
            .iter()
            .enumerate()
            .flat_map(|(i, t)| t.preconditions.iter().map(move |q| (i as u32, q.0)))
            .collect();
        // The typical tier-before utility, so that the coupling multiplier moves in steps of
        // the same size as λ and μ.
        let unit = coupled_to.map_or(1.0, |j| {
            let (n, sum) = tasks
                .iter()
                .filter(|t| t.tier == j && t.utility_micro > 0)
                .fold((0.0, 0.0), |(n, s), t| {
                    (n + 1.0, s + t.utility_micro as f64)
                });
            if n > 0.0 { sum / n } else { 1e6 }
        });
        Self {
            tier,
            coupled_to,
            coupling: 0.0,
            unit,
            grain_s,
            bonus: 2.0 * total + 1e6,
            lambda: vec![0.0; tasks.len()],
            mu: vec![0.0; pairs.len()],
            pairs,
            tuned: false,
            value: Vec::new(),
            items: Vec::new(),
            active: Vec::new(),
            best: Vec::new(),
            from: Vec::new(),
            counts: Vec::new(),
            seq: Vec::new(),
            paths: Vec::new(),
        }
    }

    /// The paths walked while tuning (each once), emptied.
    pub(super) fn take_paths(&mut self) -> Vec<Vec<TaskId>> {
        std::mem::take(&mut self.paths)
    }

    /// The tier this bound is for.
    pub(super) fn tier(&self) -> usize {
        self.tier
    }

    /// The tier before, for a coupled bound.
    pub(super) fn coupled_to(&self) -> Option<usize> {
        self.coupled_to
    }

    /// The bound at `cur`, tuning the multipliers first if this is the first call.
    pub(super) fn bound(
        &mut self,
        inst: &Instance,
        cur: &Cursor,
        cand: &Candidates,
        goal: Goal,
    ) -> PathBound {
        if !self.tuned {
            self.tuned = true;
            self.tune(inst, cur, cand, goal);
        }
        self.path(inst, cur, cand, goal.need, false)
    }

    /// Subgradient steps from `λ = μ = 0` at `cur`, keeping the multipliers of the best bound
    /// (Polyak steps toward `target`, halved when the bound stalls).
    fn tune(&mut self, inst: &Instance, cur: &Cursor, cand: &Candidates, goal: Goal) {
        let Goal {
            target,
            need,
            deadline,
        } = goal;
        let mut best = f64::INFINITY;
        let (mut best_lambda, mut best_mu) = (self.lambda.clone(), self.mu.clone());
        let mut best_coupling = self.coupling;
        let mut theta = 1.0;
        let mut stall = 0usize;
        let mut grad_l = vec![0.0; self.lambda.len()];
        let mut grad_m = vec![0.0; self.mu.len()];
        for _ in 0..TUNE_STEPS {
            if deadline.is_some_and(|d| Instant::now() >= d) {
                break;
            }
            let b = self.path(inst, cur, cand, need, true).bound;
            if !self.paths.contains(&self.seq) {
                self.paths.push(self.seq.clone());
            }
            if b < best - 1e-6 * b.abs().max(1.0) {
                best = b;
                best_lambda.clone_from(&self.lambda);
                best_mu.clone_from(&self.mu);
                best_coupling = self.coupling;
                stall = 0;
            } else {
                stall += 1;
                if stall.is_multiple_of(TUNE_HALVE) {
                    theta *= 0.5;
                }
                if stall >= TUNE_STALL {
                    break;
                }
            }
            let goal = target.unwrap_or(0.9 * b).min(b);
            // Subgradients of the dual at these multipliers: a task run twice raises its λ,
            // one never run lowers it (to 0); a successor run without its precondition
            // raises μ.
            let mut norm = 0.0;
            for &j in &cand.ids {
                let t = j.index();
                let c = self.counts[t];
                let d = if self.lambda[t] <= 0.0 && c < 1.0 {
                    0.0
                } else {
                    c - 1.0
                };
                grad_l[t] = d;
                norm += d * d;
            }
            for (e, &(i, q)) in self.pairs.iter().enumerate() {
                let d = self.counts[i as usize] - self.counts[q as usize];
                let d = if self.mu[e] <= 0.0 && d < 0.0 { 0.0 } else { d };
                grad_m[e] = d;
                norm += d * d;
            }
            // A path short of `need` in the tier before raises the coupling.
            let mut grad_c = 0.0;
            if let Some(j) = self.coupled_to {
                let got: f64 = cand
                    .ids
                    .iter()
                    .enumerate()
                    .map(|(i, t)| cand.utility[j][i] * self.counts[t.index()])
                    .sum();
                grad_c = (need - got) / self.unit;
                if self.coupling <= 0.0 && grad_c < 0.0 {
                    grad_c = 0.0;
                }
                norm += grad_c * grad_c;
            }
            if norm == 0.0 {
                break;
            }
            let step = theta * (b - goal).max(1e-3 * b.abs().max(1.0)) / norm;
            for &j in &cand.ids {
                let t = j.index();
                self.lambda[t] = (self.lambda[t] + step * grad_l[t]).max(0.0);
            }
            for (m, g) in self.mu.iter_mut().zip(&grad_m) {
                *m = (*m + step * g).max(0.0);
            }
            self.coupling = (self.coupling + step * grad_c).max(0.0);
        }
        self.lambda = best_lambda;
        self.mu = best_mu;
        self.coupling = best_coupling;
    }

    /// The longest path at `cur` with the current multipliers; with `count`, also how many
    /// times the path runs each task (in `self.counts`, by task index, candidates only).
    fn path(
        &mut self,
        inst: &Instance,
        cur: &Cursor,
        cand: &Candidates,
        need: f64,
        count: bool,
    ) -> PathBound {
        let p = inst.problem();
        let tasks = inst.tasks();
        let g = self.grain_s;
        let k = self.tier;
        let base = cur.time_s.div_euclid(g);
        let horizon = (p.end_s.div_euclid(g) - base).max(0) as usize;
        let coupled = self.coupled_to.map(|j| (j, self.coupling / self.unit));
        let Self {
            bonus,
            lambda,
            pairs,
            mu,
            value,
            items,
            active,
            best,
            from,
            counts,
            seq,
            ..
        } = self;
        // Values: utility (or the bonus), less λ, with μ moved along precedences.
        value.clear();
        value.extend(cand.ids.iter().enumerate().map(|(j, &t)| {
            let x = &tasks[t.index()];
            let mut u = if x.mandatory { *bonus } else { 0.0 } + cand.utility[k][j];
            if let Some((before, l)) = coupled {
                u += l * cand.utility[before][j];
            }
            u - lambda[t.index()]
        }));
        let mut lambda_sum = 0.0;
        let mut mandatory = 0.0;
        for &t in &cand.ids {
            lambda_sum += lambda[t.index()];
            if tasks[t.index()].mandatory {
                mandatory += 1.0;
            }
        }
        let mut moved = 0.0;
        for (&(i, q), &m) in pairs.iter().zip(mu.iter()) {
            let (pi, pq) = (cand.pos[i as usize], cand.pos[q as usize]);
            if m > 0.0 && pi != u32::MAX && pq != u32::MAX {
                value[pi as usize] -= m;
                value[pq as usize] += m;
                moved += m;
            }
        }
        // Tasks holding no slot are free: taken when worth it.
        let mut free = 0.0;
        items.clear();
        if count {
            counts.clear();
            counts.resize(tasks.len(), 0.0);
            seq.clear();
        }
        for (j, &t) in cand.ids.iter().enumerate() {
            let x = &tasks[t.index()];
            let v = value[j];
            let slots = main_time_s(x).div_euclid(g);
            if slots == 0 {
                if v > 0.0 {
                    free += v;
                    if count {
                        counts[t.index()] = 1.0;
                        seq.push(t);
                    }
                }
                continue;
            }
            if v <= 0.0 {
                continue;
            }
            let first = (cand.release_s[j].div_euclid(g) - base).max(0);
            let last = x.latest_start_s.div_euclid(g) - base;
            if last < first || first + slots > horizon as i64 {
                continue;
            }
            items.push(Item {
                first: first as u32,
                last: last.min(horizon as i64) as u32,
                slots: slots as u32,
                value: v,
                j: j as u32,
            });
        }
        items.sort_unstable_by_key(|it| (it.first, it.j));
        // best[s]: the most value of a path whose tasks all end by slot s; from[s] the item
        // ending at s on that path (u32::MAX: idle slot).
        best.clear();
        best.resize(horizon + 1, f64::NEG_INFINITY);
        from.clear();
        from.resize(horizon + 1, u32::MAX);
        best[0] = 0.0;
        active.clear();
        let mut next = 0;
        for s in 0..=horizon {
            if s > 0 && best[s - 1] > best[s] {
                best[s] = best[s - 1];
                from[s] = u32::MAX;
            }
            while next < items.len() && items[next].first as usize <= s {
                active.push(next as u32);
                next += 1;
            }
            let here = best[s];
            let mut a = 0;
            while a < active.len() {
                let it = items[active[a] as usize];
                if (it.last as usize) < s {
                    active.swap_remove(a);
                    continue;
                }
                let e = s + it.slots as usize;
                if e <= horizon && here + it.value > best[e] {
                    best[e] = here + it.value;
                    from[e] = active[a];
                }
                a += 1;
            }
        }
        if count {
            let free_tasks = seq.len();
            let mut s = horizon;
            while s > 0 {
                match from[s] {
                    u32::MAX => s -= 1,
                    i => {
                        let it = items[i as usize];
                        let t = cand.ids[it.j as usize];
                        counts[t.index()] += 1.0;
                        seq.push(t);
                        s -= it.slots as usize;
                    }
                }
            }
            // Walked backward, after the free tasks: start order, the free ones last.
            seq[free_tasks..].reverse();
            seq.rotate_left(free_tasks);
        }
        let paid = coupled.map_or(0.0, |(_, l)| l * need);
        let bound = best[horizon] + free + lambda_sum - *bonus * mandatory - paid;
        // The bonus, λ, μ and the coupling cancel: keep a margin of their size.
        let margin = 1e-9 * (*bonus * mandatory + lambda_sum + moved + paid + best[horizon].abs());
        PathBound { bound, margin }
    }
}
