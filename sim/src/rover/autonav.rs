//! One sol's drive: AutoNav follows the route's waypoints in steps of a few metres.
//!
//! Before every step the rover checks that the rest of its current path is still open at the
//! current uncertainty `r` (zones only grow as `r` grows, so an open path stays open until `r`
//! passes the smallest clearance on it); when it is not, or when a new waypoint becomes the
//! target, it re-plans with A* on the [`PlanningGrid`]. No path → `NO_PATH` fault. The rover
//! itself standing in a grown keep-out (or outside the shrunk keep-in) → `KEEP_OUT` / `KEEP_IN`.
//!
//! Each step, Visual Odometry fails with a probability set by the terrain class under the
//! wheels (or, in a replay, the historic fraction of distance without VO is charged); the true
//! motion slips and is turned by the sol's heading knowledge error; the estimate follows VO's
//! measurement (with the sol's scale error and per-step noise, but in the direction the rover
//! believes it heads) or, without VO, the commanded motion (blind to slip). The odometry
//! distance feeds the uncertainty model. [`crate::rover::errors`] lists every error term.

use nalgebra::{Rotation2, Vector2};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use crate::grid::astar::AStar;
use crate::grid::planning_grid::PlanningGrid;
use crate::rover::errors::SolErrors;
use crate::rover::pose::{EstimatedPose, TruePose};
use crate::rover::slip_profile::{SlipTable, along_across};
use crate::rover::uncertainty::{UncertaintyModel, UncertaintyState};
use crate::run::outcome::{Fault, FaultKind};
use maps::{PerTerrain, TerrainClass};

/// Upper bound on AutoNav steps in one sol (a fixed loop bound: at 2 m a step this is 200 km;
/// a sol that reaches it simply ends).
pub const MAX_STEPS_PER_SOL: usize = 100_000;

mod settings;

pub use settings::{ProfileSlip, RoverSettings, SlipModel};

/// Probability that VO fails on a step at slip 1, added in proportion to slip above 0.2 (at
/// slip `s`: `class rate + 0.5 × max(0, s − 0.2) / 0.8`). Judgement, not calibrated: a wheel
/// churning sand sprays the near field VO tracks and drags the rover off the features it
/// expected; below 20 % slip VO is taken to work as on level ground. Only
/// [`SlipModel::Profile`] uses it.
pub const VO_FAILURE_AT_FULL_SLIP: f64 = 0.5;

/// Where VO success comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VoSource {
    /// Drawn per step from the terrain class under the wheels.
    Terrain,
    /// Replay: this fraction of the distance is charged as driven without VO.
    Historic {
        /// Fraction 0..=1 of distance without VO.
        novo_fraction: f64,
    },
}

/// What ends a sol's drive besides faults and the end of the route.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriveLimits {
    /// Odometry distance budget, metres (replays: the historic distance).
    pub max_distance_m: Option<f64>,
    /// Driving time budget, seconds (what-if runs: the drive window).
    pub max_time_s: Option<f64>,
}

/// The rover as the simulator tracks it across sols.
#[derive(Clone, Debug)]
pub struct RoverState {
    /// Ground truth.
    pub truth: TruePose,
    /// The rover's belief.
    pub estimate: EstimatedPose,
    /// Odometers and margin.
    pub uncertainty: UncertaintyState,
    /// Index in the route of the waypoint being driven to.
    pub next_waypoint: usize,
    path: Option<FollowedPath>,
}

impl RoverState {
    /// A rover at `start` (truth and estimate agree) heading for route waypoint 1.
    #[must_use]
    pub fn new(start: [f64; 2], initial_margin_m: f64) -> Self {
        let p = Vector2::new(start[0], start[1]);
        Self {
            truth: TruePose { position_m: p },
            estimate: EstimatedPose { position_m: p },
            uncertainty: UncertaintyState {
                margin_m: initial_margin_m,
                ..Default::default()
            },
            next_waypoint: 1,
            path: None,
        }
    }

    /// Forget the current path (after the estimate jumps, e.g. a localization).
    pub fn clear_path(&mut self) {
        self.path = None;
    }
}

/// What one sol's drive did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DriveResult {
    /// Odometry distance, metres.
    pub distance_m: f64,
    /// Of which with VO, metres.
    pub d_vo_m: f64,
    /// Of which without VO, metres.
    pub d_novo_m: f64,
    /// Driving time, seconds.
    pub drive_time_s: f64,
    /// The fault that ended the drive, if any.
    pub fault: Option<Fault>,
    /// Whether the last waypoint was reached.
    pub reached_goal: bool,
    /// A* runs.
    pub plans: u32,
    /// Estimated positions, one per step (the start included).
    pub path_m: Vec<[f64; 2]>,
    /// Odometry distance by the terrain class under the true wheels, metres.
    pub terrain_m: PerTerrain,
}

/// A planned path being followed.
#[derive(Clone, Debug)]
struct FollowedPath {
    waypoint: usize,
    points: Vec<Vector2<f64>>,
    cum_len_m: Vec<f64>,
    cells: Vec<usize>,
    /// `suffix_min[i]` = smallest clearance of cells `i..`.
    suffix_min: Vec<f32>,
    progress_m: f64,
}

impl FollowedPath {
    fn point_at(&self, s: f64) -> Vector2<f64> {
        let last = self.points.len() - 1;
        if s >= self.cum_len_m[last] {
            return self.points[last];
        }
        let i = self.cum_len_m.partition_point(|&c| c <= s).max(1);
        let (a, b) = (self.points[i - 1], self.points[i]);
        let seg = self.cum_len_m[i] - self.cum_len_m[i - 1];
        let t = if seg > 0.0 {
            (s - self.cum_len_m[i - 1]) / seg
        } else {
            0.0
        };
        a + (b - a) * t
    }

    fn open_ahead(&self, r_m: f64) -> bool {
        let i = self
            .cum_len_m
            .partition_point(|&c| c < self.progress_m)
            .min(self.cells.len() - 1);
        f64::from(self.suffix_min[i]) > r_m
    }
}

/// The static inputs of a drive.
pub struct DriveContext<'a> {
    /// Planning grid.
    pub grid: &'a PlanningGrid,
    /// Route waypoints, map metres; waypoint 0 is the start.
    pub route: &'a [[f64; 2]],
    /// Rover settings.
    pub rover: &'a RoverSettings,
    /// Uncertainty growth.
    pub model: &'a UncertaintyModel,
}

/// Drive one sol (or one segment of it) under the sol's error draws `errs`
/// ([`crate::rover::errors::ErrorModel::draw_sol`]). Advances `state` and returns what happened.
pub fn drive_sol(
    ctx: &DriveContext<'_>,
    state: &mut RoverState,
    limits: DriveLimits,
    vo: VoSource,
    errs: SolErrors,
    rng: &mut ChaCha8Rng,
    astar: &mut AStar,
) -> DriveResult {
    let rover = ctx.rover;
    let grid = ctx.grid;
    let mut out = DriveResult {
        path_m: vec![to_array(state.estimate.position_m)],
        ..Default::default()
    };
    let errors = &rover.errors;
    let heading_err = Rotation2::new(errs.heading_error_rad);
    let rate_m_per_s = rover.drive_rate_m_per_h / 3600.0;
    // A rate that underflows to 0 m/s (5e-324 m/h) made each step's time infinite and the
    // drive time NaN, which then lifted the time limit: the rover drove 537 m in a sol. A rover
    // that cannot move in finite time does not drive ([`RoverSettings::validate`] refuses such a
    // rate; this keeps settings built in code and never validated from running on).
    if !(rate_m_per_s > 0.0 && rate_m_per_s.is_finite()) {
        return out;
    }
    for _ in 0..MAX_STEPS_PER_SOL {
        if state.next_waypoint >= ctx.route.len() {
            out.reached_goal = true;
            break;
        }
        let distance_left = limits
            .max_distance_m
            .map_or(f64::INFINITY, |m| m - out.distance_m);
        let time_left = limits
            .max_time_s
            .map_or(f64::INFINITY, |t| t - out.drive_time_s);
        // Written so a NaN budget (a time or distance computed from nonsense) ends the drive
        // rather than lifting its limit.
        if !(distance_left > 1e-9 && time_left > 1e-9) {
            break;
        }
        let r = state.uncertainty.radius_m(ctx.model);
        let est = state.estimate.position_m;
        // Waypoint reached?
        let wp = ctx.route[state.next_waypoint];
        if (est - Vector2::new(wp[0], wp[1])).norm() <= rover.waypoint_tolerance_m {
            state.next_waypoint += 1;
            state.path = None;
            continue;
        }
        // The rover's own cell must be open.
        let fault_at = |kind| Fault {
            kind,
            after_m: out.distance_m,
            uncertainty_m: r,
            position_m: to_array(est),
        };
        let Some(here) = grid.cell_of(to_array(est)) else {
            out.fault = Some(fault_at(FaultKind::KeepIn));
            break;
        };
        if f64::from(grid.keep_out_clearance_m[here]) <= r {
            out.fault = Some(fault_at(FaultKind::KeepOut));
            break;
        }
        if f64::from(grid.keep_in_clearance_m[here]) <= r {
            out.fault = Some(fault_at(FaultKind::KeepIn));
            break;
        }
        let needs_plan = match &state.path {
            None => true,
            Some(p) => p.waypoint != state.next_waypoint || !p.open_ahead(r),
        };
        if needs_plan {
            out.plans += 1;
            match plan_path(ctx, astar, here, state.next_waypoint, est, r) {
                Some(p) => state.path = Some(p),
                None => {
                    state.path = None;
                    out.fault = Some(fault_at(FaultKind::NoPath));
                    break;
                }
            }
        }
        let Some(path) = state.path.as_mut() else {
            break;
        };
        // Command a step toward the carrot one step ahead on the path.
        let carrot = path.point_at(path.progress_m + rover.step_m);
        let mut cmd = carrot - est;
        let mut cmd_len = cmd.norm();
        if cmd_len < 1e-6 {
            // At the end of the path but outside the waypoint tolerance: aim at the waypoint.
            cmd = Vector2::new(wp[0], wp[1]) - est;
            cmd_len = cmd.norm();
            if cmd_len > rover.step_m {
                cmd *= rover.step_m / cmd_len;
                cmd_len = rover.step_m;
            }
        }
        if cmd_len * 1.0 / rate_m_per_s > time_left {
            cmd *= time_left * rate_m_per_s / cmd_len;
            cmd_len = time_left * rate_m_per_s;
        }
        // The world: terrain under the true wheels, VO, slip.
        let class = grid
            .cell_of(to_array(state.truth.position_m))
            .map_or(TerrainClass::Soil, |c| grid.terrain_class(c));
        // The mean slip of the step: per class, or from the profile along the true heading.
        let (mean_slip, slip_range) = match rover.slip_model {
            SlipModel::Terrain => (errors.slip_fraction.get(class), (0.0, 0.9)),
            SlipModel::Profile(_) => {
                let (along, across) =
                    slope_components(grid, state.truth.position_m, heading_err * cmd);
                (
                    f64::from(SlipTable::bundled().slip(class, along, across)),
                    (-0.9, 0.95),
                )
            }
        };
        let draw: f64 = rng.random();
        let (vo_ok, novo_fraction) = match vo {
            VoSource::Terrain => {
                let p_fail = match rover.slip_model {
                    SlipModel::Terrain => errors.vo_failure.get(class),
                    SlipModel::Profile(_) => {
                        errors.vo_failure.get(class)
                            + VO_FAILURE_AT_FULL_SLIP * ((mean_slip - 0.2) / 0.8).clamp(0.0, 1.0)
                    }
                };
                let ok = draw >= p_fail;
                (ok, if ok { 0.0 } else { 1.0 })
            }
            VoSource::Historic { novo_fraction } => (draw >= novo_fraction, novo_fraction),
        };
        let slip_noise: f64 = rng.sample(StandardNormal);
        // `mean × (1 + σ n)`; a braking (negative) mean spreads by its magnitude.
        let slip = if mean_slip >= 0.0 {
            mean_slip * (1.0 + errors.slip_sigma_relative * slip_noise)
        } else {
            mean_slip * (1.0 - errors.slip_sigma_relative * slip_noise)
        }
        .clamp(slip_range.0, slip_range.1);
        // The rover commands `cmd` in the frame it believes; the world turns it by the heading
        // knowledge error. VO measures the motion in the rover's frame (so it sees the slip,
        // not the heading error), scaled by the sol's scale error, plus noise; without VO the
        // estimate takes the command (wheel odometry, blind to slip).
        let progress = cmd * (1.0 - slip);
        let mut d_true = heading_err * progress;
        let noise = Vector2::new(
            rng.sample::<f64, _>(StandardNormal),
            rng.sample::<f64, _>(StandardNormal),
        );
        let mut d_est = if vo_ok {
            progress * (1.0 + errs.vo_scale_error) + noise * (errors.vo_noise_fraction * cmd_len)
        } else {
            cmd
        };
        // The flight software's slip check: VO measured this step's progress against the
        // command. Without VO the rover cannot see its slip.
        let measured_slip = if vo_ok && cmd_len > 0.0 {
            1.0 - d_est.dot(&cmd) / (cmd_len * cmd_len)
        } else {
            0.0
        };
        let mut odo = d_est.norm();
        if odo > distance_left {
            let f = distance_left / odo;
            d_true *= f;
            d_est *= f;
            cmd_len *= f;
            odo = distance_left;
        }
        state.truth.position_m += d_true;
        state.estimate.position_m += d_est;
        state.uncertainty.drive(odo, novo_fraction);
        out.distance_m += odo;
        out.d_novo_m += odo * novo_fraction;
        out.d_vo_m += odo * (1.0 - novo_fraction);
        out.terrain_m.add(class, odo);
        // A zero-length step takes no time (0 / 0 would be a NaN that lifts the time limit).
        if cmd_len > 0.0 {
            out.drive_time_s += cmd_len / rate_m_per_s;
        }
        path.progress_m += odo;
        out.path_m.push(to_array(state.estimate.position_m));
        if let SlipModel::Profile(p) = rover.slip_model
            && measured_slip > p.slip_limit
        {
            out.fault = Some(Fault {
                kind: FaultKind::Slip,
                after_m: out.distance_m,
                uncertainty_m: state.uncertainty.radius_m(ctx.model),
                position_m: to_array(state.estimate.position_m),
            });
            break;
        }
    }
    out
}

/// The slope's tangent along `heading` (positive uphill) and across it, at `at` on the grid's
/// gradient layer; level where the grid has none or `at` is off it.
fn slope_components(grid: &PlanningGrid, at: Vector2<f64>, heading: Vector2<f64>) -> (f32, f32) {
    let g = grid
        .cell_of(to_array(at))
        .and_then(|i| grid.gradient.get(i))
        .copied()
        .unwrap_or([0.0; 2]);
    let n = heading.norm();
    if n <= 0.0 {
        return (0.0, 0.0);
    }
    along_across(g, (heading.x / n) as f32, (heading.y / n) as f32)
}

/// Plan from cell `here` to route waypoint `waypoint` at uncertainty `r_m`.
fn plan_path(
    ctx: &DriveContext<'_>,
    astar: &mut AStar,
    here: usize,
    waypoint: usize,
    est: Vector2<f64>,
    r_m: f64,
) -> Option<FollowedPath> {
    let grid = ctx.grid;
    let goal = grid.cell_of(ctx.route[waypoint])?;
    let buffer = ctx.rover.edge_buffer_m.max(1e-9);
    let edge_factor = |i: usize| {
        let margin = f64::from(grid.clearance_m[i]) - r_m;
        1.0 + (1.0 - margin / buffer).clamp(0.0, 1.0)
    };
    let found = match ctx.rover.slip_model {
        SlipModel::Profile(p) if p.aware_routing && !grid.gradient.is_empty() => {
            let table = SlipTable::bundled();
            let width = grid.width;
            let (limit, max_tilt) = (p.avoid_slip_above as f32, p.max_tilt_deg as f32);
            astar.plan_edges(here, goal, 1.0, |from, to| {
                if to != here && grid.closed(to, r_m) {
                    return f32::INFINITY;
                }
                if from == to {
                    return 1.0;
                }
                // The move's direction on the map (x east, y north; rows run south).
                let (dr, dc) = (
                    (to / width) as f32 - (from / width) as f32,
                    (to % width) as f32 - (from % width) as f32,
                );
                let len = dr.hypot(dc);
                let (along, across) = along_across(grid.gradient[to], dc / len, -dr / len);
                let class = grid.terrain_class(to);
                let slip = table.slip(class, along, across);
                if slip > limit || table.tilt_deg(class, along, across) > max_tilt {
                    return f32::INFINITY;
                }
                // Drive time per metre of progress.
                (f64::from(1.0 / (1.0 - slip.max(0.0))) * edge_factor(to)) as f32
            })?
        }
        _ => astar.plan(here, goal, 1.0, |i| {
            if i != here && grid.closed(i, r_m) {
                return f32::INFINITY;
            }
            (ctx.rover.terrain_cost.get(grid.terrain_class(i)) * edge_factor(i)) as f32
        })?,
    };
    let mut points: Vec<Vector2<f64>> = found
        .cells
        .iter()
        .map(|&c| {
            let p = grid.center_of(c);
            Vector2::new(p[0], p[1])
        })
        .collect();
    points[0] = est;
    if let Some(last) = points.last_mut() {
        let wp = ctx.route[waypoint];
        *last = Vector2::new(wp[0], wp[1]);
    }
    let mut cum_len_m = Vec::with_capacity(points.len());
    let mut acc = 0.0;
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            acc += (p - points[i - 1]).norm();
        }
        cum_len_m.push(acc);
    }
    let mut suffix_min = vec![f32::INFINITY; found.cells.len()];
    let mut m = f32::INFINITY;
    for (k, &c) in found.cells.iter().enumerate().rev() {
        if k > 0 {
            m = m.min(grid.clearance_m[c]);
        }
        suffix_min[k] = m;
    }
    Some(FollowedPath {
        waypoint,
        points,
        cum_len_m,
        cells: found.cells,
        suffix_min,
        progress_m: 0.0,
    })
}

fn to_array(v: Vector2<f64>) -> [f64; 2] {
    [v.x, v.y]
}
