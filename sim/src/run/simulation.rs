//! [`Simulation`]: one strategy over a scenario's calendar and route, a sol at a time.
//!
//! Each [`Simulation::step`] runs one sol: an uplink (if any) starts a plan — the ground
//! localizes the rover if it has the last drive's data, and the strategy's [`Policy`] decides
//! which of the plan's sols drive — then the rover drives ([`crate::rover::autonav`]) within the
//! sol's budget, then, under onboard strategies, localizes itself ([`crate::localizers`]). A fault
//! halts driving until the ground has seen it. Between steps the rover, its uncertainty and
//! the sols so far can be read; [`Simulation::finish`] runs the rest and returns the
//! [`CampaignOutcome`].
//!
//! Everything random comes from the run's [`RunSeeds`]: one ChaCha8 stream per strategy, and
//! the world's seeds, so a run is reproducible bit for bit.

use std::collections::BTreeMap;

use rand_chacha::ChaCha8Rng;

use crate::grid::astar::PooledAStar;
use crate::operations::policy::{GroundKnowledge, PassagesAhead, PlanStyle, Policy, RunSoFar};
use crate::operations::science::ScienceProgress;
use crate::operations::sol_plan::SolPlanRequest;
use crate::operations::strategy::Strategy;
use crate::rover::autonav::{DriveContext, DriveLimits, RoverSettings, RoverState};
use crate::rover::pose::estimate_error_m;
use crate::run::outcome::{
    ActivityStep, CampaignOutcome, DriveEnd, LegClearance, LocalizationEvent, LocalizationKind,
    LocalizationStep, PassageLimit, ScienceTally, SkipReason, SolRecord, Totals,
};
use crate::run::route::{remaining_m, route_along_m, route_position};
use crate::run::sol::{SolEnv, SolState, chain_durations, execute_sol};
use crate::seeds::{Purpose, RunSeeds};
use crate::settings::Settings;
use crate::time::SolSeconds;

/// One run of one strategy, stepped a sol at a time.
///
/// Settings built in code — an open plain, a 150 m route, three sols — stepped a sol at a
/// time (`study::Scenario::simulation` gives the same from a scenario file):
///
/// ```
/// use std::sync::Arc;
///
/// use maps::{GeoTransform, ZoneSet};
/// use sim::grid::PlanningGrid;
/// use sim::localizers::OnboardLocalizer;
/// use sim::operations::{Calendar, SolEntry};
/// use sim::run::{Simulation, leg_clearances};
/// use sim::seeds::RunSeeds;
/// use sim::time::SolSeconds;
/// use sim::{RoverSettings, Settings, Strategy, UncertaintyModel};
///
/// // 200 m × 200 m of open soil (terrain class 2) at 1 m cells, no zones.
/// let cells = 200 * 200;
/// let origin = GeoTransform::new(0.0, 200.0, 1.0); // north-west corner, 1 m pixels
/// let grid = PlanningGrid::from_parts(
///     &ZoneSet::default(), origin, 200, 200, 1.0, vec![false; cells], vec![2; cells],
/// );
/// let sol = |sol| SolEntry {
///     sol, uplink: true, restricted: false, downlink: true, downlink_lmst: None,
///     drive_allowed: true, window: None, drive_rate_m_per_h: None,
///     historic_planning: None, historic: None,
/// };
/// let settings = Settings {
///     route: vec![[20.0, 100.0], [90.0, 100.0], [170.0, 100.0]],
///     calendar: Calendar {
///         sols: (100..103).map(sol).collect(),
///         drive_start: SolSeconds(40_689), // 11:00 LMST
///         drive_end: SolSeconds(41_613),   // 11:15 LMST: 25 m at 100 m/h
///     },
///     rover: RoverSettings::default(),
///     model: UncertaintyModel::default(),
///     localizer: OnboardLocalizer::default(),
///     operator_margin_m: 1.0,
///     rules: Default::default(),
///     grid: Arc::new(grid),
///     sol_plan: Default::default(),
///     science: Default::default(),
/// };
/// settings.validate().expect("valid settings");
/// let legs = leg_clearances(&settings);
///
/// let mut sim = Simulation::new(&settings, Strategy::Onboard, &legs, RunSeeds::new(7, 0));
/// assert_eq!((sim.strategy(), sim.next_sol()), (Strategy::Onboard, Some(100)));
/// let mut log = Vec::new();
/// while let Some(sol) = sim.step() {
///     // Between sols: what the sol did, and the rover now.
///     let (sol, metres) = (sol.sol, sol.distance_m);
///     log.push((sol, metres, sim.uncertainty_m(), sim.rover().estimate.position_m.x));
/// }
/// assert_eq!(log.iter().map(|l| l.0).collect::<Vec<_>>(), [100, 101, 102]);
/// // Three sols of about 25 m do not reach the end of the 150 m route.
/// assert_eq!((sim.next_sol(), sim.goal_sol(), sim.sols().len()), (None, None, 3));
/// // Each sol drives its 15-minute window, and the onboard localization after it keeps the
/// // disc near the localizer's σ plus the margin (1.93 m), not growing with the distance.
/// assert!(log.iter().all(|&(_, metres, r, _)| metres > 20.0 && r < 2.5), "{log:?}");
/// let outcome = sim.finish();
/// assert_eq!(outcome.totals.drive_sols, 3);
/// ```
#[derive(Debug)]
pub struct Simulation<'a> {
    settings: &'a Settings,
    legs: &'a [LegClearance],
    seeds: RunSeeds,
    policy: Policy,
    rng: ChaCha8Rng,
    astar: PooledAStar<'a>,
    rover: RoverState,
    /// Distance along the route of each waypoint, metres.
    waypoint_along_m: Vec<f64>,
    ops: OpsState,
    plan: PlanInForce,
    progress: ScienceProgress,
    records: Vec<SolRecord>,
}

/// What the operations know and have done so far (between sols).
#[derive(Clone, Debug, Default)]
struct OpsState {
    /// Calendar index of the last drive sol.
    last_drive: Option<usize>,
    /// Whether the rover moved since the ground last localized it.
    moved_since_ground_fix: bool,
    /// Calendar index of the fault that halted driving, until the ground has seen it.
    halted_by_fault: Option<usize>,
    /// Drive sols since the last localization (ground or onboard).
    sols_since_localization: u32,
    /// The sol the rover reached the goal.
    goal_sol: Option<u32>,
    /// Metres driven since the last fix the plan's passage limit counts from.
    driven_since_fix_m: f64,
    /// The plan's passage limit, from the last fix.
    passage: Option<PassageLimit>,
}

/// The plan in force: what the last uplink commanded.
#[derive(Clone, Debug)]
struct PlanInForce {
    /// The sol it was uplinked on.
    uplink_sol: u32,
    /// Per calendar index: `None` if the plan drives that sol, else why not.
    drive: Vec<Option<SkipReason>>,
    /// Extension plans lay breadcrumbs through this calendar index (exclusive).
    breadcrumbs_until: usize,
    /// The calendar index whose panorama the ground needs on the afternoon pass.
    panorama_sol: Option<usize>,
}

impl<'a> Simulation<'a> {
    /// A run of `strategy` with `settings`, before its first sol. `legs` comes from
    /// [`crate::run::leg_clearances`] (once per scenario); `seeds` from
    /// [`RunSeeds::new`]`(scenario seed, run index)`.
    #[must_use]
    pub fn new(
        settings: &'a Settings,
        strategy: Strategy,
        legs: &'a [LegClearance],
        seeds: RunSeeds,
    ) -> Self {
        let c = settings;
        let cal = &c.calendar;
        let rover = RoverState::new(c.route[0], c.model.initial_margin_m);
        let mut sim = Self {
            settings,
            legs,
            seeds,
            policy: Policy::new(strategy, c.rules),
            rng: seeds.stream(Purpose::Strategy(strategy)).rng(),
            astar: c.grid.astar(),
            rover,
            waypoint_along_m: route_along_m(&c.route),
            ops: OpsState::default(),
            plan: PlanInForce {
                uplink_sol: cal.sols.first().map_or(0, |s| s.sol),
                drive: vec![Some(SkipReason::NoPlanUplinked); cal.sols.len()],
                breadcrumbs_until: 0,
                panorama_sol: None,
            },
            progress: ScienceProgress::default(),
            records: Vec::with_capacity(cal.sols.len()),
        };
        sim.ops.passage = sim.passage_budget();
        sim
    }

    /// The strategy being run.
    #[must_use]
    pub fn strategy(&self) -> Strategy {
        self.policy.strategy
    }

    /// The run's seeds.
    #[must_use]
    pub fn seeds(&self) -> RunSeeds {
        self.seeds
    }

    /// The sol the next [`Simulation::step`] runs, or `None` after the calendar's last sol.
    #[must_use]
    pub fn next_sol(&self) -> Option<u32> {
        self.settings
            .calendar
            .sols
            .get(self.records.len())
            .map(|e| e.sol)
    }

    /// The sols run so far, in order.
    #[must_use]
    pub fn sols(&self) -> &[SolRecord] {
        &self.records
    }

    /// The rover now: its true position, its estimate, its uncertainty disc's odometers and
    /// the waypoint it drives to.
    #[must_use]
    pub fn rover(&self) -> &RoverState {
        &self.rover
    }

    /// The rover's uncertainty radius now, metres.
    #[must_use]
    pub fn uncertainty_m(&self) -> f64 {
        self.rover.uncertainty.radius_m(&self.settings.model)
    }

    /// The sol the rover reached the end of the route, if it has.
    #[must_use]
    pub fn goal_sol(&self) -> Option<u32> {
        self.ops.goal_sol
    }

    /// Run the next sol of the calendar and return its record; `None` once every sol has run.
    pub fn step(&mut self) -> Option<&SolRecord> {
        let idx = self.records.len();
        let entry = self.settings.calendar.sols.get(idx)?;
        let ground_event = if entry.uplink { self.uplink(idx) } else { None };
        let skip_reason = self.policy.skip_reason(
            entry,
            self.plan.drive[idx],
            RunSoFar {
                goal_reached: self.ops.goal_sol.is_some(),
                halted_by_fault: self.ops.halted_by_fault.is_some(),
                sols_since_localization: self.ops.sols_since_localization,
                passage: self.ops.passage,
                driven_since_fix_m: self.ops.driven_since_fix_m,
            },
        );
        let start_uncertainty_m = self.uncertainty_m();
        let mut record = SolRecord {
            sol: entry.sol,
            plan_uplink_sol: self.plan.uplink_sol,
            drove: skip_reason.is_none(),
            skip_reason,
            distance_m: 0.0,
            d_vo_m: 0.0,
            d_novo_m: 0.0,
            terrain_m: maps::PerTerrain::default(),
            drive_time_s: 0.0,
            start_uncertainty_m,
            end_uncertainty_m: start_uncertainty_m,
            fault: None,
            passage_clearance_m: None,
            ground_localization: ground_event,
            onboard_localization: None,
            end_position_m: [0.0; 2],
            end_true_position_m: [0.0; 2],
            truth_error_m: estimate_error_m(&self.rover.truth, &self.rover.estimate),
            truth_inside_disc: None,
            reached_goal: false,
            plans: 0,
            shortened_for_passage: None,
            drive_end: None,
            activity_plan: None,
            path_m: Vec::new(),
        };
        if record.drove {
            self.drive(idx, &mut record);
        }
        let (estimate, truth) = (self.rover.estimate.position_m, self.rover.truth.position_m);
        record.end_position_m = [estimate.x, estimate.y];
        record.end_true_position_m = [truth.x, truth.y];
        self.records.push(record);
        self.records.last()
    }

    /// Run every sol left and return the run's outcome.
    #[must_use]
    pub fn finish(mut self) -> CampaignOutcome {
        while self.step().is_some() {}
        let c = self.settings;
        let mut totals = Totals::of(
            &self.records,
            self.ops.goal_sol,
            remaining_m(c, &self.rover),
        );
        for campaign in c.science.campaign_ids() {
            let get = |m: &BTreeMap<String, u32>| m.get(campaign).copied().unwrap_or(0);
            totals.science.insert(
                campaign.to_string(),
                ScienceTally {
                    done: get(&self.progress.done),
                    failed: get(&self.progress.failed),
                },
            );
        }
        CampaignOutcome {
            strategy: self.policy.strategy,
            seed: self.seeds.master(),
            sols: self.records,
            totals,
        }
    }

    /// The plan's passage limit from the rover's last known fix ([`Policy::passage_budget`]),
    /// from what the planners know of the passages ahead and of the last localization.
    fn passage_budget(&self) -> Option<PassageLimit> {
        let c = self.settings;
        let ahead = PassagesAhead {
            legs: self.legs,
            waypoint_along_m: &self.waypoint_along_m,
            k_vo: c.model.k_vo,
            arrival_tolerance_m: c.rover.waypoint_tolerance_m + c.rover.step_m,
        };
        self.policy.passage_budget(
            route_position(&c.route, &self.waypoint_along_m, &self.rover),
            self.uncertainty_m(),
            &ahead,
        )
    }

    /// An uplink sol: the ground localizes the rover if it has the last drive's data, and a new
    /// plan decides which sols drive. Returns the ground's localization, if it made one.
    fn uplink(&mut self, idx: usize) -> Option<LocalizationEvent> {
        let c = self.settings;
        let cal = &c.calendar;
        let entry = &cal.sols[idx];
        let next_uplink = cal.next_uplink_after(idx);
        let ground_knows = self
            .ops
            .last_drive
            .is_none_or(|s| cal.data_available(s, Some(idx)));
        if ground_knows && self.ops.halted_by_fault.is_some() {
            self.ops.halted_by_fault = None;
        }
        let ground_event =
            (ground_knows && self.ops.moved_since_ground_fix).then(|| self.ground_localization());
        // An extension plan's breadcrumbs may already cover this sol: the uplink then needs no
        // new drive plan (paper 000 §8, staffing), unless a fresh ground fix lets the planners
        // extend past a passage limit.
        let covered = self.policy.style == PlanStyle::Extension
            && next_uplink.unwrap_or(cal.sols.len()) <= self.plan.breadcrumbs_until
            && (ground_event.is_none() || self.policy.localizes_onboard);
        if !covered {
            self.plan.uplink_sol = entry.sol;
            let known = GroundKnowledge {
                knows_position: ground_knows,
                last_drive: self.ops.last_drive,
                drives_since_known: self.ops.sols_since_localization,
            };
            let decided = self.policy.plan(cal, idx, next_uplink, known);
            self.plan.panorama_sol = decided.panorama_sol;
            self.plan.breadcrumbs_until = idx + decided.reasons.len();
            self.plan.drive[idx..self.plan.breadcrumbs_until].copy_from_slice(&decided.reasons);
        }
        ground_event
    }

    /// MOB_GROUND_LOCALIZED_HERE with the plan: the mapping specialists matched the last
    /// post-drive panorama to the orbital map. Their fix is good to a HiRISE pixel or so, not
    /// perfect.
    fn ground_localization(&mut self) -> LocalizationEvent {
        let c = self.settings;
        let [de, dn] = c.rover.errors.draw_ground_error(&mut self.rng);
        let state = &mut self.rover;
        state.estimate.position_m = state.truth.position_m + nalgebra::Vector2::new(de, dn);
        state.uncertainty.reset_ground();
        state.clear_path();
        self.ops.moved_since_ground_fix = false;
        self.ops.sols_since_localization = 0;
        self.ops.driven_since_fix_m = 0.0;
        self.ops.passage = self.passage_budget();
        let p = self.rover.estimate.position_m;
        LocalizationEvent {
            kind: LocalizationKind::Ground,
            localizer: "ground",
            applied: true,
            reason: None,
            error_m: Some(de.hypot(dn)),
            matched_error_m: None,
            sigma_m: None,
            search_radius_m: None,
            ellipse: None,
            uncertainty_after_m: self.uncertainty_m(),
            start_lmst: None,
            duration_s: None,
            steps: vec![ActivityStep {
                lmst: None,
                t_s: 0.0,
                step: LocalizationStep::GroundLocalizedHere,
                detail: format!("x={:.3} y={:.3}", p.x, p.y),
            }],
        }
    }

    /// A drive sol: the drive within the sol's budget, then (onboard strategies) the
    /// localization, all into `record`.
    fn drive(&mut self, idx: usize, record: &mut SolRecord) {
        let c = self.settings;
        let cal = &c.calendar;
        let entry = &cal.sols[idx];
        let start_waypoint = self.rover.next_waypoint;
        let (drive_start, mut end) = cal.window_of(idx);
        // The ground's next plan needs this sol's panorama from the afternoon pass.
        let panorama_on_pass = entry.downlink_lmst.is_some() && self.plan.panorama_sol == Some(idx);
        // What the time limit is, for the sol log: the window, or the pass that cuts it.
        let mut time_end = DriveEnd::DriveWindow { end };
        if let (true, Some(pass)) = (panorama_on_pass, entry.downlink_lmst) {
            let stop = (pass - c.sol_plan.imaging_s).max(SolSeconds::MIDNIGHT);
            if stop < end {
                end = stop;
                time_end = DriveEnd::PanoramaPass { end, pass };
            }
        }
        let window = DriveLimits {
            max_distance_m: None,
            max_time_s: Some((end - drive_start).max(0) as f64),
        };
        let (mut limits, vo) = self.policy.drive_budget(entry, window);
        // The record's distance for a replayed sol, before the passage limit joins it.
        let record_distance_m = limits.max_distance_m;
        // The planners' passage limit (paper 000 §2: the drive is shortened).
        let passage = self.ops.passage;
        let passage_left_m = passage.map(|p| p.budget_since_fix_m - self.ops.driven_since_fix_m);
        if let Some(left) = passage_left_m {
            limits.max_distance_m = Some(limits.max_distance_m.map_or(left, |m| m.min(left)));
        }
        // The sol's own AutoNav rate, where the record gives one.
        let sol_rover = RoverSettings {
            drive_rate_m_per_h: entry
                .drive_rate_m_per_h
                .unwrap_or(c.rover.drive_rate_m_per_h),
            ..c.rover
        };
        let ctx = DriveContext {
            grid: &c.grid,
            route: &c.route,
            rover: &sol_rover,
            model: &c.model,
        };
        let env = SolEnv {
            c,
            seeds: self.seeds,
            ctx: &ctx,
            sol: entry.sol,
            onboard: self.policy.localizes_onboard,
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
            science: crate::operations::science::SolScience::default(),
        };
        let run = execute_sol(
            &env,
            &mut SolState {
                rover: &mut self.rover,
                progress: &mut self.progress,
                rng: &mut self.rng,
                astar: &mut self.astar,
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
        self.ops.driven_since_fix_m += result.distance_m;
        if passage_left_m.is_some_and(|left| result.distance_m >= left - 1e-6) {
            record.shortened_for_passage = passage;
        }
        let used = |limit: Option<f64>, spent: f64| limit.is_some_and(|l| spent >= l - 1e-6);
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
        } else if let Some((driven, planned)) = last_segment(record).filter(|(j, k)| j < k) {
            DriveEnd::PlanCut { driven, planned }
        } else {
            DriveEnd::StepLimit
        });
        if result.fault.is_some() {
            self.ops.halted_by_fault = Some(idx);
        }
        record.fault = result.fault;
        self.ops.last_drive = Some(idx);
        self.ops.moved_since_ground_fix = true;
        self.ops.sols_since_localization += 1;
        if result.reached_goal {
            self.ops.goal_sol = Some(entry.sol);
        }
        let end_waypoint = self.rover.next_waypoint.min(c.route.len() - 1).max(1);
        record.passage_clearance_m = self
            .legs
            .iter()
            .filter(|l| l.to_waypoint >= start_waypoint.max(1) && l.to_waypoint <= end_waypoint)
            .map(|l| l.clearance_m.unwrap_or(f64::NEG_INFINITY))
            .reduce(f64::min);
        record.end_uncertainty_m = run.end_uncertainty_m;
        record.truth_error_m = run.truth_error_m;
        record.truth_inside_disc = Some(record.truth_error_m <= record.end_uncertainty_m + 1e-9);
        if let Some(event) = run.localization {
            if event.applied {
                self.ops.sols_since_localization = 0;
                // The rover checks the plan's passage limits from its own fix.
                self.ops.driven_since_fix_m = 0.0;
                self.ops.passage = self.passage_budget();
            }
            record.onboard_localization = Some(event);
        }
    }
}

/// The last drive segment the sol's plan ran (`drive#4/5` → (4, 5)), if the plan split it.
fn last_segment(record: &SolRecord) -> Option<(u32, u32)> {
    record.activity_plan.as_ref().and_then(|p| {
        p.timeline
            .iter()
            .filter_map(|t| {
                let (j, k) = t.activity.strip_prefix("drive#")?.split_once('/')?;
                Some((j.parse::<u32>().ok()?, k.parse::<u32>().ok()?))
            })
            .max()
    })
}
