//! The planning problem of one drive sol: heating, the drive (split at the science stops),
//! the post-drive imaging, the afternoon pass, the onboard localization chain and the science
//! candidates, as a [`planner::Problem`].

use std::cell::RefCell;

use planner::{Activity, ActivityKind, Drive, Problem, Timeline};

use super::SolPlanSettings;
use crate::operations::science::SolScience;
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

/// Every id the sol plan gives its own activities (science may not reuse them).
pub const SOL_ACTIVITIES: [&str; 10] = [
    "heating",
    "drive",
    "post_drive_imaging",
    "comm_pass",
    LOCALIZATION_CHAIN[0],
    LOCALIZATION_CHAIN[1],
    LOCALIZATION_CHAIN[2],
    LOCALIZATION_CHAIN[3],
    LOCALIZATION_CHAIN[4],
    LOCALIZATION_CHAIN[5],
];

/// The localization chain's planned durations, s (from the co-processor model's settings).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainDurations {
    /// Writing the input file and sending it over the link: the flight-size inputs at the
    /// link rate, ~30 min at the flown 10 KB/s (paper 000 §4).
    pub transfer_s: i64,
    /// One run on the co-processor.
    pub run_s: i64,
    /// The reboot between runs.
    pub reboot_s: i64,
}

/// What the sol needs planned.
#[derive(Clone, Debug, PartialEq)]
pub struct SolPlanRequest {
    /// Drive window start.
    pub drive_start: SolSeconds,
    /// Drive window end (as the strategy and the downlink pass allow).
    pub drive_end: SolSeconds,
    /// Drive rate, m/h.
    pub drive_rate_m_per_h: f64,
    /// An afternoon pass, if any.
    pub downlink: Option<SolSeconds>,
    /// Whether the ground needs this sol's panorama from that pass for its next plan (the
    /// imaging then has to end before the pass).
    pub panorama_on_pass: bool,
    /// The onboard localization chain, under onboard strategies.
    pub chain: Option<ChainDurations>,
    /// Science candidates (targets in reach, periodic and state-based instances) and where
    /// they split the drive.
    pub science: SolScience,
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

/// The sol's planning window `[start, end]`: from the wake-up (or the heating before the
/// drive, if earlier) to the end of the sol's activities (at least four hours after the drive
/// window, room for the imaging and the localization chain).
#[must_use]
pub fn planning_window(
    p: &SolPlanSettings,
    drive_start: SolSeconds,
    drive_end: SolSeconds,
) -> [SolSeconds; 2] {
    let drive_end = drive_end.max(drive_start + 1);
    [
        p.sol_start.min(drive_start - p.heating_s),
        p.sol_end.max(drive_end + 4 * 3_600),
    ]
}

/// Metres the drive window allows at the nominal rate.
#[must_use]
pub fn planned_drive_m(req: &SolPlanRequest) -> f64 {
    let drive_end = req.drive_end.max(req.drive_start + 1);
    req.drive_rate_m_per_h * (drive_end - req.drive_start) as f64 / 3_600.0
}

/// The planning problem of one drive sol (its times cross to the planner here, as
/// [`SolSeconds::planner_s`]).
#[must_use]
pub fn sol_problem(p: &SolPlanSettings, req: &SolPlanRequest) -> Problem {
    let drive_start = req.drive_start.planner_s();
    let drive_end = req.drive_end.planner_s().max(drive_start + 1);
    let [start, end] = planning_window(p, req.drive_start, req.drive_end);
    let (start_s, end_s) = (start.planner_s(), end.planner_s());
    let late = end_s;
    let mut heating = Activity::task(
        "heating",
        p.heating_s,
        [drive_start - p.heating_s, drive_start - p.heating_s],
        p.heating_power_w,
        0.0,
    );
    heating.mandatory = true;
    let mut drive = Activity::task("drive", 1, [drive_start, drive_start], p.drive_power_w, 1.0);
    drive.kind = ActivityKind::Drive(Drive {
        length_m: planned_drive_m(req),
        rate_m_per_h: req.drive_rate_m_per_h,
        min_segment_s: drive_end - drive_start,
        max_segments: req.science.split_at_m.len() as u32 + 1,
        split_at_m: req.science.split_at_m.clone(),
        latest_end_s: Some(drive_end + p.drive_stretch_s),
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
    if let Some(pass) = req.downlink.map(SolSeconds::planner_s)
        && pass >= drive_end
        && pass + p.comm_pass_s <= end_s
    {
        let mut comm = Activity::task("comm_pass", p.comm_pass_s, [pass, pass], 10.0, 0.0);
        comm.mandatory = true;
        comm.downlink_mb = p.comm_downlink_mb;
        if req.panorama_on_pass {
            comm.preconditions = vec!["post_drive_imaging".into()];
        }
        activities.push(comm);
    }
    if let Some(c) = req.chain {
        let w = [drive_start, late];
        // The transfer, the runs and the reboot hold the HBS link, not the main timeline:
        // "although the transfer takes 30 minutes, the entire activity can be safely run in
        // parallel with other operations" (paper 000 §4). SunFind and the comparison run on
        // the rover computer.
        let (main, link) = (Timeline::Main, Timeline::HbsLink);
        let steps = [
            (p.sunfind_s, 20.0, main),
            (c.transfer_s, p.hbs_power_w, link),
            (c.run_s, p.hbs_power_w, link),
            (c.reboot_s, p.hbs_power_w, link),
            (c.run_s, p.hbs_power_w, link),
            (p.compare_apply_s, 5.0, main),
        ];
        let mut after = "post_drive_imaging";
        for (id, (duration_s, power_w, timeline)) in LOCALIZATION_CHAIN.into_iter().zip(steps) {
            let mut a = chained(id, duration_s, power_w, after, w);
            a.timeline = timeline;
            activities.push(a);
            after = id;
        }
    }
    activities.extend(req.science.activities.iter().cloned());
    Problem {
        start_s,
        end_s,
        battery_capacity_wh: p.battery_capacity_wh,
        initial_energy_wh: p.battery_capacity_wh * p.initial_charge,
        recharge_w: p.recharge_w,
        data_capacity_mb: p.data_capacity_mb,
        initial_data_mb: 0.0,
        activities,
        campaigns: req.science.campaigns.clone(),
    }
}

thread_local! {
    /// The sol problems planned on this thread while a [`capture_sol_problems`] runs, with
    /// their sol numbers (`None` otherwise, so a normal run builds and keeps nothing extra).
    static CAPTURED: RefCell<Option<Vec<(u32, Problem)>>> = const { RefCell::new(None) };
}

/// Runs `f` and returns its result with every drive sol's planning problem built on this
/// thread meanwhile, in order, each with its sol number: the problem [`sol_problem`] builds
/// for the sol's first plan (the one [`SolExecution::new`](super::SolExecution::new) plans;
/// replans after an injected goal or a disruption are not included). This is how
/// `study/examples/dump_sol_problems.rs` hands the simulator's problems to the CP-SAT peer. A
/// campaign runs on the calling thread, so `|| scenario.run(strategy, seed)` captures all of
/// its sols. A nested capture takes the problems from the outer one.
pub fn capture_sol_problems<R>(f: impl FnOnce() -> R) -> (R, Vec<(u32, Problem)>) {
    let outer = CAPTURED.with(|c| c.borrow_mut().replace(Vec::new()));
    let r = f();
    let problems = CAPTURED.with(|c| std::mem::replace(&mut *c.borrow_mut(), outer));
    (r, problems.unwrap_or_default())
}

/// Keep sol `sol`'s problem (built by `problem` only then) if a [`capture_sol_problems`] is
/// running on this thread.
pub(crate) fn note_sol_problem(sol: u32, problem: impl FnOnce() -> Problem) {
    CAPTURED.with(|c| {
        if let Some(v) = c.borrow_mut().as_mut() {
            v.push((sol, problem()));
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_capture_builds_and_keeps_problems() {
        let problem = || Problem {
            start_s: 0,
            end_s: 100,
            battery_capacity_wh: 1.0,
            initial_energy_wh: 1.0,
            recharge_w: 0.0,
            data_capacity_mb: 1.0,
            initial_data_mb: 0.0,
            activities: Vec::new(),
            campaigns: Vec::new(),
        };
        note_sol_problem(1, || unreachable!("built outside a capture"));
        let (r, got) = capture_sol_problems(|| {
            note_sol_problem(2, problem);
            let ((), inner) = capture_sol_problems(|| note_sol_problem(3, problem));
            assert_eq!(inner.len(), 1);
            note_sol_problem(4, problem);
            5
        });
        assert_eq!(r, 5);
        assert_eq!(got.iter().map(|(s, _)| *s).collect::<Vec<_>>(), vec![2, 4]);
        note_sol_problem(6, || unreachable!("built after the capture"));
    }
}
