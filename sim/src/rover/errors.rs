//! The errors the uncertainty disc must bound (docs/design.md, "Errors the disc must bound").
//!
//! The rover's estimate drifts from the truth by four things it does not know about:
//!
//! | error | drawn | what the truth does | what the estimate does |
//! |---|---|---|---|
//! | heading (attitude) knowledge | once per sol, N(0, σ_h) | moves along the command turned by θ | believes the command's direction |
//! | VO scale | once per sol, N(0, σ_s) | — | scales VO's measured length by (1 + s) |
//! | VO noise | per step, N(0, σ_n·step) per axis | — | adds it to VO's measurement |
//! | slip | per step, around a mean per terrain class | progresses (1 − slip) of the command | with VO: measures it; without VO: believes the whole command (wheel odometry) |
//! | VO failure | per step, a probability per terrain class (the expected fraction of distance driven without VO) | — | falls back to wheel odometry (blind to slip); the disc grows at 50 % for that step |
//! | ground localization | at every ground fix, N(0, σ_g) per axis | — | set to the truth plus that error, disc reset to 0 |
//!
//! Two presets: [`ErrorModel::calibrated`] (the default: the record where the paper gives it,
//! stated judgement elsewhere, each value naming its source) and [`ErrorModel::stress`] (every
//! error several times larger), under which the 5 % / 50 % disc must stop covering the truth.
//! How often it does is the disc's coverage, reported by `solsim compare` and `solsim sweep`.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use maps::{PerTerrain, TerrainClass};

use crate::settings::field_error::FieldError;
use crate::settings::physical_range::{MARGIN_M, PhysicalRange, check_fraction};

/// Which preset an [`ErrorModel`] started from (fields may be overridden after).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorPreset {
    /// [`ErrorModel::calibrated`].
    Calibrated,
    /// [`ErrorModel::stress`].
    Stress,
}

impl ErrorPreset {
    /// The name used in scenario files and outputs.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            ErrorPreset::Calibrated => "calibrated",
            ErrorPreset::Stress => "stress",
        }
    }

    /// The preset called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        [ErrorPreset::Calibrated, ErrorPreset::Stress]
            .into_iter()
            .find(|p| p.name() == name)
    }

    /// The preset's values.
    #[must_use]
    pub fn model(self) -> ErrorModel {
        match self {
            ErrorPreset::Calibrated => ErrorModel::calibrated(),
            ErrorPreset::Stress => ErrorModel::stress(),
        }
    }
}

/// Relative VO failure rate per terrain class (soil = 1). Judgement, not calibrated: VO loses
/// its features on smooth sand and keeps them on textured bedrock. Only the soil rate is fixed
/// by the record (sols 717-719 drove on the crater floor); these ratios carry it to the others.
pub const VO_FAILURE_RELATIVE: PerTerrain = PerTerrain {
    sand: 10.0,
    soil: 1.0,
    bedrock: 0.5,
};

/// Probability that VO fails on a step on soil, which is the expected fraction of distance
/// driven without VO there. Calibrated to sols 717-719 (paper 000 Fig. 2: 0.289 m of 655.8 m
/// without VO, 0.044 %), on the scenario rebuilt from the public record (issue 27; the earlier
/// hand-built map gave 2.55e-4): `solsim calibrate vo scenarios/sol717-719.toml` solves
/// `p_soil × Σ_class share_class × VO_FAILURE_RELATIVE_class / (1 − slip_class) = 0.289 / 655.8`,
/// the shares being the terrain classes under the re-simulated ground drive (a failed step
/// charges the commanded length, a VO step the length after slip). `tests/calibration_vo.rs` re-runs
/// it and checks this value.
pub const VO_FAILURE_SOIL: f64 = 3.16e-4;

/// The error model: what the estimate does not know (see the module docs for each term).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ErrorModel {
    /// The preset it started from.
    pub preset: ErrorPreset,
    /// Heading (attitude) knowledge error, 1σ degrees, drawn once per sol; the estimate does
    /// not know it (range [`ErrorModel::HEADING_SIGMA_RANGE_DEG`]).
    pub heading_sigma_deg: f64,
    /// VO scale error, 1σ fraction of the measured length, drawn once per sol (0 ..= 1).
    pub vo_scale_sigma: f64,
    /// VO measurement noise per step, 1σ per axis as a fraction of the step (0 ..= 1).
    pub vo_noise_fraction: f64,
    /// Probability that VO fails on a step, per terrain class: the expected fraction of
    /// distance driven without VO there (0 ..= 1).
    pub vo_failure: PerTerrain,
    /// Mean slip, fraction of commanded motion, per terrain class (0 ..= 1).
    pub slip_fraction: PerTerrain,
    /// Step-to-step spread of slip, 1σ as a fraction of the class mean (0 ..= 1).
    pub slip_sigma_relative: f64,
    /// Ground localization error, 1σ per axis, metres (range
    /// [`crate::settings::physical_range::MARGIN_M`]).
    pub ground_localization_sigma_m: f64,
}

impl Default for ErrorModel {
    fn default() -> Self {
        Self::calibrated()
    }
}

impl ErrorModel {
    /// The calibrated model (the default). Sources:
    /// - VO failures: [`VO_FAILURE_SOIL`] (calibrated to sols 717-719) times
    ///   [`VO_FAILURE_RELATIVE`] (judgement);
    /// - heading 0.5° 1σ: judgement for a sun-find-updated IMU attitude; paper 000 §2 names
    ///   attitude errors as what the 5 % allowance covers beyond VO;
    /// - VO scale 1 % 1σ: paper 000 §2 says VO could hold growth to 2 % of distance; taken as 2σ;
    /// - VO noise 1 % of a step per axis: judgement (it averages out over a drive);
    /// - slip sand 12 %, soil 4 %, bedrock 2 %, spread 50 %: judgement for level terrain (slope
    ///   dependence is issue 15's rapier rover);
    /// - ground localization 0.25 m 1σ per axis: one HiRISE pixel, paper 000 §4's figure for
    ///   the mode of the onboard-to-ground difference, which it calls near-human.
    #[must_use]
    pub fn calibrated() -> Self {
        Self {
            preset: ErrorPreset::Calibrated,
            heading_sigma_deg: 0.5,
            vo_scale_sigma: 0.01,
            vo_noise_fraction: 0.01,
            vo_failure: PerTerrain {
                sand: VO_FAILURE_SOIL * VO_FAILURE_RELATIVE.sand,
                soil: VO_FAILURE_SOIL * VO_FAILURE_RELATIVE.soil,
                bedrock: VO_FAILURE_SOIL * VO_FAILURE_RELATIVE.bedrock,
            },
            slip_fraction: PerTerrain {
                sand: 0.12,
                soil: 0.04,
                bedrock: 0.02,
            },
            slip_sigma_relative: 0.5,
            ground_localization_sigma_m: 0.25,
        }
    }

    /// The stress model: what the 5 % / 50 % disc is not sized for. Heading 3° (six times the
    /// calibrated value: an attitude estimate gone stale), VO scale 3 %, VO failures 20 times as
    /// often, slip doubled, ground localization 1 m. Under it the disc must fail to cover the
    /// truth on more than 1 % of sols; `solsim compare --errors stress` shows by how much.
    #[must_use]
    pub fn stress() -> Self {
        let c = Self::calibrated();
        let scale = |p: PerTerrain, k: f64| PerTerrain {
            sand: p.sand * k,
            soil: p.soil * k,
            bedrock: p.bedrock * k,
        };
        Self {
            preset: ErrorPreset::Stress,
            heading_sigma_deg: 3.0,
            vo_scale_sigma: 0.03,
            vo_noise_fraction: c.vo_noise_fraction,
            vo_failure: scale(c.vo_failure, 20.0),
            slip_fraction: scale(c.slip_fraction, 2.0),
            slip_sigma_relative: c.slip_sigma_relative,
            ground_localization_sigma_m: 1.0,
        }
    }
}

impl ErrorModel {
    /// The heading knowledge errors a model may have, 1σ degrees: the calibrated model's is
    /// 0.5° and the stress model's 3°; at 45° the rover no longer knows which way it faces.
    pub const HEADING_SIGMA_RANGE_DEG: PhysicalRange = PhysicalRange::new(0.0, 45.0, "degrees");

    /// Checks every term against its range, in the order of the fields.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::HEADING_SIGMA_RANGE_DEG.check("heading_sigma_deg", self.heading_sigma_deg)?;
        check_fraction("vo_scale_sigma", self.vo_scale_sigma)?;
        check_fraction("vo_noise_fraction", self.vo_noise_fraction)?;
        for (field, per_terrain) in [
            ("vo_failure", &self.vo_failure),
            ("slip_fraction", &self.slip_fraction),
        ] {
            for class in TerrainClass::ALL {
                check_fraction(&format!("{field}.{}", class.name()), per_terrain.get(class))?;
            }
        }
        check_fraction("slip_sigma_relative", self.slip_sigma_relative)?;
        MARGIN_M.check(
            "ground_localization_sigma_m",
            self.ground_localization_sigma_m,
        )?;
        Ok(())
    }
}

/// One sol's draws of the errors that hold for a whole sol.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct SolErrors {
    /// Heading knowledge error, radians: the world turns every command by it.
    pub heading_error_rad: f64,
    /// VO scale error, fraction: VO's measured length is `1 + vo_scale_error` times the truth.
    pub vo_scale_error: f64,
}

impl ErrorModel {
    /// Draw one sol's heading and VO scale errors (two normal draws, in that order).
    pub fn draw_sol(&self, rng: &mut ChaCha8Rng) -> SolErrors {
        let h: f64 = rng.sample(StandardNormal);
        let s: f64 = rng.sample(StandardNormal);
        SolErrors {
            heading_error_rad: self.heading_sigma_deg.to_radians() * h,
            vo_scale_error: self.vo_scale_sigma * s,
        }
    }

    /// Draw a ground localization's error, metres east and north.
    pub fn draw_ground_error(&self, rng: &mut ChaCha8Rng) -> [f64; 2] {
        let e: f64 = rng.sample(StandardNormal);
        let n: f64 = rng.sample(StandardNormal);
        [
            self.ground_localization_sigma_m * e,
            self.ground_localization_sigma_m * n,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_round_trip_and_stress_is_worse_everywhere() {
        for p in [ErrorPreset::Calibrated, ErrorPreset::Stress] {
            assert_eq!(ErrorPreset::from_name(p.name()), Some(p));
            assert_eq!(p.model().preset, p);
        }
        let (c, s) = (ErrorModel::calibrated(), ErrorModel::stress());
        assert!(s.heading_sigma_deg > c.heading_sigma_deg);
        assert!(s.vo_scale_sigma > c.vo_scale_sigma);
        assert!(s.vo_failure.sand > c.vo_failure.sand);
        assert!(s.slip_fraction.soil > c.slip_fraction.soil);
        assert!(s.ground_localization_sigma_m > c.ground_localization_sigma_m);
    }
}
