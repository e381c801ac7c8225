//! [`ParticleSettings`]: the filter's settings (plain struct, defaults in `Default`).

use super::motion::MotionModel;
use super::{ParticleError, check};

/// How the particles are redrawn when their weights degenerate.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Resampling {
    /// Systematic resampling to the same count (one uniform draw, N evenly spaced pointers):
    /// particle `i` is copied `⌊N·wᵢ⌋` or `⌈N·wᵢ⌉` times, the least variance of the common
    /// schemes (Kitagawa 1996). The default.
    Systematic,
    /// KLD-adaptive: particles are drawn one at a time in proportion to their weights until
    /// their number reaches the KLD bound for the number of occupied bins (Fox 2003), so a
    /// concentrated belief keeps few particles and a spread one many, between
    /// [`KldSettings::min_particles`] and [`ParticleSettings::particle_count`].
    Kld(KldSettings),
}

/// Settings of [`Resampling::Kld`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct KldSettings {
    /// Bin side for counting occupied bins, metres, > 0 (default: 0.5 — two orbital pixels, a
    /// little above the matcher's ~0.3 m accuracy).
    pub bin_m: f64,
    /// Bound on the Kullback-Leibler divergence between the particle and the true posterior,
    /// > 0 (default: 0.05, Fox 2003).
    pub epsilon: f64,
    /// Upper standard normal quantile `z₁₋δ` of the confidence the bound holds with, ≥ 0
    /// (default: 2.326, δ = 0.01).
    pub z_quantile: f64,
    /// Fewest particles kept, ≥ 1 (default: 200).
    pub min_particles: usize,
}

impl Default for KldSettings {
    fn default() -> Self {
        Self {
            bin_m: 0.5,
            epsilon: 0.05,
            z_quantile: 2.326,
            min_particles: 200,
        }
    }
}

/// Particle filter settings (plain struct; units, ranges and defaults on each field).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ParticleSettings {
    /// Particles drawn from the prior and kept by systematic resampling; the most kept by KLD
    /// resampling; ≥ 1 (default: 2000 — one update costs about the same with 1000 or 5000,
    /// the score surface dominates; see the module docs for timings).
    pub particle_count: usize,
    /// Odometry noise model (default: [`MotionModel::default`], the simulator's 5 % / 50 %).
    pub motion: MotionModel,
    /// Temperature `T` of the likelihood `exp(−(s − s_min) / T)`, in score units (census with
    /// the DEM term, as the onboard matcher runs: fraction of disagreeing bits + 0.3 × the DEM
    /// score), > 0 (default: 0.006, with [`ParticleSettings::registration_sigma_m`] = 0.15 m).
    ///
    /// Calibrated with `registration_sigma_m` on the synthetic benchmark set
    /// (`cargo run --release -p localization --example particle_temperature`: 264 cases, case
    /// seed 2024, map seed 1, census with both DEMs, measured 2026-12-02). The score
    /// surface over ±20 m around each true position becomes a posterior over the offsets with
    /// a flat prior through [`likelihood_grid`](super::likelihood_grid), and the pair
    /// maximises the mean log posterior density at the true position (a proper score: too
    /// sharp a belief is punished by the ~0.3 m errors, too broad a one by its spread). The
    /// best pair scores +0.115 ln(1/m²) per case, against −0.39 for the best `T` (0.011)
    /// without the registration blur; the truth then lies inside the 1σ / 2σ / 3σ ellipse of
    /// the single-panorama posterior in 52 / 95 / 100 % of the cases (a Gaussian: 39 / 86 /
    /// 99 %), and the optimum moves little with the prior's extent (T = 0.0059 for ±10 m,
    /// 0.0061 for ±5 m). The example prints the tables. A smaller `T` trusts one panorama more
    /// and kills secondary modes faster. NCC (`1 − ncc`, 0..2) and MI have other score scales:
    /// recalibrate with the same example (`-- 264 ncc`; for NCC it found T = 0.029 with no
    /// registration blur, at a mean log density of only −1.80: NCC's wrong peaks dominate).
    pub temperature: f64,
    /// σ of the registration error the score surface cannot see — the orbital map's
    /// orthorectification, the rover's heading and scale — metres, ≥ 0: the likelihood on the
    /// surface is convolved with an isotropic Gaussian of this σ
    /// ([`likelihood_grid`](super::likelihood_grid)) (default: 0.15, calibrated with
    /// [`ParticleSettings::temperature`]; the matcher's `sigma_floor_m` is the same 0.15 m,
    /// fitted independently). Applies to [`ParticleFilter::update`](super::ParticleFilter::update),
    /// not to scores given directly.
    pub registration_sigma_m: f64,
    /// Resample when the effective sample size `1 / Σ wᵢ²` after an update falls below this
    /// fraction of the particle count, 0..=1 (default: 0.5; 1 resamples after every update, 0
    /// never).
    pub resample_threshold: f64,
    /// The resampling scheme (default: [`Resampling::Systematic`]).
    pub resampling: Resampling,
    /// Whether [`ParticleFilter::update`](super::ParticleFilter::update) resamples from the
    /// posterior on the score surface's grid (the likelihood times a kernel density of the
    /// particles) rather than from the weighted particles (default: true — a census peak is
    /// narrower than the spacing of particles spread over a wide prior; see that method).
    pub resample_on_grid: bool,
    /// σ per axis of the Gaussian jitter added to every particle after resampling from the
    /// weighted particles, metres, ≥ 0 (default: 0.05): copies of one particle separate again
    /// even if the rover does not move before the next panorama. Small against the ~0.3 m
    /// accuracy of one match. (Resampling on the grid places particles uniformly in their
    /// 25 cm cell instead.)
    pub roughening_m: f64,
    /// Added on each side of the particles' bounding box before the score surface is computed,
    /// metres, ≥ 0 (default: 0.5 — two pixels, so interpolation never falls off the edge).
    pub surface_margin_m: f64,
    /// Largest half side of one score surface, metres, > 0 (default: 50): a wider spread of
    /// particles is scored in tiles of at most this half size (a 400 × 400-offset surface on
    /// a 640 × 640-pixel window with the 60 m orthomosaic), so memory stays bounded when the
    /// belief covers a whole map.
    pub max_surface_half_extent_m: f64,
}

impl Default for ParticleSettings {
    fn default() -> Self {
        Self {
            particle_count: 2000,
            motion: MotionModel::default(),
            temperature: 0.006,
            registration_sigma_m: 0.15,
            resample_threshold: 0.5,
            resampling: Resampling::Systematic,
            resample_on_grid: true,
            roughening_m: 0.05,
            surface_margin_m: 0.5,
            max_surface_half_extent_m: 50.0,
        }
    }
}

impl ParticleSettings {
    /// Checks every field against the range its documentation gives.
    ///
    /// # Errors
    /// [`ParticleError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), ParticleError> {
        let finite_nonneg = |v: f64| v >= 0.0 && v.is_finite();
        let finite_pos = |v: f64| v > 0.0 && v.is_finite();
        check(
            "params.particle_count",
            self.particle_count as f64,
            "at least 1",
            |v| v >= 1.0,
        )?;
        self.motion.validate()?;
        check(
            "params.temperature",
            self.temperature,
            "> 0, finite",
            finite_pos,
        )?;
        check(
            "params.registration_sigma_m",
            self.registration_sigma_m,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check(
            "params.resample_threshold",
            self.resample_threshold,
            "in 0..=1",
            |v| (0.0..=1.0).contains(&v),
        )?;
        check(
            "params.roughening_m",
            self.roughening_m,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check(
            "params.surface_margin_m",
            self.surface_margin_m,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check(
            "params.max_surface_half_extent_m",
            self.max_surface_half_extent_m,
            "> 0, finite",
            finite_pos,
        )?;
        if let Resampling::Kld(k) = self.resampling {
            check(
                "params.resampling.bin_m",
                k.bin_m,
                "> 0, finite",
                finite_pos,
            )?;
            check(
                "params.resampling.epsilon",
                k.epsilon,
                "> 0, finite",
                finite_pos,
            )?;
            check(
                "params.resampling.z_quantile",
                k.z_quantile,
                "≥ 0, finite",
                finite_nonneg,
            )?;
            check(
                "params.resampling.min_particles",
                k.min_particles as f64,
                "in 1..=particle_count",
                |v| v >= 1.0 && v <= self.particle_count as f64,
            )?;
        }
        Ok(())
    }
}
