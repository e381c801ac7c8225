//! Onboard global localization, as the simulator sees it: a result (an error relative to the
//! truth and the localizer's reported σ) or a rejection with a reason.
//!
//! The localizers ([`OnboardLocalizer`]), chosen per scenario with
//! `[onboard_localization] localizer = "…"`:
//!
//! - `"census"`, `"ncc"`, `"mi"` — [`ImageryLocalizer`]: the real thing. Post-drive imagery is
//!   rendered from the scenario's map at the rover's *true* position, the matcher runs from the
//!   rover's *estimate*, and the result goes through the co-processor model
//!   ([`localization::onboard::run_onboard`]); the HBS steps are sol-log events and the
//!   activity's duration sits in the sol timeline.
//! - `"particle"` — [`ParticleLocalizer`]: paper 002's particle filter on the same rendered
//!   imagery, weighted by the census score surface.
//! - `"ekf"` — [`EkfLocalizer`]: paper 004's EKF, the parked rover ranging to an orbiter.
//! - `"statistical"` (the default) — [`StatisticalLocalizer`]: a model of the published flight
//!   accuracy (paper 000 §4: 264 panoramas, mean 0.36 m, 99 % within 0.93 m, no outliers). The
//!   radial error is Weibull-distributed with shape and scale solved so that its mean and 99th
//!   percentile are exactly the configured ones; the direction is uniform. A configurable
//!   fraction of runs is rejected by the validity checks (the rover keeps its uncertainty and
//!   drives on). Thousands of times cheaper than imagery, for Monte Carlo sweeps.
//!
//! ## References
//! Paper 000 §4 (accuracy), §7 (validity checks, uncertainty after a localization).

use std::sync::Arc;

use crate::outcome::RejectionReason;
use localization::ekf::ParkedSettings;
use localization::hbs::HbsParams;
use localization::matcher::Method;
use localization::onboard::{OnboardCache, OnboardSettings};
use localization::particle::PanoramaFixSettings;
use maps::MapLayers;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Settings of the statistical localizer (plain struct).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StatisticalLocalizer {
    /// Mean radial error, metres (default: 0.36, paper 000 §4).
    pub mean_error_m: f64,
    /// 99th-percentile radial error, metres (default: 0.93, paper 000 §4). Must exceed the mean.
    pub p99_error_m: f64,
    /// Fraction of runs rejected by validity checks, 0..1 (default: 0.02).
    pub failure_rate: f64,
    /// σ the localizer reports with an accepted result, metres (default: 0.93, the p99 envelope).
    pub reported_sigma_m: f64,
    /// The co-processor the localization chain is planned on: the statistical model draws the
    /// result, but the sol plan still holds the chain, its transfer timed at this link rate
    /// (default: [`HbsParams::default`], 10 KB/s).
    pub hbs: HbsParams,
}

impl Default for StatisticalLocalizer {
    fn default() -> Self {
        Self {
            mean_error_m: 0.36,
            p99_error_m: 0.93,
            failure_rate: 0.02,
            reported_sigma_m: 0.93,
            hbs: HbsParams::default(),
        }
    }
}

/// The onboard localizer of a campaign.
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
}

impl OnboardLocalizer {
    /// The name used in scenario files and outputs: `statistical`, `census`, `ncc`, `mi`,
    /// `particle` or `ekf`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            OnboardLocalizer::Statistical(_) => "statistical",
            OnboardLocalizer::Imagery(i) => i.settings.matcher.method.name(),
            OnboardLocalizer::Particle(_) => "particle",
            OnboardLocalizer::Ekf(_) => "ekf",
        }
    }

    /// The imaging, matcher and co-processor settings of a localizer that renders post-drive
    /// imagery and runs on the co-processor (census, NCC, MI, particle); `None` otherwise.
    #[must_use]
    pub fn imagery_settings(&self) -> Option<&OnboardSettings> {
        match self {
            OnboardLocalizer::Imagery(i) => Some(&i.settings),
            OnboardLocalizer::Particle(p) => Some(&p.settings),
            OnboardLocalizer::Statistical(_) | OnboardLocalizer::Ekf(_) => None,
        }
    }

    /// The co-processor settings the chain runs (and is planned) with: the link rate, the
    /// reboot, the run time of the statistical model.
    #[must_use]
    pub fn hbs(&self) -> HbsParams {
        match self {
            OnboardLocalizer::Statistical(s) => s.hbs,
            OnboardLocalizer::Imagery(i) => i.settings.hbs,
            OnboardLocalizer::Particle(p) => p.settings.hbs,
            OnboardLocalizer::Ekf(e) => e.hbs,
        }
    }

    /// Set the HBS link rate, bytes per second (the scenario's `hbs_link_rate_kb_per_s`).
    pub fn set_link_bytes_per_s(&mut self, link_bytes_per_s: f64) {
        let hbs = match self {
            OnboardLocalizer::Statistical(s) => &mut s.hbs,
            OnboardLocalizer::Imagery(i) => &mut i.settings.hbs,
            OnboardLocalizer::Particle(p) => &mut p.settings.hbs,
            OnboardLocalizer::Ekf(e) => &mut e.hbs,
        };
        hbs.link_bytes_per_s = link_bytes_per_s;
    }
}

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
}

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
    pub hbs: HbsParams,
}

impl Default for OnboardLocalizer {
    fn default() -> Self {
        OnboardLocalizer::Statistical(StatisticalLocalizer::default())
    }
}

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
}

/// What one onboard localization run produced.
#[derive(Clone, Debug, PartialEq)]
pub enum LocalizationResult {
    /// Passed the validity checks: the estimate moves to `truth + error_m`.
    Accepted {
        /// Error of the result relative to the true position, metres (east, north).
        error_m: [f64; 2],
        /// The localizer's own σ, metres.
        sigma_m: f64,
    },
    /// Failed the validity checks; nothing is applied.
    Rejected {
        /// Why, for the sol log.
        reason: RejectionReason,
    },
}

impl StatisticalLocalizer {
    /// Weibull `(shape k, scale λ)` with the configured mean and p99.
    ///
    /// The ratio p99/mean of a Weibull depends on `k` only and falls as `k` grows, so `k` is found
    /// by bisection; then `λ = mean / Γ(1 + 1/k)`.
    #[must_use]
    pub fn weibull_parameters(&self) -> (f64, f64) {
        let target = self.p99_error_m / self.mean_error_m;
        let ratio = |k: f64| (-(0.01f64).ln()).powf(1.0 / k) / gamma(1.0 + 1.0 / k);
        let (mut lo, mut hi) = (0.3f64, 20.0f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if ratio(mid) > target {
                lo = mid
            } else {
                hi = mid
            }
        }
        let k = 0.5 * (lo + hi);
        (k, self.mean_error_m / gamma(1.0 + 1.0 / k))
    }

    /// Run one localization.
    pub fn localize(&self, rng: &mut ChaCha8Rng) -> LocalizationResult {
        let (k, lambda) = self.weibull_parameters();
        let fail: f64 = rng.random();
        let u: f64 = rng.random();
        let angle: f64 = rng.random::<f64>() * std::f64::consts::TAU;
        if fail < self.failure_rate {
            return LocalizationResult::Rejected {
                reason: RejectionReason::ModelledAmbiguousMatch,
            };
        }
        let radius = lambda * (-(1.0 - u).ln()).powf(1.0 / k);
        LocalizationResult::Accepted {
            error_m: [radius * angle.cos(), radius * angle.sin()],
            sigma_m: self.reported_sigma_m,
        }
    }
}

/// Γ(x) for x > 0 (Lanczos, g = 7; relative error below 1e-13 on 1..3).
fn gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return std::f64::consts::PI / ((std::f64::consts::PI * x).sin() * gamma(1.0 - x));
    }
    let x = x - 1.0;
    let t = x + 7.5;
    let series = C[1..]
        .iter()
        .enumerate()
        .fold(C[0], |acc, (i, c)| acc + c / (x + i as f64 + 1.0));
    (2.0 * std::f64::consts::PI).sqrt() * t.powf(x + 0.5) * (-t).exp() * series
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn gamma_known_values() {
        assert!((gamma(1.0) - 1.0).abs() < 1e-12);
        assert!((gamma(1.5) - std::f64::consts::PI.sqrt() / 2.0).abs() < 1e-12);
        assert!((gamma(5.0) - 24.0).abs() < 1e-9);
    }

    #[test]
    fn sampled_errors_match_the_published_statistics() {
        let loc = StatisticalLocalizer {
            failure_rate: 0.0,
            ..Default::default()
        };
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut errors: Vec<f64> = (0..200_000)
            .map(|_| match loc.localize(&mut rng) {
                LocalizationResult::Accepted { error_m, .. } => error_m[0].hypot(error_m[1]),
                LocalizationResult::Rejected { .. } => unreachable!("failure rate is zero"),
            })
            .collect();
        errors.sort_by(f64::total_cmp);
        let mean = errors.iter().sum::<f64>() / errors.len() as f64;
        let p99 = errors[(errors.len() as f64 * 0.99) as usize];
        assert!((mean - 0.36).abs() < 0.005, "mean {mean}");
        assert!((p99 - 0.93).abs() < 0.02, "p99 {p99}");
    }

    #[test]
    fn failure_rate_is_honoured() {
        let loc = StatisticalLocalizer {
            failure_rate: 0.25,
            ..Default::default()
        };
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let rejected = (0..40_000)
            .filter(|_| matches!(loc.localize(&mut rng), LocalizationResult::Rejected { .. }))
            .count();
        assert!((rejected as f64 / 40_000.0 - 0.25).abs() < 0.01);
    }
}
