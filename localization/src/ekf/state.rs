//! The filter's state vector, its covariance, and the index of each component.

use nalgebra::{SMatrix, SVector};

/// Number of components of [`StateVector`].
pub const STATE_DIM: usize = 8;

/// The filter state `[e, n, v_e, v_n, ψ, b_ax, b_ay, b_g]` (see [`ix`] for units).
pub type StateVector = SVector<f64, STATE_DIM>;

/// A covariance (or transition, or process-noise) matrix over [`StateVector`], in the units of
/// the components' products.
pub type StateCovariance = SMatrix<f64, STATE_DIM, STATE_DIM>;

/// Index of each component in [`StateVector`].
///
/// Position and velocity are in the navigation (ENU) frame of paper 004 §2.1.2, in metres on the
/// tangent plane at the site; heading and the biases drive the IMU propagation of §2.3 eq. 2.
pub mod ix {
    /// East position, metres.
    pub const EAST: usize = 0;
    /// North position, metres.
    pub const NORTH: usize = 1;
    /// East velocity, metres per second.
    pub const VEL_EAST: usize = 2;
    /// North velocity, metres per second.
    pub const VEL_NORTH: usize = 3;
    /// Heading ψ: angle from east to the body x axis, counter-clockwise seen from above,
    /// radians (paper 004 eq. 1 with zero roll and pitch).
    pub const HEADING: usize = 4;
    /// Accelerometer bias along body x (forward), metres per second squared.
    pub const ACCEL_BIAS_X: usize = 5;
    /// Accelerometer bias along body y (left), metres per second squared.
    pub const ACCEL_BIAS_Y: usize = 6;
    /// Gyro bias about body z (yaw), radians per second.
    pub const GYRO_BIAS: usize = 7;
}

/// `m` made exactly symmetric (the mean of it and its transpose), removing rounding drift.
pub(crate) fn symmetrized(m: &StateCovariance) -> StateCovariance {
    (m + m.transpose()) * 0.5
}
