//! One run of a paper 004 Table 1 case: the true drive, the IMU and measurement streams it
//! produces, and the filter run over them.
//!
//! Randomness comes from `ChaCha8Rng::seed_from_u64(seed)` split into four streams
//! (`set_stream`): 0 the drive, 1 the IMU noise, 2 the range noise, 3 the fix noise. A range noise
//! is drawn every second whether or not the orbiter is visible, so the four cases of one seed share
//! the drive and every normal draw (the cases differ only in σ), and a seed's cases compare
//! directly.

use nalgebra::Vector2;
use rand::RngExt;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::case_settings::{CaseError, CaseSettings, Table1Case};
use super::filter::{Ekf, EkfInitError};
use super::imu::{ImuSample, sample_imu};
use super::mars::NavigationFrame;
use super::measurement::{PositionFix, RangeMeasurement, elevation_rad, predicted_range_m};
use super::orbit::Ephemeris;
use super::state::{StateCovariance, StateVector, ix};
use super::trajectory::{TrueState, TruthTrajectory};
use super::tuning::FilterTuning;

/// Everything the filter is fed, in time order (so that another filter can be fed the same).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MeasurementStreams {
    /// IMU samples at `0..=duration_s`; step k (from k−1 to k s) uses samples k−1 and k.
    pub imu: Vec<ImuSample>,
    /// Ranges, at most one per second; at second k the filter applies the range first, then
    /// the fix.
    pub ranges: Vec<RangeMeasurement>,
    /// Position fixes, at most one per second.
    pub fixes: Vec<PositionFix>,
}

/// The truth and the filter's belief after the updates of one second.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StepRecord {
    /// The true state.
    pub truth: TrueState,
    /// The estimate.
    pub estimate: StateVector,
    /// Its covariance.
    pub covariance: StateCovariance,
    /// Estimated minus true east position, metres.
    pub error_east_m: f64,
    /// Estimated minus true north position, metres.
    pub error_north_m: f64,
    /// Horizontal distance between estimate and truth, metres.
    pub error_total_m: f64,
}

impl StepRecord {
    /// The filter's 1σ of east and north position, metres.
    pub fn sigma_enu_m(&self) -> [f64; 2] {
        [
            self.covariance[(ix::EAST, ix::EAST)].sqrt(),
            self.covariance[(ix::NORTH, ix::NORTH)].sqrt(),
        ]
    }
}

/// Maximum, RMS and final total position error over a span of a run, metres.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ErrorSummary {
    /// Largest total error.
    pub max_m: f64,
    /// Root mean square of the total error.
    pub rms_m: f64,
    /// Total error at the last second.
    pub final_m: f64,
}

/// One run of a case: settings, the filter's tuning, the streams, and the per-second record.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CaseRun {
    /// The settings run.
    pub settings: CaseSettings,
    /// The seed of the four random streams.
    pub seed: u64,
    /// `x̂₀`, `P₀`, `Q`, `R` of the filter.
    pub tuning: FilterTuning,
    /// What the filter was fed.
    pub streams: MeasurementStreams,
    /// One record per second, `t = 0..=duration_s` (t = 0 is the initial estimate).
    pub steps: Vec<StepRecord>,
    /// Updates skipped because `H P Hᵀ + R` could not be inverted (a bad outcome, not an error).
    pub rejected_updates: u32,
}

impl CaseRun {
    /// The error summary over the seconds `t_s >= from_t_s` (`None` if there are none).
    pub fn error_summary(&self, from_t_s: u32) -> Option<ErrorSummary> {
        let errors: Vec<f64> = self
            .steps
            .iter()
            .filter(|s| s.truth.t_s >= from_t_s)
            .map(|s| s.error_total_m)
            .collect();
        let final_m = *errors.last()?;
        let mean_square = errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64;
        Some(ErrorSummary {
            max_m: errors.iter().copied().fold(0.0, f64::max),
            rms_m: mean_square.sqrt(),
            final_m,
        })
    }
}

/// Runs `case` with paper 004 §5's settings and the default (bias-estimating) filter.
pub fn run_case(case: Table1Case, seed: u64) -> CaseRun {
    run_with(&CaseSettings::table1(case), seed).expect("the Table 1 settings are valid")
}

/// Runs the settings: draws the drive and the sensor streams from `seed` ([`simulate`]), then
/// filters them with the settings' filter ([`filter_streams`]).
pub fn run_with(settings: &CaseSettings, seed: u64) -> Result<CaseRun, CaseError> {
    let Simulation { truth, streams } = simulate(settings, seed)?;
    let tuning = settings.tuning(&truth[0]);
    let filtered = filter_streams(&settings.frame, &tuning, &truth, &streams)?;
    Ok(CaseRun {
        settings: *settings,
        seed,
        tuning,
        streams,
        steps: filtered.steps,
        rejected_updates: filtered.rejected_updates,
    })
}

/// The true drive and the sensor streams of one seed, before any filtering.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Simulation {
    /// The true state at `0..=duration_s`.
    pub truth: Vec<TrueState>,
    /// What the sensors report.
    pub streams: MeasurementStreams,
}

/// Draws the drive and the IMU, range and fix streams of `settings` from `seed`.
pub fn simulate(settings: &CaseSettings, seed: u64) -> Result<Simulation, CaseError> {
    settings.validate()?;
    let stream = |id: u64| {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(id);
        rng
    };
    let truth =
        TruthTrajectory::generate(&settings.trajectory, settings.duration_s, &mut stream(0));
    let truth = truth.states().to_vec();
    let streams = MeasurementStreams {
        imu: sample_imu(&truth, &settings.imu, &mut stream(1)),
        ranges: draw_ranges(settings, &truth, &mut stream(2)),
        fixes: draw_fixes(settings, &truth, &mut stream(3)),
    };
    Ok(Simulation { truth, streams })
}

/// A filter's per-second record over a simulation.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FilteredRun {
    /// One record per IMU sample (the first is the initial estimate).
    pub steps: Vec<StepRecord>,
    /// Updates skipped because `H P Hᵀ + R` was not positive definite.
    pub rejected_updates: u32,
}

/// Runs an [`Ekf`] with `tuning` over `streams` in `frame`, recording it against `truth`.
///
/// The IMU samples must be in time order, and `truth[k]` the state at the time of
/// `streams.imu[k]` (as [`simulate`] makes them);
/// records stop at the shorter of the two. At each IMU sample after the first the filter
/// predicts, then applies the range taken at that sample's second, then the fix.
pub fn filter_streams(
    frame: &NavigationFrame,
    tuning: &FilterTuning,
    truth: &[TrueState],
    streams: &MeasurementStreams,
) -> Result<FilteredRun, EkfInitError> {
    let mut ekf = Ekf::new(
        tuning.initial_state,
        tuning.initial_covariance,
        tuning.process_noise,
    )?;
    let mut steps = Vec::with_capacity(truth.len());
    if let Some(first) = truth.first() {
        steps.push(record(first, &ekf));
    }
    let mut ranges = streams.ranges.iter().peekable();
    let mut fixes = streams.fixes.iter().peekable();
    let mut rejected_updates = 0;
    for (imu, true_state) in streams.imu.windows(2).zip(truth.iter().skip(1)) {
        let (u0, u1) = (&imu[0], &imu[1]);
        ekf.predict(u0, u1, f64::from(u1.t_s) - f64::from(u0.t_s));
        let t_s = u1.t_s;
        // A measurement at a second with no step (before the first, or between samples) is
        // not used.
        while ranges.next_if(|r| r.t_s < t_s).is_some() {}
        while fixes.next_if(|f| f.t_s < t_s).is_some() {}
        if let Some(r) = ranges.next_if(|r| r.t_s == t_s) {
            let update = ekf.try_update_range(
                frame,
                f64::from(r.t_s),
                r.range_m,
                &r.orbiter_position_mci_m,
                tuning.range_variance_m2,
            );
            rejected_updates += u32::from(update.is_none());
        }
        if let Some(f) = fixes.next_if(|f| f.t_s == t_s) {
            let update = ekf.try_update_fix(&f.position_enu_m, tuning.fix_variance_m2);
            rejected_updates += u32::from(update.is_none());
        }
        steps.push(record(true_state, &ekf));
    }
    Ok(FilteredRun {
        steps,
        rejected_updates,
    })
}

fn record(truth: &TrueState, ekf: &Ekf) -> StepRecord {
    let error = ekf.position_enu_m() - truth.position_enu_m;
    StepRecord {
        truth: *truth,
        estimate: *ekf.state(),
        covariance: *ekf.covariance(),
        error_east_m: error.x,
        error_north_m: error.y,
        error_total_m: error.norm(),
    }
}

/// Ranges at every `range_period_s` while the orbiter is above the mask, seen from the true
/// position; one normal draw per second regardless.
fn draw_ranges(
    s: &CaseSettings,
    truth: &[TrueState],
    rng: &mut ChaCha8Rng,
) -> Vec<RangeMeasurement> {
    let ephemeris = Ephemeris::propagate(s.orbit.state_at(0.0), s.duration_s);
    let mask_rad = s.elevation_mask_deg.to_radians();
    let mut ranges = Vec::new();
    for (state, orbiter) in truth.iter().zip(ephemeris.states()).skip(1) {
        let noise: f64 = rng.sample(StandardNormal);
        let t = f64::from(state.t_s);
        let r_o = orbiter.position_mci_m;
        let visible = elevation_rad(&s.frame, t, &state.position_enu_m, &r_o) >= mask_rad;
        if visible && state.t_s % s.range_period_s == 0 {
            ranges.push(RangeMeasurement {
                t_s: state.t_s,
                range_m: predicted_range_m(&s.frame, t, &state.position_enu_m, &r_o)
                    + s.range_sigma_m * noise,
                orbiter_position_mci_m: r_o,
            });
        }
    }
    ranges
}

/// Position fixes at every `fix_period_s`; two normal draws (east, north) per second regardless.
fn draw_fixes(s: &CaseSettings, truth: &[TrueState], rng: &mut ChaCha8Rng) -> Vec<PositionFix> {
    let mut fixes = Vec::new();
    for state in truth.iter().skip(1) {
        let noise = Vector2::new(
            rng.sample::<f64, _>(StandardNormal),
            rng.sample::<f64, _>(StandardNormal),
        );
        if state.t_s % s.fix_period_s == 0 {
            fixes.push(PositionFix {
                t_s: state.t_s,
                position_enu_m: state.position_enu_m + s.image_resolution_m * noise,
            });
        }
    }
    fixes
}

/// `P` is symmetric and positive definite (Cholesky succeeds), for tests.
#[cfg(test)]
pub(crate) fn is_spd(p: &StateCovariance) -> bool {
    (p - p.transpose()).amax() <= 1e-12 * p.amax() && p.cholesky().is_some()
}
