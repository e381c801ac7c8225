//! Optimistic bounds: no plan extending a partial plan is worth more than these.
//!
//! Both bounds start from the *candidates*: tasks not yet done that some completion could
//! still run. A task is out when it cannot start by its latest start even at its earliest
//! start tightened by precedence (each precondition's earliest end), when a precondition is
//! out, when the battery or the data store can never carry it, or when its state-based window
//! lies beyond the metres the remaining drives can cover; ruling one task out can rule out
//! others (its successors, the survey instances its drive was to reach), so the rules repeat
//! to a fixed point at every node ([`candidates`](mod@candidates)). A remaining mandatory task
//! that is not a candidate kills the node. Campaign members are valued at the campaign's
//! [`optimistic_slope`](crate::CampaignCurve::optimistic_slope), which makes every
//! per-member sum an over-estimate of the campaign's real (possibly non-concave) gain.
//!
//! * [`BoundKind::Knapsack`]: per tier, the minimum of a capped utility sum and four
//!   fractional knapsacks, each keeping one resource and dropping the others: time under
//!   nested deadline rows, time under nested release rows, energy under the deadline rows,
//!   and net data. Nested rows form a chain, so a greedy fill by density solves each exactly
//!   ([`chain_fill`](chain::chain_fill)); the density orders and rows are precomputed per
//!   instance ([`Layout`]). Mandatory tasks are forced in and their use reserved first.
//!   Precedences between two optional candidates enter every knapsack as Lagrange
//!   multipliers: part of a task's utility moves to its precondition, so a task is not valued
//!   without paying for the precondition it needs. Three refinements use the incumbent: a tier
//!   whose bound ties it is coupled to the next tier by a Lagrangian multiplier (a better
//!   completion must also keep the tied tier's tasks), a node the fractional knapsacks leave
//!   undecided by less than one task's value gets the 0/1 time knapsacks, solved exactly by a
//!   dynamic program over the chain ([`chain_dp`](chain::chain_dp)), and evaluation stops once
//!   the comparison is decided.
//!
//!   Once the search's opening dive is over
//!   ([`SearchSettings::dive_nodes`](crate::SearchSettings::dive_nodes)), the knapsack bound
//!   of a node it does not prune is also cut by the *time-indexed* bound ([`indexed`]): the
//!   main timeline as a longest path over time slots, each candidate started inside its
//!   window, one at a time, with each task at most once and each precondition priced by
//!   Lagrange multipliers tuned at the root. It sees what the knapsacks cannot, two tasks
//!   whose windows collide (B6 n = 160 seed 3: root tier-1 bound 114 → 102, optimum 99;
//!   `examples/b6_solve.rs` prints it). A tier after the first is bounded, when the tiers
//!   before tie the incumbent, for the completions that keep them tied (the same Lagrangian
//!   coupling). [`optimistic_bound`] includes each tier's time-indexed bound, uncoupled.
//!
//! Every tier bound is rounded down to the tier's *grain*, the gcd of all its utilities
//! ([`grains`]): with whole-point utilities a fractional bound of 40.7 points becomes 40.
//! * [`BoundKind::Lp`]: per tier, a linear relaxation solved with clarabel: `x ∈ [0, 1]` per
//!   optional candidate, mandatory ones fixed at 1, and rows for time and energy before every
//!   candidate deadline, time after every candidate's release (its earliest start), net
//!   data, campaign caps and precedences (`x_i ≤ x_j`). An interior-point optimum is only approximate, so the bound is not the
//!   solver's objective but a weak-duality certificate built from its multipliers `z ≥ 0`:
//!   `u·x ≤ z·b + Σ_i max(0, u_i − (Aᵀz)_i)` for every `x ∈ [0, 1]ⁿ` with `Ax ≤ b`. It holds
//!   for any `z ≥ 0`, so a failed or inaccurate solve can only loosen the bound, never make
//!   it wrong.
//!
//! ## Where each part lives
//! - [`candidates`](mod@candidates): the candidates of a node and their optimistic utilities;
//! - [`chain`]: knapsacks over nested capacity rows (the fractional fill and the 0/1 dynamic
//!   program);
//! - [`knapsack`]: the knapsack bound and what it precomputes per instance;
//! - [`indexed`]: the time-indexed bound, its multipliers and their tuning;
//! - [`lp`]: the LP relaxation and its weak-duality certificate;
//! - [`grain`]: the utility grain of each tier and rounding to it;
//! - here: [`Bounder`], which the search calls, and [`optimistic_bound`].
//!
//! ## References
//! Paper 003 §3.1: "the optimistic maximum quality of any plan based on the candidate partial
//! plan must exceed the pessimistic minimum quality prediction of all other candidates".

mod candidates;
mod chain;
mod grain;
mod indexed;
mod knapsack;
mod lp;

use crate::instance::{Instance, TaskId};
use crate::plan::{BoundKind, SearchStats};
use crate::state::Cursor;
use crate::value::{MAX_TIERS, Value};
use candidates::{Candidates, candidates, topological};
use grain::{grains, to_value};
use indexed::{Goal, Indexed};
use knapsack::{Layout, Scratch, knapsack_bound};
use lp::{lp_bound_tier, lp_rows};
use std::cell::{Cell, RefCell};
use std::time::Instant;

/// Evaluates bounds for the search, lazily tier by tier, and counts the work.
pub(crate) struct Bounder<'a> {
    inst: &'a Instance,
    kind: BoundKind,
    tier_used: [bool; MAX_TIERS],
    grain: [i64; MAX_TIERS],
    layout: Layout,
    scratch: RefCell<Scratch>,
    cand: RefCell<Candidates>,
    topo: Vec<u32>,
    /// The time-indexed bound of each tier with utility, each after the first coupled to
    /// the one before.
    indexed: Vec<RefCell<Indexed>>,
    /// Whether the search has switched the time-indexed bounds on ([`Bounder::start_indexed`]).
    indexed_on: Cell<bool>,
    /// When tuning multipliers must stop (the search's time budget).
    deadline: Cell<Option<Instant>>,
}

impl<'a> Bounder<'a> {
    pub(crate) fn new(inst: &'a Instance, kind: BoundKind) -> Self {
        let mut tier_used = [false; MAX_TIERS];
        for t in inst.tasks() {
            if t.utility_micro > 0 {
                tier_used[t.tier] = true;
            }
        }
        for c in inst.campaigns() {
            if c.utility_micro.iter().any(|&u| u > 0) {
                tier_used[c.tier] = true;
            }
        }
        Self {
            inst,
            kind,
            tier_used,
            grain: grains(inst),
            layout: Layout::new(inst),
            scratch: RefCell::default(),
            cand: RefCell::default(),
            topo: topological(inst),
            indexed: {
                let used: Vec<usize> = (0..MAX_TIERS).filter(|&k| tier_used[k]).collect();
                used.iter()
                    .enumerate()
                    .map(|(i, &k)| {
                        RefCell::new(Indexed::new(inst, k, i.checked_sub(1).map(|b| used[b])))
                    })
                    .collect()
            },
            indexed_on: Cell::new(false),
            deadline: Cell::new(None),
        }
    }

    /// Switches the time-indexed bounds on: tunes the first tier's multipliers at `root`
    /// toward `incumbent` (stopping at `deadline`); the coupled tiers tune at the first node
    /// that ties the tier before. Their paths are then in [`Bounder::take_paths`].
    pub(crate) fn start_indexed(
        &self,
        root: &Cursor,
        incumbent: Option<Value>,
        deadline: Option<Instant>,
    ) {
        if self.kind == BoundKind::Lp {
            return;
        }
        self.indexed_on.set(true);
        self.deadline.set(deadline);
        let Some(first) = self.indexed.first() else {
            return;
        };
        let mut cand = self.cand.borrow_mut();
        if !candidates(self.inst, &self.topo, root, &mut cand) {
            return;
        }
        let mut ix = first.borrow_mut();
        let k = ix.tier();
        let target = incumbent.map(|v| (v.tiers_micro[k] - root.value.tiers_micro[k]) as f64);
        let goal = Goal {
            target,
            need: 0.0,
            deadline,
        };
        ix.bound(self.inst, root, &cand, goal);
    }

    /// An optimistic value of any plan extending `cur`, or `None` when no completion that
    /// beats `incumbent` exists (or no completion holds every mandatory task). With an
    /// incumbent, tiers are refined by the LP only until the comparison is decided.
    pub(crate) fn evaluate(
        &self,
        cur: &Cursor,
        incumbent: Option<Value>,
        stats: &mut SearchStats,
    ) -> Option<Value> {
        let inst = self.inst;
        let clock = Instant::now();
        let mut cand = self.cand.borrow_mut();
        if !candidates(inst, &self.topo, cur, &mut cand) {
            return None;
        }
        let cand = &*cand;
        let mut ub = cand.sum;
        if matches!(self.kind, BoundKind::Knapsack | BoundKind::Both) {
            stats.knapsack_evals += 1;
            let need = incumbent
                .map(|inc| std::array::from_fn(|k| inc.tiers_micro[k] - cur.value.tiers_micro[k]));
            let k = knapsack_bound(
                inst,
                &self.layout,
                cur,
                cand,
                need,
                &self.grain,
                &mut self.scratch.borrow_mut(),
            );
            stats.knapsack_time += clock.elapsed();
            ub = k?;
        }
        let mut bound = to_value(cur.value, &ub, &self.grain);
        if let Some(inc) = incumbent
            && bound <= inc
        {
            return None;
        }
        if let Some(inc) = incumbent
            && self.indexed_on.get()
            && matches!(self.kind, BoundKind::Knapsack | BoundKind::Both)
        {
            for ix in &self.indexed {
                let mut ix = ix.borrow_mut();
                let k = ix.tier();
                // Only while the tiers before tie the incumbent (a coupled bound is about the
                // completions that tie them; a plain one decides nothing otherwise).
                if bound.tiers_micro[..k] != inc.tiers_micro[..k] {
                    break;
                }
                let gain = |t: usize| (inc.tiers_micro[t] - cur.value.tiers_micro[t]) as f64;
                let need = ix.coupled_to().map_or(0.0, gain);
                let clock = Instant::now();
                let goal = Goal {
                    target: Some(gain(k)),
                    need,
                    deadline: self.deadline.get(),
                };
                let pb = ix.bound(inst, cur, cand, goal);
                stats.knapsack_time += clock.elapsed();
                ub[k] = ub[k].min(pb.bound + pb.margin);
                bound = to_value(cur.value, &ub, &self.grain);
                if bound <= inc {
                    return None;
                }
            }
        }
        if !matches!(self.kind, BoundKind::Lp | BoundKind::Both) {
            return Some(bound);
        }
        let clock = Instant::now();
        let rows = lp_rows(inst, cur, cand);
        let Some(rows) = rows else {
            stats.lp_time += clock.elapsed();
            return None;
        };
        for k in 0..MAX_TIERS {
            if self.tier_used[k] && ub[k] > 0.0 {
                stats.lp_solves += 1;
                let lp = lp_bound_tier(&rows, cand, k);
                ub[k] = ub[k].min(lp);
                bound = to_value(cur.value, &ub, &self.grain);
            }
            match incumbent {
                // Without an incumbent nothing can be pruned; tier 1 orders the frontier.
                None => break,
                Some(inc) => match bound.tiers_micro[k].cmp(&inc.tiers_micro[k]) {
                    std::cmp::Ordering::Less => {
                        stats.lp_time += clock.elapsed();
                        return None;
                    }
                    std::cmp::Ordering::Greater => break,
                    std::cmp::Ordering::Equal => {}
                },
            }
        }
        stats.lp_time += clock.elapsed();
        if incumbent.is_some_and(|inc| bound <= inc) {
            return None;
        }
        Some(bound)
    }
}

impl Bounder<'_> {
    /// The paths the time-indexed bounds walked while tuning their multipliers, each a task
    /// order worth trying as a plan (a Lagrangian heuristic); emptied.
    pub(crate) fn take_paths(&self) -> Vec<Vec<TaskId>> {
        let mut out = Vec::new();
        for ix in &self.indexed {
            for p in ix.borrow_mut().take_paths() {
                if !out.contains(&p) {
                    out.push(p);
                }
            }
        }
        out
    }
}

/// An optimistic value of every plan that extends `state` (all tiers fully evaluated), or
/// `None` when the bound proves that no extension holds every mandatory activity.
///
/// This is the bound the search prunes with; it is public so it can be tested and compared.
///
/// # Errors
/// [`PlanError::InvalidState`](crate::PlanError::InvalidState) for a malformed `state`.
pub fn optimistic_bound(
    instance: &Instance,
    state: &crate::State,
    kind: BoundKind,
) -> Result<Option<Value>, crate::PlanError> {
    let cur = Cursor::new(instance, state)?;
    let mut cand = Candidates::default();
    if !candidates(instance, &topological(instance), &cur, &mut cand) {
        return Ok(None);
    }
    let mut ub = cand.sum;
    if matches!(kind, BoundKind::Knapsack | BoundKind::Both) {
        match knapsack_bound(
            instance,
            &Layout::new(instance),
            &cur,
            &cand,
            None,
            &grains(instance),
            &mut Scratch::default(),
        ) {
            Some(k) => ub = k,
            None => return Ok(None),
        }
    }
    if matches!(kind, BoundKind::Knapsack | BoundKind::Both) {
        // Each tier's time-indexed bound on its own (coupling needs an incumbent).
        for (k, u) in ub.iter_mut().enumerate() {
            if *u > 0.0 {
                let mut ix = Indexed::new(instance, k, None);
                let goal = Goal {
                    target: None,
                    need: 0.0,
                    deadline: None,
                };
                let pb = ix.bound(instance, &cur, &cand, goal);
                *u = u.min(pb.bound + pb.margin);
            }
        }
    }
    if matches!(kind, BoundKind::Lp | BoundKind::Both) {
        let Some(rows) = lp_rows(instance, &cur, &cand) else {
            return Ok(None);
        };
        for (k, u) in ub.iter_mut().enumerate() {
            if *u > 0.0 {
                *u = u.min(lp_bound_tier(&rows, &cand, k));
            }
        }
    }
    Ok(Some(to_value(cur.value, &ub, &grains(instance))))
}
