//! One drive sol, executed: the sol's plan ([`crate::operations::sol_plan`]) step by step — drive
//! segments through AutoNav, observations against the rover's true position, the onboard
//! localization chain through the co-processor model — with each step's actual end fed back
//! so the plan is repaired or replanned.
//!
//! What comes back to the planner:
//!
//! | step | actual end | disruption (full replan) |
//! |---|---|---|
//! | drive segment | start + AutoNav's driving time | a fault (in any segment), or the end of the route or the drive budget before the last segment: the rest of the drive is cancelled |
//! | `hbs_transfer` … `compare_apply` | start + the step's time in the co-processor log (statistical localizer: as planned) | the localization is lost: the chain's steps that never ran are cancelled |
//! | a target observation | as planned | — (out of reach: logged as failed) |
//! | a new target revealed | — | added to the plan at the first step boundary after its reveal |

use rand_chacha::ChaCha8Rng;

use crate::grid::astar::AStar;
use crate::localizers::{OnboardLocalizer, PostDrive};
use crate::operations::science::{Reach, ScienceProgress, SolContext};
use crate::operations::sol_plan::{
    ChainDurations, Disruption, LOCALIZATION_CHAIN, SolExecution, SolPlan, SolPlanRequest, Step,
    note_sol_problem, planned_drive_m, planning_window, sol_problem,
};
use crate::rover::autonav::{
    DriveContext, DriveLimits, DriveResult, RoverState, VoSource, drive_sol,
};
use crate::rover::errors::SolErrors;
use crate::rover::pose::estimate_error_m;
use crate::run::outcome::{LocalizationEvent, LocalizationStep};
use crate::seeds::RunSeeds;
use crate::settings::Settings;
use crate::time::SolSeconds;
use localization::hbs::HbsStep;

/// Planned durations of the onboard localization chain: the co-processor model's settings,
/// with the transfer of a flight-size input set at the scenario's link rate
/// ([`localization::onboard::FLIGHT_SIZE_LINK_BYTES`]: 30 min at the flown 10 KB/s, 7.5 min
/// at 40 KB/s).
pub(crate) fn chain_durations(localizer: &OnboardLocalizer) -> ChainDurations {
    let hbs = localizer.hbs();
    // The particle filter runs on the co-processor like the matchers: its cost is the census
    // score surface over the same window.
    let run_s = match localizer.imagery_settings() {
        Some(s) => s.hbs_slowdown * localization::onboard::MEASURED_FLIGHT_SIZE_RUN_S,
        None => hbs.run_s,
    };
    ChainDurations {
        transfer_s: (localization::onboard::FLIGHT_SIZE_LINK_BYTES as f64 / hbs.link_bytes_per_s)
            .ceil() as i64,
        run_s: run_s.ceil() as i64,
        reboot_s: hbs.reboot_s.ceil() as i64,
    }
}

/// The rover's estimate, then the route waypoints it has still to reach.
fn route_ahead(c: &Settings, rover: &RoverState) -> Vec<[f64; 2]> {
    let est = rover.estimate.position_m;
    let mut out = vec![[est.x, est.y]];
    out.extend(c.route.iter().skip(rover.next_waypoint).copied());
    out
}

/// What one drive sol did.
#[derive(Clone, Debug)]
pub(crate) struct SolRun {
    /// The drive, all segments together.
    pub drive: DriveResult,
    /// Uncertainty radius when the drive ended, before any localization, metres.
    pub end_uncertainty_m: f64,
    /// Estimate-to-truth distance when the drive ended, metres.
    pub truth_error_m: f64,
    /// The onboard localization, if the strategy ran one.
    pub localization: Option<LocalizationEvent>,
    /// The sol's plan as executed.
    pub plan: SolPlan,
    /// The sol's heading and VO scale errors, drawn before its first drive segment.
    errors: SolErrors,
    /// Whether the end-of-drive figures above are taken.
    drive_ended: bool,
}

impl SolRun {
    /// Take the end-of-drive figures from `rover`, once: when the drive is over (a
    /// disruption, the localization about to run, or the end of the sol's plan).
    fn end_drive(
        &mut self,
        rover: &RoverState,
        model: &crate::rover::uncertainty::UncertaintyModel,
    ) {
        if !self.drive_ended {
            self.drive_ended = true;
            self.end_uncertainty_m = rover.uncertainty.radius_m(model);
            self.truth_error_m = estimate_error_m(&rover.truth, &rover.estimate);
        }
    }
}

/// The sol's environment: what [`execute_sol`] drives, localizes and observes with.
pub(crate) struct SolEnv<'a> {
    /// The settings.
    pub c: &'a Settings,
    /// The run's seeds (the world the imagery is rendered from).
    pub seeds: RunSeeds,
    /// AutoNav's context.
    pub ctx: &'a DriveContext<'a>,
    /// The sol number.
    pub sol: u32,
    /// Whether the strategy localizes onboard after the drive.
    pub onboard: bool,
    /// The sol's drive budget (window time; a replay's historic distance).
    pub limits: DriveLimits,
    /// Where VO success comes from.
    pub vo: VoSource,
}

/// The mutable state a sol runs on.
pub(crate) struct SolState<'a> {
    /// The rover.
    pub rover: &'a mut RoverState,
    /// The science campaigns' progress.
    pub progress: &'a mut ScienceProgress,
    /// The strategy's random stream.
    pub rng: &'a mut ChaCha8Rng,
    /// A* scratch.
    pub astar: &'a mut AStar,
}

/// Add a drive segment's result to the sol's.
fn merge(total: &mut DriveResult, mut seg: DriveResult) {
    if let Some(f) = &mut seg.fault {
        f.after_m += total.distance_m;
    }
    total.distance_m += seg.distance_m;
    total.d_vo_m += seg.d_vo_m;
    total.d_novo_m += seg.d_novo_m;
    total.drive_time_s += seg.drive_time_s;
    total.terrain_m += seg.terrain_m;
    total.plans += seg.plans;
    total.reached_goal |= seg.reached_goal;
    total.fault = total.fault.take().or(seg.fault);
    let skip = usize::from(!total.path_m.is_empty());
    total.path_m.extend(seg.path_m.into_iter().skip(skip));
}

/// The co-processor log step that ends each activity of [`LOCALIZATION_CHAIN`] (SunFind and
/// the compare-and-apply run on the rover computer, outside the log).
const LOG_STEP_ENDING: [Option<HbsStep>; LOCALIZATION_CHAIN.len()] = [
    None,
    Some(HbsStep::TransferToHbs),
    Some(HbsStep::Run1),
    Some(HbsStep::Reboot),
    Some(HbsStep::Run2),
    None,
];

/// Run the localization and map its log onto the chain: each chain step's actual duration, s
/// (`None` if it never ran), for the steps after SunFind.
fn localize(
    env: &SolEnv<'_>,
    st: &mut SolState<'_>,
    start: SolSeconds,
    compare_apply_s: i64,
) -> (LocalizationEvent, [Option<i64>; LOCALIZATION_CHAIN.len()]) {
    let c = env.c;
    // The co-processor log is stamped from midnight at the earliest.
    let start = start.max(SolSeconds::MIDNIGHT);
    let event = c.localizer.get().localize(&mut PostDrive {
        rover: st.rover,
        model: &c.model,
        operator_margin_m: c.operator_margin_m,
        seeds: env.seeds,
        start,
        rng: st.rng,
    });
    let mut durations = [None; LOCALIZATION_CHAIN.len()];
    if event.steps.is_empty() {
        return (event, durations);
    }
    // The co-processor log stamps each step when it ends: a step lasts from the previous
    // stamp to its own. The compare and apply on the rover computer follow the transfer back
    // and take the planned time.
    let at = |step: HbsStep| {
        event
            .steps
            .iter()
            .find(|e| e.step == LocalizationStep::Onboard(step))
            .map(|e| e.t_s)
    };
    let mut previous = 0.0;
    for (d, step) in durations.iter_mut().zip(LOG_STEP_ENDING) {
        if let Some(t) = step.and_then(at) {
            *d = Some((t - previous).round() as i64);
            previous = t;
        }
    }
    let ran_both = durations[LOCALIZATION_CHAIN.len() - 2].is_some()
        && event.steps.iter().any(|e| {
            matches!(
                e.step,
                LocalizationStep::Onboard(HbsStep::Compare | HbsStep::ApplyLocalization)
            )
        });
    if ran_both {
        let last = event.steps.last().map_or(previous, |e| e.t_s);
        durations[LOCALIZATION_CHAIN.len() - 1] =
            Some((last - previous).round() as i64 + compare_apply_s);
    }
    (event, durations)
}

/// Execute one drive sol's plan. `request` is the sol's plan request without science; the
/// science candidates of the settings' campaigns ([`Settings::science`]) are added here.
pub(crate) fn execute_sol(
    env: &SolEnv<'_>,
    st: &mut SolState<'_>,
    mut request: SolPlanRequest,
) -> SolRun {
    let c = env.c;
    let window = planning_window(&c.sol_plan, request.drive_start, request.drive_end);
    request.science = c.science.for_sol(
        st.progress,
        &SolContext {
            sol: env.sol,
            window,
            drive_start: request.drive_start,
            drive_m: planned_drive_m(&request),
            before_drive: request.drive_start - c.sol_plan.heating_s,
        },
        &route_ahead(c, st.rover),
    );
    let mut run = SolRun {
        drive: DriveResult::default(),
        end_uncertainty_m: 0.0,
        truth_error_m: 0.0,
        localization: None,
        plan: SolPlan::default(),
        errors: c.rover.errors.draw_sol(st.rng),
        drive_ended: false,
    };
    let mut now = window[0];
    note_sol_problem(env.sol, || sol_problem(&c.sol_plan, &request));
    match SolExecution::new(&c.sol_plan, &request) {
        Ok(exec) if exec.next_step().is_some() => {
            now = execute_plan(env, st, &mut run, exec, now);
        }
        planned => {
            // No plan (a malformed or infeasible problem; the log says which): drive the
            // window as commanded; the localization follows right after it.
            let r = drive_sol(
                env.ctx, st.rover, env.limits, env.vo, run.errors, st.rng, st.astar,
            );
            merge(&mut run.drive, r);
            now = request.drive_start.after_s(run.drive.drive_time_s);
            run.plan = match planned {
                Ok(exec) => exec.finish(),
                Err(e) => SolPlan::not_planned(&e),
            };
        }
    }
    run.end_drive(st.rover, &c.model);
    if env.onboard && run.localization.is_none() {
        // No plan, or the plan lost the chain (a replan could not fit it): localize when the
        // sol's activities end, as the ground would command it.
        run.localization = Some(localize(env, st, now, c.sol_plan.compare_apply_s).0);
    }
    st.progress.odometer_m += run.drive.distance_m;
    run
}

/// Run `exec` step by step (in start order; a step on the HBS link overlaps the main-timeline
/// steps after it) into `run`; returns when the sol's last activity ended.
fn execute_plan(
    env: &SolEnv<'_>,
    st: &mut SolState<'_>,
    run: &mut SolRun,
    mut exec: SolExecution,
    start: SolSeconds,
) -> SolSeconds {
    let mut last_end = start;
    let c = env.c;
    let mut chain_durations = [None; LOCALIZATION_CHAIN.len()];
    let mut considered: Vec<String> = Vec::new();
    while let Some(step) = exec.next_step() {
        if inject_revealed(env, st, &mut exec, &step, &mut considered) {
            continue;
        }
        let chain_at = LOCALIZATION_CHAIN.iter().position(|&a| a == step.activity);
        if step.activity == "drive" {
            let (end, disruption, outcome) = drive_segment(env, st, run, &step);
            last_end = last_end.max(end);
            if disruption.is_some() {
                run.end_drive(st.rover, &c.model);
            }
            exec.complete(end, outcome, disruption);
        } else if let Some(ci) = chain_at.filter(|&ci| ci >= 1 && env.onboard) {
            if ci == 1 {
                run.end_drive(st.rover, &c.model);
                // The statistical model has no co-processor log: the chain runs as planned.
                let (event, durations) =
                    localize(env, st, step.start_s, c.sol_plan.compare_apply_s);
                chain_durations = durations;
                run.localization = Some(event);
            }
            let applied = run.localization.as_ref().is_some_and(|l| l.applied);
            let modelled = run
                .localization
                .as_ref()
                .is_some_and(|l| !l.steps.is_empty());
            let end = if modelled {
                step.start_s + chain_durations[ci].unwrap_or(0)
            } else {
                step.end_s
            };
            // The chain's last step that ran: a lost localization replans what follows.
            let last_ran = !modelled && ci + 1 == LOCALIZATION_CHAIN.len()
                || modelled && chain_durations[ci + 1..].iter().all(Option::is_none);
            let disruption = (last_ran && !applied).then(|| Disruption {
                reason: format!(
                    "localization lost: {}",
                    run.localization
                        .as_ref()
                        .and_then(|l| l.reason.as_ref())
                        .map_or_else(|| "rejected".into(), ToString::to_string)
                ),
                cancel: LOCALIZATION_CHAIN[ci + 1..]
                    .iter()
                    .map(|s| (*s).to_string())
                    .collect(),
                driven_m: None,
            });
            last_end = last_end.max(end);
            exec.complete(end, None, disruption);
        } else {
            let outcome = observe(env, st, &step);
            last_end = last_end.max(step.end_s);
            exec.complete(step.end_s, outcome, None);
        }
    }
    run.plan = exec.finish();
    last_end
}

/// Drive one segment: its actual end, the disruption if the drive stopped before its
/// last segment, and the outcome note.
fn drive_segment(
    env: &SolEnv<'_>,
    st: &mut SolState<'_>,
    run: &mut SolRun,
    step: &Step,
) -> (SolSeconds, Option<Disruption>, Option<String>) {
    let (j, k) = step.segment.unwrap_or((0, 1));
    let last = j + 1 == k;
    let left_m = env.limits.max_distance_m.map(|m| m - run.drive.distance_m);
    let limits = DriveLimits {
        max_distance_m: match (last, left_m) {
            (true, m) => m,
            (false, None) => Some(step.drive_m),
            (false, Some(m)) => Some(step.drive_m.min(m)),
        },
        max_time_s: env.limits.max_time_s.map(|t| t - run.drive.drive_time_s),
    };
    let r = drive_sol(
        env.ctx, st.rover, limits, env.vo, run.errors, st.rng, st.astar,
    );
    let end = step.start_s.after_s(r.drive_time_s);
    let short = r.distance_m < step.drive_m - 0.5;
    merge(&mut run.drive, r);
    let d = &run.drive;
    let reason = if let Some(f) = &d.fault {
        Some(format!("{} after {:.1} m", f.kind.name(), f.after_m))
    } else if d.reached_goal {
        Some(format!("end of the route after {:.1} m", d.distance_m))
    } else if short && !last {
        Some(format!("drive budget used up after {:.1} m", d.distance_m))
    } else {
        None
    };
    let note = reason.clone();
    let disruption = reason
        .filter(|_| !last || d.fault.is_some())
        .map(|reason| Disruption {
            reason,
            cancel: vec!["drive".into()],
            driven_m: Some(d.distance_m),
        });
    (end, disruption, note)
}

/// Run a science observation (or any other activity): targets are judged from the true
/// position; campaign members count towards their campaign. Returns the timeline note.
fn observe(env: &SolEnv<'_>, st: &mut SolState<'_>, step: &Step) -> Option<String> {
    let science = &env.c.science;
    science.campaign_of(&step.activity)?;
    let Some(t) = science.target(&step.activity) else {
        st.progress.record(science, &step.activity, true);
        return Some("done".into());
    };
    let truth = st.rover.truth.position_m;
    let d = (t.position_m[0] - truth.x).hypot(t.position_m[1] - truth.y);
    let observed = d <= t.within_m;
    st.progress.record(science, &step.activity, observed);
    Some(if observed {
        format!("observed: {d:.1} m from the target")
    } else {
        format!(
            "out of reach: {d:.1} m from the target (needs {:.1} m)",
            t.within_m
        )
    })
}

/// Targets revealed by now: add each one in reach to the plan (one at a time; `true` if the
/// plan changed).
fn inject_revealed(
    env: &SolEnv<'_>,
    st: &SolState<'_>,
    exec: &mut SolExecution,
    step: &Step,
    considered: &mut Vec<String>,
) -> bool {
    let science = &env.c.science;
    let Some(goal_set) = science.offered_goal_set(st.progress) else {
        return false;
    };
    let window_end = exec.window()[1];
    for t in &science.targets {
        let id = t.id();
        if t.revealed.is_none_or(|(sol, _)| sol != env.sol)
            || !t.revealed_by(env.sol, step.start_s)
            || considered.iter().any(|c| c == id)
            || exec.has_activity(id)
            || st.progress.achieved.iter().any(|a| a == id)
        {
            continue;
        }
        considered.push(id.to_string());
        let ahead = route_ahead(env.c, st.rover);
        let drive_left = exec.drive_left_m();
        if t.reach(&ahead, drive_left) == Reach::OutOfReach {
            continue;
        }
        // Mid-sol there is no time before the drive left: a target the rest of the drive would
        // leave behind is not offered.
        if let Some(a) = t.candidate(
            &goal_set.id,
            [step.start_s, window_end],
            &ahead,
            drive_left,
            None,
        ) {
            exec.inject(a, Some(goal_set), "autonomous science revealed a target");
            return true;
        }
    }
    false
}
