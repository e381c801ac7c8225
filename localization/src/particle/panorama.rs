//! The particle filter as a one-panorama localizer: the prior disc, one update, a verdict.
//! What the simulator's `localizer = "particle"` and the localizer comparison run.

use super::filter::ParticleFilter;
use super::motion::Prior;
use super::posterior::{Mode, Posterior};
use super::settings::ParticleSettings;
use super::{ParticleError, check};
use crate::matcher::{MatchSettings, OrbitalMap, RoverImages};

/// Settings of a one-panorama localization (plain struct; defaults on each field).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PanoramaFixSettings {
    /// The filter (default: [`ParticleSettings::default`]).
    pub params: ParticleSettings,
    /// Cell size of the mode search, metres (default: 1).
    pub mode_cell_m: f64,
    /// Smallest mass a second mode needs to make the belief ambiguous, 0..1 (default: 0.05).
    pub mode_min_mass: f64,
}

impl Default for PanoramaFixSettings {
    fn default() -> Self {
        Self {
            params: ParticleSettings::default(),
            mode_cell_m: 1.0,
            mode_min_mass: 0.05,
        }
    }
}

/// The verdict of a one-panorama localization.
#[derive(Clone, Debug, PartialEq)]
pub enum PanoramaFix {
    /// One mode and a disc (3 × the 1σ semi-major axis) smaller than the prior's radius.
    Accepted(Posterior),
    /// Refused: the sentence says why; the posterior when the update ran.
    Rejected {
        /// Why (`ambiguous: …`, `no gain: …`, `update skipped: …`).
        reason: String,
        /// The belief after the update, if it ran.
        posterior: Option<Posterior>,
    },
}

/// Localize from one panorama: particles drawn from the uncertainty disc of radius
/// `prior_radius_m` around `prior_m` (read as 3σ, [`Prior::from_uncertainty_disc`]), one
/// [`ParticleFilter::update`] with the census (or `match_params.method`) score surface of
/// `rover` against `orbital`, then the verdict: several modes of mass ≥
/// [`PanoramaFixSettings::mode_min_mass`] are ambiguous (perceptual aliasing); a disc not
/// smaller than `prior_radius_m` is no gain; otherwise accepted.
///
/// # Errors
/// [`ParticleError`] for a bad setting or prior, or images the score surface cannot use.
pub fn localize_panorama(
    prior_m: [f64; 2],
    prior_radius_m: f64,
    orbital: &OrbitalMap<'_>,
    rover: &RoverImages<'_>,
    match_params: &MatchSettings,
    settings: &PanoramaFixSettings,
    seed: u64,
) -> Result<PanoramaFix, ParticleError> {
    check(
        "settings.mode_cell_m",
        settings.mode_cell_m,
        "> 0, finite",
        |v| v > 0.0 && v.is_finite(),
    )?;
    check(
        "settings.mode_min_mass",
        settings.mode_min_mass,
        "in 0..=1",
        |v| (0.0..=1.0).contains(&v),
    )?;
    let prior = Prior::from_uncertainty_disc(prior_m, prior_radius_m);
    let mut pf = ParticleFilter::new(&prior, settings.params, seed)?;
    let report = pf.update(orbital, rover, match_params)?;
    if let Some(why) = report.skipped {
        return Ok(PanoramaFix::Rejected {
            reason: format!("update skipped: {why}"),
            posterior: None,
        });
    }
    let modes = pf.modes(settings.mode_cell_m, settings.mode_min_mass)?;
    let posterior = pf.posterior();
    Ok(verdict(posterior, &modes, prior_radius_m))
}

fn verdict(posterior: Posterior, modes: &[Mode], prior_radius_m: f64) -> PanoramaFix {
    if let [a, b, ..] = modes {
        return PanoramaFix::Rejected {
            reason: format!(
                "ambiguous: {} modes in the belief, the two heaviest {:.1} m apart \
                 (masses {:.2} and {:.2})",
                modes.len(),
                (a.center_m[0] - b.center_m[0]).hypot(a.center_m[1] - b.center_m[1]),
                a.mass,
                b.mass
            ),
            posterior: Some(posterior),
        };
    }
    if posterior.disc_radius_m < prior_radius_m {
        PanoramaFix::Accepted(posterior)
    } else {
        PanoramaFix::Rejected {
            reason: no_gain(posterior.disc_radius_m, prior_radius_m),
            posterior: Some(posterior),
        }
    }
}

/// The sentence of a filter result that does not shrink the disc.
#[must_use]
pub fn no_gain(disc_after_m: f64, prior_radius_m: f64) -> String {
    format!(
        "no gain: the 3-sigma disc after the update is {disc_after_m:.2} m, \
         the rover had {prior_radius_m:.2} m"
    )
}
