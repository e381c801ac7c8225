//! Each drive sol's activity plan, laid out by the [`planner`] crate (paper 003 §3) and
//! checked by its independent validator.
//!
//! A drive sol holds, in this order (the planner places them; preconditions fix the order):
//!
//! | activity | when | why |
//! |---|---|---|
//! | `heating` | ends when the drive window opens | actuators warmed before driving (auxiliary) |
//! | `drive` | the drive window the strategy allows | AutoNav toward the next waypoints |
//! | `post_drive_imaging` | after the drive | the NavCam panorama (for the ground, and for onboard localization) |
//! | `comm_pass` | fixed at the sol's `downlink_lmst`, if after the drive | relays the sol's data; when the ground needs the panorama for its next plan the imaging must end before it |
//! | `sunfind` … `compare_apply` | after the imaging, onboard strategies only | the onboard localization chain of paper 000 Fig. 18-19: SunFind, transfer to the co-processor (~30 min at 10 KB/s), run, reboot, run, compare and apply; the transfer, runs and reboot on the HBS link timeline, in parallel with the main timeline |
//! | targets, `{periodic}-k`, `{state_based}-k` | where the planner fits them (scenarios with `[science]`) | goal-set observations in reach, periodic instances, state-based instances between drive segments |
//!
//! With a scenario's science campaigns ([`crate::operations::science`]) the sol also offers targets in
//! reach, periodic instances and state-based instances; the drive is split at the
//! state-based distances so a survey can run between segments (paper 003 Fig. 3).
//!
//! The simulator then **executes** the plan step by step ([`SolExecution`]): drive segments
//! through AutoNav, the localization chain through the co-processor model, observations
//! against the rover's true position. Each step's actual end comes back: a small slip is
//! **repaired** ([`planner::repair`]: later activities shift within their windows); a big
//! disruption — a fault ends the drive, the localization is lost, a new goal is revealed —
//! cancels what can no longer run and **replans** from the current state
//! ([`planner::plan_from`]). Every plan goes through [`planner::validate_plan`], which checks
//! windows, order, battery and data volume on its own re-simulation; the sol log carries the
//! executed timeline, every change and any violation.
//!
//! Passes that overlap the drive are left out: the rover relays while it drives, and the
//! planner schedules one activity at a time on the main timeline.
//!
//! ## The co-processor chain as flown
//! The chain's `hbs_transfer`, `hbs_run_1`, `hbs_reboot` and `hbs_run_2` hold the planner's
//! second timeline, the HBS link ([`planner::Timeline::HbsLink`]): while the ~30 minute
//! transfer runs (the flight-size inputs at the scenario's `hbs_link_rate_kb_per_s`,
//! [`localization::onboard::FLIGHT_SIZE_LINK_BYTES`]), the main timeline runs the pass, science
//! or anything else that fits; the runs wait for the transfer, `compare_apply` (main timeline)
//! for the second run, and no two link activities overlap. The validator checks all three.
//! The sol log's timeline shows each row's `timeline` when it is not the main one, in start
//! order, so link rows overlap main rows; each row's `energy_wh_after` counts every
//! activity that overlapped it.
//!
//! Power figures are judgement for a Perseverance-class rover (an MMRTG of ~110 W and two
//! Li-ion batteries of ~1.2 kWh each); every one is a field of [`SolPlanSettings`].
//!
//! The module is split by role: [`SolPlanSettings`] (the settings, in `settings`), the planning
//! problem of a drive sol ([`sol_problem`] from a [`SolPlanRequest`], in `problem`), its
//! execution ([`SolExecution`], in `execution`) and what the sol log keeps of it ([`SolPlan`],
//! in `record`).

mod execution;
mod problem;
mod record;
mod settings;

pub use execution::{Disruption, SolExecution, Step};
pub(crate) use problem::note_sol_problem;
pub use problem::{
    ChainDurations, LOCALIZATION_CHAIN, SOL_ACTIVITIES, SolPlanRequest, capture_sol_problems,
    planned_drive_m, planning_window, sol_problem,
};
pub use record::{SolPlan, SolPlanStatus, TimelineStep};
pub use settings::SolPlanSettings;
