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
//! | `comm_pass` | fixed at the sol's `downlink_lmst`, if after the drive | sends the panorama down |
//! | `sunfind` … `compare_apply` | after the imaging, onboard strategies only | the onboard localization chain of paper 000 Fig. 18-19: SunFind, transfer to the co-processor, run, reboot, run, compare and apply |
//!
//! The simulator then drives; when the drive ends (early at the goal or a fault, or exactly
//! at the end of its window) the plan is **repaired** ([`planner::repair`]: later activities
//! shift within their windows) or, if that fails, **replanned** from the state after the drive
//! ([`planner::plan_from`]). Both plans go through [`planner::validate_plan`], which checks
//! windows, order, battery and data volume on its own re-simulation; the sol log carries the
//! timeline and any violation.
//!
//! Passes that overlap the drive are left out: the rover relays while it drives, and the
//! planner schedules one activity at a time.
//!
//! Power figures are judgement for a Perseverance-class rover (an MMRTG of ~110 W and two
//! Li-ion batteries of ~1.2 kWh each); every one is a field of [`SolPlanParams`].

use planner::{
    Activity, ActivityKind, Drive, Instance, Plan, PlanStatus, Problem, RepairOutcome,
    SearchSettings, State, plan, plan_from, repair, validate_plan,
};

use crate::time::SolSeconds;

/// The onboard localization chain's activities, in order (paper 000 Fig. 18-19).
pub const LOCALIZATION_CHAIN: [&str; 6] = [
    "sunfind",
    "hbs_transfer",
    "hbs_run_1",
    "hbs_reboot",
    "hbs_run_2",
    "compare_apply",
];

/// Settings of the per-sol plan (plain struct; units and defaults on each field).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SolPlanParams {
    /// Battery capacity, Wh (default: 2,400 — two ~43 Ah Li-ion batteries at ~28 V).
    pub battery_capacity_wh: f64,
    /// Battery charge when the sol's plan starts, fraction of capacity (default: 0.8).
    pub initial_charge: f64,
    /// Net recharge while idle: MMRTG output minus the idle load, W (default: 40; judgement).
    pub recharge_w: f64,
    /// Power above idle while driving, W (default: 180; judgement).
    pub drive_power_w: f64,
    /// Heating before the drive, s (default: 1,800; judgement).
    pub heating_s: i64,
    /// Heating power, W (default: 60; judgement).
    pub heating_power_w: f64,
    /// Post-drive NavCam panorama, s (default: the scenario's `post_drive_imaging_s`).
    pub imaging_s: i64,
    /// Panorama power, W (default: 40; judgement).
    pub imaging_power_w: f64,
    /// Panorama data volume, MB (default: 150; judgement).
    pub imaging_data_mb: f64,
    /// SunFind before the localization imaging, s (default: 300; judgement).
    pub sunfind_s: i64,
    /// Co-processor power while transferring and running, W (default: 15; judgement).
    pub hbs_power_w: f64,
    /// Compare the two results and apply, s (default: 60; judgement).
    pub compare_apply_s: i64,
    /// Onboard data volume available, MB (default: 4,000; judgement).
    pub data_capacity_mb: f64,
    /// Communication pass, s (default: 600).
    pub comm_pass_s: i64,
    /// Data a pass downlinks, MB (default: 500; judgement).
    pub comm_downlink_mb: f64,
    /// End of the planning window, seconds after local midnight (default: 17:00 LMST).
    pub sol_end: SolSeconds,
    /// Node budget of each search (deterministic; default: 20,000).
    pub node_budget: u64,
}

impl Default for SolPlanParams {
    fn default() -> Self {
        Self {
            battery_capacity_wh: 2_400.0,
            initial_charge: 0.8,
            recharge_w: 40.0,
            drive_power_w: 180.0,
            heating_s: 1_800,
            heating_power_w: 60.0,
            imaging_s: 1_800,
            imaging_power_w: 40.0,
            imaging_data_mb: 150.0,
            sunfind_s: 300,
            hbs_power_w: 15.0,
            compare_apply_s: 60,
            data_capacity_mb: 4_000.0,
            comm_pass_s: 600,
            comm_downlink_mb: 500.0,
            sol_end: SolSeconds(62_882), // 17:00 LMST
            node_budget: 20_000,
        }
    }
}

/// The localization chain's planned durations, s (from the co-processor model's settings).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainDurations {
    /// Writing the input file and sending it over the link.
    pub transfer_s: i64,
    /// One run on the co-processor.
    pub run_s: i64,
    /// The reboot between runs.
    pub reboot_s: i64,
}

/// What the sol needs planned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolPlanRequest {
    /// Drive window start.
    pub drive_start: SolSeconds,
    /// Drive window end (as the strategy and the downlink pass allow).
    pub drive_end: SolSeconds,
    /// Drive rate, m/h.
    pub drive_rate_m_per_h: f64,
    /// An afternoon pass, if any.
    pub downlink: Option<SolSeconds>,
    /// The onboard localization chain, under onboard strategies.
    pub chain: Option<ChainDurations>,
}

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
}

/// The sol's plan as laid out, and as repaired after the drive.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SolPlan {
    /// Search result: `optimal`, `feasible` (budget hit), `infeasible` or `no plan found`.
    pub status: &'static str,
    /// The timeline: the activities up to and including the drive as executed, then the rest
    /// as repaired or replanned after it.
    pub timeline: Vec<TimelineStep>,
    /// What happened after the drive: `as planned`, `shifted N`, `replanned: …`.
    pub after_drive: String,
    /// Violations the independent validator found, in either plan (must be empty).
    pub violations: Vec<String>,
}

impl SolPlan {
    /// The log entry of a sol the planner could not plan (its error is the violation).
    #[must_use]
    pub fn not_planned(e: &planner::PlanError) -> Self {
        Self {
            status: "not planned",
            timeline: Vec::new(),
            after_drive: String::new(),
            violations: vec![format!("planner: {e}")],
        }
    }
}

fn status_name(s: PlanStatus) -> &'static str {
    match s {
        PlanStatus::Optimal => "optimal",
        PlanStatus::Feasible => "feasible",
        PlanStatus::Infeasible => "infeasible",
        PlanStatus::NoPlanFound => "no plan found",
    }
}

/// A mandatory task after `after`, starting from `window[0]` and ending by `window[1]`.
fn chained(id: &str, duration_s: i64, power_w: f64, after: &str, window: [i64; 2]) -> Activity {
    let duration_s = duration_s.max(1);
    let latest = (window[1] - duration_s).max(window[0]);
    let mut a = Activity::task(id, duration_s, [window[0], latest], power_w, 0.0);
    a.mandatory = true;
    a.preconditions = vec![after.to_string()];
    a
}

/// The planning problem of one drive sol.
#[must_use]
pub fn sol_problem(p: &SolPlanParams, req: &SolPlanRequest) -> Problem {
    let drive_start = i64::from(req.drive_start.0);
    let drive_end = i64::from(req.drive_end.0).max(drive_start + 1);
    let start_s = drive_start - p.heating_s;
    let end_s = i64::from(p.sol_end.0).max(drive_end + 4 * 3_600);
    let late = end_s;
    let mut heating = Activity::task(
        "heating",
        p.heating_s,
        [start_s, start_s],
        p.heating_power_w,
        0.0,
    );
    heating.mandatory = true;
    let mut drive = Activity::task("drive", 1, [drive_start, drive_start], p.drive_power_w, 1.0);
    drive.kind = ActivityKind::Drive(Drive {
        length_m: req.drive_rate_m_per_h * (drive_end - drive_start) as f64 / 3_600.0,
        rate_m_per_h: req.drive_rate_m_per_h,
        min_segment_s: drive_end - drive_start,
        max_segments: 1,
        split_at_m: Vec::new(),
    });
    drive.mandatory = true;
    drive.preconditions = vec!["heating".into()];
    let mut imaging = chained(
        "post_drive_imaging",
        p.imaging_s,
        p.imaging_power_w,
        "drive",
        [drive_start, late],
    );
    imaging.data_mb = p.imaging_data_mb;
    let mut activities = vec![heating, drive, imaging];
    if let Some(pass) = req.downlink.map(|t| i64::from(t.0))
        && pass >= drive_end
        && pass + p.comm_pass_s <= end_s
    {
        let mut comm = Activity::task("comm_pass", p.comm_pass_s, [pass, pass], 10.0, 0.0);
        comm.mandatory = true;
        comm.downlink_mb = p.comm_downlink_mb;
        activities.push(comm);
    }
    if let Some(c) = req.chain {
        let w = [drive_start, late];
        let steps = [
            (p.sunfind_s, 20.0),
            (c.transfer_s, p.hbs_power_w),
            (c.run_s, p.hbs_power_w),
            (c.reboot_s, p.hbs_power_w),
            (c.run_s, p.hbs_power_w),
            (p.compare_apply_s, 5.0),
        ];
        let mut after = "post_drive_imaging";
        for (id, (duration_s, power_w)) in LOCALIZATION_CHAIN.into_iter().zip(steps) {
            activities.push(chained(id, duration_s, power_w, after, w));
            after = id;
        }
    }
    Problem {
        start_s,
        end_s,
        battery_capacity_wh: p.battery_capacity_wh,
        initial_energy_wh: p.battery_capacity_wh * p.initial_charge,
        recharge_w: p.recharge_w,
        data_capacity_mb: p.data_capacity_mb,
        initial_data_mb: 0.0,
        activities,
        campaigns: Vec::new(),
    }
}

/// Timeline rows of `plan` run from `state`, with the battery and data after each step
/// (idle recharge clipped at capacity).
fn timeline(
    inst: &Instance,
    p: &SolPlanParams,
    state: &State,
    plan: &Plan,
    out: &mut Vec<TimelineStep>,
) {
    let cap = inst.problem().battery_capacity_wh;
    let (mut t, mut e, mut d) = (state.time_s, state.energy_wh, state.data_mb);
    for s in &plan.steps {
        let task = inst.task(s.task);
        e = (e + p.recharge_w * (s.start_s - t).max(0) as f64 / 3_600.0).min(cap);
        e = (e + (p.recharge_w - task.power_w) * (s.end_s - s.start_s) as f64 / 3_600.0).min(cap);
        d = (d + task.data_mb - task.downlink_mb).max(0.0);
        t = s.end_s;
        out.push(TimelineStep {
            activity: task.name.clone(),
            start_lmst: SolSeconds(s.start_s.max(0) as u32).lmst(),
            end_lmst: SolSeconds(s.end_s.max(0) as u32).lmst(),
            start_s: s.start_s,
            end_s: s.end_s,
            energy_wh_after: e,
            data_mb_after: d,
        });
    }
}

/// A laid-out sol plan, ready for the drive to run.
#[derive(Clone, Debug)]
pub struct PlannedSol {
    inst: Instance,
    start: State,
    plan: Plan,
    status: &'static str,
    violations: Vec<String>,
}

impl PlannedSol {
    /// Plan the sol.
    ///
    /// # Errors
    /// The planner's error if the problem is malformed (a bug in [`sol_problem`] or settings
    /// that leave no room, e.g. a drive window past the end of the sol).
    pub fn new(p: &SolPlanParams, req: &SolPlanRequest) -> Result<Self, planner::PlanError> {
        let problem = sol_problem(p, req);
        let inst = Instance::new(&problem)?;
        let settings = SearchSettings {
            node_budget: Some(p.node_budget),
            ..SearchSettings::default()
        };
        let outcome = plan(&problem, &settings)?;
        let start = State::initial(&inst);
        let violations = validate_plan(&inst, &start, &outcome.plan)
            .iter()
            .map(|v| format!("planned: {v:?}"))
            .collect();
        Ok(Self {
            inst,
            start,
            plan: outcome.plan,
            status: status_name(outcome.status),
            violations,
        })
    }

    /// Finish the sol: the drive ended at `drive_end_s`; repair (or replan) what follows it
    /// and return the sol log's plan.
    #[must_use]
    pub fn finish(self, p: &SolPlanParams, drive_end_s: i64) -> SolPlan {
        let mut violations = self.violations;
        let mut rows = Vec::new();
        let Some(drive_step) = self
            .plan
            .steps
            .iter()
            .position(|s| self.inst.task(s.task).name.starts_with("drive"))
        else {
            timeline(&self.inst, p, &self.start, &self.plan, &mut rows);
            return SolPlan {
                status: self.status,
                timeline: rows,
                after_drive: "no drive in the plan".into(),
                violations,
            };
        };
        let drive_start = self.plan.steps[drive_step].start_s;
        let actual_end = drive_end_s.max(drive_start + 1);
        let mut executed = Plan {
            steps: self.plan.steps[..=drive_step].to_vec(),
        };
        executed.steps[drive_step].end_s = actual_end;
        timeline(&self.inst, p, &self.start, &executed, &mut rows);
        let (after_drive, state, rest) =
            match repair(&self.inst, &self.start, &self.plan, drive_step, actual_end) {
                Ok(RepairOutcome::Repaired {
                    state,
                    plan,
                    shifted,
                }) => (
                    if shifted == 0 {
                        "as planned".to_string()
                    } else {
                        format!("shifted {shifted}")
                    },
                    state,
                    plan,
                ),
                Ok(RepairOutcome::ReplanNeeded { state, reason, .. }) => {
                    let settings = SearchSettings {
                        node_budget: Some(p.node_budget),
                        ..SearchSettings::default()
                    };
                    match plan_from(&self.inst, &state, &settings) {
                        Ok(o) => (format!("replanned ({reason:?})"), state, o.plan),
                        Err(e) => (format!("replan failed: {e}"), state, Plan::default()),
                    }
                }
                Err(e) => {
                    violations.push(format!("repair: {e}"));
                    (
                        format!("repair failed: {e}"),
                        self.start.clone(),
                        Plan::default(),
                    )
                }
            };
        violations.extend(
            validate_plan(&self.inst, &state, &rest)
                .iter()
                .map(|v| format!("after the drive: {v:?}")),
        );
        timeline(&self.inst, p, &state, &rest, &mut rows);
        SolPlan {
            status: self.status,
            timeline: rows,
            after_drive,
            violations,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(chain: bool) -> SolPlanRequest {
        SolPlanRequest {
            drive_start: SolSeconds::parse_lmst("11:30").unwrap_or(SolSeconds(0)),
            drive_end: SolSeconds::parse_lmst("14:05").unwrap_or(SolSeconds(0)),
            drive_rate_m_per_h: 100.0,
            downlink: SolSeconds::parse_lmst("16:00"),
            chain: chain.then_some(ChainDurations {
                transfer_s: 74,
                run_s: 32,
                reboot_s: 120,
            }),
        }
    }

    fn names(plan: &SolPlan) -> Vec<&str> {
        plan.timeline.iter().map(|s| s.activity.as_str()).collect()
    }

    #[test]
    fn onboard_sol_has_the_localization_chain_after_the_drive() {
        let p = SolPlanParams::default();
        let planned = PlannedSol::new(&p, &req(true)).expect("plans");
        let drive_end = i64::from(req(true).drive_end.0);
        let plan = planned.finish(&p, drive_end);
        assert_eq!(plan.status, "optimal");
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
        let n = names(&plan);
        let at = |name: &str| n.iter().position(|a| a.starts_with(name));
        assert!(at("heating") < at("drive"));
        assert!(at("drive") < at("post_drive_imaging"));
        for w in LOCALIZATION_CHAIN.windows(2) {
            assert!(at(w[0]).is_some() && at(w[0]) < at(w[1]), "{n:?}");
        }
        assert!(at("post_drive_imaging") < at("sunfind"));
        assert!(n.contains(&"comm_pass"), "{n:?}");
        assert_eq!(plan.after_drive, "as planned");
    }

    #[test]
    fn an_early_drive_end_shifts_the_rest_and_stays_valid() {
        let p = SolPlanParams::default();
        let planned = PlannedSol::new(&p, &req(true)).expect("plans");
        let early = i64::from(SolSeconds::parse_lmst("12:10").map_or(0, |t| t.0));
        let plan = planned.finish(&p, early);
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
        let imaging = plan
            .timeline
            .iter()
            .find(|s| s.activity == "post_drive_imaging")
            .expect("imaging");
        assert_eq!(imaging.start_s, early, "{plan:?}");
        assert!(
            plan.after_drive.starts_with("shifted"),
            "{}",
            plan.after_drive
        );
        assert!(plan.timeline.iter().all(|s| s.energy_wh_after >= 0.0));
    }

    #[test]
    fn ground_sol_has_no_chain() {
        let p = SolPlanParams::default();
        let plan = PlannedSol::new(&p, &req(false))
            .expect("plans")
            .finish(&p, i64::from(req(false).drive_end.0));
        assert!(!names(&plan).contains(&"sunfind"));
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
    }
}
