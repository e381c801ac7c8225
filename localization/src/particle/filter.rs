//! [`ParticleFilter`]: the particles, prediction, reweighting, resampling from the particles,
//! and the posterior.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::motion::{Odometry, Prior};
use super::posterior::{Ellipse, Mode, Posterior, mean_and_covariance, modes};
use super::resample::{effective_sample_size, kld_indices, systematic_indices};
use super::settings::{ParticleSettings, Resampling};
use super::{ParticleError, check};

/// Why a measurement update left the weights as they were (an outcome, not an error).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub enum SkipReason {
    /// Too few valid orthomosaic pixels to say anything (below the matcher's
    /// [`MatchSettings::min_valid_fraction`](crate::matcher::MatchSettings::min_valid_fraction)).
    TooFewValid {
        /// Fraction of valid pixels, 0..1.
        fraction: f64,
    },
    /// No particle with weight sits where the orthomosaic can be scored on the map (the map
    /// must extend half the orthomosaic beyond the rover).
    NoParticleOnMap,
    /// Every particle's likelihood was zero or not finite, so the weights would vanish.
    DegenerateWeights,
}

impl std::fmt::Display for SkipReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SkipReason::TooFewValid { fraction } => write!(
                f,
                "only {:.1} % of the orthomosaic is valid",
                fraction * 100.0
            ),
            SkipReason::NoParticleOnMap => {
                f.write_str("no particle lies where the orthomosaic fits on the map")
            }
            SkipReason::DegenerateWeights => f.write_str("every particle's likelihood vanished"),
        }
    }
}

/// What one measurement update did.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct UpdateReport {
    /// `None` if the weights were updated, else why not (the belief is then unchanged).
    pub skipped: Option<SkipReason>,
    /// Fraction of the particles with weight left after the update (the others were not
    /// scored or their likelihood underflowed to 0), 0..1.
    pub scored_fraction: f64,
    /// Lowest score the likelihood is relative to (score units, lower is better): over the
    /// surfaces for [`ParticleFilter::update`], over the particles for
    /// [`ParticleFilter::update_with_scores`].
    pub best_score: Option<f64>,
    /// Effective sample size right after the reweighting, before any resampling.
    pub effective_sample_size: f64,
    /// Whether the particles were resampled.
    pub resampled: bool,
    /// Whether that resampling drew from the posterior on the score surface's grid (the
    /// regularised resampling of [`ParticleFilter::update`]) rather than from the weighted
    /// particles.
    pub resampled_on_grid: bool,
    /// Score surfaces computed (one per tile of [`ParticleSettings::max_surface_half_extent_m`]).
    pub surfaces: usize,
}

impl UpdateReport {
    pub(super) fn skip(reason: SkipReason, ess: f64, surfaces: usize) -> Self {
        Self {
            skipped: Some(reason),
            scored_fraction: 0.0,
            best_score: None,
            effective_sample_size: ess,
            resampled: false,
            resampled_on_grid: false,
            surfaces,
        }
    }
}

/// A particle filter over the rover's map position (see the [module docs](super)).
#[derive(Clone, Debug)]
pub struct ParticleFilter {
    /// Particle positions, map metres (x east, y north).
    pub(super) positions_m: Vec<[f64; 2]>,
    /// Normalised importance weights (sum 1).
    pub(super) weights: Vec<f64>,
    pub(super) params: ParticleSettings,
    pub(super) rng: ChaCha8Rng,
}

impl ParticleFilter {
    /// [`ParticleSettings::particle_count`] particles drawn from `prior`, equally weighted, with
    /// the filter's random stream seeded by `seed`.
    ///
    /// # Errors
    /// [`ParticleError::InvalidParameter`] if `params` or `prior` is out of range.
    pub fn new(prior: &Prior, params: ParticleSettings, seed: u64) -> Result<Self, ParticleError> {
        params.validate()?;
        prior.validate()?;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let n = params.particle_count;
        let positions_m = (0..n).map(|_| prior.sample(&mut rng)).collect();
        Ok(Self {
            positions_m,
            weights: vec![1.0 / n as f64; n],
            params,
            rng,
        })
    }

    /// A filter holding the given particles; `weights` need not sum to 1 (they are normalised)
    /// but must be finite, ≥ 0 and not all 0.
    ///
    /// # Errors
    /// [`ParticleError::LengthMismatch`] if the lengths differ;
    /// [`ParticleError::InvalidParameter`] if `params` is out of range, there is no particle,
    /// a position is not finite or the weights are not as above.
    pub fn from_particles(
        positions_m: Vec<[f64; 2]>,
        weights: Vec<f64>,
        params: ParticleSettings,
        seed: u64,
    ) -> Result<Self, ParticleError> {
        params.validate()?;
        if positions_m.len() != weights.len() {
            return Err(ParticleError::LengthMismatch {
                positions: positions_m.len(),
                weights: weights.len(),
            });
        }
        check(
            "positions_m.len()",
            positions_m.len() as f64,
            "at least 1",
            |v| v >= 1.0,
        )?;
        for p in &positions_m {
            check("positions_m[_]", p[0], "finite", f64::is_finite)?;
            check("positions_m[_]", p[1], "finite", f64::is_finite)?;
        }
        for &w in &weights {
            check("weights[_]", w, "≥ 0, finite", |v| {
                v >= 0.0 && v.is_finite()
            })?;
        }
        let sum: f64 = weights.iter().sum();
        check("weights (sum)", sum, "> 0, finite", |v| {
            v > 0.0 && v.is_finite()
        })?;
        Ok(Self {
            positions_m,
            weights: weights.iter().map(|w| w / sum).collect(),
            params,
            rng: ChaCha8Rng::seed_from_u64(seed),
        })
    }

    /// Number of particles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.positions_m.len()
    }

    /// Whether there is no particle (never, for a filter built by [`ParticleFilter::new`] or
    /// [`ParticleFilter::from_particles`]).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.positions_m.is_empty()
    }

    /// Particle positions, map metres (x east, y north).
    #[must_use]
    pub fn positions_m(&self) -> &[[f64; 2]] {
        &self.positions_m
    }

    /// Normalised weights (sum 1), one per particle.
    #[must_use]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The settings.
    #[must_use]
    pub fn params(&self) -> &ParticleSettings {
        &self.params
    }

    /// Effective sample size of the weights, `1 / Σ wᵢ²` (1..N).
    #[must_use]
    pub fn effective_sample_size(&self) -> f64 {
        effective_sample_size(&self.weights)
    }

    /// Prediction (paper 002 eq. 4): every particle moves by the odometry displacement plus
    /// isotropic Gaussian noise of σ = [`super::MotionModel::sigma_m`] per axis, one draw per
    /// particle and axis.
    ///
    /// # Errors
    /// [`ParticleError::InvalidParameter`] if the odometry is not finite or a distance is
    /// negative.
    pub fn predict(&mut self, odometry: &Odometry) -> Result<(), ParticleError> {
        odometry.validate()?;
        let sigma = self.params.motion.sigma_m(odometry);
        let [dx, dy] = odometry.displacement_m;
        for p in &mut self.positions_m {
            let (a, b): (f64, f64) = (
                self.rng.sample(StandardNormal),
                self.rng.sample(StandardNormal),
            );
            p[0] += dx + sigma * a;
            p[1] += dy + sigma * b;
        }
        Ok(())
    }

    /// The weight update and resampling of [`ParticleFilter::update`] from scores already
    /// computed, one per particle (lower is better, in the units
    /// [`ParticleSettings::temperature`] is calibrated in; `None` or a non-finite score means
    /// likelihood 0), for a caller with its own similarity source: each weight is multiplied
    /// by `exp(−(s − s_min) / T)`. There is no grid here, so no registration blur, and the
    /// resampling, when the effective sample size calls for it, draws from the weighted
    /// particles ([`ParticleFilter::resample`]).
    ///
    /// # Errors
    /// [`ParticleError::ScoreCountMismatch`] if there is not one score per particle.
    pub fn update_with_scores(
        &mut self,
        scores: &[Option<f64>],
    ) -> Result<UpdateReport, ParticleError> {
        if scores.len() != self.len() {
            return Err(ParticleError::ScoreCountMismatch {
                particles: self.len(),
                scores: scores.len(),
            });
        }
        let usable = |i: usize| -> Option<f64> {
            scores[i].filter(|s| s.is_finite() && self.weights[i] > 0.0)
        };
        let best = (0..self.len()).filter_map(usable).min_by(f64::total_cmp);
        let t = self.params.temperature;
        let likelihood: Vec<f64> = (0..self.len())
            .map(|i| match (usable(i), best) {
                (Some(s), Some(b)) => (-(s - b) / t).exp(),
                _ => 0.0,
            })
            .collect();
        let no_score = scores.iter().all(Option::is_none);
        let report = self.reweight(&likelihood, best, no_score);
        if report.resampled {
            self.resample();
        }
        Ok(report)
    }

    /// Multiplies each weight by its `likelihood` (one per particle, ≥ 0; not finite counts as
    /// 0) and normalises. In the report returned, `resampled` means resampling is *due* (the
    /// effective sample size fell below the threshold): the caller does it. When no weight
    /// survives, the weights are unchanged and the update is skipped, as
    /// [`SkipReason::NoParticleOnMap`] if `no_score` (nothing could be scored at all), else
    /// [`SkipReason::DegenerateWeights`].
    pub(super) fn reweight(
        &mut self,
        likelihood: &[f64],
        best_score: Option<f64>,
        no_score: bool,
    ) -> UpdateReport {
        let ess = self.effective_sample_size();
        let new: Vec<f64> = self
            .weights
            .iter()
            .zip(likelihood)
            .map(|(w, l)| {
                if l.is_finite() && *l > 0.0 {
                    w * l
                } else {
                    0.0
                }
            })
            .collect();
        let scored = new.iter().filter(|&&v| v > 0.0).count();
        let sum: f64 = new.iter().sum();
        if !(sum > 0.0 && sum.is_finite()) {
            let reason = if no_score {
                SkipReason::NoParticleOnMap
            } else {
                SkipReason::DegenerateWeights
            };
            return UpdateReport::skip(reason, ess, 0);
        }
        self.weights = new.iter().map(|w| w / sum).collect();
        let ess_after = self.effective_sample_size();
        UpdateReport {
            skipped: None,
            scored_fraction: scored as f64 / self.len().max(1) as f64,
            best_score,
            effective_sample_size: ess_after,
            resampled: ess_after < self.params.resample_threshold * self.len() as f64,
            resampled_on_grid: false,
            surfaces: 0,
        }
    }

    /// Resample now (paper 002 eq. 6) by [`ParticleSettings::resampling`], then jitter every
    /// particle by [`ParticleSettings::roughening_m`]; the weights become equal.
    pub fn resample(&mut self) {
        let indices = match self.params.resampling {
            Resampling::Systematic => {
                let u0: f64 = self.rng.random();
                systematic_indices(&self.weights, self.params.particle_count, u0)
            }
            Resampling::Kld(k) => kld_indices(
                &self.weights,
                &self.positions_m,
                &k,
                self.params.particle_count,
                &mut self.rng,
            ),
        };
        if indices.is_empty() {
            return;
        }
        let rough = self.params.roughening_m;
        let mut positions: Vec<[f64; 2]> = indices.iter().map(|&i| self.positions_m[i]).collect();
        if rough > 0.0 {
            for p in &mut positions {
                let (a, b): (f64, f64) = (
                    self.rng.sample(StandardNormal),
                    self.rng.sample(StandardNormal),
                );
                p[0] += rough * a;
                p[1] += rough * b;
            }
        }
        let n = positions.len();
        self.positions_m = positions;
        self.weights = vec![1.0 / n as f64; n];
    }

    /// The belief's mean, covariance, 1σ ellipse and conservative disc.
    #[must_use]
    pub fn posterior(&self) -> Posterior {
        let (mean_m, covariance_m2) = mean_and_covariance(&self.positions_m, &self.weights);
        // The weighted sums are positive semi-definite up to rounding; if rounding ever broke
        // that, fall back to the circle of the larger variance (conservative).
        let ellipse = Ellipse::try_from_covariance(&covariance_m2).unwrap_or_else(|| {
            let r = covariance_m2[0][0].max(covariance_m2[1][1]).max(0.0).sqrt();
            Ellipse {
                semi_major_m: r,
                semi_minor_m: r,
                azimuth_deg: 0.0,
            }
        });
        Posterior {
            mean_m,
            covariance_m2,
            ellipse,
            disc_radius_m: self.params.motion.disc_sigmas * ellipse.semi_major_m,
            effective_sample_size: self.effective_sample_size(),
            particle_count: self.len(),
        }
    }

    /// The clusters of the belief: particles binned into `cell_m` squares (metres, > 0), cells
    /// taken in decreasing weight, each starting a mode with its untaken 3 × 3 neighbours; the
    /// modes of mass ≥ `min_mass` (0..1), heaviest first. Two modes closer than about
    /// 2 × `cell_m` may merge, and one wider than 3 cells may split off small remnants (which
    /// `min_mass` drops): a diagnostic of multi-modality, not a density estimate.
    ///
    /// # Errors
    /// [`ParticleError::InvalidParameter`] if `cell_m` is not positive and finite.
    pub fn modes(&self, cell_m: f64, min_mass: f64) -> Result<Vec<Mode>, ParticleError> {
        check("cell_m", cell_m, "> 0, finite", |v| {
            v > 0.0 && v.is_finite()
        })?;
        Ok(modes(&self.positions_m, &self.weights, cell_m, min_mass))
    }
}
