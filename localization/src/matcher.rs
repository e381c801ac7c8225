//! One global localization: the rover orthomosaic (and DEM) matched against the orbital map around
//! the prior position (paper 000 §5).
//!
//! 1. The rover orthomosaic is resampled in easting by the map's scale factor (the orbital map is
//!    equirectangular with true scale at one latitude, Jezero's 18.4663°; at another latitude a
//!    map metre east is not a ground metre). See [`easting_scale`].
//! 2. The orbital appearance is cropped to the search window (prior ± search radius) and the
//!    appearance score of every 25 cm offset is computed by the [`Method`] of [`MatchSettings`]:
//!    by default both are census-transformed and
//!    [`hamming_scores`](crate::census::hamming_scores) scores every offset exactly;
//!    the baselines of paper 000 §4 are masked NCC
//!    ([`ncc_scores`](crate::baselines::ncc_scores), `1 − ncc`) and mutual information
//!    ([`mi_scores`](crate::baselines::mi_scores), scored `1 − MI / H(T)`, see
//!    [`Method::MutualInformation`]).
//! 3. With DEMs, the mean-removed sum of squared height differences per valid cell is computed at
//!    every 1 m offset, mapped to `[0, 1)` as `msd / (msd + dem_scale²)` and interpolated onto the
//!    appearance offsets; the two are summed with appearance weighted more. Steps 1-3 are
//!    [`score_surface`], public for callers that want the whole [`ScoreSurface`] (the particle
//!    filter of [`crate::particle`] reads it at each particle).
//! 4. The best offset is refined to sub-pixel by the quadratic fit of [`subpixel_peak`].
//! 5. Confidence: σ from the fitted curvature and the noise of the best score (census: binomial
//!    noise of the fraction of disagreeing bits, one independent sample per
//!    [`MatchSettings::census_bits_per_sample`] bits; NCC and MI: the residual of the quadratic
//!    fit, see [`Method`]) plus [`MatchSettings::sigma_floor_m`] in quadrature, both calibrated on
//!    the synthetic 264-case set; the ratio of the best other local minimum outside the peak's
//!    neighbourhood to the best; and the fraction of valid pixels; validity checks turn any of them out of bounds into a
//!    rejection with a reason. The DEM term, sub-pixel fit, σ propagation and checks are shared
//!    by all methods.
//!
//! ## References
//! Paper 000 §4 (accuracy, search radius), §5 (census matching, DEM SSD, sub-pixel fit, easting
//! scale), §7 (validity checks before the result is applied).

use maps::Raster;

use crate::census::{MatchError, subpixel_peak};

mod surface;

pub use surface::{ScoreSurface, score_surface};

/// Latitude of true scale of the Jezero orbital maps, degrees (paper 000 §5).
pub const JEZERO_TRUE_SCALE_LATITUDE_DEG: f64 = 18.4663;

/// Map metres east per ground metre east at `latitude_deg` on an equirectangular map with true
/// scale at `true_scale_latitude_deg`: `cos φ₀ / cos φ`.
#[must_use]
pub fn easting_scale(latitude_deg: f64, true_scale_latitude_deg: f64) -> f64 {
    true_scale_latitude_deg.to_radians().cos() / latitude_deg.to_radians().cos()
}

/// Appearance score used by [`localize`] (paper 000 §4: census, and the two baselines it is
/// compared against). All are "lower is better".
///
/// Serialized (and named by [`Method::name`] / [`Method::from_name`]) as `"census"`, `"ncc"`,
/// `"mi"`.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum Method {
    /// Modified census transform + masked Hamming distance (the flight method): the fraction of
    /// disagreeing valid census bits, in `[0, 1]`. σ uses the binomial noise of that fraction.
    #[default]
    #[serde(rename = "census")]
    Census,
    /// Masked zero-mean normalized cross-correlation, scored `1 − ncc` in `[0, 2]`
    /// ([`ncc_scores`](crate::baselines::ncc_scores)). The binomial model does not apply: the
    /// score noise for σ is estimated from the residual of the 3×3 quadratic fit (residual sum
    /// of squares ÷ 3 degrees of freedom), floored like census at `1/√12` px.
    #[serde(rename = "ncc")]
    Ncc,
    /// Mutual information of rank-quantized intensities
    /// ([`mi_scores`](crate::baselines::mi_scores)), scored
    /// `1 − MI / H(T)` in `[0, 1]` — the fraction of the template's (constant) entropy the map
    /// does not explain; the same minimum as `−MI`, but positive so the peak ratio keeps its
    /// meaning. σ as for [`Method::Ncc`]. MI is evaluated exactly on a 2× subsampled offset grid
    /// and refined at full resolution around its best local minima; other offsets are
    /// interpolated (see [`crate::baselines`]).
    #[serde(rename = "mi")]
    MutualInformation,
}

impl Method {
    /// All methods, census first.
    pub const ALL: [Method; 3] = [Method::Census, Method::Ncc, Method::MutualInformation];

    /// Short lowercase name: `"census"`, `"ncc"` or `"mi"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Method::Census => "census",
            Method::Ncc => "ncc",
            Method::MutualInformation => "mi",
        }
    }

    /// The method called `name` (as [`Method::name`], case-insensitive), if any.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Method> {
        Method::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name.trim()))
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Matcher settings (plain struct; units and defaults on each field).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MatchSettings {
    /// Search radius around the prior, metres (default: 30, paper 000 §4; up to 100).
    pub search_radius_m: f64,
    /// Weight of the appearance (census) score (default: 1.0).
    pub appearance_weight: f64,
    /// Weight of the DEM score (default: 0.3 — appearance weighted more).
    pub dem_weight: f64,
    /// Height misfit at which the DEM score is one half, metres (default: 0.3).
    pub dem_scale_m: f64,
    /// Site latitude for the easting scale correction, degrees (default: 18.4663, no correction).
    pub latitude_deg: f64,
    /// Latitude of true scale of the map, degrees (default: 18.4663, Jezero).
    pub true_scale_latitude_deg: f64,
    /// Peaks closer than this to the best are the same peak, metres (default: 2.0).
    pub peak_exclusion_m: f64,
    /// Reject unless the best other local minimum of the score outside `peak_exclusion_m` is at
    /// least this many times the best (census and MI; NCC has `ncc_min_peak_ratio`)
    /// (default: 1.04). Chosen on the synthetic 264-case set
    /// (`localization::benchmark_set`, case seed 2024, map seed 1, census): with the DEM term
    /// off, so that wrong matches occur, every match more than 2 m off had a ratio ≤ 1.019 and
    /// the correct ones a median of 1.16 (5 % below 1.034); 1.04 then accepts 230 of 264 with
    /// a largest accepted error of 1.03 m, and with the DEM term (the default) 263 of 264
    /// (largest error 1.03 m). 1.15, the old value, rejects 31 correct matches here (30 of them
    /// rocky or plain). Measured 2026-11-25 with `cargo run --release -- localize-bench` and an
    /// ablation run of the same cases with `dem_weight = 0` and `min_peak_ratio = 1`.
    pub min_peak_ratio: f64,
    /// `min_peak_ratio` for [`Method::Ncc`], whose `1 − ncc` scores put ratios on another scale
    /// (default: 1.12). On the same 264-case run (`cargo run --release -- localize-bench`,
    /// 2026-11-25) every NCC error over 2 m had a ratio ≤ 1.107; at 1.04 NCC accepted three of
    /// them (7.5 m, 30.1 m, 31.2 m), at 1.12 it accepts 200 of 264 with a largest error of 0.98 m.
    pub ncc_min_peak_ratio: f64,
    /// Reject when the estimated σ exceeds this, metres (default: 1.5).
    pub max_sigma_m: f64,
    /// Census bits per statistically independent sample in the binomial noise of the census
    /// score, which σ propagates through the peak curvature (default: 4000). Census bits are far
    /// from independent and the score's error at the peak is mostly systematic (lighting,
    /// epoch, geometry), so this is an empirical calibration, not a physical count: counting
    /// every bit (1) gave σ of 2–14 mm against real errors of ~0.3 m. Fitted together with
    /// `sigma_floor_m` on the synthetic 264-case set (case seed 2024, map seed 1, census,
    /// 2026-11-25, `cargo run --release -- localize-bench --methods census --json`) so that
    /// the share of accepted cases with a position error under 1, 2 and 3 σ (σ per axis)
    /// comes close to the 2-D Gaussian's 39 %, 86 % and 99 %; see BENCHMARKS.md.
    pub census_bits_per_sample: f64,
    /// Error added to σ in quadrature, metres: what the score noise cannot see — orbital map
    /// registration, rover heading and scale, pixel quantisation (default: 0.15, fitted with
    /// `census_bits_per_sample`; it replaces the old floor of 1/√12 px = 0.072 m, at which
    /// almost every σ sat).
    pub sigma_floor_m: f64,
    /// Reject when fewer than this fraction of the orthomosaic pixels are valid (default: 0.1).
    pub min_valid_fraction: f64,
    /// Appearance score (default: [`Method::Census`]).
    pub method: Method,
}

impl Default for MatchSettings {
    fn default() -> Self {
        Self {
            search_radius_m: 30.0,
            appearance_weight: 1.0,
            dem_weight: 0.3,
            dem_scale_m: 0.3,
            latitude_deg: JEZERO_TRUE_SCALE_LATITUDE_DEG,
            true_scale_latitude_deg: JEZERO_TRUE_SCALE_LATITUDE_DEG,
            peak_exclusion_m: 2.0,
            min_peak_ratio: 1.04,
            ncc_min_peak_ratio: 1.12,
            max_sigma_m: 1.5,
            census_bits_per_sample: 4000.0,
            sigma_floor_m: 0.15,
            min_valid_fraction: 0.1,
            method: Method::Census,
        }
    }
}

/// What the rover observed, centred on its true position (which it does not know).
#[derive(Clone, Copy, Debug)]
pub struct RoverImages<'a> {
    /// Orthomosaic (same resolution as the orbital appearance); the rover is at its centre.
    pub ortho: &'a Raster<u8>,
    /// Validity of each orthomosaic pixel.
    pub ortho_valid: &'a [bool],
    /// Rover DEM and its validity (same resolution as the orbital DEM), if any.
    pub dem: Option<(&'a Raster<f32>, &'a [bool])>,
}

/// The orbital map.
#[derive(Clone, Copy, Debug)]
pub struct OrbitalMap<'a> {
    /// Appearance (orthoimage).
    pub appearance: &'a Raster<u8>,
    /// DEM, if any.
    pub dem: Option<&'a Raster<f32>>,
}

impl<'a> OrbitalMap<'a> {
    /// The appearance and DEM of rendered orbital products.
    #[must_use]
    pub fn of(products: &'a crate::synthetic::OrbitalProducts) -> Self {
        Self {
            appearance: &products.appearance,
            dem: Some(&products.dem),
        }
    }
}

impl<'a> RoverImages<'a> {
    /// The orthomosaic and rover DEM, with their validity, of a rendered rover observation.
    #[must_use]
    pub fn of(observation: &'a crate::synthetic::RoverObservation) -> Self {
        Self {
            ortho: &observation.ortho,
            ortho_valid: &observation.valid,
            dem: Some((&observation.dem, &observation.dem_valid)),
        }
    }
}

/// Why a match was rejected by its validity checks.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub enum Rejection {
    /// Too few valid orthomosaic pixels.
    TooFewValid {
        /// Fraction valid.
        fraction: f64,
    },
    /// Another peak scores almost as well.
    Ambiguous {
        /// Best score elsewhere ÷ best score.
        peak_ratio: f64,
    },
    /// The peak is too flat for the required accuracy.
    Imprecise {
        /// Estimated σ, metres.
        sigma_m: f64,
    },
    /// The best offset lies on the edge of the search window (the truth may be outside it).
    OnWindowEdge,
}

impl Rejection {
    /// Every reason's [`Rejection::name`], in declaration order.
    pub const NAMES: [&'static str; 4] =
        ["too_few_valid", "ambiguous", "imprecise", "on_window_edge"];

    /// The reason as a short snake-case name (`on_window_edge`), as tables and JSON counts
    /// print it; [`std::fmt::Display`] gives the sentence with the measured value.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Rejection::TooFewValid { .. } => Self::NAMES[0],
            Rejection::Ambiguous { .. } => Self::NAMES[1],
            Rejection::Imprecise { .. } => Self::NAMES[2],
            Rejection::OnWindowEdge => Self::NAMES[3],
        }
    }
}

impl std::fmt::Display for Rejection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Rejection::TooFewValid { fraction } => write!(
                f,
                "only {:.1} % of the orthomosaic is valid",
                fraction * 100.0
            ),
            Rejection::Ambiguous { peak_ratio } => write!(
                f,
                "ambiguous match: second peak at {peak_ratio:.3} × the best score"
            ),
            Rejection::Imprecise { sigma_m } => write!(f, "peak too flat: σ = {sigma_m:.2} m"),
            Rejection::OnWindowEdge => write!(f, "best offset on the edge of the search window"),
        }
    }
}

/// Result of one localization.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MatchResult {
    /// Estimated rover position, map metres.
    pub position_m: [f64; 2],
    /// Correction from the prior, metres (east, north).
    pub correction_m: [f64; 2],
    /// Estimated 1σ position uncertainty, metres.
    pub sigma_m: f64,
    /// Combined score at the peak (lower is better).
    pub best_score: f64,
    /// Best other local minimum of the score outside the peak's neighbourhood ÷ best score
    /// (higher is more distinctive; infinite if there is none).
    pub peak_ratio: f64,
    /// Fraction of valid orthomosaic pixels.
    pub valid_fraction: f64,
    /// `None` if accepted, else why not.
    pub rejection: Option<Rejection>,
}

/// Why a localization could not even be attempted (bad input).
#[derive(Debug, thiserror::Error)]
pub enum LocalizeError {
    /// The orthomosaic and orbital resolutions differ.
    #[error("orthomosaic resolution {ortho} m/px differs from the orbital map's {map} m/px")]
    ResolutionMismatch {
        /// Orthomosaic m/px.
        ortho: f64,
        /// Orbital m/px.
        map: f64,
    },
    /// The search window around the prior leaves the orbital map.
    #[error("the search window ({radius_m} m around the prior {prior_m:?}) leaves the orbital map")]
    WindowOffMap {
        /// Prior position.
        prior_m: [f64; 2],
        /// Search radius.
        radius_m: f64,
    },
    /// No orthomosaic pixel is valid.
    #[error("the orthomosaic has no valid pixels")]
    NoValidPixels,
    /// A census buffer was inconsistent.
    #[error(transparent)]
    Census(#[from] MatchError),
}

/// Score noise (variance) from the residual of the least-squares quadratic over the 3×3
/// neighbourhood of `(bx, by)` (6 parameters, 9 points: residual sum of squares ÷ 3). The basis
/// `1, x, y, x² − ⅔, xy, y² − ⅔` is orthogonal on that grid, so each coefficient is a projection.
fn quadratic_residual_variance(g: &[f64], w: usize, (bx, by): (usize, usize)) -> f64 {
    let z = |x: isize, y: isize| g[(by as isize + y) as usize * w + (bx as isize + x) as usize];
    let pts = || (-1isize..=1).flat_map(|y| (-1isize..=1).map(move |x| (x, y)));
    let proj = |f: &dyn Fn(isize, isize) -> f64| {
        let num: f64 = pts().map(|(x, y)| f(x, y) * z(x, y)).sum();
        let den: f64 = pts().map(|(x, y)| f(x, y) * f(x, y)).sum();
        num / den
    };
    let basis: [&dyn Fn(isize, isize) -> f64; 6] = [
        &|_, _| 1.0,
        &|x, _| x as f64,
        &|_, y| y as f64,
        &|x, _| (x * x) as f64 - 2.0 / 3.0,
        &|x, y| (x * y) as f64,
        &|_, y| (y * y) as f64 - 2.0 / 3.0,
    ];
    let coef: Vec<f64> = basis.iter().map(|f| proj(*f)).collect();
    let rss: f64 = pts()
        .map(|(x, y)| {
            let fit: f64 = basis.iter().zip(&coef).map(|(f, c)| c * f(x, y)).sum();
            (z(x, y) - fit).powi(2)
        })
        .sum();
    rss / 3.0
}

/// Localize: match the rover's images against the orbital map around `prior_m`.
pub fn localize(
    orbital: &OrbitalMap<'_>,
    rover: &RoverImages<'_>,
    prior_m: [f64; 2],
    p: &MatchSettings,
) -> Result<MatchResult, LocalizeError> {
    let surface = score_surface(
        orbital,
        rover,
        prior_m,
        [p.search_radius_m, p.search_radius_m],
        p,
    )?;
    let (sw, sh) = (surface.width, surface.height);
    let res = surface.resolution_m_per_px;
    let valid_fraction = surface.valid_fraction;
    let combined = surface.scores.as_slice();
    let census_bits = surface.census_valid_bits.as_ref();

    let best = (0..combined.len())
        .filter(|&i| combined[i].is_finite())
        .min_by(|&a, &b| combined[a].total_cmp(&combined[b]).then(a.cmp(&b)))
        .ok_or(LocalizeError::NoValidPixels)?;
    let (bx, by) = (best % sw, best / sw);
    let best_score = combined[best];
    let (fx, fy, sigma_px) = match subpixel_peak(combined, sw, sh, (bx, by)) {
        Some((dx, dy, curv)) => {
            // Census: binomial noise of a fraction of disagreeing bits; NCC / MI: the residual
            // of the quadratic fit. Propagated through the fitted bowl:
            // var(position) ≈ var(score) / smallest curvature (per px²).
            // Census bits are not independent (each pixel's 8 bits share its centre, and the
            // PSF correlates neighbours): the binomial variance counts one sample per
            // `census_bits_per_sample` bits.
            let var_score = match &census_bits {
                Some(valid_bits) => {
                    let bits = f64::from(valid_bits[best].max(1));
                    let samples = (bits / p.census_bits_per_sample.max(1.0)).max(1.0);
                    let s = best_score.clamp(1e-6, 1.0 - 1e-6);
                    s * (1.0 - s) / samples
                }
                None => quadratic_residual_variance(combined, sw, (bx, by)),
            };
            let tr = curv.f_xx + curv.f_yy;
            let det = curv.determinant();
            let lambda_min = 0.5 * (tr - (tr * tr - 4.0 * det).max(0.0).sqrt());
            let sigma = if lambda_min > 0.0 {
                (2.0 * var_score / lambda_min).sqrt()
            } else {
                f64::INFINITY
            };
            // The errors no score noise shows (map registration, rover geometry, pixel
            // quantisation) add in quadrature.
            let floor_px = p.sigma_floor_m / res;
            (dx, dy, sigma.hypot(floor_px))
        }
        None => (0.0, 0.0, f64::INFINITY),
    };
    // The runner-up is the best *other local minimum* outside the exclusion square: the
    // lowest score just outside the square can be the shoulder of the best peak itself (the
    // 1 m DEM term makes the bowl several metres wide), which made distinct peaks look more
    // ambiguous than they are. A valley along repetitive crests still has local minima along it, and a
    // second peak a ripple or bedform wavelength away is a local minimum, so real
    // ambiguities are still caught.
    let exclusion_px = (p.peak_exclusion_m / res).ceil() as isize;
    let is_local_min = |i: usize| {
        let (x, y) = ((i % sw) as isize, (i / sw) as isize);
        let v = combined[i];
        (-1isize..=1).all(|ddy| {
            (-1isize..=1).all(|ddx| {
                let (nx, ny) = (x + ddx, y + ddy);
                nx < 0
                    || ny < 0
                    || nx >= sw as isize
                    || ny >= sh as isize
                    || v <= combined[ny as usize * sw + nx as usize]
            })
        })
    };
    let second = (0..combined.len())
        .filter(|&i| {
            let (x, y) = ((i % sw) as isize, (i / sw) as isize);
            (x - bx as isize).abs() > exclusion_px || (y - by as isize).abs() > exclusion_px
        })
        .filter(|&i| combined[i].is_finite() && is_local_min(i))
        .map(|i| combined[i])
        .fold(f64::INFINITY, f64::min);
    let peak_ratio = if best_score > 0.0 {
        second / best_score
    } else {
        f64::INFINITY
    };

    // Offset (bx, by) puts the template NW corner at window pixel (bx, by): the rover (template
    // centre) is at that pixel's corner + half the template.
    let [x, y] = surface.position_m(bx as f64 + fx, by as f64 + fy);
    let sigma_m = sigma_px * res;
    let rejection = if valid_fraction < p.min_valid_fraction {
        Some(Rejection::TooFewValid {
            fraction: valid_fraction,
        })
    } else if bx == 0 || by == 0 || bx + 1 == sw || by + 1 == sh {
        Some(Rejection::OnWindowEdge)
    } else if peak_ratio
        < match p.method {
            Method::Ncc => p.ncc_min_peak_ratio,
            Method::Census | Method::MutualInformation => p.min_peak_ratio,
        }
    {
        Some(Rejection::Ambiguous { peak_ratio })
    } else if sigma_m > p.max_sigma_m {
        Some(Rejection::Imprecise { sigma_m })
    } else {
        None
    };
    Ok(MatchResult {
        position_m: [x, y],
        correction_m: [x - prior_m[0], y - prior_m[1]],
        sigma_m,
        best_score,
        peak_ratio,
        valid_fraction,
        rejection,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::synthetic::sinusoid_texture;
    use maps::GeoTransform;

    #[test]
    fn easting_scale_is_one_at_true_scale_and_grows_poleward() {
        assert!((easting_scale(18.4663, 18.4663) - 1.0).abs() < 1e-15);
        assert!(easting_scale(30.0, 18.4663) > 1.0);
        assert!((easting_scale(60.0, 0.0) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn recovers_a_planted_offset_and_rejects_featureless_terrain() {
        let geo = GeoTransform::new(0.0, 200.0, 0.25);
        let map = sinusoid_texture(800, 800, geo, 7);
        // The rover is truly at (100, 90); the prior is 11.5 m east, 7.25 m south of it.
        let truth = [100.0, 90.0];
        let (tc, tr) = map.geo.pixel_of(truth[0], truth[1]);
        let (c0, r0) = (tc as usize - 120, tr as usize - 120);
        let mut ortho = map.try_crop(c0, r0, 240, 240).unwrap();
        // A different monotonic camera response: census does not care.
        for v in &mut ortho.data {
            *v = (f64::from(*v).powf(0.8) * 2.0).min(255.0) as u8;
        }
        let mut valid = vec![true; 240 * 240];
        for (i, v) in valid.iter_mut().enumerate() {
            if (i % 240) < 60 {
                *v = false; // a rear wedge without data
            }
        }
        let rover = RoverImages {
            ortho: &ortho,
            ortho_valid: &valid,
            dem: None,
        };
        let orbital = OrbitalMap {
            appearance: &map,
            dem: None,
        };
        let prior = [truth[0] + 11.5, truth[1] - 7.25];
        let m = localize(&orbital, &rover, prior, &MatchSettings::default()).unwrap();
        let err = (m.position_m[0] - truth[0]).hypot(m.position_m[1] - truth[1]);
        assert!(err < 0.05, "{m:?}");
        assert_eq!(m.rejection, None, "{m:?}");
        assert!(m.peak_ratio > 1.5 && m.sigma_m < 0.5, "{m:?}");

        // A flat grey orthomosaic cannot be matched: rejected, not applied.
        let flat = Raster::filled(240, 240, geo, 128u8);
        let rover = RoverImages {
            ortho: &flat,
            ortho_valid: &valid,
            dem: None,
        };
        let m = localize(&orbital, &rover, prior, &MatchSettings::default()).unwrap();
        assert!(m.rejection.is_some(), "{m:?}");
    }

    #[test]
    fn method_names_round_trip() {
        for m in Method::ALL {
            assert_eq!(Method::from_name(m.name()), Some(m));
            assert_eq!(m.to_string(), m.name());
        }
        assert_eq!(Method::from_name("MI"), Some(Method::MutualInformation));
        assert_eq!(Method::from_name("sad"), None);
        assert_eq!(MatchSettings::default().method, Method::Census);
    }

    #[test]
    fn ncc_and_mi_recover_a_planted_offset() {
        let geo = GeoTransform::new(0.0, 200.0, 0.25);
        let map = sinusoid_texture(800, 800, geo, 7);
        let truth = [100.0, 90.0];
        let (tc, tr) = map.geo.pixel_of(truth[0], truth[1]);
        let mut ortho = map
            .try_crop(tc as usize - 120, tr as usize - 120, 240, 240)
            .unwrap();
        // A linear camera response change (gain and offset).
        for v in &mut ortho.data {
            *v = (0.7 * f64::from(*v) + 40.0) as u8;
        }
        let valid: Vec<bool> = (0..240 * 240).map(|i| i % 240 >= 60).collect();
        let orbital = OrbitalMap {
            appearance: &map,
            dem: None,
        };
        let prior = [truth[0] + 11.5, truth[1] - 7.25];
        let flat = Raster::filled(240, 240, geo, 128u8);
        for method in [Method::Ncc, Method::MutualInformation] {
            let p = MatchSettings {
                method,
                ..MatchSettings::default()
            };
            let rover = RoverImages {
                ortho: &ortho,
                ortho_valid: &valid,
                dem: None,
            };
            let m = localize(&orbital, &rover, prior, &p).unwrap();
            let err = (m.position_m[0] - truth[0]).hypot(m.position_m[1] - truth[1]);
            assert!(err < 0.1, "{method}: {m:?}");
            assert_eq!(m.rejection, None, "{method}: {m:?}");
            assert!(m.sigma_m < 0.5, "{method}: {m:?}");

            // Featureless terrain is rejected, not applied.
            let rover = RoverImages {
                ortho: &flat,
                ortho_valid: &valid,
                dem: None,
            };
            let m = localize(&orbital, &rover, prior, &p).unwrap();
            assert!(m.rejection.is_some(), "{method}: {m:?}");
        }
    }

    #[test]
    fn dem_term_keeps_the_planted_offset() {
        let geo = GeoTransform::new(0.0, 200.0, 0.25);
        let map = sinusoid_texture(800, 800, geo, 11);
        // Orbital DEM at 1 m: heights from another texture (metres, ~±2 m).
        let dem_u8 = sinusoid_texture(200, 200, GeoTransform::new(0.0, 200.0, 1.0), 12);
        let dem = Raster {
            data: dem_u8.data.iter().map(|&v| f32::from(v) / 20.0).collect(),
            width: dem_u8.width,
            height: dem_u8.height,
            geo: dem_u8.geo,
        };
        let truth = [100.0, 90.0];
        let (tc, tr) = map.geo.pixel_of(truth[0], truth[1]);
        let ortho = map
            .try_crop(tc as usize - 120, tr as usize - 120, 240, 240)
            .unwrap();
        let (dc, dr) = dem.geo.pixel_of(truth[0], truth[1]);
        let mut rdem = dem
            .try_crop(dc as usize - 30, dr as usize - 30, 60, 60)
            .unwrap();
        for v in &mut rdem.data {
            *v += 3.0; // the rover's heights have an unknown vertical offset
        }
        let valid = vec![true; 240 * 240];
        let dvalid = vec![true; 60 * 60];
        let rover = RoverImages {
            ortho: &ortho,
            ortho_valid: &valid,
            dem: Some((&rdem, &dvalid)),
        };
        let orbital = OrbitalMap {
            appearance: &map,
            dem: Some(&dem),
        };
        let m = localize(
            &orbital,
            &rover,
            [truth[0] - 6.0, truth[1] + 9.5],
            &MatchSettings::default(),
        )
        .unwrap();
        let err = (m.position_m[0] - truth[0]).hypot(m.position_m[1] - truth[1]);
        assert!(err < 0.05 && m.rejection.is_none(), "{m:?}");
    }

    #[test]
    fn bad_inputs_are_errors() {
        let geo = GeoTransform::new(0.0, 150.0, 0.25);
        let map = sinusoid_texture(600, 600, geo, 1);
        let ortho = map.try_crop(0, 0, 240, 240).unwrap();
        let valid = vec![true; 240 * 240];
        let orbital = OrbitalMap {
            appearance: &map,
            dem: None,
        };
        let rover = RoverImages {
            ortho: &ortho,
            ortho_valid: &valid,
            dem: None,
        };
        assert!(matches!(
            localize(&orbital, &rover, [10.0, 10.0], &MatchSettings::default()),
            Err(LocalizeError::WindowOffMap { .. })
        ));
        let none = vec![false; 240 * 240];
        let rover = RoverImages {
            ortho: &ortho,
            ortho_valid: &none,
            dem: None,
        };
        assert!(matches!(
            localize(&orbital, &rover, [75.0, 75.0], &MatchSettings::default()),
            Err(LocalizeError::NoValidPixels)
        ));
        let coarse = Raster::filled(60, 60, GeoTransform::new(0.0, 150.0, 1.0), 0u8);
        let rover = RoverImages {
            ortho: &coarse,
            ortho_valid: &valid[..3600],
            dem: None,
        };
        assert!(matches!(
            localize(&orbital, &rover, [75.0, 75.0], &MatchSettings::default()),
            Err(LocalizeError::ResolutionMismatch { .. })
        ));
    }
}
