//! A particle filter over the rover's map position, fed by the census score surface (paper 002
//! §4 with the matcher of paper 000 §5).
//!
//! One post-drive panorama can match several places equally well — repeated bedforms, rows of
//! rocks — and the matcher then rejects it as ambiguous (paper 000 §7, [`Rejection::Ambiguous`]).
//! Paper 002 keeps the belief as particles, propagates it with odometry and weights it by the
//! image similarity at each particle, so a *sequence* of panoramas along a drive can settle what
//! one cannot.
//!
//! - [`ParticleFilter`]: `N` particles of map position `(x east, y north)` in metres with
//!   normalised weights and a seeded `ChaCha8Rng`; built from a [`Prior`].
//!   - [`ParticleFilter::predict`] — the motion model (paper 002 eq. 4): the [`Odometry`]
//!     displacement plus isotropic Gaussian noise whose σ grows with the distance driven exactly
//!     as the simulator's uncertainty disc does, 5 % of the distance with VO and 50 % without
//!     ([`MotionModel`]; the disc radius is read as a 3σ bound).
//!   - [`ParticleFilter::update`] — the measurement update (eq. 5): one
//!     [`score_surface`](crate::matcher::score_surface) over the particles' bounding window (in
//!     tiles if it is large), turned into a likelihood by [`likelihood_grid`] —
//!     `exp(−(s − s_min) / T)`, convolved with a Gaussian of the registration error the score
//!     cannot see — and read bilinearly at each particle. `T` and that σ
//!     ([`ParticleSettings::temperature`], [`ParticleSettings::registration_sigma_m`]) are
//!     calibrated together on the synthetic benchmark set. Particles where nothing can be
//!     scored get likelihood 0; if that leaves no weight the update is skipped and says why
//!     ([`UpdateReport::skipped`]).
//!   - Resampling (eq. 6) when the effective sample size falls below
//!     [`ParticleSettings::resample_threshold`] × N. In [`ParticleFilter::update`] the new
//!     particles are drawn from the posterior on the surface's 25 cm grid (the likelihood
//!     times a kernel density of the particles), so a census peak narrower than the spacing
//!     of the particles is not missed; elsewhere from the weighted particles. Either way by
//!     systematic resampling ([`systematic_indices`]) by default, or KLD-adaptive
//!     ([`Resampling::Kld`], [`kld_sample_count`]).
//!   - [`ParticleFilter::posterior`]: the weighted mean, the 2×2 covariance, its 1σ
//!     [`Ellipse`] (semi-axes in metres, the major axis's azimuth in degrees east of north, and
//!     [`Ellipse::mmgis_angle_deg`] for MMGIS) and a conservative disc radius, 3 × the 1σ
//!     semi-major axis: the radius the simulator's keep-out zones would grow by.
//!   - [`ParticleFilter::modes`]: the clusters of the belief, to see multi-modality.
//! - [`localize_panorama`]: the filter as a one-panorama localizer (prior disc, one update,
//!   accepted or rejected as ambiguous or for no gain), as the simulator runs it.
//!
//! One update costs about 6 ms with the particles within a 6 m disc and 13-20 ms within the
//! simulator's 30 m disc (a 64 m square of particles), for N = 1000 and 5000 alike: the score
//! surface dominates (2 threads, `tests/particle_aliasing.rs`, `update_timing`).
//!
//! **Heading is not a state.** The registration is a 2-D translation search because SunFind
//! gives the rover an accurate absolute heading before localization (paper 000 §5), so the
//! particles carry position only and odometry arrives already rotated into the map frame.
//!
//! Bad input (a non-finite odometry, a zero particle count, a parameter out of range) is a
//! [`ParticleError`]; a measurement that carries no information is a skipped update, not an
//! error. The same seed and inputs give the same particles, bit for bit, on any thread count.
//!
//! ```
//! use localization::particle::{Odometry, ParticleFilter, ParticleSettings, Prior};
//!
//! // 1000 particles around the odometry estimate after a 100 m drive with VO (a 5 m disc).
//! let params = ParticleSettings { particle_count: 1000, ..ParticleSettings::default() };
//! let prior = Prior::from_uncertainty_disc([500.0, 300.0], 5.0);
//! let mut pf = ParticleFilter::new(&prior, params, 7)?;
//! // Drive 40 m east, all with VO: the disc grows by 2 m, σ per axis by 2/3 m.
//! pf.predict(&Odometry::straight([40.0, 0.0], 0.0))?;
//! let post = pf.posterior();
//! assert!((post.mean_m[0] - 540.0).abs() < 0.5 && (post.mean_m[1] - 300.0).abs() < 0.5);
//! // No image yet: the disc is the simulator's, √(5² + 2²) ≈ 5.4 m (legs add in quadrature).
//! assert!((post.disc_radius_m - 5.39).abs() < 0.4, "{post:?}");
//! # Ok::<(), localization::particle::ParticleError>(())
//! ```
//!
//! ## References
//! - Paper 002 §2 (state, odometry action, observation), §4 (belief as particles, uniform
//!   initial belief, prediction eq. 4, update eq. 5, resampling eq. 6, recursion eq. 7).
//! - Paper 000 §2 (uncertainty growth 5 % of distance with VO, 50 % without), §5 (census
//!   score surface over 2-D translations, known heading), §7 (validity checks).
//! - G. Kitagawa, "Monte Carlo filter and smoother for non-Gaussian nonlinear state space
//!   models", J. Comput. Graph. Stat. 5, 1996 (systematic resampling).
//! - D. Fox, "Adapting the sample size in particle filters through KLD-sampling", IJRR 22,
//!   2003 (the KLD bound).
//! - C. Musso, N. Oudjane and F. Le Gland, "Improving regularised particle filters", in
//!   *Sequential Monte Carlo Methods in Practice*, Springer, 2001 (kernel-regularised
//!   resampling).
//! - B. W. Silverman, *Density Estimation for Statistics and Data Analysis*, 1986 (the
//!   bandwidth rule).
//!
//! [`Rejection::Ambiguous`]: crate::matcher::Rejection::Ambiguous

mod filter;
mod likelihood;
mod motion;
mod panorama;
mod posterior;
mod resample;
mod settings;
#[cfg(test)]
mod tests;
mod update;

pub use filter::{ParticleFilter, SkipReason, UpdateReport};
pub use likelihood::likelihood_grid;
pub use motion::{MotionModel, Odometry, Prior};
pub use panorama::{PanoramaFix, PanoramaFixSettings, localize_panorama, no_gain};
pub use posterior::{Ellipse, Mode, Posterior};
pub use resample::{effective_sample_size, kld_sample_count, systematic_indices};
pub use settings::{KldSettings, ParticleSettings, Resampling};

use crate::matcher::LocalizeError;

/// Why a particle filter could not be built or stepped (bad input, not a bad outcome).
#[derive(Debug, thiserror::Error)]
pub enum ParticleError {
    /// A parameter, prior or odometry field is outside the range its documentation gives.
    #[error("{field} = {value} is invalid: expected {expected}")]
    InvalidParameter {
        /// The field, as a path (`params.temperature`, `odometry.distance_vo_m`, …).
        field: &'static str,
        /// The value given (counts are converted to `f64`).
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// Particle positions and weights of different lengths were given.
    #[error("{positions} particle positions but {weights} weights")]
    LengthMismatch {
        /// Number of positions.
        positions: usize,
        /// Number of weights.
        weights: usize,
    },
    /// Scores were given for a different number of particles than the filter holds.
    #[error("{scores} scores for {particles} particles")]
    ScoreCountMismatch {
        /// Particles in the filter.
        particles: usize,
        /// Scores given.
        scores: usize,
    },
    /// The score surface could not be computed from the images (e.g. the orthomosaic's pixel
    /// size differs from the map's, or its validity mask has the wrong length).
    #[error(transparent)]
    Localize(#[from] LocalizeError),
}

/// `Ok` if `ok(value)`, else [`ParticleError::InvalidParameter`].
fn check(
    field: &'static str,
    value: f64,
    expected: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<(), ParticleError> {
    if ok(value) {
        Ok(())
    } else {
        Err(ParticleError::InvalidParameter {
            field,
            value,
            expected,
        })
    }
}
