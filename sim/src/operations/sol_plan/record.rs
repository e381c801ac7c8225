//! What the sol log keeps of a sol's plan: the executed timeline, the repairs and replans, and
//! any violation the validator found.

use planner::{PlanStatus, Timeline};

use crate::time::SolSeconds;

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
    pub start_s: SolSeconds,
    /// End, seconds after local midnight.
    pub end_s: SolSeconds,
    /// The planner timeline it held: `hbs_link` for the co-processor chain's transfer, runs and
    /// reboot, which overlap main-timeline rows (left out of the JSON for `main`).
    #[serde(skip_serializing_if = "Timeline::is_main")]
    pub timeline: Timeline,
    /// Battery energy when it ended, Wh (counting every activity that overlapped it).
    pub energy_wh_after: f64,
    /// Stored data after it, MB.
    pub data_mb_after: f64,
    /// What it achieved, when the simulator judged it (a science observation done or out
    /// of reach, a drive stopped by a fault).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outcome: Option<String>,
}

/// How the sol's plan came about: the planner's search status ([`PlanStatus`]), or no plan at
/// all. Serialised and displayed as `optimal`, `feasible`, `infeasible`, `no plan found` or
/// `not planned`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
pub enum SolPlanStatus {
    /// The search finished: the plan is optimal.
    #[serde(rename = "optimal")]
    Optimal,
    /// The node budget ran out: the plan is feasible.
    #[serde(rename = "feasible")]
    Feasible,
    /// No plan holds every mandatory activity.
    #[serde(rename = "infeasible")]
    Infeasible,
    /// The budget ran out before any plan holding every mandatory activity was found.
    #[serde(rename = "no plan found")]
    NoPlanFound,
    /// The planner refused the sol's problem (its error is the plan's violation); the sol
    /// drove its window as commanded.
    #[default]
    #[serde(rename = "not planned")]
    NotPlanned,
}

impl SolPlanStatus {
    /// The sol log's name (`optimal`, `feasible`, `infeasible`, `no plan found`,
    /// `not planned`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            SolPlanStatus::Optimal => "optimal",
            SolPlanStatus::Feasible => "feasible",
            SolPlanStatus::Infeasible => "infeasible",
            SolPlanStatus::NoPlanFound => "no plan found",
            SolPlanStatus::NotPlanned => "not planned",
        }
    }
}

impl From<PlanStatus> for SolPlanStatus {
    fn from(s: PlanStatus) -> Self {
        match s {
            PlanStatus::Optimal => SolPlanStatus::Optimal,
            PlanStatus::Feasible => SolPlanStatus::Feasible,
            PlanStatus::Infeasible => SolPlanStatus::Infeasible,
            PlanStatus::NoPlanFound => SolPlanStatus::NoPlanFound,
        }
    }
}

impl std::fmt::Display for SolPlanStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// The sol's plan as executed, with its repairs and replans.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct SolPlan {
    /// Search result: `optimal`, `feasible` (budget hit), `infeasible`, `no plan found`, or
    /// `not planned` (the planner refused the problem).
    pub status: SolPlanStatus,
    /// The timeline as executed: actual start and end of every activity, in start order
    /// (rows on the HBS link overlap main-timeline rows).
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
            status: SolPlanStatus::NotPlanned,
            timeline: Vec::new(),
            changes: Vec::new(),
            violations: vec![format!("planner: {e}")],
        }
    }
}
