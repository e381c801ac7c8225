//! The IMU of paper 004 §3.1 and §5: a 3-axis accelerometer and the yaw gyro, sampled once a
//! second, each with a constant bias and white Gaussian noise.
//!
//! `ã = a_body + g_up + b_a + ζ_a` and `ω̃ = ψ̇ + b_ω + ζ_ω` (eqs. 2-4). On level ground the body
//! z axis is up, so z reads Mars gravity and the 2-D filter drops it (`Ξ[·]₃→₂` in eq. 2).

use nalgebra::Vector3;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::mars::MARS_SURFACE_GRAVITY_M_PER_S2;
use super::trajectory::TrueState;

/// IMU error model (plain struct; defaults are paper 004 §5's MER-derived values).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ImuErrors {
    /// Accelerometer constant bias per body axis (x forward, y left, z up), m/s²
    /// (default: 3e-3 on each axis).
    pub accel_bias_m_per_s2: [f64; 3],
    /// Yaw-gyro constant bias, rad/s (default: 5e-6).
    pub gyro_bias_rad_per_s: f64,
    /// Variance of the accelerometer white noise per 1 s sample and axis, (m/s²)²
    /// (default: 5e-8, σ ≈ 2.2e-4 m/s²).
    pub accel_noise_var_m2_per_s4: f64,
    /// Variance of the yaw-gyro white noise per 1 s sample, (rad/s)² (default: 9e-8,
    /// σ = 3e-4 rad/s).
    pub gyro_noise_var_rad2_per_s2: f64,
}

impl Default for ImuErrors {
    fn default() -> Self {
        Self {
            accel_bias_m_per_s2: [3e-3; 3],
            gyro_bias_rad_per_s: 5e-6,
            accel_noise_var_m2_per_s4: 5e-8,
            gyro_noise_var_rad2_per_s2: 9e-8,
        }
    }
}

impl ImuErrors {
    /// A perfect IMU: no bias, no noise.
    pub fn none() -> Self {
        Self {
            accel_bias_m_per_s2: [0.0; 3],
            gyro_bias_rad_per_s: 0.0,
            accel_noise_var_m2_per_s4: 0.0,
            gyro_noise_var_rad2_per_s2: 0.0,
        }
    }
}

/// One IMU output, taken at a whole second.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ImuSample {
    /// Seconds since the start of the run.
    pub t_s: u32,
    /// Specific force along body x (forward), y (left), z (up), m/s².
    pub accel_body_m_per_s2: Vector3<f64>,
    /// Yaw rate about body z, rad/s.
    pub yaw_rate_rad_per_s: f64,
}

/// The IMU outputs at the times of `truth`, with `errors`; noise from `rng` (four normal draws per
/// sample: accel x, y, z, then gyro).
pub fn sample_imu(truth: &[TrueState], errors: &ImuErrors, rng: &mut ChaCha8Rng) -> Vec<ImuSample> {
    let sigma_a = errors.accel_noise_var_m2_per_s4.sqrt();
    let sigma_g = errors.gyro_noise_var_rad2_per_s2.sqrt();
    let bias_a = Vector3::from(errors.accel_bias_m_per_s2);
    truth
        .iter()
        .map(|s| {
            let noise = Vector3::new(
                rng.sample::<f64, _>(StandardNormal),
                rng.sample::<f64, _>(StandardNormal),
                rng.sample::<f64, _>(StandardNormal),
            );
            let gyro_noise: f64 = rng.sample(StandardNormal);
            let specific_force = Vector3::new(
                s.accel_body_m_per_s2.x,
                s.accel_body_m_per_s2.y,
                MARS_SURFACE_GRAVITY_M_PER_S2,
            );
            ImuSample {
                t_s: s.t_s,
                accel_body_m_per_s2: specific_force + bias_a + sigma_a * noise,
                yaw_rate_rad_per_s: s.yaw_rate_rad_per_s
                    + errors.gyro_bias_rad_per_s
                    + sigma_g * gyro_noise,
            }
        })
        .collect()
}
