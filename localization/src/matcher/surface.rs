//! The score surface: the combined appearance (+ DEM) score of the rover orthomosaic at every
//! 25 cm offset inside a search window (paper 000 §5, steps 1-3 of [`super::localize`]).
//!
//! [`localize`](super::localize) takes the minimum of this surface and checks it; the particle
//! filter ([`crate::particle`]) reads it at each particle's position instead. Both get the same
//! numbers from [`score_surface`].

use maps::Raster;

use super::{LocalizeError, MatchSettings, Method, OrbitalMap, RoverImages, easting_scale};
use crate::baselines::{mi_scores, ncc_scores, template_entropy};
use crate::census::{ScoreMap, census_transform_raster};

/// The combined score of the rover orthomosaic at every offset of a search window (lower is
/// better): `appearance_weight × appearance + dem_weight × dem` as [`super::localize`] computes
/// it (see the steps in [`super`]).
///
/// Offset `(col, row)` puts the rover (the centre of the orthomosaic) at
/// [`ScoreSurface::position_m`]`(col, row)`: columns run east and rows south, one orbital pixel
/// apart.
#[derive(Clone, Debug, PartialEq)]
pub struct ScoreSurface {
    /// Number of offsets east-west.
    pub width: usize,
    /// Number of offsets north-south.
    pub height: usize,
    /// Combined score per offset, row-major (row 0 north); `+∞` where no census bit was
    /// comparable. Units: those of the [`Method`] (census: fraction of disagreeing bits, 0..1),
    /// plus the weighted DEM term (0..1) when both DEMs are given.
    pub scores: Vec<f64>,
    /// Census only: valid census bits compared at each offset (the binomial noise model of the
    /// matcher's σ uses them); `None` for NCC and MI.
    pub census_valid_bits: Option<Vec<u32>>,
    /// Map position of the north-west corner of the orbital window the surface was scored in,
    /// metres (x east, y north).
    pub window_origin_m: [f64; 2],
    /// Size of the (easting-rescaled) orthomosaic, pixels (width, height).
    pub template_px: [usize; 2],
    /// Orbital pixel size = offset spacing, metres.
    pub resolution_m_per_px: f64,
    /// Fraction of valid orthomosaic pixels, 0..1.
    pub valid_fraction: f64,
}

impl ScoreSurface {
    /// Map position of the rover (x east, y north, metres) for a fractional offset `(col, row)`.
    #[must_use]
    pub fn position_m(&self, col: f64, row: f64) -> [f64; 2] {
        let res = self.resolution_m_per_px;
        let [wx0, wy0] = self.window_origin_m;
        // Written as `localize` always wrote it, so its positions stay bit-identical.
        [
            wx0 + col * res + self.template_px[0] as f64 * res / 2.0,
            wy0 - row * res - self.template_px[1] as f64 * res / 2.0,
        ]
    }

    /// Fractional offset `(col, row)` of the rover position `position_m` (inverse of
    /// [`ScoreSurface::position_m`]).
    #[must_use]
    pub fn offset_of(&self, position_m: [f64; 2]) -> (f64, f64) {
        let [x0, y0] = self.position_m(0.0, 0.0);
        let res = self.resolution_m_per_px;
        ((position_m[0] - x0) / res, (y0 - position_m[1]) / res)
    }

    /// Bilinear interpolation of the score at the rover position `position_m` (map metres), or
    /// `None` if the position is outside the surface or next to an offset without a score.
    #[must_use]
    pub fn score_at(&self, position_m: [f64; 2]) -> Option<f64> {
        let (fx, fy) = self.offset_of(position_m);
        if !(fx >= 0.0 && fy >= 0.0) || self.width == 0 || self.height == 0 {
            return None;
        }
        let (xmax, ymax) = ((self.width - 1) as f64, (self.height - 1) as f64);
        if fx > xmax || fy > ymax {
            return None;
        }
        let (x0, y0) = (fx.floor() as usize, fy.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (tx, ty) = (fx - x0 as f64, fy - y0 as f64);
        let g = |x: usize, y: usize| self.scores[y * self.width + x];
        let top = g(x0, y0) * (1.0 - tx) + g(x1, y0) * tx;
        let bottom = g(x0, y1) * (1.0 - tx) + g(x1, y1) * tx;
        let s = top * (1.0 - ty) + bottom * ty;
        s.is_finite().then_some(s)
    }
}

/// Resample `ortho` in x by `scale` (map metres per ground metre) about its centre, nearest
/// neighbour, keeping its size; pixels that fall outside become invalid.
fn rescale_easting(ortho: &Raster<u8>, valid: &[bool], scale: f64) -> (Raster<u8>, Vec<bool>) {
    if (scale - 1.0).abs() < 1e-12 {
        return (ortho.clone(), valid.to_vec());
    }
    let (w, h) = (ortho.width, ortho.height);
    let cx = w as f64 / 2.0;
    let mut out = Raster::filled(w, h, ortho.geo, 0u8);
    let mut out_valid = vec![false; w * h];
    for row in 0..h {
        for col in 0..w {
            let src = ((col as f64 + 0.5 - cx) / scale + cx - 0.5).round();
            if src >= 0.0 && (src as usize) < w {
                let i = row * w + src as usize;
                out.data[row * w + col] = ortho.data[i];
                out_valid[row * w + col] = valid[i];
            }
        }
    }
    (out, out_valid)
}

/// Census appearance scores of the (rescaled) orthomosaic at every offset inside `window`.
fn census_scores(
    window: &Raster<u8>,
    ortho: &Raster<u8>,
    ortho_valid: &[bool],
) -> Result<ScoreMap, LocalizeError> {
    let map_census = census_transform_raster(window, &vec![true; window.width * window.height])?;
    let template = census_transform_raster(ortho, ortho_valid)?;
    let scores = crate::census::hamming_scores_fft(&template, &map_census)?;
    Ok(scores)
}

/// The combined score surface of `rover` against `orbital` for rover positions within
/// `half_extent_m = [east-west, north-south]` of `center_m` (map metres), by the method and
/// weights of `p` (its `search_radius_m` is not used: the extent is given).
///
/// Each half extent is rounded up to whole orbital pixels (a negative or NaN one counts as 0);
/// [`super::localize`] calls this with `[search_radius_m; 2]` around its prior.
///
/// # Errors
/// [`LocalizeError::ResolutionMismatch`] if the orthomosaic and the orbital appearance have
/// different pixel sizes; [`LocalizeError::NoValidPixels`] if no orthomosaic pixel is valid;
/// [`LocalizeError::WindowOffMap`] (with `prior_m = center_m` and `radius_m` the larger half
/// extent) if the window, orthomosaic included, is not entirely on the orbital map;
/// [`LocalizeError::Census`] if a buffer is inconsistent (e.g. `ortho_valid` of the wrong
/// length).
pub fn score_surface(
    orbital: &OrbitalMap<'_>,
    rover: &RoverImages<'_>,
    center_m: [f64; 2],
    half_extent_m: [f64; 2],
    p: &MatchSettings,
) -> Result<ScoreSurface, LocalizeError> {
    let map = orbital.appearance;
    let res = map.geo.resolution_m_per_px;
    if (rover.ortho.geo.resolution_m_per_px - res).abs() > 1e-9 {
        return Err(LocalizeError::ResolutionMismatch {
            ortho: rover.ortho.geo.resolution_m_per_px,
            map: res,
        });
    }
    let valid_fraction = rover.ortho_valid.iter().filter(|&&v| v).count() as f64
        / rover.ortho_valid.len().max(1) as f64;
    if valid_fraction == 0.0 {
        return Err(LocalizeError::NoValidPixels);
    }
    let (ortho, ortho_valid) = rescale_easting(
        rover.ortho,
        rover.ortho_valid,
        easting_scale(p.latitude_deg, p.true_scale_latitude_deg),
    );
    let (tw, th) = (ortho.width, ortho.height);
    let off_map = || LocalizeError::WindowOffMap {
        prior_m: center_m,
        radius_m: half_extent_m[0].max(half_extent_m[1]),
    };
    let rx_px = (half_extent_m[0] / res).ceil() as usize;
    let ry_px = (half_extent_m[1] / res).ceil() as usize;
    // The template's north-west corner sits at the centre minus half the template.
    let (pc, pr) = map.geo.pixel_of(center_m[0], center_m[1]);
    let c0 = pc - tw as f64 / 2.0 - rx_px as f64;
    let r0 = pr - th as f64 / 2.0 - ry_px as f64;
    let (cols, rows) = (tw + 2 * rx_px, th + 2 * ry_px);
    if !(c0 >= 0.0 && r0 >= 0.0) {
        return Err(off_map());
    }
    let window = map
        .try_crop(c0.round() as usize, r0.round() as usize, cols, rows)
        .ok_or_else(off_map)?;
    // Appearance score per offset (lower is better) and, for census, the valid bits per offset.
    let (sw, sh, appearance, census_bits) = match p.method {
        Method::Census => {
            let scores = census_scores(&window, &ortho, &ortho_valid)?;
            let normalized = scores.normalized_scores();
            (scores.width, scores.height, normalized, Some(scores.valid))
        }
        Method::Ncc => {
            let s = ncc_scores(&ortho.data, &ortho_valid, tw, th, &window.data, cols, rows)?;
            (s.width, s.height, s.scores, None)
        }
        Method::MutualInformation => {
            let s = mi_scores(&ortho.data, &ortho_valid, tw, th, &window.data, cols, rows)?;
            let h = template_entropy(&ortho.data, &ortho_valid);
            let scores = s
                .scores
                .iter()
                .map(|&neg_mi| if h > 0.0 { 1.0 + neg_mi / h } else { 1.0 })
                .collect();
            (s.width, s.height, scores, None)
        }
    };
    let mut combined: Vec<f64> = appearance.iter().map(|s| p.appearance_weight * s).collect();

    if let (Some((rdem, rvalid)), Some(mdem)) = (rover.dem, orbital.dem) {
        let dres = mdem.geo.resolution_m_per_px;
        let k = (dres / res).round().max(1.0) as usize;
        // The DEM window covering the appearance window (whole DEM cells).
        let (x0, y0) = window.geo.center_of(0, 0);
        let (dc, dr) = mdem.geo.pixel_of(x0, y0);
        let (dc0, dr0) = (dc.floor() as isize, dr.floor() as isize);
        let dcols = rdem.width + 2 * (rx_px / k) + 2;
        let drows = rdem.height + 2 * (ry_px / k) + 2;
        if dc0 >= 0
            && dr0 >= 0
            && let Some(dwin) = mdem.try_crop(dc0 as usize, dr0 as usize, dcols, drows)
        {
            let (ow, oh, ds) = crate::dem_score::dem_scores(rdem, rvalid, &dwin, p.dem_scale_m);
            // Appearance offset (ax, ay) puts the template's NW corner at window pixel (ax, ay);
            // the rover DEM's NW corner is the template's (both centred on the rover).
            let (tx0, ty0) = (window.geo.origin_m[0], window.geo.origin_m[1]);
            let (rx_off, ry_off) = (
                (tw as f64 * res - rdem.width as f64 * dres) / 2.0,
                (th as f64 * res - rdem.height as f64 * dres) / 2.0,
            );
            for ay in 0..sh {
                for ax in 0..sw {
                    let x = tx0 + ax as f64 * res + rx_off;
                    let y = ty0 - ay as f64 * res - ry_off;
                    let fx = (x - dwin.geo.origin_m[0]) / dres;
                    let fy = (dwin.geo.origin_m[1] - y) / dres;
                    combined[ay * sw + ax] += p.dem_weight * bilinear(&ds, ow, oh, fx, fy);
                }
            }
        }
    }
    Ok(ScoreSurface {
        width: sw,
        height: sh,
        scores: combined,
        census_valid_bits: census_bits,
        window_origin_m: window.geo.origin_m,
        template_px: [tw, th],
        resolution_m_per_px: res,
        valid_fraction,
    })
}

/// Bilinear interpolation of a `w × h` grid whose sample `(i, j)` sits at coordinate `(i, j)`,
/// clamped at the edges.
fn bilinear(g: &[f64], w: usize, h: usize, fx: f64, fy: f64) -> f64 {
    let x = fx.clamp(0.0, (w - 1) as f64);
    let y = fy.clamp(0.0, (h - 1) as f64);
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
    let (tx, ty) = (x - x0 as f64, y - y0 as f64);
    let top = g[y0 * w + x0] * (1.0 - tx) + g[y0 * w + x1] * tx;
    let bottom = g[y1 * w + x0] * (1.0 - tx) + g[y1 * w + x1] * tx;
    top * (1.0 - ty) + bottom * ty
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::matcher::localize;
    use crate::synthetic::sinusoid_texture;
    use maps::GeoTransform;

    #[test]
    fn surface_is_what_localize_minimises_and_reads_back_at_positions() {
        let geo = GeoTransform::new(0.0, 200.0, 0.25);
        let map = sinusoid_texture(800, 800, geo, 7);
        let truth = [100.0, 90.0];
        let (tc, tr) = map.geo.pixel_of(truth[0], truth[1]);
        let ortho = map
            .try_crop(tc as usize - 120, tr as usize - 120, 240, 240)
            .unwrap();
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
        let p = MatchSettings::default();
        let prior = [truth[0] + 3.0, truth[1] - 2.0];
        // A rectangular window: 2·⌈h/res⌉ + 1 offsets per axis.
        let s = score_surface(&orbital, &rover, prior, [6.0, 4.1], &p).unwrap();
        assert_eq!((s.width, s.height), (49, 35));
        assert_eq!(s.scores.len(), 49 * 35);
        assert_eq!(s.census_valid_bits.as_ref().map(Vec::len), Some(49 * 35));
        // Its best offset is the truth (the crop was exact), where the score is 0.
        let best = (0..s.scores.len())
            .min_by(|&a, &b| s.scores[a].total_cmp(&s.scores[b]))
            .unwrap();
        let at = s.position_m((best % s.width) as f64, (best / s.width) as f64);
        assert!(
            (at[0] - truth[0]).abs() < 1e-9 && (at[1] - truth[1]).abs() < 1e-9,
            "{at:?}"
        );
        assert_eq!(s.score_at(truth), Some(0.0));
        let (c, r) = s.offset_of(at);
        assert!(
            (c - (best % s.width) as f64).abs() < 1e-9
                && (r - (best / s.width) as f64).abs() < 1e-9
        );
        // Between offsets it interpolates; off the surface it is None.
        let mid = s.score_at([truth[0] + 0.125, truth[1]]).unwrap();
        let right = s.score_at([truth[0] + 0.25, truth[1]]).unwrap();
        assert!((mid - 0.5 * right).abs() < 1e-12);
        assert_eq!(s.score_at([prior[0] + 6.5, prior[1]]), None);
        assert_eq!(s.score_at([prior[0], prior[1] - 4.6]), None);
        // The square window is localize's: same minimum.
        let sq = score_surface(&orbital, &rover, prior, [p.search_radius_m; 2], &p).unwrap();
        let m = localize(&orbital, &rover, prior, &p).unwrap();
        assert_eq!(sq.valid_fraction, m.valid_fraction);
        let best_sq = sq.scores.iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!(best_sq, m.best_score);
        // Off the map: the error localize gives, naming the larger half extent.
        assert!(matches!(
            score_surface(&orbital, &rover, [20.0, 100.0], [3.0, 1.0], &p),
            Err(LocalizeError::WindowOffMap { radius_m, .. }) if radius_m == 3.0
        ));
    }
}
