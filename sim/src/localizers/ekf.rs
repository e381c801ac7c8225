//! The EKF of paper 004 as the post-drive localizer: the parked rover ranging to an orbiter
//! (see the module docs of [`crate::localizers`] for the disc it leaves).

use localization::ekf::ParkedSettings;
use localization::hbs::HbsSettings;

use super::{Localizer, PostDrive};
use crate::run::outcome::{LocalizationEvent, PositionEllipse, RejectionReason};
use crate::settings::field_error::FieldError;
use crate::settings::physical_range::PhysicalRange;

/// The EKF of paper 004 as the post-drive localizer: the parked rover ranges to the orbiter
/// through one pass ([`localization::ekf::parked_fix`]); the filter starts at the estimate with
/// the uncertainty disc as 3σ, and its final 2×2 position covariance becomes the disc
/// (3 × the 1σ semi-major axis). Rejected when the filter could not run or ends with a disc no
/// smaller than the prior's.
///
/// Its activity takes the onboard localization chain's slot in the sol plan at the
/// statistical model's planned durations: the pass itself is not scheduled against the
/// calendar's relay passes.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct EkfLocalizer {
    /// Ranging, pass and terrain-fix settings.
    pub settings: ParkedSettings,
    /// The chain's planned durations (the link rate is the scenario's).
    pub hbs: HbsSettings,
}

impl EkfLocalizer {
    /// The radio-range noise σ a pass may have, metres: paper 004 Table 1 has 0.25 to 10 m;
    /// below 1 cm the EKF's measurement covariance is numerically singular.
    pub const RANGE_SIGMA_RANGE_M: PhysicalRange = PhysicalRange::new(0.01, 100.0, "metres");
    /// The ranging durations a pass may have, seconds: a low orbiter is visible for under an
    /// hour; below a minute there is no pass.
    pub const PASS_DURATION_RANGE_S: PhysicalRange = PhysicalRange::new(60.0, 3_600.0, "seconds");
    /// The elevation masks a pass may have, degrees: above 80° the orbiter is almost never
    /// in view.
    pub const ELEVATION_MASK_RANGE_DEG: PhysicalRange = PhysicalRange::new(0.0, 80.0, "degrees");
    /// The satellite image resolutions of a terrain fix, metres per pixel: 1 cm to 100 m
    /// (HiRISE 0.25 m, CTX 6 m).
    pub const IMAGE_RESOLUTION_RANGE_M: PhysicalRange =
        PhysicalRange::new(0.01, 100.0, "metres per pixel");

    /// Checks the ranging, pass and terrain-fix settings against their ranges.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first setting outside its range.
    pub fn validate_settings(settings: &ParkedSettings) -> Result<(), FieldError> {
        Self::RANGE_SIGMA_RANGE_M.check("range_sigma_m", settings.range_sigma_m)?;
        Self::PASS_DURATION_RANGE_S
            .check("pass_duration_s", f64::from(settings.pass_duration_s))?;
        Self::ELEVATION_MASK_RANGE_DEG.check("elevation_mask_deg", settings.elevation_mask_deg)?;
        if let Some(v) = settings.image_resolution_m {
            Self::IMAGE_RESOLUTION_RANGE_M.check("image_resolution_m", v)?;
        }
        Ok(())
    }

    /// [`EkfLocalizer::validate_settings`] of its settings (as `settings.…`).
    ///
    /// # Errors
    /// A [`FieldError`] naming the first setting outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::validate_settings(&self.settings).map_err(|e| e.within("settings"))
    }
}

impl Localizer for EkfLocalizer {
    fn name(&self) -> &'static str {
        "ekf"
    }

    fn hbs(&self) -> HbsSettings {
        self.hbs
    }

    /// Paper 004's EKF: the parked rover ranging to the orbiter through one pass.
    fn localize(&self, at: &mut PostDrive<'_>) -> LocalizationEvent {
        let seed = rand::RngExt::random::<u64>(at.rng);
        let mut event = LocalizationEvent::pending_onboard("ekf", at.start.lmst());
        let r = at.radius_m();
        let offset = at.rover.estimate.position_m - at.rover.truth.position_m;
        if r > 0.0 {
            match localization::ekf::parked_fix(&self.settings, [offset.x, offset.y], r / 3.0, seed)
            {
                Err(e) => event.reason = Some(RejectionReason::Filter(e.to_string())),
                Ok(fix) => match fix.ellipse().map(PositionEllipse::from_ellipse) {
                    Some(ellipse) => {
                        let truth = at.rover.truth.position_m;
                        let mean = [truth.x + fix.error_enu_m[0], truth.y + fix.error_enu_m[1]];
                        at.apply_if_gain(&mut event, r, mean, ellipse);
                    }
                    None => {
                        event.reason = Some(RejectionReason::Filter(
                            "the filter's covariance is not a covariance".into(),
                        ));
                    }
                },
            }
        } else {
            event.reason = Some(RejectionReason::Filter(
                "no gain: the rover's uncertainty is already 0 m".into(),
            ));
        }
        event.uncertainty_after_m = at.radius_m();
        event
    }
}
