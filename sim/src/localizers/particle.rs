//! The particle filter of paper 002 as the post-drive localizer (see the module docs of
//! [`crate::localizers`] for the disc it leaves).

use std::sync::Arc;

use localization::hbs::HbsSettings;
use localization::onboard::{LostReason, OnboardCache, OnboardSettings, render_activity_imagery};
use localization::particle::{PanoramaFix, PanoramaFixSettings, localize_panorama};
use maps::MapLayers;
use rand::SeedableRng as _;
use rand_chacha::ChaCha8Rng;

use super::imagery::ImageryLocalizer;
use super::{Localizer, PostDrive};
use crate::run::outcome::{LocalizationEvent, PositionEllipse, RejectionReason};
use crate::settings::field_error::FieldError;
use crate::settings::physical_range::PhysicalRange;

/// The particle filter of paper 002 as the post-drive localizer.
///
/// Each localization renders the post-drive imagery at the rover's true position (as the
/// image-matching localizers do) and runs
/// [`localize_panorama`](localization::particle::localize_panorama): particles drawn from the
/// uncertainty disc around the estimate (read as 3σ), one measurement update with the census
/// score surface, accepted when the belief has one mode and its disc — 3 × the 1σ semi-major
/// axis of the posterior covariance — is smaller than the rover's. The estimate then moves to
/// the posterior mean and the disc becomes the localizer's σ in the uncertainty margin;
/// otherwise the rejection says why (several modes: perceptual aliasing; no gain; nothing
/// scored).
///
/// It runs on the co-processor like the census matcher (its cost is the same score surface),
/// so it is planned with the image-matching chain's durations; the co-processor's upsets are
/// not modelled for it.
#[derive(Clone, Debug)]
pub struct ParticleLocalizer {
    /// The map the imagery is rendered from.
    pub layers: Arc<MapLayers>,
    /// Imaging, orbital products, matcher (census unless changed) and co-processor settings.
    pub settings: OnboardSettings,
    /// The filter and its verdict (default: [`PanoramaFixSettings::default`]).
    pub fix: PanoramaFixSettings,
    /// Renders shared with the other runs of the scenario (see [`ImageryLocalizer::cache`]).
    pub cache: Arc<OnboardCache>,
}

impl ParticleLocalizer {
    /// A particle localizer on `layers` with default settings.
    #[must_use]
    pub fn new(layers: Arc<MapLayers>) -> Self {
        let settings = OnboardSettings::default();
        let cache = Arc::new(OnboardCache::new(Arc::clone(&layers), &settings.orbital));
        Self {
            layers,
            settings,
            fix: PanoramaFixSettings::default(),
            cache,
        }
    }

    /// The particle counts a filter may have: below 100 a 30 m prior is sampled a particle per
    /// 9 m²; above 100 000 an update holds hundreds of MB and takes seconds.
    pub const PARTICLE_COUNT_RANGE: PhysicalRange =
        PhysicalRange::new(100.0, 100_000.0, "particles");

    /// Checks the filter's settings: the particle count.
    ///
    /// # Errors
    /// A [`FieldError`] naming the setting outside its range.
    pub fn validate_fix(fix: &PanoramaFixSettings) -> Result<(), FieldError> {
        Self::PARTICLE_COUNT_RANGE
            .check("params.particle_count", fix.params.particle_count as f64)?;
        Ok(())
    }

    /// Checks the imaging settings ([`ImageryLocalizer::validate_settings`], as `settings.…`)
    /// and the filter's ([`ParticleLocalizer::validate_fix`], as `fix.…`).
    ///
    /// # Errors
    /// A [`FieldError`] naming the first setting outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        ImageryLocalizer::validate_settings(&self.settings).map_err(|e| e.within("settings"))?;
        Self::validate_fix(&self.fix).map_err(|e| e.within("fix"))
    }
}

impl Localizer for ParticleLocalizer {
    fn name(&self) -> &'static str {
        "particle"
    }

    fn hbs(&self) -> HbsSettings {
        self.settings.hbs
    }

    fn imagery_settings(&self) -> Option<&OnboardSettings> {
        Some(&self.settings)
    }

    /// Paper 002's particle filter on this sol's post-drive imagery.
    fn localize(&self, at: &mut PostDrive<'_>) -> LocalizationEvent {
        let sol_seed = rand::RngExt::random::<u64>(at.rng);
        let mut event = LocalizationEvent::pending_onboard("particle", at.start.lmst());
        let truth = at.rover.truth.position_m;
        let estimate = at.rover.estimate.position_m;
        let r = at.radius_m();
        let window_m = r.clamp(
            self.settings.min_search_radius_m,
            self.settings.max_search_radius_m,
        );
        event.search_radius_m = Some(window_m);
        let request = at.onboard_request(r, sol_seed);
        let mut sol_rng = ChaCha8Rng::seed_from_u64(sol_seed);
        let rover_seed = rand::RngExt::random::<u64>(&mut sol_rng);
        let filter_seed = rand::RngExt::random::<u64>(&mut sol_rng);
        let imagery = match render_activity_imagery(
            &self.layers,
            Some(&self.cache),
            &request,
            &self.settings,
            window_m,
            rover_seed,
        ) {
            Ok(imagery) => imagery,
            Err(e) => {
                event.reason = Some(RejectionReason::Onboard(LostReason::NoImagery(e)));
                event.uncertainty_after_m = r;
                return event;
            }
        };
        let outcome = localize_panorama(
            [estimate.x, estimate.y],
            r,
            &imagery.orbital_map(),
            &imagery.rover_images(),
            &self.settings.matcher,
            &self.fix,
            filter_seed,
        );
        match outcome {
            Err(e) => event.reason = Some(RejectionReason::Filter(e.to_string())),
            Ok(PanoramaFix::Rejected { reason, posterior }) => {
                if let Some(post) = posterior {
                    event.matched_error_m =
                        Some((post.mean_m[0] - truth.x).hypot(post.mean_m[1] - truth.y));
                    event.ellipse = Some(PositionEllipse::from_ellipse(post.ellipse));
                }
                event.reason = Some(RejectionReason::Filter(reason));
            }
            Ok(PanoramaFix::Accepted(post)) => {
                let ellipse = PositionEllipse::from_ellipse(post.ellipse);
                at.apply_if_gain(&mut event, r, post.mean_m, ellipse);
            }
        }
        event.uncertainty_after_m = at.radius_m();
        event
    }
}
