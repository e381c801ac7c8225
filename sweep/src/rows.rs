//! The rows of a sweep's two tables, and their Arrow schemas.
//!
//! `runs.parquet` has one row per run × strategy ([`RunRow`]), `sols.parquet` one row per
//! run × strategy × sol ([`SolRow`]). Rows are ordered by run index, then by the sweep's
//! strategy order, then by sol. Every column name carries its unit (`_m`, `_s`) or is a count,
//! a flag, an index or a name; a column that has no value for a row (a goal never reached, a
//! sol without a fault) is null.

use std::sync::Arc;

use arrow_array::builder::{
    BooleanBuilder, Float64Builder, StringBuilder, UInt32Builder, UInt64Builder,
};
use arrow_array::cast::AsArray as _;
use arrow_array::types::{Float64Type, UInt32Type, UInt64Type};
use arrow_array::{Array, ArrayRef, RecordBatch};
use arrow_schema::{ArrowError, DataType, Field, Schema, SchemaRef};
use sim::{CampaignOutcome, FaultKind, Strategy};
use study::scenario::StudySegment;

/// One run of one strategy: a row of `runs.parquet`.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRow {
    /// Run index in the sweep (0 = the scenario's own seed).
    pub run_index: u64,
    /// The strategy.
    pub strategy: Strategy,
    /// The run's master seed ([`sim::seeds::RunSeeds::master`]); the strategy's stream is
    /// [`Strategy::stream_id`] under it.
    pub run_seed: u64,
    /// Sols until the end of the route (`None`: not reached within the calendar).
    pub sols_to_goal: Option<u32>,
    /// Whether the end of the route was reached.
    pub goal_reached: bool,
    /// Sols on which the rover drove.
    pub drive_sols: u32,
    /// Metres driven.
    pub distance_m: f64,
    /// Metres of route left at the end.
    pub route_remaining_m: f64,
    /// AutoNav NO_PATH faults.
    pub no_path_faults: u32,
    /// KEEP_OUT faults (the true footprint entered a keep-out).
    pub keep_out_faults: u32,
    /// KEEP_IN faults (the true footprint left the keep-in).
    pub keep_in_faults: u32,
    /// All faults.
    pub faults: u32,
    /// Largest position-uncertainty radius, metres.
    pub max_uncertainty_m: f64,
    /// Onboard localizations applied.
    pub onboard_localizations_applied: u32,
    /// Onboard localizations rejected (validity checks, co-processor losses).
    pub onboard_localizations_rejected: u32,
    /// Ground localizations.
    pub ground_localizations: u32,
    /// Sols that ended with the true position outside the uncertainty disc.
    pub truth_outside_disc_sols: u32,
    /// Largest distance between the estimated and the true position at the end of a sol, m.
    pub max_truth_error_m: f64,
    /// Sols to cover the study segment (`None`: no segment, or not covered).
    pub segment_sols: Option<u32>,
    /// Metres driven from the study segment's first sol to the end of the calendar (`None`:
    /// no segment).
    pub segment_distance_m: Option<f64>,
    /// Time spent driving, seconds ([`CampaignOutcome::drive_time_s`]).
    pub drive_time_s: f64,
    /// Uplinks whose plan commanded a drive ([`CampaignOutcome::drive_plan_uplinks`]).
    pub drive_plan_uplinks: u32,
}

/// One sol of one run of one strategy: a row of `sols.parquet`.
#[derive(Debug, Clone, PartialEq)]
pub struct SolRow {
    /// Run index in the sweep.
    pub run_index: u64,
    /// The strategy.
    pub strategy: Strategy,
    /// Mission sol number.
    pub sol: u32,
    /// Sol of the uplink whose plan this sol ran.
    pub plan_uplink_sol: u32,
    /// Whether the rover drove.
    pub drove: bool,
    /// Why it did not drive (the sol log's sentence).
    pub skip_reason: Option<String>,
    /// Metres driven.
    pub distance_m: f64,
    /// Metres driven with visual odometry.
    pub vo_distance_m: f64,
    /// Metres driven without visual odometry.
    pub novo_distance_m: f64,
    /// Driving time, seconds.
    pub drive_time_s: f64,
    /// Uncertainty radius at the start of the sol, metres.
    pub start_uncertainty_m: f64,
    /// Uncertainty radius at the end of the sol, metres.
    pub end_uncertainty_m: f64,
    /// The fault that ended the drive (`NO_PATH`, `KEEP_OUT`, `KEEP_IN`).
    pub fault: Option<FaultKind>,
    /// Metres driven before the fault.
    pub fault_after_m: Option<f64>,
    /// Uncertainty radius at the fault, metres.
    pub fault_uncertainty_m: Option<f64>,
    /// Clearance of the narrowest passage on the sol's leg, metres (`None` also when a leg has
    /// no path at any radius).
    pub passage_clearance_m: Option<f64>,
    /// Whether the ground localized the rover with this sol's uplink.
    pub ground_localized: bool,
    /// Whether an onboard localization ran after the drive.
    pub onboard_localization: bool,
    /// Whether it was applied.
    pub onboard_applied: Option<bool>,
    /// Why it was rejected.
    pub onboard_rejection: Option<String>,
    /// Distance from the applied onboard estimate to the truth, metres.
    pub onboard_error_m: Option<f64>,
    /// Distance from the estimated to the true position at the end of the sol, metres.
    pub truth_error_m: f64,
    /// Whether the true position lay inside the uncertainty disc at the end of the drive
    /// (`None`: no drive this sol, nothing checked).
    pub truth_inside_disc: Option<bool>,
    /// Whether the rover reached the end of the route this sol.
    pub reached_goal: bool,
    /// Estimated position at the end of the sol, map easting, metres.
    pub end_x_m: f64,
    /// Estimated position at the end of the sol, map northing, metres.
    pub end_y_m: f64,
    /// True position at the end of the sol, map easting, metres.
    pub end_true_x_m: f64,
    /// True position at the end of the sol, map northing, metres.
    pub end_true_y_m: f64,
}

/// The rows of one run of one strategy.
#[must_use]
pub fn rows_of(
    run_index: u64,
    run_seed: u64,
    outcome: &CampaignOutcome,
    segment: Option<StudySegment>,
) -> (RunRow, Vec<SolRow>) {
    let t = &outcome.totals;
    let count = |kind: FaultKind| {
        outcome
            .sols
            .iter()
            .filter(|s| s.fault.as_ref().is_some_and(|f| f.kind == kind))
            .count() as u32
    };
    let run = RunRow {
        run_index,
        strategy: outcome.strategy,
        run_seed,
        sols_to_goal: t.sols_to_goal,
        goal_reached: t.goal_reached,
        drive_sols: t.drive_sols,
        distance_m: t.distance_m,
        route_remaining_m: t.route_remaining_m,
        no_path_faults: t.no_path_faults,
        keep_out_faults: count(FaultKind::KeepOut),
        keep_in_faults: count(FaultKind::KeepIn),
        faults: t.faults,
        max_uncertainty_m: t.max_uncertainty_m,
        onboard_localizations_applied: t.onboard_localizations_applied,
        onboard_localizations_rejected: t.onboard_localizations_rejected,
        ground_localizations: t.ground_localizations,
        truth_outside_disc_sols: t.truth_outside_disc,
        max_truth_error_m: outcome
            .sols
            .iter()
            .map(|s| s.truth_error_m)
            .fold(0.0, f64::max),
        segment_sols: segment.and_then(|g| outcome.sols_to_cover(g.from_sol, g.distance_m)),
        segment_distance_m: segment.map(|g| {
            outcome
                .sols
                .iter()
                .filter(|s| s.sol >= g.from_sol)
                .map(|s| s.distance_m)
                .sum()
        }),
        drive_time_s: outcome.drive_time_s(),
        drive_plan_uplinks: outcome.drive_plan_uplinks(),
    };
    let sols = outcome
        .sols
        .iter()
        .map(|s| {
            let onboard = s.onboard_localization.as_ref();
            SolRow {
                run_index,
                strategy: outcome.strategy,
                sol: s.sol,
                plan_uplink_sol: s.plan_uplink_sol,
                drove: s.drove,
                skip_reason: s.skip_reason.map(|r| r.to_string()),
                distance_m: s.distance_m,
                vo_distance_m: s.d_vo_m,
                novo_distance_m: s.d_novo_m,
                drive_time_s: s.drive_time_s,
                start_uncertainty_m: s.start_uncertainty_m,
                end_uncertainty_m: s.end_uncertainty_m,
                fault: s.fault.as_ref().map(|f| f.kind),
                fault_after_m: s.fault.as_ref().map(|f| f.after_m),
                fault_uncertainty_m: s.fault.as_ref().map(|f| f.uncertainty_m),
                // −∞ (no path at any radius) is stored as null: Parquet readers need not
                // expect infinities.
                passage_clearance_m: s.passage_clearance_m.filter(|v| v.is_finite()),
                ground_localized: s.ground_localization.is_some(),
                onboard_localization: onboard.is_some(),
                onboard_applied: onboard.map(|e| e.applied),
                onboard_rejection: onboard.and_then(|e| e.reason.as_ref().map(|r| r.to_string())),
                onboard_error_m: onboard.and_then(|e| e.error_m),
                truth_error_m: s.truth_error_m,
                truth_inside_disc: s.truth_inside_disc,
                reached_goal: s.reached_goal,
                end_x_m: s.end_position_m[0],
                end_y_m: s.end_position_m[1],
                end_true_x_m: s.end_true_position_m[0],
                end_true_y_m: s.end_true_position_m[1],
            }
        })
        .collect();
    (run, sols)
}

fn field(name: &str, data_type: DataType, nullable: bool) -> Field {
    Field::new(name, data_type, nullable)
}

/// The schema of `runs.parquet`, in column order.
#[must_use]
pub fn runs_schema() -> SchemaRef {
    use DataType::{Boolean, Float64, UInt32, UInt64, Utf8};
    Arc::new(Schema::new(vec![
        field("run_index", UInt64, false),
        field("strategy", Utf8, false),
        field("run_seed", UInt64, false),
        field("sols_to_goal", UInt32, true),
        field("goal_reached", Boolean, false),
        field("drive_sols", UInt32, false),
        field("distance_m", Float64, false),
        field("route_remaining_m", Float64, false),
        field("no_path_faults", UInt32, false),
        field("keep_out_faults", UInt32, false),
        field("keep_in_faults", UInt32, false),
        field("faults", UInt32, false),
        field("max_uncertainty_m", Float64, false),
        field("onboard_localizations_applied", UInt32, false),
        field("onboard_localizations_rejected", UInt32, false),
        field("ground_localizations", UInt32, false),
        field("truth_outside_disc_sols", UInt32, false),
        field("max_truth_error_m", Float64, false),
        field("segment_sols", UInt32, true),
        field("segment_distance_m", Float64, true),
        field("drive_time_s", Float64, false),
        field("drive_plan_uplinks", UInt32, false),
    ]))
}

/// The schema of `sols.parquet`, in column order.
#[must_use]
pub fn sols_schema() -> SchemaRef {
    use DataType::{Boolean, Float64, UInt32, UInt64, Utf8};
    Arc::new(Schema::new(vec![
        field("run_index", UInt64, false),
        field("strategy", Utf8, false),
        field("sol", UInt32, false),
        field("plan_uplink_sol", UInt32, false),
        field("drove", Boolean, false),
        field("skip_reason", Utf8, true),
        field("distance_m", Float64, false),
        field("vo_distance_m", Float64, false),
        field("novo_distance_m", Float64, false),
        field("drive_time_s", Float64, false),
        field("start_uncertainty_m", Float64, false),
        field("end_uncertainty_m", Float64, false),
        field("fault", Utf8, true),
        field("fault_after_m", Float64, true),
        field("fault_uncertainty_m", Float64, true),
        field("passage_clearance_m", Float64, true),
        field("ground_localized", Boolean, false),
        field("onboard_localization", Boolean, false),
        field("onboard_applied", Boolean, true),
        field("onboard_rejection", Utf8, true),
        field("onboard_error_m", Float64, true),
        field("truth_error_m", Float64, false),
        field("truth_inside_disc", Boolean, true),
        field("reached_goal", Boolean, false),
        field("end_x_m", Float64, false),
        field("end_y_m", Float64, false),
        field("end_true_x_m", Float64, false),
        field("end_true_y_m", Float64, false),
    ]))
}

fn u64s<T>(rows: &[T], f: impl Fn(&T) -> u64) -> ArrayRef {
    let mut b = UInt64Builder::with_capacity(rows.len());
    rows.iter().for_each(|r| b.append_value(f(r)));
    Arc::new(b.finish())
}

fn u32s<T>(rows: &[T], f: impl Fn(&T) -> Option<u32>) -> ArrayRef {
    let mut b = UInt32Builder::with_capacity(rows.len());
    rows.iter().for_each(|r| b.append_option(f(r)));
    Arc::new(b.finish())
}

fn f64s<T>(rows: &[T], f: impl Fn(&T) -> Option<f64>) -> ArrayRef {
    let mut b = Float64Builder::with_capacity(rows.len());
    rows.iter().for_each(|r| b.append_option(f(r)));
    Arc::new(b.finish())
}

fn bools<T>(rows: &[T], f: impl Fn(&T) -> Option<bool>) -> ArrayRef {
    let mut b = BooleanBuilder::with_capacity(rows.len());
    rows.iter().for_each(|r| b.append_option(f(r)));
    Arc::new(b.finish())
}

fn strings<T>(rows: &[T], f: impl Fn(&T) -> Option<&str>) -> ArrayRef {
    let mut b = StringBuilder::new();
    rows.iter().for_each(|r| b.append_option(f(r)));
    Arc::new(b.finish())
}

/// `runs.parquet` rows as an Arrow batch.
///
/// # Errors
/// Only if the columns disagree with [`runs_schema`] (a bug).
pub fn runs_batch(rows: &[RunRow]) -> Result<RecordBatch, ArrowError> {
    RecordBatch::try_new(
        runs_schema(),
        vec![
            u64s(rows, |r| r.run_index),
            strings(rows, |r| Some(r.strategy.name())),
            u64s(rows, |r| r.run_seed),
            u32s(rows, |r| r.sols_to_goal),
            bools(rows, |r| Some(r.goal_reached)),
            u32s(rows, |r| Some(r.drive_sols)),
            f64s(rows, |r| Some(r.distance_m)),
            f64s(rows, |r| Some(r.route_remaining_m)),
            u32s(rows, |r| Some(r.no_path_faults)),
            u32s(rows, |r| Some(r.keep_out_faults)),
            u32s(rows, |r| Some(r.keep_in_faults)),
            u32s(rows, |r| Some(r.faults)),
            f64s(rows, |r| Some(r.max_uncertainty_m)),
            u32s(rows, |r| Some(r.onboard_localizations_applied)),
            u32s(rows, |r| Some(r.onboard_localizations_rejected)),
            u32s(rows, |r| Some(r.ground_localizations)),
            u32s(rows, |r| Some(r.truth_outside_disc_sols)),
            f64s(rows, |r| Some(r.max_truth_error_m)),
            u32s(rows, |r| r.segment_sols),
            f64s(rows, |r| r.segment_distance_m),
            f64s(rows, |r| Some(r.drive_time_s)),
            u32s(rows, |r| Some(r.drive_plan_uplinks)),
        ],
    )
}

/// `sols.parquet` rows as an Arrow batch.
///
/// # Errors
/// Only if the columns disagree with [`sols_schema`] (a bug).
pub fn sols_batch(rows: &[SolRow]) -> Result<RecordBatch, ArrowError> {
    RecordBatch::try_new(
        sols_schema(),
        vec![
            u64s(rows, |r| r.run_index),
            strings(rows, |r| Some(r.strategy.name())),
            u32s(rows, |r| Some(r.sol)),
            u32s(rows, |r| Some(r.plan_uplink_sol)),
            bools(rows, |r| Some(r.drove)),
            strings(rows, |r| r.skip_reason.as_deref()),
            f64s(rows, |r| Some(r.distance_m)),
            f64s(rows, |r| Some(r.vo_distance_m)),
            f64s(rows, |r| Some(r.novo_distance_m)),
            f64s(rows, |r| Some(r.drive_time_s)),
            f64s(rows, |r| Some(r.start_uncertainty_m)),
            f64s(rows, |r| Some(r.end_uncertainty_m)),
            strings(rows, |r| r.fault.map(FaultKind::name)),
            f64s(rows, |r| r.fault_after_m),
            f64s(rows, |r| r.fault_uncertainty_m),
            f64s(rows, |r| r.passage_clearance_m),
            bools(rows, |r| Some(r.ground_localized)),
            bools(rows, |r| Some(r.onboard_localization)),
            bools(rows, |r| r.onboard_applied),
            strings(rows, |r| r.onboard_rejection.as_deref()),
            f64s(rows, |r| r.onboard_error_m),
            f64s(rows, |r| Some(r.truth_error_m)),
            bools(rows, |r| r.truth_inside_disc),
            bools(rows, |r| Some(r.reached_goal)),
            f64s(rows, |r| Some(r.end_x_m)),
            f64s(rows, |r| Some(r.end_y_m)),
            f64s(rows, |r| Some(r.end_true_x_m)),
            f64s(rows, |r| Some(r.end_true_y_m)),
        ],
    )
}

fn bad(what: &str) -> ArrowError {
    ArrowError::SchemaError(format!("runs table: {what}"))
}

/// Reads [`RunRow`]s back from a batch with the [`runs_schema`] (what the statistics need).
///
/// # Errors
/// A batch whose schema is not [`runs_schema`], or an unknown strategy name.
pub fn run_rows_from(batch: &RecordBatch) -> Result<Vec<RunRow>, ArrowError> {
    if batch.schema() != runs_schema() {
        return Err(bad("the columns are not those of runs.parquet"));
    }
    let c = |i: usize| batch.column(i);
    let u64c = |i: usize| c(i).as_primitive::<UInt64Type>().clone();
    let u32c = |i: usize| c(i).as_primitive::<UInt32Type>().clone();
    let f64c = |i: usize| c(i).as_primitive::<Float64Type>().clone();
    let (run_index, strategy, run_seed) = (u64c(0), c(1).as_string::<i32>().clone(), u64c(2));
    let (sols_to_goal, goal_reached) = (u32c(3), c(4).as_boolean().clone());
    let opt = |a: &arrow_array::UInt32Array, i: usize| (!a.is_null(i)).then(|| a.value(i));
    let [
        drive_sols,
        no_path,
        keep_out,
        keep_in,
        faults,
        applied,
        rejected,
        ground,
        outside,
        segment,
        plan_uplinks,
    ] = [5, 8, 9, 10, 11, 13, 14, 15, 16, 18, 21].map(u32c);
    let [distance, remaining, max_r, max_truth, drive_time] = [6, 7, 12, 17, 20].map(f64c);
    let segment_distance = f64c(19);
    (0..batch.num_rows())
        .map(|i| {
            let name = strategy.value(i);
            Ok(RunRow {
                run_index: run_index.value(i),
                strategy: Strategy::from_name(name)
                    .ok_or_else(|| bad(&format!("unknown strategy {name:?}")))?,
                run_seed: run_seed.value(i),
                sols_to_goal: opt(&sols_to_goal, i),
                goal_reached: goal_reached.value(i),
                drive_sols: drive_sols.value(i),
                distance_m: distance.value(i),
                route_remaining_m: remaining.value(i),
                no_path_faults: no_path.value(i),
                keep_out_faults: keep_out.value(i),
                keep_in_faults: keep_in.value(i),
                faults: faults.value(i),
                max_uncertainty_m: max_r.value(i),
                onboard_localizations_applied: applied.value(i),
                onboard_localizations_rejected: rejected.value(i),
                ground_localizations: ground.value(i),
                truth_outside_disc_sols: outside.value(i),
                max_truth_error_m: max_truth.value(i),
                segment_sols: opt(&segment, i),
                segment_distance_m: (!segment_distance.is_null(i))
                    .then(|| segment_distance.value(i)),
                drive_time_s: drive_time.value(i),
                drive_plan_uplinks: plan_uplinks.value(i),
            })
        })
        .collect()
}
