//! The per-run figures and rates of a Monte Carlo sweep, by name: what `summary.json`
//! reports and what a statistical `[[expect]]` entry (`runs = N`) may check. The sweep crate
//! computes them from its run table.

/// A per-run figure of a sweep's `runs.parquet` that a study summarises and an `[[expect]]`
/// entry over a sweep may check.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// `sols_to_goal` (runs that reached the goal).
    SolsToGoal,
    /// `segment_sols`: sols to cover the study segment (runs that covered it).
    SegmentSols,
    /// `segment_distance_m`: metres driven from the study segment's first sol on.
    SegmentDistanceM,
    /// `drive_sols`.
    DriveSols,
    /// `distance_m`.
    DistanceM,
    /// `no_path_faults`.
    NoPathFaults,
    /// `faults`.
    Faults,
    /// `max_uncertainty_m`.
    MaxUncertaintyM,
    /// `onboard_localizations_applied`.
    OnboardApplied,
    /// `onboard_localizations_rejected`.
    OnboardRejected,
    /// `max_truth_error_m`.
    MaxTruthErrorM,
    /// `drive_time_s`: time spent driving, seconds.
    DriveTimeS,
    /// `drive_plan_uplinks`: uplinks whose plan commanded a drive.
    DrivePlanUplinks,
}

impl Metric {
    /// Every figure, in report order. New figures go at the end: a figure's place seeds its
    /// bootstrap (`sweep::summary::bootstrap_seed`), so reordering would change every interval.
    pub const ALL: [Metric; 13] = [
        Metric::SolsToGoal,
        Metric::SegmentSols,
        Metric::SegmentDistanceM,
        Metric::DriveSols,
        Metric::DistanceM,
        Metric::NoPathFaults,
        Metric::Faults,
        Metric::MaxUncertaintyM,
        Metric::OnboardApplied,
        Metric::OnboardRejected,
        Metric::MaxTruthErrorM,
        Metric::DriveTimeS,
        Metric::DrivePlanUplinks,
    ];

    /// The column name in `runs.parquet`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Metric::SolsToGoal => "sols_to_goal",
            Metric::SegmentSols => "segment_sols",
            Metric::SegmentDistanceM => "segment_distance_m",
            Metric::DriveSols => "drive_sols",
            Metric::DistanceM => "distance_m",
            Metric::NoPathFaults => "no_path_faults",
            Metric::Faults => "faults",
            Metric::MaxUncertaintyM => "max_uncertainty_m",
            Metric::OnboardApplied => "onboard_localizations_applied",
            Metric::OnboardRejected => "onboard_localizations_rejected",
            Metric::MaxTruthErrorM => "max_truth_error_m",
            Metric::DriveTimeS => "drive_time_s",
            Metric::DrivePlanUplinks => "drive_plan_uplinks",
        }
    }

    /// The figure named `name` (a `runs.parquet` column).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// A yes/no outcome of a run whose rate the study reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RateKind {
    /// At least one NO_PATH fault.
    NoPath,
    /// At least one fault of any kind.
    Fault,
    /// The true position outside the uncertainty disc at the end of at least one sol.
    TruthOutsideDisc,
    /// The end of the route reached within the calendar.
    GoalReached,
}

impl RateKind {
    /// Every rate, in report order.
    pub const ALL: [RateKind; 4] = [
        RateKind::NoPath,
        RateKind::Fault,
        RateKind::TruthOutsideDisc,
        RateKind::GoalReached,
    ];

    /// The name in `summary.json` and in `[[expect]]` (`no_path_rate`, …).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            RateKind::NoPath => "no_path_rate",
            RateKind::Fault => "fault_rate",
            RateKind::TruthOutsideDisc => "truth_outside_disc_rate",
            RateKind::GoalReached => "goal_reached_rate",
        }
    }

    /// The rate named `name` (`no_path_rate`, …).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|r| r.name() == name)
    }
}
