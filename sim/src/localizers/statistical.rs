//! The statistical localizer: a model of the flight accuracy (paper 000 §4), drawn, not run.

use localization::hbs::HbsSettings;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::{Localizer, PostDrive};
use crate::run::outcome::{LocalizationEvent, RejectionReason};
use crate::settings::field_error::FieldError;
use crate::settings::physical_range::{MARGIN_M, PhysicalRange, check_fraction};

/// Settings of the statistical localizer (plain struct).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StatisticalLocalizer {
    /// Mean radial error, metres (default: 0.36, paper 000 §4; range
    /// [`StatisticalLocalizer::ERROR_RANGE_M`]).
    pub mean_error_m: f64,
    /// 99th-percentile radial error, metres (default: 0.93, paper 000 §4; range
    /// [`StatisticalLocalizer::ERROR_RANGE_M`]). Must exceed the mean: more than 1.05 ×
    /// `mean_error_m`.
    pub p99_error_m: f64,
    /// Fraction of runs rejected by validity checks, 0..1 (default: 0.02).
    pub failure_rate: f64,
    /// σ the localizer reports with an accepted result, metres (default: 0.93, the p99 envelope;
    /// range [`crate::settings::physical_range::MARGIN_M`]).
    pub reported_sigma_m: f64,
    /// The co-processor the localization chain is planned on: the statistical model draws the
    /// result, but the sol plan still holds the chain, its transfer timed at this link rate
    /// (default: [`HbsSettings::default`], 10 KB/s).
    pub hbs: HbsSettings,
}

impl Default for StatisticalLocalizer {
    fn default() -> Self {
        Self {
            mean_error_m: 0.36,
            p99_error_m: 0.93,
            failure_rate: 0.02,
            reported_sigma_m: 0.93,
            hbs: HbsSettings::default(),
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
    /// The typical errors a localizer may have (`mean_error_m`, `p99_error_m`), metres: 1 cm
    /// is below any orbital map's pixel (HiRISE: 25 cm), 1 km is no localization.
    pub const ERROR_RANGE_M: PhysicalRange = PhysicalRange::new(0.01, 1_000.0, "metres");

    /// Checks each setting against its range and the p99 against the mean.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field at fault.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::ERROR_RANGE_M.check("mean_error_m", self.mean_error_m)?;
        Self::ERROR_RANGE_M.check("p99_error_m", self.p99_error_m)?;
        check_fraction("failure_rate", self.failure_rate)?;
        MARGIN_M.check("reported_sigma_m", self.reported_sigma_m)?;
        if self.p99_error_m <= self.mean_error_m * 1.05 {
            return Err(FieldError::new(
                "p99_error_m",
                format!("more than 1.05 × mean_error_m ({} m)", self.mean_error_m),
                self.p99_error_m,
            )
            .naming("mean_error_m"));
        }
        Ok(())
    }

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

    /// Draw one localization's result: three draws from `rng`, whatever the outcome.
    pub fn draw(&self, rng: &mut ChaCha8Rng) -> LocalizationResult {
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

impl Localizer for StatisticalLocalizer {
    fn name(&self) -> &'static str {
        "statistical"
    }

    fn hbs(&self) -> HbsSettings {
        self.hbs
    }

    fn localize(&self, at: &mut PostDrive<'_>) -> LocalizationEvent {
        let result = self.draw(at.rng);
        let mut event = LocalizationEvent::pending_onboard("statistical", at.start.lmst());
        match result {
            LocalizationResult::Accepted { error_m, sigma_m } => {
                let truth = at.rover.truth.position_m;
                let fix = [truth.x + error_m[0], truth.y + error_m[1]];
                at.apply(&mut event, fix, sigma_m);
                // The error as drawn, not as recomputed from the rounded fix.
                event.error_m = Some(error_m[0].hypot(error_m[1]));
            }
            LocalizationResult::Rejected { reason } => event.reason = Some(reason),
        }
        event.uncertainty_after_m = at.radius_m();
        event
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
            .map(|_| match loc.draw(&mut rng) {
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
            .filter(|_| matches!(loc.draw(&mut rng), LocalizationResult::Rejected { .. }))
            .count();
        assert!((rejected as f64 / 40_000.0 - 0.25).abs() < 0.01);
    }
}
