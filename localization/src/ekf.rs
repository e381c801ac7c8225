//! Rover localization by an extended Kalman filter fusing the IMU, radio ranges to an orbiting
//! beacon and terrain-matching position fixes (paper 004: Jiang, Li, Tao and Wang, "Multi-information
//! fusion based localization algorithm for Mars rover", 2014).
//!
//! - [`Ekf`]: the filter — [`Ekf::predict`] from two IMU samples, [`Ekf::try_update_range`],
//!   [`Ekf::try_update_fix`], and [`Ekf::position_covariance_m2`] for an uncertainty disc.
//!   [`propagate_state`] and [`transition_matrix`] are its process model.
//! - [`FilterModel`] and [`FilterTuning`]: the paper's 4-state filter or the bias-estimating one,
//!   with their `P₀`, `Q`, `R` (and how the paper's `R` maps to these measurements).
//! - [`run_case`] / [`run_with`]: one [`Table1Case`] over the paper's 1000 s drive — truth, the
//!   [`MeasurementStreams`], and per-second [`StepRecord`]s in a [`CaseRun`]; the two halves,
//!   [`simulate`] (truth and streams of a seed) and [`filter_streams`] (any [`FilterTuning`] over
//!   given streams), for feeding several filters the same data.
//! - The world: [`NavigationFrame`] (ENU at a [`Site`] on rotating Mars → MCI),
//!   [`CircularOrbit`] and its RK4 [`Ephemeris`], the random drive [`TruthTrajectory`], the
//!   IMU ([`ImuErrors`], [`sample_imu`]), and the measurement models ([`predicted_range_m`],
//!   [`range_jacobian`], [`elevation_rad`], [`position_fix_jacobian`]).
//! - [`parked_fix`]: the filter as the simulator's post-drive localizer, a parked rover
//!   ranging through one pass with zero-velocity updates ([`ParkedSettings`], [`ParkedFix`]).
//!
//! ## State
//! The paper estimates `X = [p, v]`, position and velocity in the navigation (east-north-up) frame
//! (§4.1; `P₀` and `Q` of §5 are 4×4, in metres). Issue 14 adds the IMU biases; a bias acts in
//! the body frame, so the heading that turns body into ENU joins the state:
//!
//! `x = [e, n, v_e, v_n, ψ, b_ax, b_ay, b_g]` (m, m, m/s, m/s, rad, m/s², m/s², rad/s — [`ix`]).
//!
//! Position is metres on the plane tangent at the site rather than the latitude and longitude of
//! eq. 2 (`D = I` then); the rover moves ~150 m in a run. Only the horizontal accelerometer axes
//! and the yaw gyro matter on level ground; the z bias is read by the accelerometer but
//! dropped with z (`Ξ[·]₃→₂`). [`FilterModel::Paper`] freezes `ψ, b_a, b_g` (zero covariance),
//! which is exactly the paper's 4-state filter.
//!
//! ## Observability
//! Ranges and fixes observe position; the accelerometer biases reach position through `½bt²`
//! (1.5 km of drift in 1000 s for 3e-3 m/s²) and are well observed. The gyro bias reaches position
//! only through heading error times acceleration (`5e-6 rad/s × 1000 s × ~1e-3 m/s²`), so it stays
//! near its prior: it is in the state for the issue's sake and for longer drives.
//!
//! ```
//! use localization::ekf::{Table1Case, run_case};
//!
//! let run = run_case(Table1Case::Case4, 7);
//! assert_eq!(run.steps.len(), 1001); // t = 0..=1000 s
//! let last_half = run.error_summary(500).expect("the run has seconds 500..=1000");
//! assert!(last_half.rms_m < 0.35, "{last_half:?}");
//! ```
//!
//! ## References
//! Paper 004 §2.1 (frames), §2.3 eq. 2 (dynamics), §3.1-§3.3 eqs. 3-11 (gyro, range, camera),
//! §4 eqs. 19-30 (EKF, Joseph form), §5 (parameters, X₀, P₀, Q, R) and Table 1 (the four cases).

mod case_settings;
mod filter;
mod imu;
mod mars;
mod measurement;
mod orbit;
mod parked;
mod state;
mod table1;
mod trajectory;
mod tuning;

pub use case_settings::{CaseError, CaseSettings, Table1Case};
pub use filter::{
    Ekf, EkfInitError, Innovation, process_jacobian, propagate_state, transition_matrix,
};
pub use imu::{ImuErrors, ImuSample, sample_imu};
pub use mars::{
    MARS_RADIUS_M, MARS_ROTATION_RAD_PER_S, MARS_SURFACE_GRAVITY_M_PER_S2, MU_MARS_M3_PER_S2,
    NavigationFrame, Site,
};
pub use measurement::{
    PositionFix, RangeMeasurement, elevation_rad, fix_covariance_m2, position_fix_jacobian,
    predicted_fix_m, predicted_range_m, range_jacobian,
};
pub use orbit::{CircularOrbit, Ephemeris, OrbitState};
pub use parked::{ParkedFix, ParkedSettings, parked_fix};
pub use state::{STATE_DIM, StateCovariance, StateVector, ix};
pub use table1::{
    CaseRun, ErrorSummary, FilteredRun, MeasurementStreams, Simulation, StepRecord, filter_streams,
    run_case, run_with, simulate,
};
pub use trajectory::{TrajectorySettings, TrueState, TruthTrajectory};
pub use tuning::{BiasPriors, FilterModel, FilterTuning};

#[cfg(test)]
mod tests;
