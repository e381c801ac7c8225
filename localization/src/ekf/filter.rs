//! The extended Kalman filter of paper 004 §4: IMU propagation by RK4 (eq. 26), covariance
//! propagation through the transition matrix (eq. 27), and measurement updates with the Joseph
//! form of the covariance (eqs. 28-30).
//!
//! ## Process model
//! Between IMU samples `u₀ = (ã₀, ω̃₀)` at `t` and `u₁` at `t + Δt` the input is interpolated
//! linearly (causal: the step is taken when `u₁` arrives), and
//!
//! ```text
//! ṗ = v,   v̇ = R(ψ)·(ã_xy − b_a),   ψ̇ = ω̃ − b_g,   ḃ_a = 0,   ḃ_g = 0
//! ```
//!
//! with `R(ψ)` the 2-D rotation of eq. 1 at zero roll and pitch, integrated by classical RK4 over
//! the step (paper §5). The transition matrix is `Φ = exp(FΔt)` for the Jacobian `F = ∂f/∂x`
//! taken at the start of the step with the mean input; `F⁴ = 0` for this model, so
//! `Φ = I + FΔt + F²Δt²/2 + F³Δt³/6` exactly. (Eq. 19's first-order `I + FΔt` is the same for the
//! paper's 4-state `[p, v]`, where `F² = 0`, but drops the `½Δt²` path from the biases to position
//! once they are states.)

use nalgebra::{SMatrix, SVector, Vector2};

use super::imu::ImuSample;
use super::mars::NavigationFrame;
use super::measurement::{
    position_fix_jacobian, predicted_fix_m, predicted_range_m, range_jacobian,
};
use super::state::{STATE_DIM, StateCovariance, StateVector, ix, symmetrized};

/// Why a filter could not be built from the given initial values (bad input).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EkfInitError {
    /// A value of the state or of a matrix is NaN or infinite.
    #[error("{what} has a non-finite value")]
    NonFinite {
        /// `"initial state"`, `"initial covariance"` or `"process noise"`.
        what: &'static str,
    },
    /// A covariance is not symmetric, or is not positive semidefinite.
    #[error("{what} is not a symmetric positive semidefinite matrix")]
    NotCovariance {
        /// `"initial covariance"` or `"process noise"`.
        what: &'static str,
    },
}

/// What one measurement update did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Innovation<const M: usize> {
    /// `y = z − h(x⁻)`, in the measurement's units.
    pub residual: SVector<f64, M>,
    /// Its predicted covariance `S = H P⁻ Hᵀ + R`.
    pub covariance: SMatrix<f64, M, M>,
}

/// `f(x, u)`: the state's time derivative for accelerometer `accel_xy` (body x, y, m/s²) and
/// yaw rate `yaw_rate` (rad/s).
fn derivative(x: &StateVector, accel_xy: &Vector2<f64>, yaw_rate: f64) -> StateVector {
    let (sin, cos) = x[ix::HEADING].sin_cos();
    let ax = accel_xy.x - x[ix::ACCEL_BIAS_X];
    let ay = accel_xy.y - x[ix::ACCEL_BIAS_Y];
    let mut d = StateVector::zeros();
    d[ix::EAST] = x[ix::VEL_EAST];
    d[ix::NORTH] = x[ix::VEL_NORTH];
    d[ix::VEL_EAST] = cos * ax - sin * ay;
    d[ix::VEL_NORTH] = sin * ax + cos * ay;
    d[ix::HEADING] = yaw_rate - x[ix::GYRO_BIAS];
    d
}

/// The state propagated by one RK4 step of `dt_s` seconds from IMU sample `u0` to `u1`
/// (eq. 26; input interpolated linearly across the step).
pub fn propagate_state(x: &StateVector, u0: &ImuSample, u1: &ImuSample, dt_s: f64) -> StateVector {
    let a0 = u0.accel_body_m_per_s2.xy();
    let a1 = u1.accel_body_m_per_s2.xy();
    let (a_mid, w_mid) = (
        (a0 + a1) * 0.5,
        0.5 * (u0.yaw_rate_rad_per_s + u1.yaw_rate_rad_per_s),
    );
    let k1 = derivative(x, &a0, u0.yaw_rate_rad_per_s);
    let k2 = derivative(&(x + 0.5 * dt_s * k1), &a_mid, w_mid);
    let k3 = derivative(&(x + 0.5 * dt_s * k2), &a_mid, w_mid);
    let k4 = derivative(&(x + dt_s * k3), &a1, u1.yaw_rate_rad_per_s);
    x + dt_s / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
}

/// `F = ∂f/∂x` at `x` for the mean input of the step from `u0` to `u1` (eq. 22).
pub fn process_jacobian(x: &StateVector, u0: &ImuSample, u1: &ImuSample) -> StateCovariance {
    let accel = (u0.accel_body_m_per_s2.xy() + u1.accel_body_m_per_s2.xy()) * 0.5;
    let (sin, cos) = x[ix::HEADING].sin_cos();
    let ax = accel.x - x[ix::ACCEL_BIAS_X];
    let ay = accel.y - x[ix::ACCEL_BIAS_Y];
    let mut f = StateCovariance::zeros();
    f[(ix::EAST, ix::VEL_EAST)] = 1.0;
    f[(ix::NORTH, ix::VEL_NORTH)] = 1.0;
    f[(ix::VEL_EAST, ix::HEADING)] = -sin * ax - cos * ay;
    f[(ix::VEL_NORTH, ix::HEADING)] = cos * ax - sin * ay;
    f[(ix::VEL_EAST, ix::ACCEL_BIAS_X)] = -cos;
    f[(ix::VEL_EAST, ix::ACCEL_BIAS_Y)] = sin;
    f[(ix::VEL_NORTH, ix::ACCEL_BIAS_X)] = -sin;
    f[(ix::VEL_NORTH, ix::ACCEL_BIAS_Y)] = -cos;
    f[(ix::HEADING, ix::GYRO_BIAS)] = -1.0;
    f
}

/// The transition matrix `Φ = I + FΔt + F²Δt²/2 + F³Δt³/6` of one step (exact `exp(FΔt)`, since
/// `F⁴ = 0`), dimensionless in the state's units.
pub fn transition_matrix(
    x: &StateVector,
    u0: &ImuSample,
    u1: &ImuSample,
    dt_s: f64,
) -> StateCovariance {
    let f_dt = process_jacobian(x, u0, u1) * dt_s;
    let f2 = f_dt * f_dt;
    StateCovariance::identity() + f_dt + f2 * 0.5 + f2 * f_dt / 6.0
}

/// The extended Kalman filter: state, covariance and the per-step process noise.
///
/// ```
/// use localization::ekf::{Ekf, ImuSample, StateCovariance, StateVector, ix};
/// use nalgebra::{Vector2, Vector3};
///
/// let mut ekf = Ekf::new(
///     StateVector::zeros(),
///     StateCovariance::identity(),
///     StateCovariance::identity() * 1e-6,
/// )?;
/// let still = |t_s| ImuSample { t_s, accel_body_m_per_s2: Vector3::zeros(), yaw_rate_rad_per_s: 0.0 };
/// ekf.predict(&still(0), &still(1), 1.0);
/// let fix = ekf.try_update_fix(&Vector2::new(0.5, 0.0), 0.25).expect("S is invertible");
/// assert_eq!(fix.residual, Vector2::new(0.5, 0.0));
/// assert!(ekf.state()[ix::EAST] > 0.0 && ekf.position_covariance_m2()[(0, 0)] < 0.25);
/// # Ok::<(), localization::ekf::EkfInitError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Ekf {
    x: StateVector,
    p: StateCovariance,
    q: StateCovariance,
}

impl Ekf {
    /// A filter at estimate `x0` with covariance `p0`, adding `q` to the covariance each step
    /// (units: [`ix`] and their products).
    pub fn new(
        x0: StateVector,
        p0: StateCovariance,
        q: StateCovariance,
    ) -> Result<Self, EkfInitError> {
        if x0.iter().any(|v| !v.is_finite()) {
            return Err(EkfInitError::NonFinite {
                what: "initial state",
            });
        }
        for (m, what) in [(&p0, "initial covariance"), (&q, "process noise")] {
            if m.iter().any(|v| !v.is_finite()) {
                return Err(EkfInitError::NonFinite { what });
            }
            let scale = m.amax().max(f64::MIN_POSITIVE);
            let asymmetric = (m - m.transpose()).amax() > 1e-12 * scale;
            let negative = m.symmetric_eigenvalues().min() < -1e-12 * scale;
            if asymmetric || negative {
                return Err(EkfInitError::NotCovariance { what });
            }
        }
        Ok(Self { x: x0, p: p0, q })
    }

    /// The current estimate.
    pub fn state(&self) -> &StateVector {
        &self.x
    }

    /// The current covariance.
    pub fn covariance(&self) -> &StateCovariance {
        &self.p
    }

    /// The estimated position (east, north), metres.
    pub fn position_enu_m(&self) -> Vector2<f64> {
        predicted_fix_m(&self.x)
    }

    /// The 2×2 covariance of the position, m² (east, north): what an uncertainty disc or ellipse
    /// is drawn from.
    pub fn position_covariance_m2(&self) -> nalgebra::Matrix2<f64> {
        self.p.fixed_view::<2, 2>(ix::EAST, ix::EAST).into_owned()
    }

    /// Time update from IMU sample `u0` to `u1`, `dt_s` seconds apart (eqs. 26-27):
    /// `x ← RK4(x)`, `P ← Φ P Φᵀ + Q`.
    pub fn predict(&mut self, u0: &ImuSample, u1: &ImuSample, dt_s: f64) {
        let phi = transition_matrix(&self.x, u0, u1, dt_s);
        self.x = propagate_state(&self.x, u0, u1, dt_s);
        self.p = symmetrized(&(phi * self.p * phi.transpose() + self.q));
    }

    /// Measurement update (eqs. 28-30) with measurement `z`, prediction `h = h(x⁻)`, Jacobian
    /// `h_jac` and noise covariance `r`; the covariance in Joseph form
    /// `P = (I − KH) P (I − KH)ᵀ + K R Kᵀ`. `None` (and no change) if `S = H P Hᵀ + R` is not
    /// positive definite.
    #[must_use]
    pub fn try_update<const M: usize>(
        &mut self,
        z: &SVector<f64, M>,
        h: &SVector<f64, M>,
        h_jac: &SMatrix<f64, M, STATE_DIM>,
        r: &SMatrix<f64, M, M>,
    ) -> Option<Innovation<M>> {
        let pht = self.p * h_jac.transpose();
        let s = h_jac * pht + r;
        // K = P Hᵀ S⁻¹ through S's Cholesky factor (S is symmetric positive definite when R is).
        let k = s.cholesky()?.solve(&pht.transpose()).transpose();
        let residual = z - h;
        self.x += k * residual;
        let i_kh = StateCovariance::identity() - k * h_jac;
        self.p = symmetrized(&(i_kh * self.p * i_kh.transpose() + k * r * k.transpose()));
        Some(Innovation {
            residual,
            covariance: s,
        })
    }

    /// Update with a range `range_m` (metres, noise variance `variance_m2`) to an orbiter at
    /// `orbiter_mci_m`, taken `t_s` seconds after the epoch.
    #[must_use]
    pub fn try_update_range(
        &mut self,
        frame: &NavigationFrame,
        t_s: f64,
        range_m: f64,
        orbiter_mci_m: &nalgebra::Vector3<f64>,
        variance_m2: f64,
    ) -> Option<Innovation<1>> {
        let p = self.position_enu_m();
        let h = SVector::<f64, 1>::new(predicted_range_m(frame, t_s, &p, orbiter_mci_m));
        let h_jac = range_jacobian(frame, t_s, &p, orbiter_mci_m);
        let r = SMatrix::<f64, 1, 1>::new(variance_m2);
        self.try_update(&SVector::<f64, 1>::new(range_m), &h, &h_jac, &r)
    }

    /// Update with a position fix `z_enu_m` (east, north, metres) of noise variance
    /// `variance_m2` per axis.
    #[must_use]
    pub fn try_update_fix(
        &mut self,
        z_enu_m: &Vector2<f64>,
        variance_m2: f64,
    ) -> Option<Innovation<2>> {
        let h = predicted_fix_m(&self.x);
        let r = nalgebra::Matrix2::identity() * variance_m2;
        self.try_update(z_enu_m, &h, &position_fix_jacobian(), &r)
    }
}
