//! The EKF as a post-drive localizer: the rover parked through one orbiter pass, fusing the IMU,
//! radio ranges to the orbiter, zero-velocity updates and (optionally) one terrain-matching fix.
//!
//! This is how the simulator runs paper 004's filter at the end of a drive sol
//! (`localizer = "ekf"`): the filter starts at the rover's estimate with the uncertainty disc
//! as a 3σ prior on position, and ends with a position error (relative to the truth) and a
//! covariance that the simulator turns into the disc its keep-out zones grow by.
//!
//! - The truth is a static rover ([`TrajectorySettings`] with zero velocity and amplitudes) at
//!   paper 004 §5's site and X0, so the orbiter geometry is the paper's pass over Jezero
//!   ([`CircularOrbit::default`]: above the horizon from 61 s to 920 s of the 1000 s run).
//! - The IMU reads its biases and noise (paper §5 values, [`ImuErrors::default`]); the filter is
//!   the bias-estimating one ([`FilterModel::BiasEstimating`]).
//! - A parked rover knows it is not moving: each second a zero-velocity pseudo-measurement
//!   (`v = 0` with σ [`ParkedSettings::zero_velocity_sigma_m_per_s`]) pins the velocity, which
//!   makes the accelerometer biases observable and stops them from walking the position. This
//!   is standard practice for stationary inertial alignment; paper 004's rover is always moving
//!   and has no such update.
//! - A terrain fix from a parked rover is one panorama matched once, not a fresh independent
//!   fix every second: with [`ParkedSettings::image_resolution_m`] set, one fix of that σ at
//!   the end of the pass (paper 004 §3.3 models the fix error as the image resolution).
//!
//! [`TrajectorySettings`]: super::TrajectorySettings
//! [`CircularOrbit::default`]: super::CircularOrbit::default
//! [`ImuErrors::default`]: super::ImuErrors::default
//! [`FilterModel::BiasEstimating`]: super::FilterModel::BiasEstimating

use nalgebra::{Matrix2, SMatrix, Vector2};

use super::case_settings::Table1Case;
use super::case_settings::{CaseError, CaseSettings};
use super::filter::Ekf;
use super::state::{STATE_DIM, ix};
use super::table1::{Simulation, simulate};
use super::trajectory::TrajectorySettings;
use super::tuning::FilterModel;
use crate::particle::Ellipse;

/// Settings of a parked-rover EKF localization (plain struct; defaults on each field).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ParkedSettings {
    /// Range noise σ, metres (default: 1, paper 004 Table 1 cases 2 and 4).
    pub range_sigma_m: f64,
    /// Seconds of ranging; one filter step per second (default: 1000, paper 004 §5's run, which
    /// holds the default pass's 61-920 s of visibility).
    pub pass_duration_s: u32,
    /// Lowest orbiter elevation that gives a range, degrees (default: 0, as paper 004).
    pub elevation_mask_deg: f64,
    /// σ of the zero-velocity pseudo-measurement, m/s (default: 0.001: a parked rover's wheels
    /// do not turn; the value stands for vibration and thermal creep of the mast).
    pub zero_velocity_sigma_m_per_s: f64,
    /// With a value: one terrain-matching fix at the end of the pass, σ = this satellite image
    /// resolution in metres (paper 004 Table 1: 10 or 0.25). Default: none (ranges only).
    pub image_resolution_m: Option<f64>,
}

impl Default for ParkedSettings {
    fn default() -> Self {
        Self {
            range_sigma_m: 1.0,
            pass_duration_s: 1000,
            elevation_mask_deg: 0.0,
            zero_velocity_sigma_m_per_s: 1e-3,
            image_resolution_m: None,
        }
    }
}

/// What a parked-rover localization produced.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ParkedFix {
    /// The filter's final position minus the truth, metres (east, north).
    pub error_enu_m: [f64; 2],
    /// The filter's 2×2 position covariance at the end, m² (east, north).
    pub covariance_m2: [[f64; 2]; 2],
    /// Ranges applied.
    pub ranges_used: u32,
    /// Updates skipped because `H P Hᵀ + R` was not positive definite.
    pub rejected_updates: u32,
}

impl ParkedFix {
    /// The 1σ ellipse of the final position covariance (`None` if it is not a covariance);
    /// its [`Ellipse::disc_radius_m`] is the disc the simulator grows keep-outs by.
    #[must_use]
    pub fn ellipse(&self) -> Option<Ellipse> {
        Ellipse::try_from_covariance(&self.covariance_m2)
    }
}

impl ParkedSettings {
    /// The Table 1 settings these stand for: a static drive of `pass_duration_s`, these range
    /// and fix noises, the bias-estimating filter.
    fn case_settings(&self) -> CaseSettings {
        let mut cs =
            CaseSettings::table1(Table1Case::Case4).with_model(FilterModel::BiasEstimating);
        cs.duration_s = self.pass_duration_s;
        cs.range_sigma_m = self.range_sigma_m;
        // A fix is drawn every second by `simulate`; only the last one is used.
        cs.image_resolution_m = self.image_resolution_m.unwrap_or(1.0);
        cs.elevation_mask_deg = self.elevation_mask_deg;
        cs.trajectory = TrajectorySettings {
            initial_velocity_enu_m_per_s: [0.0, 0.0],
            speed_amplitude_m_per_s: 0.0,
            heading_amplitude_deg: 0.0,
            ..TrajectorySettings::default()
        };
        cs
    }

    /// `Ok` if every field is in range.
    ///
    /// # Errors
    /// [`CaseError::Invalid`] naming the field.
    pub fn validate(&self) -> Result<(), CaseError> {
        let checks: [(&'static str, f64, bool, &'static str); 4] = [
            (
                "range_sigma_m",
                self.range_sigma_m,
                self.range_sigma_m.is_finite() && self.range_sigma_m > 0.0,
                "finite and > 0",
            ),
            (
                "pass_duration_s",
                f64::from(self.pass_duration_s),
                (1..=86_400).contains(&self.pass_duration_s),
                "1 ..= 86400 s",
            ),
            (
                "zero_velocity_sigma_m_per_s",
                self.zero_velocity_sigma_m_per_s,
                self.zero_velocity_sigma_m_per_s.is_finite()
                    && self.zero_velocity_sigma_m_per_s > 0.0,
                "finite and > 0",
            ),
            (
                "image_resolution_m",
                self.image_resolution_m.unwrap_or(1.0),
                self.image_resolution_m
                    .is_none_or(|v| v.is_finite() && v > 0.0),
                "finite and > 0",
            ),
        ];
        for (field, value, ok, expected) in checks {
            if !ok {
                return Err(CaseError::Invalid {
                    field,
                    value,
                    expected,
                });
            }
        }
        self.case_settings().validate()
    }
}

/// Localize a parked rover through one pass: the filter starts `prior_offset_m` (east, north,
/// metres) from the truth with σ `prior_sigma_m` per axis on position, and runs the pass drawn
/// from `seed`.
///
/// # Errors
/// [`CaseError`] if a setting, the offset or σ is out of range.
pub fn parked_fix(
    settings: &ParkedSettings,
    prior_offset_m: [f64; 2],
    prior_sigma_m: f64,
    seed: u64,
) -> Result<ParkedFix, CaseError> {
    settings.validate()?;
    for (field, value) in [
        ("prior_offset_m[0]", prior_offset_m[0]),
        ("prior_offset_m[1]", prior_offset_m[1]),
    ] {
        if !value.is_finite() {
            return Err(CaseError::Invalid {
                field,
                value,
                expected: "finite",
            });
        }
    }
    if !(prior_sigma_m.is_finite() && prior_sigma_m > 0.0) {
        return Err(CaseError::Invalid {
            field: "prior_sigma_m",
            value: prior_sigma_m,
            expected: "finite and > 0",
        });
    }
    let cs = settings.case_settings();
    let Simulation { truth, streams } = simulate(&cs, seed)?;
    let mut tuning = cs.tuning(&truth[0]);
    tuning.initial_state[ix::EAST] += prior_offset_m[0];
    tuning.initial_state[ix::NORTH] += prior_offset_m[1];
    let zv_var = settings.zero_velocity_sigma_m_per_s.powi(2);
    for (i, var) in [
        (ix::EAST, prior_sigma_m.powi(2)),
        (ix::NORTH, prior_sigma_m.powi(2)),
        (ix::VEL_EAST, zv_var),
        (ix::VEL_NORTH, zv_var),
    ] {
        for j in 0..STATE_DIM {
            tuning.initial_covariance[(i, j)] = 0.0;
            tuning.initial_covariance[(j, i)] = 0.0;
        }
        tuning.initial_covariance[(i, i)] = var;
    }
    let mut ekf = Ekf::new(
        tuning.initial_state,
        tuning.initial_covariance,
        tuning.process_noise,
    )
    .map_err(|_| CaseError::Invalid {
        field: "prior_sigma_m",
        value: prior_sigma_m,
        expected: "a covariance the filter accepts",
    })?;
    let mut velocity_jac = SMatrix::<f64, 2, STATE_DIM>::zeros();
    velocity_jac[(0, ix::VEL_EAST)] = 1.0;
    velocity_jac[(1, ix::VEL_NORTH)] = 1.0;
    let zv_r = Matrix2::identity() * zv_var;
    let (mut ranges_used, mut rejected_updates) = (0, 0);
    let mut ranges = streams.ranges.iter().peekable();
    for imu in streams.imu.windows(2) {
        let (u0, u1) = (&imu[0], &imu[1]);
        ekf.predict(u0, u1, f64::from(u1.t_s) - f64::from(u0.t_s));
        let t_s = u1.t_s;
        while ranges.next_if(|r| r.t_s < t_s).is_some() {}
        if let Some(r) = ranges.next_if(|r| r.t_s == t_s) {
            let update = ekf.try_update_range(
                &cs.frame,
                f64::from(r.t_s),
                r.range_m,
                &r.orbiter_position_mci_m,
                tuning.range_variance_m2,
            );
            ranges_used += u32::from(update.is_some());
            rejected_updates += u32::from(update.is_none());
        }
        let velocity = Vector2::new(ekf.state()[ix::VEL_EAST], ekf.state()[ix::VEL_NORTH]);
        let update = ekf.try_update(&Vector2::zeros(), &velocity, &velocity_jac, &zv_r);
        rejected_updates += u32::from(update.is_none());
    }
    let last = truth
        .last()
        .expect("simulate returns duration_s + 1 states");
    if settings.image_resolution_m.is_some()
        && let Some(fix) = streams.fixes.iter().find(|f| f.t_s == last.t_s)
    {
        let update = ekf.try_update_fix(&fix.position_enu_m, tuning.fix_variance_m2);
        rejected_updates += u32::from(update.is_none());
    }
    let error = ekf.position_enu_m() - last.position_enu_m;
    let p = ekf.position_covariance_m2();
    Ok(ParkedFix {
        error_enu_m: [error.x, error.y],
        covariance_m2: [[p[(0, 0)], p[(0, 1)]], [p[(1, 0)], p[(1, 1)]]],
        ranges_used,
        rejected_updates,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Over 30 seeds the filter's error is consistent with its covariance (normalised squared
    /// error near 2, the position's dimension) and ranges shrink a 10 m prior.
    #[test]
    fn parked_pass_is_consistent_and_informative() {
        let s = ParkedSettings::default();
        let (mut nees, mut worst_sigma) = (0.0, 0.0f64);
        let n = 30;
        for seed in 0..n {
            let fix = parked_fix(&s, [6.0, -4.0], 10.0 / 3.0, seed).expect("as documented");
            let p = Matrix2::new(
                fix.covariance_m2[0][0],
                fix.covariance_m2[0][1],
                fix.covariance_m2[1][0],
                fix.covariance_m2[1][1],
            );
            let e = Vector2::new(fix.error_enu_m[0], fix.error_enu_m[1]);
            nees += (e.transpose() * p.try_inverse().expect("as documented") * e)[(0, 0)];
            worst_sigma = worst_sigma.max(p.symmetric_eigenvalues().max().sqrt());
            assert!(fix.ranges_used > 500, "{fix:?}");
        }
        let mean_nees = nees / n as f64;
        println!("mean NEES {mean_nees:.2}, worst 1σ semi-major {worst_sigma:.3} m");
        assert!((0.8..3.5).contains(&mean_nees), "mean NEES {mean_nees}");
        assert!(worst_sigma < 10.0 / 3.0, "worst σ {worst_sigma}");
    }

    #[test]
    fn bad_settings_name_the_field() {
        let s = ParkedSettings {
            range_sigma_m: f64::NAN,
            ..ParkedSettings::default()
        };
        let e = parked_fix(&s, [0.0, 0.0], 1.0, 0)
            .expect_err("refused")
            .to_string();
        assert!(e.contains("range_sigma_m"), "{e}");
        let e = parked_fix(&ParkedSettings::default(), [0.0, 0.0], 0.0, 0)
            .expect_err("refused")
            .to_string();
        assert!(e.contains("prior_sigma_m"), "{e}");
    }
}
