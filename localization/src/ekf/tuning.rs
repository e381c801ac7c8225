//! The filter's initial covariance `P₀`, process noise `Q` and measurement noise `R`: the paper's
//! values (§5), or values derived from the simulated sensors.
//!
//! ## Paper 004 §5 and what it maps to here
//! - `X₀ = [0, 0, 0.1, 0.1]`: the initial estimate (and the true initial state) of `[p, v]`.
//! - `P₀ = diag(10² I₂, I₂)`, `Q = diag(25 I₂, 4 I₂)` per 1 s step: used as printed for `[p, v]`
//!   in both models (P₀) and in [`FilterModel::Paper`] (Q).
//! - `R = diag(9e-8, 10, 1e-6 I₂)` for `[ω̃, R̃, m̃]`:
//!   - **9e-8 (rad/s)²** is the gyro's noise variance. Yaw rate is not a state of the paper's
//!     `X = [p, v]`, so `∂ω̃/∂X = 0` and it cannot be an EKF measurement; here the gyro drives the
//!     propagation (heading) and 9e-8 is its simulated noise.
//!   - **10 m²** is the range noise the paper's filter assumes, one value for all four cases
//!     while Table 1 sets the simulated range accuracy to 10 m or 1 m. [`FilterModel::Paper`]
//!     keeps 10 m²; [`FilterModel::BiasEstimating`] uses the simulated σ².
//!   - **1e-6 I₂** is in image-plane units of eq. 11 (the paper gives neither focal length nor
//!     landmark distances, so it has no value in metres) and does not change with the image
//!     resolution of Table 1. Both models use the simulated fix variance (one pixel)² instead —
//!     the only way Table 1's resolution reaches the filter. (Read as 1e-6 m², it would make the
//!     filter copy each fix, and cases 1-2 and 3-4 would be identical.)

use super::imu::ImuErrors;
use super::state::{StateCovariance, StateVector, ix};

/// Which filter runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub enum FilterModel {
    /// Paper 004's 4-state filter `[p, v]`: the biases are not estimated (the filter integrates
    /// the raw IMU outputs) and the paper's `Q` absorbs them. Implemented as the 8-state filter
    /// with zero covariance and zero process noise on heading and biases, which is exactly the
    /// 4-state filter: their gains stay zero and `[p, v]` evolves as the 4-state one would.
    Paper,
    /// `[p, v, ψ, b_a, b_g]` (issue 14): accelerometer and gyro biases estimated, `Q` from the
    /// IMU noise, `R` from the simulated sensors (default).
    #[default]
    BiasEstimating,
}

/// `P₀`, `Q` and `R` of one filter.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct FilterTuning {
    /// Initial estimate `x̂₀`.
    pub initial_state: StateVector,
    /// Initial covariance `P₀`.
    pub initial_covariance: StateCovariance,
    /// Process noise `Q` added per 1 s step.
    pub process_noise: StateCovariance,
    /// Range noise variance the filter assumes, m².
    pub range_variance_m2: f64,
    /// Position-fix noise variance per axis the filter assumes, m².
    pub fix_variance_m2: f64,
}

/// Settings of the bias-estimating model that the paper does not give.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct BiasPriors {
    /// Prior σ of the initial heading, radians (default: 1e-3; the run starts from a known
    /// attitude, as the paper's gyro integration assumes).
    pub heading_sigma_rad: f64,
    /// Prior σ of each horizontal accelerometer bias, m/s² (default: 3e-3: the MER-class bias of
    /// paper 004 §5 as a 1σ value, sign unknown).
    pub accel_bias_sigma_m_per_s2: f64,
    /// Prior σ of the gyro bias, rad/s (default: 5e-6, likewise).
    pub gyro_bias_sigma_rad_per_s: f64,
    /// Random walk of the accelerometer biases, m/s² per √s (default: 1e-7: the truth is
    /// constant; a floor 10⁴ below the bias keeps the biases' gain from vanishing on long runs).
    pub accel_bias_walk_m_per_s2_per_sqrt_s: f64,
    /// Random walk of the gyro bias, rad/s per √s (default: 1e-10).
    pub gyro_bias_walk_rad_per_s_per_sqrt_s: f64,
}

impl Default for BiasPriors {
    fn default() -> Self {
        Self {
            heading_sigma_rad: 1e-3,
            accel_bias_sigma_m_per_s2: 3e-3,
            gyro_bias_sigma_rad_per_s: 5e-6,
            accel_bias_walk_m_per_s2_per_sqrt_s: 1e-7,
            gyro_bias_walk_rad_per_s_per_sqrt_s: 1e-10,
        }
    }
}

/// Paper 004 §5's `P₀` on `[p, v]`: `diag(10² I₂, I₂)`.
fn paper_p0_position_velocity(p0: &mut StateCovariance) {
    for (i, var) in [
        (ix::EAST, 100.0),
        (ix::NORTH, 100.0),
        (ix::VEL_EAST, 1.0),
        (ix::VEL_NORTH, 1.0),
    ] {
        p0[(i, i)] = var;
    }
}

impl FilterTuning {
    /// Paper 004's filter: `P₀`, `Q` as printed in §5, `R_range = 10 m²`, fix variance
    /// `fix_variance_m2` (see the module doc for why not 1e-6). `x0` is the initial estimate.
    pub fn paper(x0: StateVector, fix_variance_m2: f64) -> Self {
        let mut p0 = StateCovariance::zeros();
        paper_p0_position_velocity(&mut p0);
        let mut q = StateCovariance::zeros();
        for (i, var) in [
            (ix::EAST, 25.0),
            (ix::NORTH, 25.0),
            (ix::VEL_EAST, 4.0),
            (ix::VEL_NORTH, 4.0),
        ] {
            q[(i, i)] = var;
        }
        Self {
            initial_state: x0,
            initial_covariance: p0,
            process_noise: q,
            range_variance_m2: 10.0,
            fix_variance_m2,
        }
    }

    /// The bias-estimating filter: `P₀` on `[p, v]` from the paper, `priors` on heading and
    /// biases; `Q` from `imu`'s white noise (per 1 s step: velocity `σ_a²`, position `σ_a²/3`,
    /// their covariance `σ_a²/2`, heading `σ_ω²`) plus the biases' random walks; `R` the given
    /// simulated variances.
    pub fn bias_estimating(
        x0: StateVector,
        imu: &ImuErrors,
        priors: &BiasPriors,
        range_variance_m2: f64,
        fix_variance_m2: f64,
    ) -> Self {
        let mut p0 = StateCovariance::zeros();
        paper_p0_position_velocity(&mut p0);
        p0[(ix::HEADING, ix::HEADING)] = priors.heading_sigma_rad.powi(2);
        p0[(ix::ACCEL_BIAS_X, ix::ACCEL_BIAS_X)] = priors.accel_bias_sigma_m_per_s2.powi(2);
        p0[(ix::ACCEL_BIAS_Y, ix::ACCEL_BIAS_Y)] = priors.accel_bias_sigma_m_per_s2.powi(2);
        p0[(ix::GYRO_BIAS, ix::GYRO_BIAS)] = priors.gyro_bias_sigma_rad_per_s.powi(2);
        // White acceleration of variance σ_a² per 1 s sample = PSD σ_a²·(1 s); over Δt = 1 s:
        // [[Δt³/3, Δt²/2], [Δt²/2, Δt]]·PSD on each axis.
        let qa = imu.accel_noise_var_m2_per_s4;
        let mut q = StateCovariance::zeros();
        for (p, v) in [(ix::EAST, ix::VEL_EAST), (ix::NORTH, ix::VEL_NORTH)] {
            q[(p, p)] = qa / 3.0;
            q[(p, v)] = qa / 2.0;
            q[(v, p)] = qa / 2.0;
            q[(v, v)] = qa;
        }
        q[(ix::HEADING, ix::HEADING)] = imu.gyro_noise_var_rad2_per_s2;
        let walk_a = priors.accel_bias_walk_m_per_s2_per_sqrt_s.powi(2);
        q[(ix::ACCEL_BIAS_X, ix::ACCEL_BIAS_X)] = walk_a;
        q[(ix::ACCEL_BIAS_Y, ix::ACCEL_BIAS_Y)] = walk_a;
        q[(ix::GYRO_BIAS, ix::GYRO_BIAS)] = priors.gyro_bias_walk_rad_per_s_per_sqrt_s.powi(2);
        Self {
            initial_state: x0,
            initial_covariance: p0,
            process_noise: q,
            range_variance_m2,
            fix_variance_m2,
        }
    }
}
