//! The multi-sol runner: one strategy over a scenario's calendar and route.
//!
//! Each sol: an uplink (if any) starts a plan — the ground localizes the rover if it has the
//! last drive's data, and the strategy's [`Policy`] decides which of the plan's sols drive —
//! then the rover drives ([`crate::autonav`]) within the sol's budget, then, under onboard
//! strategies, localizes itself. A fault halts driving until the ground has seen it. Everything random comes from one
//! ChaCha8 stream per (scenario seed, strategy), so a run is reproducible bit for bit.

use std::sync::Arc;

use crate::seeds::{Purpose, stream_seed};

use crate::autonav::{DriveContext, DriveLimits, RoverParams, RoverState};
use crate::calendar::Calendar;
use crate::localizer::OnboardLocalizer;
use crate::outcome::{
    ActivityStep, CampaignOutcome, DriveEnd, FaultKind, LegClearance, LocalizationEvent,
    LocalizationKind, LocalizationStep, ScienceTally, SkipReason, SolRecord, Totals,
};
use crate::planning_grid::PlanningGrid;
use crate::policy::{
    GroundKnowledge, OperationsRules, PassagesAhead, PlanStyle, Policy, RoutePosition, RunSoFar,
};
use crate::pose::estimate_error_m;
use crate::science::{Science, ScienceProgress, SolScience};
use crate::sol_plan::{SolPlanParams, SolPlanRequest};
use crate::sol_run::{SolEnv, SolState, chain_durations, execute_sol};
use crate::strategy::Strategy;
use crate::time::SolSeconds;
use crate::uncertainty::UncertaintyModel;
use crate::widest_path::widest_path_bottleneck;

/// Everything a campaign run needs (resolved from a scenario file by the binary).
#[derive(Clone, Debug)]
pub struct Campaign {
    /// Scenario name (for reports).
    pub name: String,
    /// Master seed of every random draw.
    pub seed: u64,
    /// Route waypoints, map metres; waypoint 0 is the start.
    pub route: Vec<[f64; 2]>,
    /// Operations calendar.
    pub calendar: Calendar,
    /// Rover and AutoNav settings.
    pub rover: RoverParams,
    /// Uncertainty growth.
    pub model: UncertaintyModel,
    /// Onboard localizer: the statistical model or image matching through the co-processor.
    pub localizer: OnboardLocalizer,
    /// Operator margin added to the localizer's σ after an onboard localization, metres.
    pub operator_margin_m: f64,
    /// Post-drive imaging before a downlink pass, seconds (a ground-planned drive whose panorama
    /// must make an afternoon pass stops this long before it).
    pub post_drive_imaging_s: u32,
    /// The operations rules every strategy plans under: plan lengths, the optional extension
    /// cap, the planners' passage margin.
    pub rules: OperationsRules,
    /// The planning grid, shared by every run of the scenario (and every thread).
    pub grid: Arc<PlanningGrid>,
    /// Each drive sol's activity plan settings.
    pub sol_plan: SolPlanParams,
    /// Science campaigns planned onboard each drive sol (none in most scenarios).
    pub science: Science,
}

/// Margin of the window around each leg within which [`leg_clearances`] searches, metres.
pub const LEG_WINDOW_MARGIN_M: f64 = 150.0;

/// Most waypoints a route may have. Rover routes have tens to hundreds; every waypoint costs a
/// passage search when a scenario is loaded and a leg in every run (issue 26: 100 000 took 5
/// minutes).
pub const MAX_WAYPOINTS: usize = 10_000;

/// Most grid cells the passage searches of one route may cover together
/// ([`leg_search_cells`]). Measured (issue 26, one core): 2000 legs through the sol 383-386
/// passage, each needing the full search (2.8e8 cells), load in 16 s; legs through open ground
/// take a fraction of that, and a second core halves it.
pub const MAX_LEG_SEARCH_CELLS: u64 = 300_000_000;

/// Per-leg passage clearance of the route (independent of strategy).
///
/// Leg `i` runs from waypoint `i − 1` to waypoint `i`; its clearance is the largest uncertainty
/// radius at which a path between them still exists (a maximin path over cell clearance, slope
/// hazards excluded), searched within [`LEG_WINDOW_MARGIN_M`] of the leg's box. The legs are
/// searched in parallel; the result does not depend on the thread count.
#[must_use]
pub fn leg_clearances(c: &Campaign) -> Vec<LegClearance> {
    leg_clearances_observed(c, &|| {})
}

/// [`leg_clearances`], calling `on_leg` as each leg is done (from any thread; for a progress
/// bar).
#[must_use]
pub fn leg_clearances_observed(c: &Campaign, on_leg: &(dyn Fn() + Sync)) -> Vec<LegClearance> {
    use rayon::prelude::*;
    let g = &c.grid;
    // Where each leg starts along the route, summed in order before the parallel part.
    let lengths: Vec<f64> = c
        .route
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .collect();
    let starts_m: Vec<f64> = lengths
        .iter()
        .scan(0.0, |at, l| {
            let start = *at;
            *at += l;
            Some(start)
        })
        .collect();
    (1..c.route.len())
        .into_par_iter()
        .map(|i| {
            let (p, q) = (c.route[i - 1], c.route[i]);
            let bottleneck = match (g.cell_of(p), g.cell_of(q)) {
                (Some(a), Some(b)) => widest_path_bottleneck(
                    g.width,
                    g.height,
                    &g.clearance_m,
                    |k| !g.hazard[k],
                    a,
                    b,
                    Some(leg_window(g, a, b)),
                ),
                _ => None,
            };
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let (length_m, leg_start_m) = (lengths[i - 1], starts_m[i - 1]);
            let leg = LegClearance {
                to_waypoint: i,
                clearance_m: bottleneck.map(|b| f64::from(b.clearance)),
                narrowest_along_route_m: bottleneck.map(|b| {
                    // Project the narrowest cell onto the leg.
                    let at = g.center_of(b.narrowest_cell);
                    let t = if length_m > 0.0 {
                        (((at[0] - p[0]) * dx + (at[1] - p[1]) * dy) / (length_m * length_m))
                            .clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    leg_start_m + t * length_m
                }),
                narrowest_m: bottleneck.map(|b| g.center_of(b.narrowest_cell)),
            };
            on_leg();
            leg
        })
        .collect()
}

/// The window `(col0, row0, col1, row1)` [`leg_clearances`] searches for the leg between cells
/// `a` and `b`: their box grown by [`LEG_WINDOW_MARGIN_M`], clipped to the grid.
fn leg_window(g: &PlanningGrid, a: usize, b: usize) -> (usize, usize, usize, usize) {
    let margin = (LEG_WINDOW_MARGIN_M / g.geo.resolution_m_per_px).ceil() as usize;
    let (ca, ra, cb, rb) = (a % g.width, a / g.width, b % g.width, b / g.width);
    (
        ca.min(cb).saturating_sub(margin),
        ra.min(rb).saturating_sub(margin),
        (ca.max(cb) + margin).min(g.width - 1),
        (ra.max(rb) + margin).min(g.height - 1),
    )
}

/// Cells [`leg_clearances`] may search over the whole route, at most: the sum of its legs'
/// windows (legs with an end off the grid count nothing). The time of [`leg_clearances`] is
/// about proportional to it in the worst case, so a scenario can be refused from it before the
/// search runs.
#[must_use]
pub fn leg_search_cells(grid: &PlanningGrid, route: &[[f64; 2]]) -> u64 {
    route
        .windows(2)
        .filter_map(|w| Some((grid.cell_of(w[0])?, grid.cell_of(w[1])?)))
        .map(|(a, b)| {
            let (c0, r0, c1, r1) = leg_window(grid, a, b);
            ((c1 - c0 + 1) as u64).saturating_mul((r1 - r0 + 1) as u64)
        })
        .fold(0u64, u64::saturating_add)
}

/// Run `strategy` over the campaign. `legs` comes from [`leg_clearances`].
#[must_use]
pub fn run_campaign(c: &Campaign, strategy: Strategy, legs: &[LegClearance]) -> CampaignOutcome {
    let cal = &c.calendar;
    let mut rng = stream_seed(c.seed, Purpose::Strategy(strategy), 0).rng();
    let mut astar = c.grid.astar();
    let ctx = DriveContext {
        grid: &c.grid,
        route: &c.route,
        rover: &c.rover,
        model: &c.model,
    };
    let mut state = RoverState::new(c.route[0], c.model.initial_margin_m);

    let mut records = Vec::with_capacity(cal.sols.len());
    let mut last_drive: Option<usize> = None;
    let mut moved_since_ground_fix = false;
    let mut halted_by_fault: Option<usize> = None;
    let mut sols_since_localization = 0u32;
    let mut goal_sol: Option<u32> = None;
    // Per plan: the sols that may drive and why the others may not.
    let policy = Policy::new(strategy, c.rules);
    // What the planners know of the passages, and of the last localization they know of.
    let waypoint_along_m = route_along_m(&c.route);
    let ahead = PassagesAhead {
        legs,
        waypoint_along_m: &waypoint_along_m,
        k_vo: c.model.k_vo,
        arrival_tolerance_m: c.rover.waypoint_tolerance_m + c.rover.step_m,
    };
    let mut driven_since_fix_m = 0.0;
    let mut passage = policy.passage_budget(
        route_position(&c.route, &waypoint_along_m, &state),
        state.uncertainty.radius_m(&c.model),
        &ahead,
    );
    // Extension plans lay breadcrumbs through this calendar index (exclusive).
    let mut breadcrumbs_until = 0usize;
    let mut plan_uplink = cal.sols.first().map_or(0, |s| s.sol);
    let mut plan_drive: Vec<Option<SkipReason>> =
        vec![Some(SkipReason::NoPlanUplinked); cal.sols.len()];
    let mut panorama_sol: Option<usize> = None;
    let mut progress = ScienceProgress::default();

    for (idx, entry) in cal.sols.iter().enumerate() {
        let mut ground_event = None;
        if entry.uplink {
            let next_uplink = cal.next_uplink_after(idx);
            let ground_knows = last_drive.is_none_or(|s| cal.data_available(s, Some(idx)));
            if ground_knows && halted_by_fault.is_some() {
                halted_by_fault = None;
            }
            if ground_knows && moved_since_ground_fix {
                // MOB_GROUND_LOCALIZED_HERE with the plan: the mapping specialists matched the
                // last post-drive panorama to the orbital map.
                // Their fix is good to a HiRISE pixel or so, not perfect.
                let [de, dn] = c.rover.errors.draw_ground_error(&mut rng);
                state.estimate.position_m = state.truth.position_m + nalgebra::Vector2::new(de, dn);
                state.uncertainty.reset_ground();
                state.clear_path();
                moved_since_ground_fix = false;
                sols_since_localization = 0;
                driven_since_fix_m = 0.0;
                passage = policy.passage_budget(
                    route_position(&c.route, &waypoint_along_m, &state),
                    state.uncertainty.radius_m(&c.model),
                    &ahead,
                );
                let p = state.estimate.position_m;
                ground_event = Some(LocalizationEvent {
                    kind: LocalizationKind::Ground,
                    localizer: "ground",
                    applied: true,
                    reason: None,
                    error_m: Some(de.hypot(dn)),
                    matched_error_m: None,
                    sigma_m: None,
                    search_radius_m: None,
                    ellipse: None,
                    uncertainty_after_m: state.uncertainty.radius_m(&c.model),
                    start_lmst: None,
                    duration_s: None,
                    steps: vec![ActivityStep {
                        lmst: None,
                        t_s: 0.0,
                        step: LocalizationStep::GroundLocalizedHere,
                        detail: format!("x={:.3} y={:.3}", p.x, p.y),
                    }],
                });
            }
            // An extension plan's breadcrumbs may already cover this sol: the uplink then
            // needs no new drive plan (paper 000 §8, staffing), unless a fresh ground fix lets
            // the planners extend past a passage limit.
            let covered = policy.style == PlanStyle::Extension
                && next_uplink.unwrap_or(cal.sols.len()) <= breadcrumbs_until
                && (ground_event.is_none() || policy.localizes_onboard);
            if !covered {
                plan_uplink = entry.sol;
                let known = GroundKnowledge {
                    knows_position: ground_knows,
                    last_drive,
                    drives_since_known: sols_since_localization,
                };
                let decided = policy.plan(cal, idx, next_uplink, known);
                panorama_sol = decided.panorama_sol;
                breadcrumbs_until = idx + decided.reasons.len();
                plan_drive[idx..breadcrumbs_until].copy_from_slice(&decided.reasons);
            }
        }

        let skip_reason = policy.skip_reason(
            entry,
            plan_drive[idx],
            RunSoFar {
                goal_reached: goal_sol.is_some(),
                halted_by_fault: halted_by_fault.is_some(),
                sols_since_localization,
                passage,
                driven_since_fix_m,
            },
        );

        let start_uncertainty_m = state.uncertainty.radius_m(&c.model);
        let start_waypoint = state.next_waypoint;
        let mut record = SolRecord {
            sol: entry.sol,
            plan_uplink_sol: plan_uplink,
            drove: skip_reason.is_none(),
            skip_reason,
            distance_m: 0.0,
            d_vo_m: 0.0,
            d_novo_m: 0.0,
            terrain_m: crate::autonav::PerTerrain::default(),
            drive_time_s: 0.0,
            start_uncertainty_m,
            end_uncertainty_m: start_uncertainty_m,
            fault: None,
            passage_clearance_m: None,
            ground_localization: ground_event,
            onboard_localization: None,
            end_position_m: [0.0; 2],
            end_true_position_m: [0.0; 2],
            truth_error_m: estimate_error_m(&state.truth, &state.estimate),
            truth_inside_disc: None,
            reached_goal: false,
            plans: 0,
            shortened_for_passage: None,
            drive_end: None,
            activity_plan: None,
            path_m: Vec::new(),
        };

        if record.drove {
            let (drive_start, mut end) = cal.window_of(idx);
            // The ground's next plan needs this sol's panorama from the afternoon pass.
            let panorama_on_pass = entry.downlink_lmst.is_some() && panorama_sol == Some(idx);
            // What the time limit is, for the sol log: the window, or the pass that cuts it.
            let mut time_end = DriveEnd::DriveWindow { end };
            if let (true, Some(pass)) = (panorama_on_pass, entry.downlink_lmst) {
                let stop = (pass - i64::from(c.post_drive_imaging_s)).max(SolSeconds::MIDNIGHT);
                if stop < end {
                    end = stop;
                    time_end = DriveEnd::PanoramaPass { end, pass };
                }
            }
            let window = DriveLimits {
                max_distance_m: None,
                max_time_s: Some((end - drive_start).max(0) as f64),
            };
            let (mut limits, vo) = policy.drive_budget(entry, window);
            // The record's distance for a replayed sol, before the passage limit joins it.
            let record_distance_m = limits.max_distance_m;
            // The planners' passage limit (paper 000 §2: the drive is shortened).
            let passage_left_m = passage.map(|p| p.budget_since_fix_m - driven_since_fix_m);
            if let Some(left) = passage_left_m {
                limits.max_distance_m = Some(limits.max_distance_m.map_or(left, |m| m.min(left)));
            }
            // The sol's own AutoNav rate, where the record gives one.
            let sol_rover = RoverParams {
                drive_rate_m_per_h: entry
                    .drive_rate_m_per_h
                    .unwrap_or(c.rover.drive_rate_m_per_h),
                ..c.rover
            };
            let sol_ctx = DriveContext {
                rover: &sol_rover,
                ..ctx
            };
            let env = SolEnv {
                c,
                ctx: &sol_ctx,
                sol: entry.sol,
                onboard: policy.localizes_onboard,
                limits,
                vo,
            };
            let request = SolPlanRequest {
                drive_start,
                drive_end: end.max(drive_start),
                drive_rate_m_per_h: sol_rover.drive_rate_m_per_h,
                downlink: entry.downlink_lmst,
                panorama_on_pass,
                chain: env.onboard.then(|| chain_durations(&c.localizer)),
                science: SolScience::default(),
            };
            let run = execute_sol(
                &env,
                &mut SolState {
                    rover: &mut state,
                    progress: &mut progress,
                    rng: &mut rng,
                    astar: &mut astar,
                },
                request,
            );
            let result = run.drive;
            record.activity_plan = Some(run.plan);
            record.distance_m = result.distance_m;
            record.d_vo_m = result.d_vo_m;
            record.d_novo_m = result.d_novo_m;
            record.terrain_m = result.terrain_m;
            record.drive_time_s = result.drive_time_s;
            record.plans = result.plans;
            record.path_m = result.path_m;
            record.reached_goal = result.reached_goal;
            driven_since_fix_m += result.distance_m;
            if passage_left_m.is_some_and(|left| result.distance_m >= left - 1e-6) {
                record.shortened_for_passage = passage;
            }
            let used = |limit: Option<f64>, spent: f64| limit.is_some_and(|l| spent >= l - 1e-6);
            // The last drive segment the sol's plan ran (`drive#4/5`), if the plan split it.
            let last_segment = record.activity_plan.as_ref().and_then(|p| {
                p.timeline
                    .iter()
                    .filter_map(|t| {
                        let (j, k) = t.activity.strip_prefix("drive#")?.split_once('/')?;
                        Some((j.parse::<u32>().ok()?, k.parse::<u32>().ok()?))
                    })
                    .max()
            });
            record.drive_end = Some(if let Some(f) = &result.fault {
                DriveEnd::Fault(f.kind)
            } else if result.reached_goal {
                DriveEnd::ReachedGoal
            } else if let Some(p) = record.shortened_for_passage {
                DriveEnd::ShortenedForPassage(p)
            } else if used(record_distance_m, result.distance_m) {
                DriveEnd::RecordDistance
            } else if used(limits.max_time_s, result.drive_time_s) {
                time_end
            } else if let Some((driven, planned)) = last_segment.filter(|(j, k)| j < k) {
                DriveEnd::PlanCut { driven, planned }
            } else {
                DriveEnd::StepLimit
            });
            if result.fault.is_some() {
                halted_by_fault = Some(idx);
            }
            record.fault = result.fault;
            last_drive = Some(idx);
            moved_since_ground_fix = true;
            sols_since_localization += 1;
            if result.reached_goal {
                goal_sol = Some(entry.sol);
            }
            let end_waypoint = state.next_waypoint.min(c.route.len() - 1).max(1);
            record.passage_clearance_m = legs
                .iter()
                .filter(|l| l.to_waypoint >= start_waypoint.max(1) && l.to_waypoint <= end_waypoint)
                .map(|l| l.clearance_m.unwrap_or(f64::NEG_INFINITY))
                .reduce(f64::min);
            record.end_uncertainty_m = run.end_uncertainty_m;
            record.truth_error_m = run.truth_error_m;
            record.truth_inside_disc =
                Some(record.truth_error_m <= record.end_uncertainty_m + 1e-9);
            if let Some(event) = run.localization {
                if event.applied {
                    sols_since_localization = 0;
                    // The rover checks the plan's passage limits from its own fix.
                    driven_since_fix_m = 0.0;
                    passage = policy.passage_budget(
                        route_position(&c.route, &waypoint_along_m, &state),
                        state.uncertainty.radius_m(&c.model),
                        &ahead,
                    );
                }
                record.onboard_localization = Some(event);
            }
        }
        record.end_position_m = [state.estimate.position_m.x, state.estimate.position_m.y];
        record.end_true_position_m = [state.truth.position_m.x, state.truth.position_m.y];
        records.push(record);
    }

    let mut totals = totals(c, &records, goal_sol, &state);
    for campaign in c.science.campaign_ids() {
        let get =
            |m: &std::collections::BTreeMap<String, u32>| m.get(campaign).copied().unwrap_or(0);
        totals.science.insert(
            campaign.to_string(),
            ScienceTally {
                done: get(&progress.done),
                failed: get(&progress.failed),
            },
        );
    }
    CampaignOutcome {
        strategy,
        seed: c.seed,
        sols: records,
        totals,
    }
}

/// Distance along the route of each waypoint, metres (waypoint 0 at 0).
fn route_along_m(route: &[[f64; 2]]) -> Vec<f64> {
    let mut along = Vec::with_capacity(route.len());
    let mut s = 0.0;
    for (i, w) in route.iter().enumerate() {
        if i > 0 {
            s += (w[0] - route[i - 1][0]).hypot(w[1] - route[i - 1][1]);
        }
        along.push(s);
    }
    along
}

/// Where the rover's estimate lies along the route: projected onto the leg it drives.
fn route_position(route: &[[f64; 2]], along: &[f64], state: &RoverState) -> RoutePosition {
    let next = state.next_waypoint.clamp(1, route.len().max(2) - 1);
    if route.len() < 2 {
        return RoutePosition {
            along_m: 0.0,
            next_waypoint: next,
        };
    }
    let (p, q) = (route[next - 1], route[next]);
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let len2 = dx * dx + dy * dy;
    let e = state.estimate.position_m;
    let t = if len2 > 0.0 {
        (((e.x - p[0]) * dx + (e.y - p[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    RoutePosition {
        along_m: along[next - 1] + t * len2.sqrt(),
        next_waypoint: state.next_waypoint.max(1),
    }
}

fn totals(
    c: &Campaign,
    records: &[SolRecord],
    goal_sol: Option<u32>,
    state: &RoverState,
) -> Totals {
    let first = records.first().map_or(0, |r| r.sol);
    let mut remaining = 0.0;
    if state.next_waypoint < c.route.len() {
        let pos = state.estimate.position_m;
        let wp = c.route[state.next_waypoint];
        remaining += (pos - nalgebra::Vector2::new(wp[0], wp[1])).norm();
        for w in c.route[state.next_waypoint..].windows(2) {
            remaining += ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
        }
    }
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
        route_remaining_m: remaining,
        science: std::collections::BTreeMap::new(),
    }
}
