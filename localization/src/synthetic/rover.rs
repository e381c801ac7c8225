//! The rover's post-drive NavCam orthomosaic and DEM of a truth patch.

use maps::{GeoTransform, Raster};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::image_ops::{bilinear, radiance};
use super::noise::{CachedValue, gaussian, sub_seed};
use super::rover_settings::RoverImagingSettings;
use super::shading::{ExactDiv, HeightField, Sun};
use super::{
    ORTHO_RESOLUTION_M_PER_PX, ORTHO_SIZE_PX, ROVER_DEM_BLOCK_PX, SyntheticError, TruthPatch,
    check_param,
};

const SALT_JITTER: u64 = 21;
const SALT_HEIGHT_SMOOTH: u64 = 22;
const SALT_HEIGHT_WHITE: u64 = 23;
const SALT_SENSOR: u64 = 24;
const SALT_DROPOUT: u64 = 25;
/// Size of the holes stereo dropouts leave, metres.
const DROPOUT_WAVELENGTH_M: f64 = 1.0;
/// Correlation length of the stereo errors, metres (a block-matching window at mid range).
const STEREO_ERROR_WAVELENGTH_M: f64 = 0.75;
/// [`value`] noise has a standard deviation of about this; dividing by it gives unit variance.
const VALUE_NOISE_SD: f64 = 0.75;
/// Ground around the window that the radiance image also covers, metres: room for the
/// range jitter and the radial footprint of far pixels.
const RADIANCE_MARGIN_M: f64 = 2.0;
/// Most samples averaged along the radial footprint of one ortho pixel.
const MAX_FOOTPRINT_SAMPLES: usize = 5;

/// The camera response of one stereo wedge (drawn from the seed).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct WedgeResponse {
    /// Azimuth of the wedge's left edge, degrees clockwise from north, 0..360; it spans
    /// [`RoverImagingSettings::wedge_width_deg`] clockwise from there.
    pub start_azimuth_deg: f64,
    /// Gain (dimensionless).
    pub gain: f64,
    /// Offset, DN.
    pub offset_dn: f64,
    /// Response exponent (dimensionless).
    pub gamma: f64,
}

/// The imaging conditions drawn for one observation: truth, for diagnostics and tests only.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct RoverLighting {
    /// Sun azimuth, degrees clockwise from north (direction the light comes from).
    pub sun_azimuth_deg: f64,
    /// Sun elevation, degrees.
    pub sun_elevation_deg: f64,
    /// One response per wedge, in azimuth order from the seeded start.
    pub wedges: Vec<WedgeResponse>,
}

/// The geometric errors drawn for one observation: truth, for diagnostics and tests only.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RoverGeometryErrors {
    /// Heading error of the mosaic, degrees: the mosaic is the truth rotated counter-clockwise
    /// (seen from above) by this angle about its centre.
    pub heading_error_deg: f64,
    /// Scale of the mosaic, dimensionless: ground `r` m away appears `r × scale` m away.
    pub scale: f64,
    /// Map position of the mosaic centre minus the rover's true position, metres (east, north):
    /// the best any matcher can do is to find the rover here.
    pub mosaic_offset_m: [f64; 2],
}

/// The rover's post-drive observation: a top-down orthomosaic and DEM centred on the rover.
#[derive(Clone, Debug, PartialEq)]
pub struct RoverObservation {
    /// Orthomosaic, [`ORTHO_SIZE_PX`]² pixels of [`ORTHO_RESOLUTION_M_PER_PX`] (60 m square)
    /// whose centre (the corner between the four middle pixels) is where the rover believes it
    /// is in its own frame: the true position plus [`RoverGeometryErrors::mosaic_offset_m`],
    /// with the content rotated by the heading error and scaled by the scale error about it.
    /// The raster's georeference is the true geometry's (centred on the true position), for
    /// scoring only. Invalid pixels hold 0.
    pub ortho: Raster<u8>,
    /// Per ortho pixel, row-major: whether stereo mapped it (in a wedge, within range, not the
    /// rover body, not occluded, no stereo dropout).
    pub valid: Vec<bool>,
    /// Rover DEM, metres: 1 m cells over the same square (60 × 60), each the mean of the valid
    /// noisy stereo heights of its 4 × 4 ortho pixels. Invalid cells hold 0.
    pub dem: Raster<f32>,
    /// Per DEM cell, row-major: whether it had at least
    /// [`RoverImagingSettings::dem_min_samples`] valid samples.
    pub dem_valid: Vec<bool>,
    /// The rover's true map position, metres (x east, y north): truth, for scoring only.
    pub true_position_m: [f64; 2],
    /// The sun and wedge responses this observation was rendered with: truth, for diagnostics.
    pub lighting: RoverLighting,
    /// The heading, scale and mosaic-centre errors it was rendered with: truth, for
    /// diagnostics.
    pub geometry_errors: RoverGeometryErrors,
}

impl RoverObservation {
    /// Fraction of ortho pixels that are valid, 0..1.
    #[must_use]
    pub fn valid_fraction(&self) -> f64 {
        self.valid.iter().filter(|&&v| v).count() as f64 / self.valid.len().max(1) as f64
    }
}

/// A uniform draw from `[lo, hi]` (`lo == hi` allowed).
fn draw(rng: &mut ChaCha8Rng, [lo, hi]: [f64; 2]) -> f64 {
    lo + (hi - lo) * rng.random::<f64>()
}

/// A standard normal draw (Box–Muller on two uniforms).
fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1 = 1.0 - rng.random::<f64>();
    let u2 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// `a.rem_euclid(360.0)`, without the `fmod` call for `|a| < 360` (the per-pixel case: an
/// azimuth or a difference of two), where `a % 360 = a` exactly.
#[inline]
fn rem_euclid_360(a: f64) -> f64 {
    if a.abs() < 360.0 {
        if a < 0.0 { a + 360.0 } else { a }
    } else {
        a.rem_euclid(360.0)
    }
}

/// The wedge whose centre is nearest to `azimuth_deg` among those containing it.
fn wedge_of(azimuth_deg: f64, wedges: &[WedgeResponse], width_deg: f64) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (k, w) in wedges.iter().enumerate() {
        let rel = rem_euclid_360(azimuth_deg - w.start_azimuth_deg);
        let off_centre = (rel - 0.5 * width_deg).abs();
        if rel < width_deg && best.is_none_or(|(_, d)| off_centre < d) {
            best = Some((k, off_centre));
        }
    }
    best.map(|(k, _)| k)
}

/// Renders the rover's post-drive orthomosaic and DEM at `rover_m`, deterministically.
///
/// The mast camera stands [`RoverImagingSettings::mast_height_m`] above the mean truth height of
/// the rover's footprint. A pixel of the 60 m window is valid if it lies between `min_range_m`
/// and `max_range_m` of the rover, inside one of the evenly spaced wedges, on the patch, in
/// sight of the camera (no truth terrain between them rises above the sight line), and not in
/// a stereo dropout (more of them with range). Its gray level is the Lambertian radiance under
/// a seeded late-afternoon sun, with cast shadows, sampled where stereo places it (shifted
/// along the line of sight by a range error growing with range², averaged over the pixel's
/// radial footprint), through the wedge's own monotonic response, plus sensor noise. Its
/// height is the truth there plus a stereo height error growing with range². Overlapping
/// wedges give a pixel to the wedge whose centre is nearest. The sun and the wedge responses
/// drawn are returned in [`RoverObservation::lighting`].
///
/// # Errors
/// [`SyntheticError::InvalidParameter`] if `p` fails [`RoverImagingSettings::validate`] or
/// `rover_m` is not finite or the patch's pixel size is not positive;
/// [`SyntheticError::MalformedPatch`] if the patch's rasters disagree;
/// [`SyntheticError::RoverOutsidePatch`] if the rover is not on the patch.
pub fn render_rover(
    patch: &TruthPatch,
    rover_m: [f64; 2],
    p: &RoverImagingSettings,
    seed: u64,
) -> Result<RoverObservation, SyntheticError> {
    p.validate()?;
    patch.check()?;
    for (field, value) in [("rover_m[0]", rover_m[0]), ("rover_m[1]", rover_m[1])] {
        check_param(field, value, "a finite map coordinate", f64::is_finite)?;
    }
    let hf = HeightField::new(&patch.height_m);
    let pgeo = patch.height_m.geo;
    let res = hf.resolution_m;
    // Pixel-centre coordinates of a map point on the truth grid.
    // `pgeo.pixel_of(x, y)`, with its divisions by the pixel size done exactly and faster.
    let per_px = ExactDiv::new(pgeo.resolution_m_per_px);
    let to_px = |x: f64, y: f64| {
        let [ox, oy] = pgeo.origin_m;
        [per_px.of(x - ox) - 0.5, per_px.of(oy - y) - 0.5]
    };
    let cam = to_px(rover_m[0], rover_m[1]);
    if !hf.contains(cam[0], cam[1]) {
        let (x0, y0, x1, y1) = patch.height_m.extent_m();
        return Err(SyntheticError::RoverOutsidePatch {
            rover_m,
            patch_extent_m: [x0, y0, x1, y1],
        });
    }

    // Imaging conditions of this observation.
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let sun_azimuth_deg = draw(&mut rng, p.sun_azimuth_range_deg).rem_euclid(360.0);
    let sun_elevation_deg = draw(&mut rng, p.sun_elevation_range_deg);
    let start_deg = 360.0 * rng.random::<f64>();
    let spacing_deg = 360.0 / p.wedge_count as f64;
    let wedges: Vec<WedgeResponse> = (0..p.wedge_count)
        .map(|k| WedgeResponse {
            start_azimuth_deg: (start_deg + k as f64 * spacing_deg).rem_euclid(360.0),
            gain: draw(&mut rng, p.gain_range),
            offset_dn: draw(&mut rng, p.offset_range_dn),
            gamma: draw(&mut rng, p.gamma_range),
        })
        .collect();
    let sun = Sun::new(sun_azimuth_deg, sun_elevation_deg, res);
    let shadows = hf.shadows(sun);
    // Geometric errors of the mosaic (drawn after the lighting so those draws do not move).
    let geometry_errors = RoverGeometryErrors {
        heading_error_deg: p.heading_sigma_deg * normal(&mut rng),
        scale: 1.0 + p.scale_sigma * normal(&mut rng),
        mosaic_offset_m: [
            p.mosaic_offset_sigma_m * normal(&mut rng),
            p.mosaic_offset_sigma_m * normal(&mut rng),
        ],
    };
    let (rot_sin, rot_cos) = geometry_errors.heading_error_deg.to_radians().sin_cos();
    let inv_scale = 1.0 / geometry_errors.scale;
    let mosaic_center = [
        rover_m[0] + geometry_errors.mosaic_offset_m[0],
        rover_m[1] + geometry_errors.mosaic_offset_m[1],
    ];

    let camera_z = footprint_mean_height(&hf, cam, p.min_range_m) + p.mast_height_m as f32;

    // Radiance under the rover's sun on the truth grid around the window.
    let half_m = 0.5 * ORTHO_SIZE_PX as f64 * ORTHO_RESOLUTION_M_PER_PX;
    let reach_px = (half_m + RADIANCE_MARGIN_M) / res;
    let clip = |v: f64, n: usize| v.clamp(0.0, n as f64) as usize;
    let (c0, c1) = (
        clip((cam[0] - reach_px).floor(), hf.width),
        clip((cam[0] + reach_px).ceil() + 1.0, hf.width),
    );
    let (r0, r1) = (
        clip((cam[1] - reach_px).floor(), hf.height),
        clip((cam[1] + reach_px).ceil() + 1.0, hf.height),
    );
    let (rw, rh) = (c1 - c0, r1 - r0);
    let lit_reach_px = (p.max_range_m + RADIANCE_MARGIN_M) / res;
    let reach2 = lit_reach_px * lit_reach_px;
    let (reach2_lo, reach2_hi) = (reach2 * (1.0 - 1e-9), reach2 * (1.0 + 1e-9));
    let mut rad = vec![0.0f32; rw * rh];
    rad.par_chunks_mut(rw.max(1))
        .enumerate()
        .for_each(|(i, out)| {
            let row = r0 + i;
            for (j, v) in out.iter_mut().enumerate() {
                let col = c0 + j;
                let (dc, dr) = (col as f64 - cam[0], row as f64 - cam[1]);
                // `hypot > reach`, settled by the squares unless within rounding of the edge.
                let d2 = dc * dc + dr * dr;
                let outside = if d2 > reach2_hi {
                    true
                } else if d2 < reach2_lo {
                    false
                } else {
                    dc.hypot(dr) > lit_reach_px
                };
                if outside {
                    continue;
                }
                let cos = hf.cos_incidence(col, row, sun.dir);
                let lit = cos > 0.0 && shadows.sunlit(col, row);
                let albedo = patch.albedo.data[row * hf.width + col];
                *v = radiance(albedo, cos, lit, p.ambient) as f32;
            }
        });
    let radiance_at =
        |[c, r]: [f64; 2]| f64::from(bilinear(&rad, rw, rh, c - c0 as f64, r - r0 as f64));

    // The orthomosaic: one pass over its pixels, rows in parallel.
    let n = ORTHO_SIZE_PX;
    let ortho_geo = GeoTransform::new(
        rover_m[0] - half_m,
        rover_m[1] + half_m,
        ORTHO_RESOLUTION_M_PER_PX,
    );
    let jitter_seed = sub_seed(seed, SALT_JITTER);
    let smooth_h_seed = sub_seed(seed, SALT_HEIGHT_SMOOTH);
    let white_h_seed = sub_seed(seed, SALT_HEIGHT_WHITE);
    let sensor_seed = sub_seed(seed, SALT_SENSOR);
    let dropout_seed = sub_seed(seed, SALT_DROPOUT);
    let ifov_rad = 1e-3 * p.pixel_ifov_mrad;
    let mut ortho = vec![0u8; n * n];
    let mut valid = vec![false; n * n];
    let mut heights = vec![0.0f32; n * n];
    ortho
        .par_chunks_mut(n)
        .zip(valid.par_chunks_mut(n))
        .zip(heights.par_chunks_mut(n))
        .enumerate()
        .for_each_init(
            || {
                (
                    CachedValue::new(dropout_seed),
                    CachedValue::new(jitter_seed),
                    CachedValue::new(smooth_h_seed),
                )
            },
            |(dropout_noise, jitter_noise, smooth_h_noise), (row, ((o_row, v_row), h_row))| {
                for col in 0..n {
                    // Where the rover maps this pixel, relative to its mosaic centre, back to the
                    // ground point it actually shows: undo the scale, then the rotation.
                    let (ex, ey) = ortho_geo.center_of(col, row);
                    let (qx, qy) = ((ex - rover_m[0]) * inv_scale, (ey - rover_m[1]) * inv_scale);
                    let (x, y) = (
                        mosaic_center[0] + rot_cos * qx + rot_sin * qy,
                        mosaic_center[1] - rot_sin * qx + rot_cos * qy,
                    );
                    let (dx, dy) = (x - rover_m[0], y - rover_m[1]);
                    let range_m = dx.hypot(dy);
                    if range_m < p.min_range_m || range_m > p.max_range_m {
                        continue;
                    }
                    let azimuth_deg = rem_euclid_360(dx.atan2(dy).to_degrees());
                    let Some(k) = wedge_of(azimuth_deg, &wedges, p.wedge_width_deg) else {
                        continue;
                    };
                    // Stereo dropouts: blotches where smooth noise, mapped to (0, 1) by a logistic
                    // approximation of the normal CDF, falls below the range-dependent rate.
                    let dropout = p.stereo_dropout_at_max_range * (range_m / p.max_range_m).powi(2);
                    let blotch = dropout_noise
                        .at(x / DROPOUT_WAVELENGTH_M, y / DROPOUT_WAVELENGTH_M)
                        / VALUE_NOISE_SD;
                    // The logistic is at least ½ where `blotch ≥ 0` (1 / (1 + e) with e ≤ 1), so
                    // a rate of at most ½ needs no exponential there.
                    let dropped = dropout > 0.0
                        && !(blotch >= 0.0 && dropout <= 0.5)
                        && 1.0 / (1.0 + (-1.702 * blotch).exp()) < dropout;
                    if dropped {
                        continue;
                    }
                    let target = to_px(x, y);
                    if !hf.contains(target[0], target[1]) {
                        continue;
                    }
                    let target_z = hf.bilinear(target[0], target[1]);
                    if !hf.line_of_sight(cam, camera_z, target, target_z) {
                        continue;
                    }
                    // Stereo errors: along the line of sight, growing with range².
                    let r2 = (range_m / 10.0).powi(2);
                    let (ux, uy) = (dx / range_m, dy / range_m);
                    let (sx, sy) = (x / STEREO_ERROR_WAVELENGTH_M, y / STEREO_ERROR_WAVELENGTH_M);
                    let shift_m =
                        p.range_sigma_m_at_10m * r2 * jitter_noise.at(sx, sy) / VALUE_NOISE_SD;
                    let footprint_m = range_m * range_m * ifov_rad / p.mast_height_m;
                    let samples = if footprint_m < res {
                        1
                    } else {
                        (1 + (footprint_m / res).ceil() as usize).min(MAX_FOOTPRINT_SAMPLES)
                    };
                    let mut sum = 0.0;
                    for s in 0..samples {
                        let along_m = if samples == 1 {
                            shift_m
                        } else {
                            shift_m + footprint_m * (s as f64 / (samples - 1) as f64 - 0.5)
                        };
                        sum += radiance_at(to_px(x + ux * along_m, y + uy * along_m));
                    }
                    let w = &wedges[k];
                    let response = (sum / samples as f64 / p.white_level)
                        .max(0.0)
                        .powf(w.gamma);
                    let dn = w.offset_dn
                        + w.gain * 255.0 * response
                        + p.noise_sigma_dn * gaussian(sensor_seed, col as i64, row as i64);
                    o_row[col] = dn.clamp(0.0, 255.0).round() as u8;
                    v_row[col] = true;
                    let seen = to_px(x + ux * shift_m, y + uy * shift_m);
                    let height_error = 0.8 * smooth_h_noise.at(sx, sy) / VALUE_NOISE_SD
                        + 0.6 * gaussian(white_h_seed, col as i64, row as i64);
                    h_row[col] = hf.bilinear(seen[0], seen[1])
                        + (p.height_sigma_m_at_10m * r2 * height_error) as f32;
                }
            },
        );

    let (dem, dem_valid) = block_mean_dem(&heights, &valid, ortho_geo, p.dem_min_samples);
    Ok(RoverObservation {
        ortho: Raster {
            width: n,
            height: n,
            geo: ortho_geo,
            data: ortho,
        },
        valid,
        dem,
        dem_valid,
        true_position_m: rover_m,
        lighting: RoverLighting {
            sun_azimuth_deg,
            sun_elevation_deg,
            wedges,
        },
        geometry_errors,
    })
}

/// Mean truth height of the pixels whose centres lie within `radius_m` of `cam` (pixel-centre
/// coordinates); the bilinear height at `cam` if there are none.
fn footprint_mean_height(hf: &HeightField<'_>, cam: [f64; 2], radius_m: f64) -> f32 {
    let r_px = radius_m / hf.resolution_m;
    let lo = |v: f64| (v - r_px).floor().max(0.0) as usize;
    let (mut sum, mut count) = (0.0f64, 0usize);
    for row in lo(cam[1])..((cam[1] + r_px).ceil() as usize + 1).min(hf.height) {
        for col in lo(cam[0])..((cam[0] + r_px).ceil() as usize + 1).min(hf.width) {
            if (col as f64 - cam[0]).hypot(row as f64 - cam[1]) <= r_px {
                sum += f64::from(hf.at(col, row));
                count += 1;
            }
        }
    }
    if count == 0 {
        hf.bilinear(cam[0], cam[1])
    } else {
        (sum / count as f64) as f32
    }
}

/// Averages the valid heights of each [`ROVER_DEM_BLOCK_PX`]² block of ortho pixels.
fn block_mean_dem(
    heights: &[f32],
    valid: &[bool],
    ortho_geo: GeoTransform,
    min_samples: usize,
) -> (Raster<f32>, Vec<bool>) {
    let (n, b) = (ORTHO_SIZE_PX, ROVER_DEM_BLOCK_PX);
    let m = n / b;
    let mut dem = vec![0.0f32; m * m];
    let mut dem_valid = vec![false; m * m];
    for br in 0..m {
        for bc in 0..m {
            let (mut sum, mut count) = (0.0f64, 0usize);
            for row in br * b..(br + 1) * b {
                for col in bc * b..(bc + 1) * b {
                    if valid[row * n + col] {
                        sum += f64::from(heights[row * n + col]);
                        count += 1;
                    }
                }
            }
            if count >= min_samples {
                dem[br * m + bc] = (sum / count as f64) as f32;
                dem_valid[br * m + bc] = true;
            }
        }
    }
    (
        Raster {
            width: m,
            height: m,
            geo: ortho_geo.scaled(b as f64),
            data: dem,
        },
        dem_valid,
    )
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn rem_euclid_360_equals_rem_euclid() {
        let mut values: Vec<f64> = (-80_000..80_000).map(|i| f64::from(i) * 0.00913).collect();
        for v in [
            0.0,
            -0.0,
            360.0,
            -360.0,
            720.5,
            -1e300,
            1e-300,
            -1e-300,
            f64::NAN,
        ] {
            values.extend([v, v.next_up(), v.next_down()]);
        }
        values.extend([f64::INFINITY, f64::NEG_INFINITY]);
        for v in values {
            assert_eq!(
                rem_euclid_360(v).to_bits(),
                v.rem_euclid(360.0).to_bits(),
                "{v}"
            );
        }
    }

    #[test]
    fn wedges_pick_the_nearest_centre_and_leave_gaps() {
        let three: Vec<WedgeResponse> = (0..3)
            .map(|k| WedgeResponse {
                start_azimuth_deg: 120.0 * k as f64,
                gain: 1.0,
                offset_dn: 0.0,
                gamma: 1.0,
            })
            .collect();
        assert_eq!(wedge_of(10.0, &three, 96.0), Some(0));
        assert_eq!(wedge_of(100.0, &three, 96.0), None); // the 96°..120° gap
        assert_eq!(wedge_of(359.0, &three, 96.0), None);
        assert_eq!(wedge_of(130.0, &three, 96.0), Some(1));
        let mut four = three.clone();
        four.truncate(1);
        for k in 1..4 {
            four.push(WedgeResponse {
                start_azimuth_deg: 90.0 * k as f64,
                ..three[0]
            });
        }
        // 95° is in wedges 0 (0°..96°, centre 48°) and 1 (90°..186°, centre 138°).
        assert_eq!(wedge_of(95.0, &four, 96.0), Some(1));
        assert_eq!(wedge_of(91.0, &four, 96.0), Some(0));
    }
}
