//! What a run depends on besides its seed: [`CaseSettings`], and [`CaseError`] when they are
//! out of range.

use super::filter::EkfInitError;
use super::imu::ImuErrors;
use super::mars::NavigationFrame;
use super::orbit::CircularOrbit;
use super::state::{StateVector, ix};
use super::trajectory::{TrajectorySettings, TrueState};
use super::tuning::{BiasPriors, FilterModel, FilterTuning};

/// The four simulation cases of paper 004 Table 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Table1Case {
    /// 10 m satellite image, 10 m radio range.
    Case1,
    /// 10 m image, 1 m range.
    Case2,
    /// 0.25 m image, 10 m range.
    Case3,
    /// 0.25 m image, 1 m range.
    Case4,
}

impl Table1Case {
    /// The four cases in order.
    pub const ALL: [Table1Case; 4] = [Self::Case1, Self::Case2, Self::Case3, Self::Case4];

    /// 1 to 4.
    pub fn number(self) -> u8 {
        match self {
            Self::Case1 => 1,
            Self::Case2 => 2,
            Self::Case3 => 3,
            Self::Case4 => 4,
        }
    }

    /// Resolution of the satellite image, metres per pixel.
    pub fn image_resolution_m(self) -> f64 {
        match self {
            Self::Case1 | Self::Case2 => 10.0,
            Self::Case3 | Self::Case4 => 0.25,
        }
    }

    /// Accuracy (1σ) of the radio range, metres.
    pub fn range_sigma_m(self) -> f64 {
        match self {
            Self::Case1 | Self::Case3 => 10.0,
            Self::Case2 | Self::Case4 => 1.0,
        }
    }

    /// The paper's total localization error for this case, metres, and how the paper words it
    /// (the text of §5 on Figs. 3, 5, 7 and 9).
    pub fn paper_error_m(self) -> (f64, &'static str) {
        match self {
            Self::Case1 => (20.0, "about 20 m"),
            Self::Case2 => (5.0, "within 5 m"),
            Self::Case3 => (2.0, "within 2 m"),
            Self::Case4 => (0.35, "within 35 cm"),
        }
    }
}

/// Everything a run depends on besides the seed (plain struct; [`CaseSettings::table1`] gives
/// paper 004 §5's values).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CaseSettings {
    /// The filter (default: [`FilterModel::BiasEstimating`]).
    pub model: FilterModel,
    /// Length of the run, seconds; one filter step per second (default: 1000, paper §5).
    pub duration_s: u32,
    /// Satellite image resolution: the fix's σ, metres (Table 1).
    pub image_resolution_m: f64,
    /// Range noise σ, metres (Table 1).
    pub range_sigma_m: f64,
    /// Seconds between position fixes (default: 1, the paper's sample step).
    pub fix_period_s: u32,
    /// Seconds between ranges while the orbiter is visible (default: 1).
    pub range_period_s: u32,
    /// Lowest orbiter elevation that gives a range, degrees (default: 0, the geometric horizon:
    /// the paper sets no mask. The default pass is above it from 61 s to 920 s; a 10° relay-link
    /// mask shortens that to 218-763 s).
    pub elevation_mask_deg: f64,
    /// The navigation frame and Mars rotation (default: Jezero, ω_M of paper §5).
    pub frame: NavigationFrame,
    /// The beacon's orbit (default: [`CircularOrbit::default`], which passes over the default
    /// site; for another site use [`CircularOrbit::pass_over`]).
    pub orbit: CircularOrbit,
    /// IMU biases and noise (default: paper §5).
    pub imu: ImuErrors,
    /// The random drive (default: starts at paper §5's X0).
    pub trajectory: TrajectorySettings,
    /// Priors of the bias-estimating model (ignored by [`FilterModel::Paper`]).
    pub priors: BiasPriors,
}

impl CaseSettings {
    /// Paper 004 §5's settings for `case`, with the default [`FilterModel`].
    pub fn table1(case: Table1Case) -> Self {
        Self {
            model: FilterModel::default(),
            duration_s: 1000,
            image_resolution_m: case.image_resolution_m(),
            range_sigma_m: case.range_sigma_m(),
            fix_period_s: 1,
            range_period_s: 1,
            elevation_mask_deg: 0.0,
            frame: NavigationFrame::default(),
            orbit: CircularOrbit::default(),
            imu: ImuErrors::default(),
            trajectory: TrajectorySettings::default(),
            priors: BiasPriors::default(),
        }
    }

    /// The same settings with `model`.
    #[must_use]
    pub fn with_model(mut self, model: FilterModel) -> Self {
        self.model = model;
        self
    }

    /// The filter's `x̂₀`, `P₀`, `Q`, `R` for these settings, starting at `truth0`.
    pub fn tuning(&self, truth0: &TrueState) -> FilterTuning {
        let mut x0 = StateVector::zeros();
        x0[ix::EAST] = truth0.position_enu_m.x;
        x0[ix::NORTH] = truth0.position_enu_m.y;
        x0[ix::VEL_EAST] = truth0.velocity_enu_m_per_s.x;
        x0[ix::VEL_NORTH] = truth0.velocity_enu_m_per_s.y;
        x0[ix::HEADING] = truth0.heading_rad;
        let fix_var = self.image_resolution_m.powi(2);
        match self.model {
            FilterModel::Paper => FilterTuning::paper(x0, fix_var),
            FilterModel::BiasEstimating => FilterTuning::bias_estimating(
                x0,
                &self.imu,
                &self.priors,
                self.range_sigma_m.powi(2),
                fix_var,
            ),
        }
    }

    pub(crate) fn validate(&self) -> Result<(), CaseError> {
        let positive = [
            ("image_resolution_m", self.image_resolution_m),
            ("range_sigma_m", self.range_sigma_m),
            ("orbit.altitude_m", self.orbit.altitude_m),
            (
                "trajectory.period_range_s[0]",
                self.trajectory.period_range_s[0],
            ),
        ];
        for (field, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(CaseError::Invalid {
                    field,
                    value,
                    expected: "finite and > 0",
                });
            }
        }
        let non_negative = [
            (
                "imu.accel_noise_var_m2_per_s4",
                self.imu.accel_noise_var_m2_per_s4,
            ),
            (
                "imu.gyro_noise_var_rad2_per_s2",
                self.imu.gyro_noise_var_rad2_per_s2,
            ),
            (
                "trajectory.speed_amplitude_m_per_s",
                self.trajectory.speed_amplitude_m_per_s,
            ),
            (
                "trajectory.heading_amplitude_deg",
                self.trajectory.heading_amplitude_deg,
            ),
            ("priors.heading_sigma_rad", self.priors.heading_sigma_rad),
            (
                "priors.accel_bias_sigma_m_per_s2",
                self.priors.accel_bias_sigma_m_per_s2,
            ),
            (
                "priors.gyro_bias_sigma_rad_per_s",
                self.priors.gyro_bias_sigma_rad_per_s,
            ),
            (
                "priors.accel_bias_walk_m_per_s2_per_sqrt_s",
                self.priors.accel_bias_walk_m_per_s2_per_sqrt_s,
            ),
            (
                "priors.gyro_bias_walk_rad_per_s_per_sqrt_s",
                self.priors.gyro_bias_walk_rad_per_s_per_sqrt_s,
            ),
        ];
        for (field, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(CaseError::Invalid {
                    field,
                    value,
                    expected: "finite and >= 0",
                });
            }
        }
        let finite = [
            (
                "imu.accel_bias_m_per_s2[0]",
                self.imu.accel_bias_m_per_s2[0],
            ),
            (
                "imu.accel_bias_m_per_s2[1]",
                self.imu.accel_bias_m_per_s2[1],
            ),
            (
                "imu.accel_bias_m_per_s2[2]",
                self.imu.accel_bias_m_per_s2[2],
            ),
            ("imu.gyro_bias_rad_per_s", self.imu.gyro_bias_rad_per_s),
            (
                "trajectory.initial_velocity_enu_m_per_s[0]",
                self.trajectory.initial_velocity_enu_m_per_s[0],
            ),
            (
                "trajectory.initial_velocity_enu_m_per_s[1]",
                self.trajectory.initial_velocity_enu_m_per_s[1],
            ),
            ("orbit.inclination_deg", self.orbit.inclination_deg),
            ("orbit.raan_deg", self.orbit.raan_deg),
            (
                "orbit.argument_of_latitude_deg",
                self.orbit.argument_of_latitude_deg,
            ),
            ("frame.rotation_rad_per_s", self.frame.rotation_rad_per_s),
            (
                "frame.prime_meridian_at_epoch_rad",
                self.frame.prime_meridian_at_epoch_rad,
            ),
            ("frame.site.latitude_deg", self.frame.site.latitude_deg),
            ("frame.site.longitude_deg", self.frame.site.longitude_deg),
        ];
        for (field, value) in finite {
            if !value.is_finite() {
                return Err(CaseError::Invalid {
                    field,
                    value,
                    expected: "finite",
                });
            }
        }
        let [p_min, p_max] = self.trajectory.period_range_s;
        if !(p_max.is_finite() && p_max >= p_min) {
            return Err(CaseError::Invalid {
                field: "trajectory.period_range_s[1]",
                value: p_max,
                expected: "finite and >= period_range_s[0]",
            });
        }
        if !(-90.0..=90.0).contains(&self.elevation_mask_deg) {
            return Err(CaseError::Invalid {
                field: "elevation_mask_deg",
                value: self.elevation_mask_deg,
                expected: "within -90..=90",
            });
        }
        for (field, value) in [
            ("duration_s", self.duration_s),
            ("fix_period_s", self.fix_period_s),
            ("range_period_s", self.range_period_s),
        ] {
            if value == 0 {
                return Err(CaseError::Invalid {
                    field,
                    value: 0.0,
                    expected: ">= 1",
                });
            }
        }
        Ok(())
    }
}

/// Why a case could not be run (bad settings).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CaseError {
    /// A setting is out of its range.
    #[error("{field} = {value}: expected {expected}")]
    Invalid {
        /// The [`CaseSettings`] field, as a path (`imu.gyro_bias_rad_per_s`).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// The settings give a filter that cannot start (a non-finite or non-covariance matrix).
    #[error("the filter's initial values are unusable: {0}")]
    Filter(#[from] EkfInitError),
}
