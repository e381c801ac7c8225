//! The motion model (odometry and its noise) and the initial belief.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::{ParticleError, check};

/// How odometry error grows with distance: the simulator's uncertainty disc read as a 3σ bound.
///
/// The flight software grows a disc of radius `r = k_vo·d_vo + k_novo·d_novo` with the
/// distance driven with and without Visual Odometry (paper 000 §2; `sim::rover::uncertainty`'s
/// `UncertaintyModel` with the same defaults, 5 % and 50 %). The filter reads that radius as
/// [`MotionModel::disc_sigmas`] standard deviations of an isotropic Gaussian per axis: a leg adds
/// noise of `σ = r / disc_sigmas` metres to each coordinate of every particle. With the default
/// 3, a 2-D Gaussian lies inside the disc with probability `1 − e^(−9/2)` = 98.9 %, and
/// `σ / d` = 1.67 % with VO sits above the simulator's calibrated truth errors (about 1 % per
/// axis from the 1 % VO scale and 0.5° heading errors), as a conservative bound should.
/// [`super::Posterior::disc_radius_m`] maps back with the same factor, so a belief fed only by
/// odometry reports the simulator's disc for one leg.
///
/// Noise is drawn once per particle per [`super::ParticleFilter::predict`] call, so within a
/// leg σ grows linearly with distance like the disc; separate legs add in quadrature, where
/// the flight disc adds their radii (its worst case). Give one call per leg between panoramas.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MotionModel {
    /// Disc growth per metre driven with VO, dimensionless, ≥ 0 (default: 0.05 — 5 % of
    /// distance, paper 000 §2).
    pub k_vo: f64,
    /// Disc growth per metre driven without VO, dimensionless, ≥ 0 (default: 0.50 — 50 % of
    /// distance, paper 000 §2).
    pub k_novo: f64,
    /// How many per-axis standard deviations the disc radius is, > 0 (default: 3).
    pub disc_sigmas: f64,
}

impl Default for MotionModel {
    fn default() -> Self {
        Self {
            k_vo: 0.05,
            k_novo: 0.50,
            disc_sigmas: 3.0,
        }
    }
}

impl MotionModel {
    /// The disc radius a leg adds, metres: `k_vo·d_vo + k_novo·d_novo`.
    #[must_use]
    pub fn disc_growth_m(&self, odometry: &Odometry) -> f64 {
        self.k_vo * odometry.distance_vo_m + self.k_novo * odometry.distance_novo_m
    }

    /// The per-axis σ of a leg's position noise, metres: [`MotionModel::disc_growth_m`] ÷
    /// [`MotionModel::disc_sigmas`].
    #[must_use]
    pub fn sigma_m(&self, odometry: &Odometry) -> f64 {
        self.disc_growth_m(odometry) / self.disc_sigmas
    }

    /// Checks every field against the range its documentation gives.
    ///
    /// # Errors
    /// [`ParticleError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), ParticleError> {
        let finite_nonneg = |v: f64| v >= 0.0 && v.is_finite();
        check(
            "params.motion.k_vo",
            self.k_vo,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check(
            "params.motion.k_novo",
            self.k_novo,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check(
            "params.motion.disc_sigmas",
            self.disc_sigmas,
            "> 0, finite",
            |v| v > 0.0 && v.is_finite(),
        )
    }
}

/// One leg of odometry: what the rover measured between two panoramas.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Odometry {
    /// Displacement the rover's odometry measured, in the map frame (east, north), metres. The
    /// rover's heading knowledge has already rotated it there.
    pub displacement_m: [f64; 2],
    /// Path length driven while VO measured the motion, metres, ≥ 0.
    pub distance_vo_m: f64,
    /// Path length driven without VO (wheel odometry only), metres, ≥ 0.
    pub distance_novo_m: f64,
}

impl Odometry {
    /// A straight leg of `displacement_m` whose length is the path length, a fraction
    /// `novo_fraction` (clamped to 0..=1) of it driven without VO (as the simulator's
    /// `UncertaintyState::drive` splits it).
    #[must_use]
    pub fn straight(displacement_m: [f64; 2], novo_fraction: f64) -> Self {
        let d = displacement_m[0].hypot(displacement_m[1]);
        let novo = d * novo_fraction.clamp(0.0, 1.0);
        Self {
            displacement_m,
            distance_vo_m: d - novo,
            distance_novo_m: novo,
        }
    }

    /// Checks that the displacement is finite and the distances finite and ≥ 0.
    ///
    /// # Errors
    /// [`ParticleError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), ParticleError> {
        let finite = |v: f64| v.is_finite();
        let finite_nonneg = |v: f64| v >= 0.0 && v.is_finite();
        check(
            "odometry.displacement_m[0]",
            self.displacement_m[0],
            "finite",
            finite,
        )?;
        check(
            "odometry.displacement_m[1]",
            self.displacement_m[1],
            "finite",
            finite,
        )?;
        check(
            "odometry.distance_vo_m",
            self.distance_vo_m,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check(
            "odometry.distance_novo_m",
            self.distance_novo_m,
            "≥ 0, finite",
            finite_nonneg,
        )
    }
}

/// The initial belief the particles are drawn from.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Prior {
    /// An isotropic Gaussian: `mean_m` (map metres) and σ per axis `sigma_m` (metres, ≥ 0).
    Gaussian {
        /// Mean, map metres (x east, y north).
        mean_m: [f64; 2],
        /// Standard deviation per axis, metres.
        sigma_m: f64,
    },
    /// Uniform over a disc (centre and radius in metres, radius ≥ 0).
    Disc {
        /// Centre, map metres.
        center_m: [f64; 2],
        /// Radius, metres.
        radius_m: f64,
    },
    /// Uniform over an axis-aligned rectangle, map metres — paper 002's "equally likely
    /// anywhere on the map" (`min_m` ≤ `max_m` per axis).
    Rectangle {
        /// South-west corner (smallest x and y).
        min_m: [f64; 2],
        /// North-east corner (largest x and y).
        max_m: [f64; 2],
    },
}

impl Prior {
    /// The belief the simulator's uncertainty disc stands for under the default
    /// [`MotionModel`]: a Gaussian at `center_m` with σ = `radius_m` / 3 per axis.
    #[must_use]
    pub fn from_uncertainty_disc(center_m: [f64; 2], radius_m: f64) -> Self {
        Prior::Gaussian {
            mean_m: center_m,
            sigma_m: radius_m / MotionModel::default().disc_sigmas,
        }
    }

    /// Checks coordinates are finite and sizes ≥ 0.
    ///
    /// # Errors
    /// [`ParticleError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), ParticleError> {
        let finite = |v: f64| v.is_finite();
        let finite_nonneg = |v: f64| v >= 0.0 && v.is_finite();
        match *self {
            Prior::Gaussian { mean_m, sigma_m } => {
                check("prior.mean_m[0]", mean_m[0], "finite", finite)?;
                check("prior.mean_m[1]", mean_m[1], "finite", finite)?;
                check("prior.sigma_m", sigma_m, "≥ 0, finite", finite_nonneg)
            }
            Prior::Disc { center_m, radius_m } => {
                check("prior.center_m[0]", center_m[0], "finite", finite)?;
                check("prior.center_m[1]", center_m[1], "finite", finite)?;
                check("prior.radius_m", radius_m, "≥ 0, finite", finite_nonneg)
            }
            Prior::Rectangle { min_m, max_m } => {
                check("prior.min_m[0]", min_m[0], "finite", finite)?;
                check("prior.min_m[1]", min_m[1], "finite", finite)?;
                check("prior.max_m[0]", max_m[0], "finite, ≥ min_m[0]", |v| {
                    v.is_finite() && v >= min_m[0]
                })?;
                check("prior.max_m[1]", max_m[1], "finite, ≥ min_m[1]", |v| {
                    v.is_finite() && v >= min_m[1]
                })
            }
        }
    }

    /// One draw from the prior.
    pub(super) fn sample(&self, rng: &mut ChaCha8Rng) -> [f64; 2] {
        match *self {
            Prior::Gaussian { mean_m, sigma_m } => {
                let (a, b): (f64, f64) = (rng.sample(StandardNormal), rng.sample(StandardNormal));
                [mean_m[0] + sigma_m * a, mean_m[1] + sigma_m * b]
            }
            Prior::Disc { center_m, radius_m } => {
                // √u for the radius makes the density uniform over the area.
                let r = radius_m * rng.random::<f64>().sqrt();
                let t = std::f64::consts::TAU * rng.random::<f64>();
                [center_m[0] + r * t.cos(), center_m[1] + r * t.sin()]
            }
            Prior::Rectangle { min_m, max_m } => {
                let (u, v): (f64, f64) = (rng.random(), rng.random());
                [
                    min_m[0] + (max_m[0] - min_m[0]) * u,
                    min_m[1] + (max_m[1] - min_m[1]) * v,
                ]
            }
        }
    }
}
