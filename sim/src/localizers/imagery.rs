//! The image-matching localizers (census, NCC, MI): post-drive imagery rendered at the true
//! position, matched from the estimate through the co-processor model (paper 000 §5, §7).

use std::sync::Arc;

use localization::hbs::HbsSettings;
use localization::matcher::Method;
use localization::onboard::{OnboardCache, OnboardSettings, run_onboard_with};
use maps::MapLayers;

use super::{Localizer, PostDrive};
use crate::run::outcome::{ActivityStep, LocalizationEvent, LocalizationKind, RejectionReason};
use crate::settings::field_error::FieldError;
use crate::settings::physical_range::PhysicalRange;

/// Image-matching localizer: the scenario's map (shared between strategies) and the activity's
/// settings.
#[derive(Clone, Debug)]
pub struct ImageryLocalizer {
    /// The map the imagery is rendered from (appearance, DEM, terrain class).
    pub layers: Arc<MapLayers>,
    /// Matcher, imaging and co-processor settings.
    pub settings: OnboardSettings,
    /// What the localizations on `layers` share (terrain fields, recent renders), filled by
    /// the runs as they go and shared by every run of the scenario (and every thread). Used only
    /// while it is the cache of `layers` ([`OnboardCache::serves`]); the results are the same
    /// with or without it.
    pub cache: Arc<OnboardCache>,
}

impl ImageryLocalizer {
    /// A localizer with `method` and default settings otherwise.
    #[must_use]
    pub fn new(layers: Arc<MapLayers>, method: Method) -> Self {
        let mut settings = OnboardSettings::default();
        settings.matcher.method = method;
        let cache = Arc::new(OnboardCache::new(Arc::clone(&layers), &settings.orbital));
        Self {
            layers,
            settings,
            cache,
        }
    }

    /// The co-processor slowdowns a localizer may run with, seconds per second of the
    /// development machine's run: the flown chain is 1758.2 (a flight-size run takes 32 s,
    /// paper 000); 1 is a co-processor as fast as a desktop; at 100,000 a run takes half an
    /// hour.
    pub const HBS_SLOWDOWN_RANGE: PhysicalRange =
        PhysicalRange::new(1.0, 100_000.0, "seconds per second");

    /// Checks the settings an image-matching localizer runs with (the particle filter's too):
    /// the co-processor slowdown.
    ///
    /// # Errors
    /// A [`FieldError`] naming the setting outside its range.
    pub fn validate_settings(settings: &OnboardSettings) -> Result<(), FieldError> {
        Self::HBS_SLOWDOWN_RANGE.check("hbs_slowdown", settings.hbs_slowdown)?;
        Ok(())
    }

    /// [`ImageryLocalizer::validate_settings`] of its settings (as `settings.…`).
    ///
    /// # Errors
    /// A [`FieldError`] naming the setting outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::validate_settings(&self.settings).map_err(|e| e.within("settings"))
    }
}

impl Localizer for ImageryLocalizer {
    fn name(&self) -> &'static str {
        self.settings.matcher.method.name()
    }

    fn hbs(&self) -> HbsSettings {
        self.settings.hbs
    }

    fn imagery_settings(&self) -> Option<&OnboardSettings> {
        Some(&self.settings)
    }

    /// Render the post-drive imagery at the true position, match it from the estimate through
    /// the co-processor model, and apply the result if it passed every check.
    fn localize(&self, at: &mut PostDrive<'_>) -> LocalizationEvent {
        let sol_seed = rand::RngExt::random::<u64>(at.rng);
        let truth = at.rover.truth.position_m;
        // One world and one orbital map per run; the imaging and upsets change each sol.
        let request = at.onboard_request(at.radius_m(), sol_seed);
        let run = run_onboard_with(&self.layers, Some(&self.cache), &request, &self.settings);
        let start = at.start;
        let lmst = |t_s: f64| start.after_s(t_s).lmst();
        let mut event = LocalizationEvent {
            kind: LocalizationKind::Onboard,
            localizer: self.name(),
            applied: false,
            reason: run.lost_reason.clone().map(RejectionReason::Onboard),
            error_m: None,
            matched_error_m: run
                .matched
                .as_ref()
                .map(|m| (m.position_m[0] - truth.x).hypot(m.position_m[1] - truth.y)),
            sigma_m: None,
            search_radius_m: Some(run.search_radius_m),
            ellipse: None,
            uncertainty_after_m: 0.0,
            start_lmst: Some(start.lmst()),
            duration_s: Some(run.log.duration_s),
            steps: run
                .log
                .events
                .iter()
                .map(|e| ActivityStep {
                    lmst: Some(lmst(e.t_s)),
                    t_s: e.t_s,
                    step: e.step.into(),
                    detail: e.detail.clone(),
                })
                .collect(),
        };
        if let Some(fix) = run.applied {
            at.apply(&mut event, fix.position_m, fix.sigma_m);
        }
        event.uncertainty_after_m = at.radius_m();
        event
    }
}
