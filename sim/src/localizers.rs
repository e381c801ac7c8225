//! Onboard global localization at the end of a drive sol, behind one trait: [`Localizer`].
//!
//! A localizer reads the rover's true and estimated position and its uncertainty
//! ([`PostDrive`]), draws what it needs from the run's random stream, and either applies a fix
//! (the estimate moves, the disc resets to the localizer's σ plus the operator margin) or
//! rejects it with a reason. Either way it returns the sol log's [`LocalizationEvent`].
//!
//! The localizers, chosen per scenario with `[onboard_localization] localizer = "…"`
//! ([`OnboardLocalizer`]), one file each:
//!
//! - `"statistical"` (the default) — [`StatisticalLocalizer`]: a model of the published flight
//!   accuracy (paper 000 §4: 264 panoramas, mean 0.36 m, 99 % within 0.93 m, no outliers). The
//!   radial error is Weibull-distributed with shape and scale solved so that its mean and 99th
//!   percentile are exactly the configured ones; the direction is uniform. A configurable
//!   fraction of runs is rejected by the validity checks (the rover keeps its uncertainty and
//!   drives on). Thousands of times cheaper than imagery, for Monte Carlo sweeps.
//! - `"census"`, `"ncc"`, `"mi"` — [`ImageryLocalizer`]: the real thing. Post-drive imagery is
//!   rendered from the scenario's map at the rover's *true* position, the matcher runs from the
//!   rover's *estimate*, and the result goes through the co-processor model
//!   ([`localization::onboard::run_onboard`]); the HBS steps are sol-log events and the
//!   activity's duration sits in the sol timeline.
//! - `"particle"` — [`ParticleLocalizer`]: paper 002's particle filter on the same rendered
//!   imagery, weighted by the census score surface.
//! - `"ekf"` — [`EkfLocalizer`]: paper 004's EKF, the parked rover ranging to an orbiter.
//!
//! **A localizer of your own** implements [`Localizer`] and goes in
//! [`OnboardLocalizer::Custom`]; the runner plans its chain with [`Localizer::hbs`]'s durations
//! and calls [`Localizer::localize`] where the chain's first co-processor step starts.
//!
//! ## The two filters' disc
//! The particle filter and the EKF start from the rover's uncertainty disc read as a 3σ bound
//! around its estimate, and both end with a 2×2 position covariance. That covariance becomes
//! the disc the keep-out zones grow by **conservatively**: its radius is 3 × the 1σ semi-major
//! axis, so the disc holds the whole 3σ ellipse (≥ 98.9 % of a Gaussian belief whatever its
//! shape, against 98.9 % for the 3σ ellipse itself). The disc is the localizer's σ in
//! [`crate::rover::uncertainty::UncertaintyState::reset_onboard`], plus the operator margin, as
//! the statistical model's p99 is. The 1σ ellipse goes to the sol log ([`PositionEllipse`]). A
//! filter result is applied only if it gains ([`PostDrive::apply_if_gain`]): its disc must be
//! smaller than the radius the rover had, and the particle belief must have one mode. Neither
//! filter runs on the co-processor's fault model; their activity keeps the chain's planned
//! durations.
//!
//! ## References
//! Paper 000 §4 (accuracy), §7 (validity checks, uncertainty after a localization).

use std::sync::Arc;

use localization::hbs::HbsSettings;
use localization::onboard::{OnboardRequest, OnboardSettings};
use localization::particle::no_gain;
use rand_chacha::ChaCha8Rng;

use crate::rover::autonav::RoverState;
use crate::rover::uncertainty::UncertaintyModel;
use crate::run::outcome::{LocalizationEvent, PositionEllipse, RejectionReason};
use crate::seeds::{Purpose, RunSeeds};
use crate::settings::field_error::FieldError;
use crate::settings::physical_range::PhysicalRange;
use crate::time::SolSeconds;

mod ekf;
mod imagery;
mod particle;
mod statistical;

pub use ekf::EkfLocalizer;
pub use imagery::ImageryLocalizer;
pub use particle::ParticleLocalizer;
pub use statistical::{LocalizationResult, StatisticalLocalizer};

/// An onboard localizer: what runs at the end of a drive sol to fix the rover's position.
pub trait Localizer: std::fmt::Debug + Send + Sync {
    /// The name used in scenario files and outputs (`statistical`, `census`, …).
    fn name(&self) -> &'static str;

    /// The co-processor settings the localization chain runs (and is planned) with: the link
    /// rate, the reboot, the run time.
    fn hbs(&self) -> HbsSettings;

    /// The imaging, matcher and co-processor settings of a localizer that renders post-drive
    /// imagery and runs on the co-processor (census, NCC, MI, particle): its run is planned at
    /// the measured flight-size run time scaled by `hbs_slowdown`. `None` otherwise.
    fn imagery_settings(&self) -> Option<&OnboardSettings> {
        None
    }

    /// Localize the rover at the end of a drive: apply a fix to `at.rover` or reject it, and
    /// return the sol log's event. Every random draw comes from `at.rng`, in the same order
    /// every time, so a run repeats bit for bit.
    fn localize(&self, at: &mut PostDrive<'_>) -> LocalizationEvent;
}

/// What a localizer reads and changes at the end of a drive sol.
pub struct PostDrive<'a> {
    /// The rover: its true position, its estimate and its uncertainty disc.
    pub rover: &'a mut RoverState,
    /// The uncertainty model the disc grows under.
    pub model: &'a UncertaintyModel,
    /// Added to the localizer's σ after a fix, metres.
    pub operator_margin_m: f64,
    /// The run's seeds: its world (the true terrain the post-drive imagery is rendered from,
    /// the orbital map it is matched against) and any stream a localizer draws from.
    pub seeds: RunSeeds,
    /// When the chain's first co-processor step starts (not before midnight).
    pub start: SolSeconds,
    /// The run's random stream.
    pub rng: &'a mut ChaCha8Rng,
}

impl PostDrive<'_> {
    /// The rover's uncertainty radius now, metres.
    #[must_use]
    pub fn radius_m(&self) -> f64 {
        self.rover.uncertainty.radius_m(self.model)
    }

    /// The co-processor's request for this rover: matched from its estimate within
    /// `uncertainty_m`, the imagery rendered at its true position in the run's world, the sol's
    /// imaging and upsets drawn from `sol_seed`.
    #[must_use]
    pub fn onboard_request(&self, uncertainty_m: f64, sol_seed: u64) -> OnboardRequest {
        let (truth, estimate) = (self.rover.truth.position_m, self.rover.estimate.position_m);
        OnboardRequest {
            truth_m: [truth.x, truth.y],
            prior_m: [estimate.x, estimate.y],
            uncertainty_m,
            truth_seed: self.seeds.stream(Purpose::WorldTruth).seed,
            orbital_seed: self.seeds.stream(Purpose::WorldOrbital).seed,
            sol_seed,
        }
    }

    /// Move the estimate to `position_m` and reset the disc to `sigma_m` plus the operator
    /// margin; marks `event` applied with the fix's error and σ.
    pub fn apply(&mut self, event: &mut LocalizationEvent, position_m: [f64; 2], sigma_m: f64) {
        let truth = self.rover.truth.position_m;
        self.rover.estimate.position_m = nalgebra::Vector2::new(position_m[0], position_m[1]);
        self.rover
            .uncertainty
            .reset_onboard(sigma_m, self.operator_margin_m);
        self.rover.clear_path();
        event.applied = true;
        event.error_m = Some((position_m[0] - truth.x).hypot(position_m[1] - truth.y));
        event.sigma_m = Some(sigma_m);
    }

    /// Apply a filter's posterior (mean `mean_m`, 1σ ellipse) if its disc is smaller than the
    /// radius `prior_r_m` the rover had; otherwise reject it for no gain.
    pub fn apply_if_gain(
        &mut self,
        event: &mut LocalizationEvent,
        prior_r_m: f64,
        mean_m: [f64; 2],
        ellipse: PositionEllipse,
    ) {
        let truth = self.rover.truth.position_m;
        event.matched_error_m = Some((mean_m[0] - truth.x).hypot(mean_m[1] - truth.y));
        event.ellipse = Some(ellipse);
        if ellipse.disc_radius_m < prior_r_m {
            self.apply(event, mean_m, ellipse.disc_radius_m);
        } else {
            event.reason = Some(RejectionReason::Filter(no_gain(
                ellipse.disc_radius_m,
                prior_r_m,
            )));
        }
    }
}

/// The onboard localizer of a scenario: one of the built-in localizers, or your own.
#[derive(Clone, Debug)]
pub enum OnboardLocalizer {
    /// The statistical model of the flight accuracy.
    Statistical(StatisticalLocalizer),
    /// Image matching on rendered post-drive imagery, through the co-processor model.
    Imagery(Box<ImageryLocalizer>),
    /// The particle filter of paper 002 on the census score surface of the post-drive imagery.
    Particle(Box<ParticleLocalizer>),
    /// The EKF of paper 004: the parked rover ranging to an orbiter through one pass.
    Ekf(EkfLocalizer),
    /// A localizer of your own.
    Custom(Arc<dyn Localizer>),
}

/// The HBS serial link rates a built-in localizer may be planned with, KB/s (1 KB = 1000
/// bytes; its settings hold bytes per second): 10 KB/s flown, 40 possible (paper 000 §6).
/// Below 1 KB/s the flight-size inputs take over five hours, beyond a sol's activities; above
/// 1000 it is not this serial link.
pub const HBS_LINK_RATE_KB_PER_S: PhysicalRange = PhysicalRange::new(
    1.0,
    1_000.0,
    "KB/s (1 KB = 1000 bytes; 10 flown, 40 after an RCE flight-software update)",
);

impl OnboardLocalizer {
    /// Checks a built-in localizer's own settings (`StatisticalLocalizer::validate`, …) and
    /// its link rate ([`HBS_LINK_RATE_KB_PER_S`], named `hbs_link_rate_kb_per_s`); a custom
    /// localizer checks its own.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first setting at fault.
    pub fn validate(&self) -> Result<(), FieldError> {
        match self {
            OnboardLocalizer::Statistical(s) => s.validate()?,
            OnboardLocalizer::Imagery(i) => i.validate()?,
            OnboardLocalizer::Particle(p) => p.validate()?,
            OnboardLocalizer::Ekf(e) => e.validate()?,
            OnboardLocalizer::Custom(_) => return Ok(()),
        }
        let link_kb_per_s = self.hbs().link_bytes_per_s / 1_000.0;
        HBS_LINK_RATE_KB_PER_S.check("hbs_link_rate_kb_per_s", link_kb_per_s)?;
        Ok(())
    }

    /// The localizer behind the setting.
    #[must_use]
    pub fn get(&self) -> &dyn Localizer {
        match self {
            OnboardLocalizer::Statistical(s) => s,
            OnboardLocalizer::Imagery(i) => i.as_ref(),
            OnboardLocalizer::Particle(p) => p.as_ref(),
            OnboardLocalizer::Ekf(e) => e,
            OnboardLocalizer::Custom(c) => c.as_ref(),
        }
    }

    /// The name used in scenario files and outputs: `statistical`, `census`, `ncc`, `mi`,
    /// `particle`, `ekf`, or a custom localizer's.
    #[must_use]
    pub fn name(&self) -> &'static str {
        self.get().name()
    }

    /// See [`Localizer::imagery_settings`].
    #[must_use]
    pub fn imagery_settings(&self) -> Option<&OnboardSettings> {
        self.get().imagery_settings()
    }

    /// See [`Localizer::hbs`].
    #[must_use]
    pub fn hbs(&self) -> HbsSettings {
        self.get().hbs()
    }

    /// Set the HBS link rate, bytes per second (the scenario's `hbs_link_rate_kb_per_s`), of
    /// a built-in localizer; a custom one keeps its own.
    pub fn set_link_bytes_per_s(&mut self, link_bytes_per_s: f64) {
        let hbs = match self {
            OnboardLocalizer::Statistical(s) => &mut s.hbs,
            OnboardLocalizer::Imagery(i) => &mut i.settings.hbs,
            OnboardLocalizer::Particle(p) => &mut p.settings.hbs,
            OnboardLocalizer::Ekf(e) => &mut e.hbs,
            OnboardLocalizer::Custom(_) => return,
        };
        hbs.link_bytes_per_s = link_bytes_per_s;
    }
}

impl Default for OnboardLocalizer {
    fn default() -> Self {
        OnboardLocalizer::Statistical(StatisticalLocalizer::default())
    }
}
