//! What the sol log keeps of a sol's plan: the executed timeline, the repairs and replans, and
//! any violation the validator found.

use planner::PlanStatus;

/// One activity of the sol timeline, for the sol log.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TimelineStep {
    /// Activity (drive segments as `drive#j/k`).
    pub activity: String,
    /// Start, LMST `HH:MM`.
    pub start_lmst: String,
    /// End, LMST `HH:MM`.
    pub end_lmst: String,
    /// Start, seconds after local midnight.
    pub start_s: i64,
    /// End, seconds after local midnight.
    pub end_s: i64,
    /// Battery energy after it, Wh.
    pub energy_wh_after: f64,
    /// Stored data after it, MB.
    pub data_mb_after: f64,
    /// What it achieved, when the simulator judged it (a science observation done or out
    /// of reach, a drive stopped by a fault).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outcome: Option<String>,
}

/// The sol's plan as executed, with its repairs and replans.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct SolPlan {
    /// Search result: `optimal`, `feasible` (budget hit), `infeasible` or `no plan found`.
    pub status: &'static str,
    /// The timeline as executed: actual start and end of every activity.
    pub timeline: Vec<TimelineStep>,
    /// Every repair and replan, in order (`HH:MM: drive#1/1 ended at … : 3 later activities
    /// shifted`, `HH:MM: NO_PATH after 14.0 m (cancelled …): replanned`); empty if the sol
    /// ran as planned.
    pub changes: Vec<String>,
    /// Violations the independent validator found in any plan the sol used (must be empty).
    pub violations: Vec<String>,
}

impl SolPlan {
    /// The log entry of a sol the planner could not plan (its error is the violation).
    #[must_use]
    pub fn not_planned(e: &planner::PlanError) -> Self {
        Self {
            status: "not planned",
            timeline: Vec::new(),
            changes: Vec::new(),
            violations: vec![format!("planner: {e}")],
        }
    }
}

/// The sol log's name of a search status.
pub(super) fn status_name(s: PlanStatus) -> &'static str {
    match s {
        PlanStatus::Optimal => "optimal",
        PlanStatus::Feasible => "feasible",
        PlanStatus::Infeasible => "infeasible",
        PlanStatus::NoPlanFound => "no plan found",
    }
}
