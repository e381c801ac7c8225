//! What the planner returns: a [`Plan`], its [`Value`], the best bound and how it stopped.

use crate::instance::{Instance, TaskId};
use crate::value::Value;
use serde::{Deserialize, Serialize};
use std::time::Duration;

/// One scheduled task.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct PlanStep {
    /// The task.
    pub task: TaskId,
    /// Start, s after midnight.
    pub start_s: i64,
    /// End, s after midnight (start plus the task's duration, unless it ran late).
    pub end_s: i64,
}

/// A sol plan: tasks in time order.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Plan {
    /// Steps in start order.
    pub steps: Vec<PlanStep>,
}

impl Plan {
    /// `"name@start_s"` for each step, for logs and test messages.
    #[must_use]
    pub fn describe(&self, instance: &Instance) -> Vec<String> {
        self.steps
            .iter()
            .map(|s| format!("{}@{}", instance.task(s.task).name, s.start_s))
            .collect()
    }
}

/// How the search ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum PlanStatus {
    /// The search finished: the plan is optimal.
    Optimal,
    /// A budget ran out: the plan is feasible, within `best_bound` of optimal.
    Feasible,
    /// The search finished without any plan holding every mandatory activity.
    Infeasible,
    /// A budget ran out before any plan holding every mandatory activity was found.
    NoPlanFound,
}

/// Which optimistic bound prunes the search (see the crate docs for how they compare).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum BoundKind {
    /// Fractional knapsacks on time, energy and data separately (under nested deadline and
    /// release rows), plus capped utility sums; after the search's opening dive, also the
    /// time-indexed bound (the main timeline as a path over time slots).
    Knapsack,
    /// A clarabel LP relaxation over all resources, with deadline, precedence and campaign
    /// rows, certified by weak duality.
    Lp,
    /// The knapsack bound first, the LP only for nodes it fails to prune.
    Both,
}

/// Search settings. Defaults are written once, in `impl Default`.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchSettings {
    /// Most nodes to expand; with `time_budget: None` the result is a deterministic function
    /// of the input. (default: `Some(100_000)`)
    pub node_budget: Option<u64>,
    /// Wall-clock budget; when it binds the result depends on the machine. (default: `None`)
    pub time_budget: Option<Duration>,
    /// The optimistic bound. (default: [`BoundKind::Knapsack`]; on the B6 instances it proves
    /// optimality 38–71× faster than `Both` at n = 40 and 80, see the crate docs)
    pub bound: BoundKind,
    /// During the dive (see `dive_nodes`), sort the frontier by bound every this many
    /// expansions (≥ 1; depth-first in between). (default: 64)
    pub resort_every: u64,
    /// Expansions of the opening dive, which finds incumbents fast with the knapsack bounds
    /// alone; after it the search tunes the time-indexed bounds at the root, adds them to
    /// every node's bound and goes best-first, which proves faster. 0 starts best-first.
    /// (default: 64; the B6 n = 160 proofs take 241–475 nodes)
    pub dive_nodes: u64,
    /// Drop a partial plan when another reached the same done tasks no later, with no less
    /// energy and no more data. (default: true)
    pub dominance: bool,
}

impl Default for SearchSettings {
    fn default() -> Self {
        Self {
            node_budget: Some(100_000),
            time_budget: None,
            bound: BoundKind::Knapsack,
            resort_every: 64,
            dive_nodes: 64,
            dominance: true,
        }
    }
}

/// Counters of one search. The times are measurements only; nothing depends on them.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SearchStats {
    /// Nodes expanded.
    pub nodes_expanded: u64,
    /// Children generated.
    pub nodes_generated: u64,
    /// Children or frontier nodes pruned by a bound.
    pub nodes_pruned: u64,
    /// Children dropped as dominated by an earlier node with the same done tasks.
    pub nodes_dominated: u64,
    /// Knapsack bound evaluations.
    pub knapsack_evals: u64,
    /// LP solves (one per node and tier).
    pub lp_solves: u64,
    /// Time in knapsack bounds.
    pub knapsack_time: Duration,
    /// Time in LP bounds.
    pub lp_time: Duration,
    /// Total search time.
    pub total_time: Duration,
}

/// The result of a search.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanOutcome {
    /// How the search ended.
    pub status: PlanStatus,
    /// The best plan found (empty when none holds every mandatory activity), starting from
    /// the given state.
    pub plan: Plan,
    /// Its value, including tasks already done in the start state.
    pub value: Value,
    /// No plan is worth more (lexicographically); equals `value` when optimal.
    pub best_bound: Value,
    /// Counters.
    pub stats: SearchStats,
}

impl PlanOutcome {
    /// The optimality gap per tier in points (`best_bound − value`).
    #[must_use]
    pub fn gap_points(&self) -> [f64; crate::MAX_TIERS] {
        let b = self.best_bound.to_points();
        let v = self.value.to_points();
        std::array::from_fn(|i| b[i] - v[i])
    }

    /// The search proved its plan optimal.
    #[must_use]
    pub fn is_proven_optimal(&self) -> bool {
        self.status == PlanStatus::Optimal
    }
}
