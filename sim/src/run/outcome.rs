//! What a campaign run reports: one [`SolRecord`] per sol and the [`Totals`].
//!
//! Bad outcomes are data, not errors: a `NO_PATH` is a [`Fault`] in the sol record, a rejected
//! localization is a [`LocalizationEvent`] with `applied = false` and a reason.
//!
//! Every kind, reason and step is an enum — [`FaultKind`], [`SkipReason`], [`LocalizationKind`],
//! [`RejectionReason`], [`LocalizationStep`], the plan's [`crate::operations::sol_plan::SolPlanStatus`] and
//! the run's [`Strategy`] — matched by variant; the sol log's text is each one's `Display`,
//! which is also what it serialises to.

use std::fmt;

use serde::Serialize;

use crate::operations::strategy::Strategy;

mod localization_event;

pub use localization_event::{
    ActivityStep, LocalizationEvent, LocalizationKind, LocalizationStep, PositionEllipse,
    RejectionReason,
};

/// Kind of drive-ending fault.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum FaultKind {
    /// No path to the next waypoint through the grown zones and hazards.
    #[serde(rename = "NO_PATH")]
    NoPath,
    /// The rover's estimated position lies inside a grown keep-out.
    #[serde(rename = "KEEP_OUT")]
    KeepOut,
    /// The rover's estimated position lies outside the shrunk keep-in union.
    #[serde(rename = "KEEP_IN")]
    KeepIn,
    /// The onboard slip check stopped the drive: VO measured slip above the limit
    /// ([`crate::rover::autonav::ProfileSlip::slip_limit`]).
    #[serde(rename = "SLIP")]
    Slip,
}

impl FaultKind {
    /// Every fault kind.
    pub const ALL: [FaultKind; 4] = [
        FaultKind::NoPath,
        FaultKind::KeepOut,
        FaultKind::KeepIn,
        FaultKind::Slip,
    ];

    /// The fault kind called `name` (as printed by [`FaultKind::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The flight-style name (`NO_PATH`, `KEEP_OUT`, `KEEP_IN`, `SLIP`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            FaultKind::NoPath => "NO_PATH",
            FaultKind::KeepOut => "KEEP_OUT",
            FaultKind::KeepIn => "KEEP_IN",
            FaultKind::Slip => "SLIP",
        }
    }
}

impl fmt::Display for FaultKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// A fault that ended a drive.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Fault {
    /// What happened.
    pub kind: FaultKind,
    /// Metres driven that sol before the fault.
    pub after_m: f64,
    /// Uncertainty radius at the fault, metres.
    pub uncertainty_m: f64,
    /// Estimated position at the fault, map metres.
    pub position_m: [f64; 2],
}

/// Why a sol did not drive. Displayed, and serialised as a string, as the sol log's sentence
/// (`route complete`, `extension limit: 3 sols without a localization`, …).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkipReason {
    /// The rover already reached the end of the route.
    RouteComplete,
    /// The calendar allows no drive this sol.
    NoDriveInCalendar,
    /// A fault halted driving until the ground has seen its data.
    HaltedAfterFault,
    /// No plan covers this sol yet (before the first uplink).
    NoPlanUplinked,
    /// The replay: the historic record has no drive this sol.
    NoHistoricDrive,
    /// Ground planning without the last drive's data: the ground does not know where the
    /// rover is.
    AwaitingPostDriveData,
    /// Ground planning: this sol's post-drive data would reach Earth after the next plan is
    /// made.
    DataTooLateForNextPlan,
    /// Ground planning, looking ahead: driving this sol would leave a later plan without the
    /// rover's position (its post-drive data too late), and fewer sols driven in all (paper 000
    /// §8's reason for sols 403 and 406).
    CostsLaterDrives {
        /// Drive sols over the plans looked at, if this sol drove.
        if_driven: u32,
        /// Drive sols over the same plans, if it does not.
        if_skipped: u32,
    },
    /// Extension drives stop after this many sols without a localization (the scenario's
    /// optional `max_extension_sols` cap).
    ExtensionLimit {
        /// Sols driven since the last localization (the scenario's `max_extension_sols`).
        sols_without_localization: u32,
    },
    /// The plan's commanded drive sols are used up (`max_drive_sols_per_plan`; extension
    /// plans lay breadcrumbs instead).
    PlanDriveSolsUsed {
        /// Drive sols the plan commanded.
        drive_sols: u32,
    },
    /// The planners' prediction of the uncertainty radius, from the last localization they
    /// know of, closes a passage ahead before the rover can be localized again: the plan
    /// stops short of it (paper 000 §2, "pre-emptively shortened"; for extension drives, the
    /// limit of paper 000 §8).
    PassageAhead(PassageLimit),
}

/// A passage the planners' predicted uncertainty would close: why a drive was shortened or
/// skipped (see [`crate::operations::policy`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PassageLimit {
    /// The leg's destination waypoint (the passage lies on the leg into it).
    pub to_waypoint: usize,
    /// The passage's clearance, metres: a path through it exists while r is below this.
    pub clearance_m: f64,
    /// The radius the planners predicted at the passage, metres.
    pub predicted_r_m: f64,
    /// Odometry the rover may drive from the last localization the planners know of, metres.
    pub budget_since_fix_m: f64,
}

impl fmt::Display for SkipReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match self {
            SkipReason::RouteComplete => "route complete",
            SkipReason::NoDriveInCalendar => "no drive in the calendar",
            SkipReason::HaltedAfterFault => "halted after a fault: awaiting ground review",
            SkipReason::NoPlanUplinked => "no plan uplinked yet",
            SkipReason::NoHistoricDrive => "no drive in the historic record",
            SkipReason::AwaitingPostDriveData => {
                "rover position not yet known on the ground: awaiting post-drive data"
            }
            SkipReason::DataTooLateForNextPlan => {
                "post-drive data would not reach Earth in time for the next plan"
            }
            SkipReason::ExtensionLimit {
                sols_without_localization,
            } => {
                return f.pad(&format!(
                    "extension limit: {sols_without_localization} sols without a localization"
                ));
            }
            SkipReason::CostsLaterDrives {
                if_driven,
                if_skipped,
            } => {
                return f.pad(&format!(
                    "its post-drive data would reach Earth too late for a later plan: {if_driven} drive sols over the next plans if driven, {if_skipped} if not"
                ));
            }
            SkipReason::PlanDriveSolsUsed { drive_sols } => {
                return f.pad(&format!(
                    "the plan's {drive_sols} commanded drive sols are used"
                ));
            }
            SkipReason::PassageAhead(p) => {
                return f.pad(&format!(
                    "predicted r {:.1} m would close the passage to waypoint {} (clearance {:.1} m) before a localization",
                    p.predicted_r_m, p.to_waypoint, p.clearance_m
                ));
            }
        };
        f.pad(text)
    }
}

impl Serialize for SkipReason {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// Why a sol's drive ended: what stopped the rover, or the limit it ran into. Displayed, and
/// serialised as a string, as the sol log's words (`time limit: drive window ends at 14:31
/// LMST`, `shortened for passage: …`, `fault: NO_PATH`, …); `solsim run` prints it in its
/// note column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DriveEnd {
    /// The rover reached the end of the route.
    ReachedGoal,
    /// A fault stopped the drive (the sol's [`SolRecord::fault`]).
    Fault(FaultKind),
    /// The planners shortened the drive so their predicted uncertainty would not close the
    /// passage ahead (the sol's [`SolRecord::shortened_for_passage`]).
    ShortenedForPassage(PassageLimit),
    /// A replay drove the distance the record gives for the sol.
    RecordDistance,
    /// The sol's drive window ran out.
    DriveWindow {
        /// When the window ends, seconds after local midnight.
        end: crate::time::SolSeconds,
    },
    /// The drive was cut short so the post-drive panorama makes the afternoon pass the
    /// ground's next plan needs.
    PanoramaPass {
        /// When the drive had to stop, seconds after local midnight.
        end: crate::time::SolSeconds,
        /// The pass, seconds after local midnight.
        pass: crate::time::SolSeconds,
    },
    /// The sol's activity plan cut the drive: the segments after the last one driven no longer
    /// fit the sol (science and the drive's own delays took their time) and were cancelled.
    PlanCut {
        /// Segments driven.
        driven: u32,
        /// Segments the plan had.
        planned: u32,
    },
    /// None of the above: AutoNav's per-sol step cap
    /// ([`crate::rover::autonav::MAX_STEPS_PER_SOL`]) ended the drive.
    StepLimit,
}

impl fmt::Display for DriveEnd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match self {
            DriveEnd::ReachedGoal => "reached goal".to_string(),
            DriveEnd::Fault(kind) => format!("fault: {kind}"),
            DriveEnd::ShortenedForPassage(p) => format!(
                "shortened for passage: predicted r {:.1} m would close the passage to waypoint {} (clearance {:.1} m)",
                p.predicted_r_m, p.to_waypoint, p.clearance_m
            ),
            DriveEnd::RecordDistance => "drove the record's distance".to_string(),
            DriveEnd::DriveWindow { end } => {
                format!("time limit: drive window ends at {} LMST", end.lmst())
            }
            DriveEnd::PanoramaPass { end, pass } => format!(
                "time limit: stopped at {} LMST so the panorama makes the {} LMST pass",
                end.lmst(),
                pass.lmst()
            ),
            DriveEnd::PlanCut { driven, planned } => format!(
                "sol plan cut the drive: segments after {driven} of {planned} no longer fit"
            ),
            DriveEnd::StepLimit => "AutoNav step limit".to_string(),
        };
        f.pad(&text)
    }
}

impl Serialize for DriveEnd {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// One sol of one campaign run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SolRecord {
    /// Mission sol number.
    pub sol: u32,
    /// Sol of the uplink whose plan covers this sol.
    pub plan_uplink_sol: u32,
    /// Whether the rover was commanded to drive.
    pub drove: bool,
    /// Why it was not commanded to drive (`None` when it drove).
    pub skip_reason: Option<SkipReason>,
    /// Odometry distance driven, metres.
    pub distance_m: f64,
    /// Of which with VO, metres.
    pub d_vo_m: f64,
    /// Of which without VO, metres.
    pub d_novo_m: f64,
    /// Distance by the terrain class under the true wheels, metres.
    pub terrain_m: maps::PerTerrain,
    /// Time spent driving, seconds.
    pub drive_time_s: f64,
    /// Uncertainty radius at the start of the sol's activities (after any ground localization).
    pub start_uncertainty_m: f64,
    /// Uncertainty radius at the end of the drive, before any end-of-sol localization.
    pub end_uncertainty_m: f64,
    /// The fault that ended the drive, if any.
    pub fault: Option<Fault>,
    /// Largest uncertainty at which every route leg driven this sol stays open, metres
    /// (the passage clearance: "this passage closes at r = …").
    pub passage_clearance_m: Option<f64>,
    /// Ground localization applied with this sol's uplink.
    pub ground_localization: Option<LocalizationEvent>,
    /// Onboard localization after this sol's drive.
    pub onboard_localization: Option<LocalizationEvent>,
    /// Estimated position at the end of the sol (after localization), map metres.
    pub end_position_m: [f64; 2],
    /// True position at the end of the sol, map metres.
    pub end_true_position_m: [f64; 2],
    /// Estimate-to-truth distance at the end of the drive, before localization, metres.
    pub truth_error_m: f64,
    /// Whether the uncertainty disc contained the truth at the end of the drive (before any
    /// localization); `None` on a sol without a drive, when nothing is checked (after a ground
    /// localization the disc is 0 m and the fix's own error lies outside it until the rover
    /// drives).
    pub truth_inside_disc: Option<bool>,
    /// Whether the rover reached the end of the route this sol.
    pub reached_goal: bool,
    /// Number of path plans (A* runs) this sol.
    pub plans: u32,
    /// The planners shortened this drive so their predicted uncertainty would not close the
    /// passage ahead (paper 000 §2): the limit it ran into.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shortened_for_passage: Option<PassageLimit>,
    /// Why the drive ended (`None` on a sol without a drive): the goal, a fault, the passage
    /// limit, the record's distance, the drive window, the afternoon pass or the sol plan.
    pub drive_end: Option<DriveEnd>,
    /// The sol's activity plan and timeline (drive sols only).
    pub activity_plan: Option<crate::operations::sol_plan::SolPlan>,
    /// Estimated positions along the drive, map metres (exported as GeoJSON, not in the JSON).
    #[serde(skip)]
    pub path_m: Vec<[f64; 2]>,
}

/// Totals of one campaign run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Totals {
    /// Sols simulated.
    pub sols: u32,
    /// Sols from the first sol to the one that reached the goal, inclusive (`None` if not reached).
    pub sols_to_goal: Option<u32>,
    /// Sols with a commanded drive.
    pub drive_sols: u32,
    /// Metres driven in all.
    pub distance_m: f64,
    /// `NO_PATH` faults.
    pub no_path_faults: u32,
    /// All faults.
    pub faults: u32,
    /// Largest uncertainty radius reached, metres.
    pub max_uncertainty_m: f64,
    /// Ground localizations applied.
    pub ground_localizations: u32,
    /// Onboard localizations applied.
    pub onboard_localizations_applied: u32,
    /// Onboard localizations rejected by validity checks.
    pub onboard_localizations_rejected: u32,
    /// Sols whose end-of-drive disc did not contain the truth.
    pub truth_outside_disc: u32,
    /// Whether the end of the route was reached.
    pub goal_reached: bool,
    /// Route metres left at the end of the run (distance along the remaining waypoints).
    pub route_remaining_m: f64,
    /// Science campaigns: members done and failed per campaign id (scenarios with
    /// `[science]` only).
    #[serde(skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub science: std::collections::BTreeMap<String, ScienceTally>,
}

/// One science campaign's tally over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct ScienceTally {
    /// Members done (targets observed, instances taken).
    pub done: u32,
    /// Members that ran but failed (a target out of reach when observed).
    pub failed: u32,
}

/// Route-leg clearance, computed once per scenario (independent of strategy).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LegClearance {
    /// Index of the leg's destination waypoint in the route (leg `i` runs from waypoint `i−1`).
    pub to_waypoint: usize,
    /// Largest uncertainty radius at which a path along this leg exists, metres
    /// (`None`: no path even at zero uncertainty).
    pub clearance_m: Option<f64>,
    /// Where the leg's narrowest point lies, as the distance along the route from waypoint 0 of
    /// its projection onto the leg, metres: the rover must keep its uncertainty below
    /// `clearance_m` until it is past this point (`None` with `clearance_m`).
    pub narrowest_along_route_m: Option<f64>,
    /// The narrowest point itself, map metres (`None` with `clearance_m`).
    pub narrowest_m: Option<[f64; 2]>,
}

/// One strategy's run over a scenario.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CampaignOutcome {
    /// The strategy (serialised as its name: `replay`, `ground`, `onboard`, `extension`,
    /// `extension+onboard`).
    pub strategy: Strategy,
    /// Seed of the run's random stream.
    pub seed: u64,
    /// One record per sol, in order.
    pub sols: Vec<SolRecord>,
    /// Totals.
    pub totals: Totals,
}

impl CampaignOutcome {
    /// The record of sol `sol`, if simulated.
    #[must_use]
    pub fn sol(&self, sol: u32) -> Option<&SolRecord> {
        self.sols.iter().find(|s| s.sol == sol)
    }

    /// How many sols, counted from `from_sol` inclusive, it took to drive `distance_m` metres
    /// (`None` if never reached).
    #[must_use]
    pub fn sols_to_cover(&self, from_sol: u32, distance_m: f64) -> Option<u32> {
        let mut total = 0.0;
        for s in self.sols.iter().filter(|s| s.sol >= from_sol) {
            total += s.distance_m;
            if total >= distance_m - 1e-9 {
                return Some(s.sol - from_sol + 1);
            }
        }
        None
    }

    /// Time spent driving over the run: the sols' `drive_time_s`, summed in sol order.
    ///
    /// # Units
    /// Seconds.
    #[must_use]
    pub fn drive_time_s(&self) -> f64 {
        self.sols.iter().fold(0.0, |acc, s| acc + s.drive_time_s)
    }

    /// Uplinks whose plan commanded a drive: the distinct `plan_uplink_sol`s of the sols that
    /// drove. Each is a sol on which the ground had to build a drive plan (the staffing figure
    /// of paper 000 §8); a multi-sol plan counts once.
    #[must_use]
    pub fn drive_plan_uplinks(&self) -> u32 {
        let mut uplinks: Vec<u32> = self
            .sols
            .iter()
            .filter(|s| s.drove)
            .map(|s| s.plan_uplink_sol)
            .collect();
        uplinks.sort_unstable();
        uplinks.dedup();
        uplinks.len() as u32
    }
}

impl Totals {
    /// The totals of a run's sols: `goal_sol` is the sol it reached the goal, `remaining_m`
    /// the route left from its last estimate. The science tallies start empty.
    #[must_use]
    pub(crate) fn of(records: &[SolRecord], goal_sol: Option<u32>, remaining_m: f64) -> Totals {
        let first = records.first().map_or(0, |r| r.sol);
        Totals {
            sols: records.len() as u32,
            sols_to_goal: goal_sol.map(|g| g - first + 1),
            drive_sols: records.iter().filter(|r| r.drove).count() as u32,
            distance_m: records.iter().map(|r| r.distance_m).sum(),
            no_path_faults: records
                .iter()
                .filter(|r| {
                    r.fault
                        .as_ref()
                        .is_some_and(|f| f.kind == FaultKind::NoPath)
                })
                .count() as u32,
            faults: records.iter().filter(|r| r.fault.is_some()).count() as u32,
            max_uncertainty_m: records
                .iter()
                .map(|r| r.end_uncertainty_m.max(r.start_uncertainty_m))
                .fold(0.0, f64::max),
            ground_localizations: records
                .iter()
                .filter(|r| r.ground_localization.is_some())
                .count() as u32,
            onboard_localizations_applied: records
                .iter()
                .filter(|r| r.onboard_localization.as_ref().is_some_and(|l| l.applied))
                .count() as u32,
            onboard_localizations_rejected: records
                .iter()
                .filter(|r| r.onboard_localization.as_ref().is_some_and(|l| !l.applied))
                .count() as u32,
            truth_outside_disc: records
                .iter()
                .filter(|r| r.truth_inside_disc == Some(false))
                .count() as u32,
            goal_reached: goal_sol.is_some(),
            route_remaining_m: remaining_m,
            science: std::collections::BTreeMap::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use localization::hbs::{HbsStep, LossReason};
    use localization::onboard::LostReason;

    #[test]
    fn fault_kind_names_round_trip() {
        for k in FaultKind::ALL {
            assert_eq!(FaultKind::from_name(k.name()), Some(k));
            assert_eq!(k.to_string(), k.name());
        }
        assert_eq!(FaultKind::from_name("none"), None);
    }

    #[test]
    fn outcomes_display_as_the_sol_log_text() {
        assert_eq!(LocalizationKind::Onboard.to_string(), "onboard");
        assert_eq!(
            LocalizationStep::from(HbsStep::Compare).to_string(),
            "COMPARE"
        );
        assert_eq!(
            format!("{:<12}|", LocalizationStep::GroundLocalizedHere),
            "MOB_GROUND_LOCALIZED_HERE|"
        );
        assert_eq!(format!("{:<8}|", LocalizationKind::Ground), "ground  |");
        assert_eq!(
            SkipReason::DataTooLateForNextPlan.to_string(),
            "post-drive data would not reach Earth in time for the next plan"
        );
        assert_eq!(
            SkipReason::ExtensionLimit {
                sols_without_localization: 0
            }
            .to_string(),
            "extension limit: 0 sols without a localization"
        );
        assert_eq!(
            RejectionReason::Onboard(LostReason::Hbs(LossReason::ResultsDiffer)).to_string(),
            "the two result files differ"
        );
    }
}
