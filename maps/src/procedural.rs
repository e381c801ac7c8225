//! Seeded procedural Mars terrain: DEM, terrain classes and a hill-shaded appearance.
//!
//! [`generate`] turns [`TerrainSettings`] into [`MapLayers`]:
//! 1. **DEM** (metres) = base height + fBm relief + craters (parabolic bowl, raised rim,
//!    ejecta falloff; fresh rims exceed 25° and become hazards) + long linear ridges + dune
//!    ripples inside [`DuneField`]s, clamped to 0..=655 m so it fits 16-bit centimetre files.
//! 2. **Terrain classes**: sand inside dune fields and sand patches; elsewhere sand in the
//!    lowest-lying, flattest, sand-noisiest [`TerrainSettings::sand_fraction`] of the map
//!    (hollows, crater floors), bedrock in the highest-standing, steepest, rock-noisiest
//!    [`TerrainSettings::bedrock_fraction`] (rims, ridges, knobs), soil in the rest.
//!    "Lying low" is measured against the mean height within 40 m.
//! 3. **Appearance** (8-bit): Lambertian hill shade under the given sun, times an albedo by
//!    class (sand dark, soil mid, bedrock bright) with broad albedo mottling, plus seeded
//!    texture (weak on sand, strong on bedrock — as the rover's cameras see them).
//!
//! Determinism: craters and ridges are drawn once from `ChaCha8Rng::seed_from_u64(seed)`;
//! every per-pixel value is a pure function of (seed, map position) through hash-based noise,
//! and the class thresholds are quantiles of a fixed pixel sample. The same parameters
//! therefore give byte-identical layers on any number of threads.
//!
//! ## References
//! - K. Perlin, "Improving noise", SIGGRAPH 2002 (gradient noise).
//! - R. J. Pike, "Control of crater morphology by gravity and target type: Mars, Earth, Moon",
//!   Proc. Lunar Planet. Sci. Conf. 11, 1980 (simple craters: depth ≈ 0.2 × diameter).
//! - W. K. Hartmann, "Martian cratering 8: Isochron refinement and the chronology of Mars",
//!   Icarus 174, 2005 (small craters follow a steep power-law size-frequency distribution).

mod landforms;
pub mod noise;

use rayon::prelude::*;

use crate::raster::{GeoTransform, Raster};
use crate::raster_io::MapLayers;
use crate::terrain::TerrainClass;
use landforms::Landforms;
use noise::{Fbm, sub_seed, white};

/// Heights are clamped to this range so the DEM fits 16-bit centimetres above datum 0.
const HEIGHT_RANGE_M: (f64, f64) = (0.0, 655.0);
/// Radius of the neighbourhood whose mean height defines "lying low" / "standing high".
const LOCAL_MEAN_RADIUS_M: f64 = 40.0;
/// Wavelength of the noise that places sand and bedrock patches.
const CLASS_NOISE_WAVELENGTH_M: f64 = 150.0;
/// Cap on [`TerrainSettings::ridge_count`], so a typo cannot stall generation.
const MAX_RIDGES: usize = 1000;
/// Upper bound on the pixels sampled to set the class thresholds.
const THRESHOLD_SAMPLE_PX: usize = 250_000;
/// Share of the light that reaches surfaces facing away from the sun (sky and scatter).
const AMBIENT: f64 = 0.25;
/// Gray level of flat, sunlit bedrock before texture.
const FLAT_BEDROCK_GRAY: f64 = 150.0;

const SALT_SAND: u64 = 101;
const SALT_ROCK: u64 = 102;
const SALT_ALBEDO: u64 = 103;
const SALT_TEXTURE: u64 = 104;
const SALT_GRAIN: u64 = 105;

/// A field of transverse dunes: a disc of sand whose DEM carries periodic ripples.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DuneField {
    /// Centre of the field, map metres (x east, y north). (default: `[0, 0]`)
    pub center_m: [f64; 2],
    /// Radius of the field, metres; ripples fade out over its outer 20 %. (default: 100)
    pub radius_m: f64,
    /// Crest-to-crest spacing, metres; 0 gives flat sand. (default: 20)
    pub wavelength_m: f64,
    /// Half the crest-to-trough height, metres. The lee faces then stand near the 33° angle
    /// of repose with the default wavelength. (default: 1.5)
    pub amplitude_m: f64,
    /// Direction the crests run, degrees clockwise from north (0: crests run north–south and
    /// repeat from west to east). (default: 0)
    pub crest_azimuth_deg: f64,
}

impl Default for DuneField {
    fn default() -> Self {
        Self {
            center_m: [0.0, 0.0],
            radius_m: 100.0,
            wavelength_m: 20.0,
            amplitude_m: 1.5,
            crest_azimuth_deg: 0.0,
        }
    }
}

impl DuneField {
    /// A dune field with the default wavelength and amplitude.
    #[must_use]
    pub fn new(center_m: [f64; 2], radius_m: f64, crest_azimuth_deg: f64) -> Self {
        Self {
            center_m,
            radius_m,
            crest_azimuth_deg,
            ..Self::default()
        }
    }
}

/// Settings of the terrain generator. Non-finite numbers are replaced by their defaults and
/// negative sizes by zero, so [`generate`] never panics.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TerrainSettings {
    /// Master seed: the same parameters and seed give byte-identical layers. (default: 1)
    pub seed: u64,
    /// Map width in pixels (columns). (default: 1000)
    pub width_px: usize,
    /// Map height in pixels (rows). (default: 1000)
    pub height_px: usize,
    /// Placement and pixel size. (default: north-west corner at (0 m, 1000 m), 1 m/px, so the
    /// default map covers x and y in 0..1000 m)
    pub geo: GeoTransform,
    /// Mean ground height, metres above datum 0; keep it well inside 0..655 m. (default: 100)
    pub base_height_m: f64,
    /// Amplitude of the large-scale fBm relief (wavelengths 400 m down to 25 m), metres;
    /// heights vary by about ± this much. (default: 15)
    pub relief_m: f64,
    /// Mean number of craters per square kilometre (range 0..~50). (default: 3)
    pub crater_density_per_km2: f64,
    /// Smallest crater radius, metres (at least 1 cm). (default: 5)
    pub crater_radius_min_m: f64,
    /// Largest crater radius, metres (raised to the smallest if below it); radii follow a
    /// power law, N(>r) ∝ r⁻². (default: 60)
    pub crater_radius_max_m: f64,
    /// Number of long linear ridges (each 30–80 % of the map diagonal long; at most 1000).
    /// (default: 3)
    pub ridge_count: usize,
    /// Typical ridge crest height, metres (each ridge gets 0.6–1.4 times this). (default: 3)
    pub ridge_height_m: f64,
    /// Dune fields: sand, with ripples in the DEM. (default: none)
    pub dune_fields: Vec<DuneField>,
    /// Sand patches without ripples, as (centre in map metres, radius in metres). (default: none)
    pub sand_patches: Vec<([f64; 2], f64)>,
    /// Target share of sand outside the dune fields and sand patches, 0..1. (default: 0.15)
    pub sand_fraction: f64,
    /// Target share of bedrock outside the dune fields and sand patches, 0..1; soil takes
    /// what sand and bedrock leave. (default: 0.30)
    pub bedrock_fraction: f64,
    /// Direction the sunlight comes from, degrees clockwise from north. (default: 250, mid
    /// afternoon, from the west-southwest)
    pub sun_azimuth_deg: f64,
    /// Sun elevation above the horizon, degrees (clamped to 1..90). (default: 35)
    pub sun_elevation_deg: f64,
}

impl Default for TerrainSettings {
    fn default() -> Self {
        Self {
            seed: 1,
            width_px: 1000,
            height_px: 1000,
            geo: GeoTransform::new(0.0, 1000.0, 1.0),
            base_height_m: 100.0,
            relief_m: 15.0,
            crater_density_per_km2: 3.0,
            crater_radius_min_m: 5.0,
            crater_radius_max_m: 60.0,
            ridge_count: 3,
            ridge_height_m: 3.0,
            dune_fields: Vec::new(),
            sand_patches: Vec::new(),
            sand_fraction: 0.15,
            bedrock_fraction: 0.30,
            sun_azimuth_deg: 250.0,
            sun_elevation_deg: 35.0,
        }
    }
}

impl TerrainSettings {
    /// A copy with every non-finite number replaced by its default and every size made
    /// non-negative and the ridges capped, so generation never meets NaN: what [`generate`]
    /// uses.
    #[must_use]
    pub fn sanitized(&self) -> Self {
        let d = Self::default();
        let fin = |v: f64, def: f64| if v.is_finite() { v } else { def };
        let pos = |v: f64, def: f64| if v.is_finite() { v.max(0.0) } else { def };
        let mut geo = self.geo;
        if !(geo.resolution_m_per_px.is_finite() && geo.resolution_m_per_px > 0.0) {
            geo.resolution_m_per_px = 1.0;
        }
        geo.origin_m = geo.origin_m.map(|v| fin(v, 0.0));
        let dune_d = DuneField::default();
        let finite_pt = |c: [f64; 2]| c.map(|v| fin(v, 0.0));
        Self {
            seed: self.seed,
            width_px: self.width_px,
            height_px: self.height_px,
            geo,
            base_height_m: fin(self.base_height_m, d.base_height_m),
            relief_m: pos(self.relief_m, d.relief_m),
            crater_density_per_km2: pos(self.crater_density_per_km2, d.crater_density_per_km2),
            crater_radius_min_m: pos(self.crater_radius_min_m, d.crater_radius_min_m),
            crater_radius_max_m: pos(self.crater_radius_max_m, d.crater_radius_max_m),
            ridge_count: self.ridge_count.min(MAX_RIDGES),
            ridge_height_m: fin(self.ridge_height_m, d.ridge_height_m),
            dune_fields: self
                .dune_fields
                .iter()
                .map(|f| DuneField {
                    center_m: finite_pt(f.center_m),
                    radius_m: pos(f.radius_m, 0.0),
                    wavelength_m: pos(f.wavelength_m, dune_d.wavelength_m),
                    amplitude_m: fin(f.amplitude_m, dune_d.amplitude_m),
                    crest_azimuth_deg: fin(f.crest_azimuth_deg, 0.0),
                })
                .collect(),
            sand_patches: self
                .sand_patches
                .iter()
                .map(|&(c, r)| (finite_pt(c), pos(r, 0.0)))
                .collect(),
            sand_fraction: pos(self.sand_fraction, d.sand_fraction).min(1.0),
            bedrock_fraction: pos(self.bedrock_fraction, d.bedrock_fraction).min(1.0),
            sun_azimuth_deg: fin(self.sun_azimuth_deg, d.sun_azimuth_deg),
            sun_elevation_deg: fin(self.sun_elevation_deg, d.sun_elevation_deg).clamp(1.0, 90.0),
        }
    }
}

/// Most landform evaluations ([`landform_evaluations`]) a recipe may ask for. Measured
/// (issue 26, one core): a crater evaluation costs about 7 ns, a ridge 2 ns, a dune field or
/// sand patch under 1 ns, so a recipe at this cap spends at most about 15 s in its landforms,
/// beyond the ~0.5 µs per pixel every map costs (a recipe of 1 000 000 large craters ran 3
/// minutes before).
pub const MAX_LANDFORM_EVALUATIONS: u64 = 2_000_000_000;

/// How many times [`generate`] evaluates a landform at a pixel for `params`: each crater at
/// every pixel of the 32 × 32 px bins its ejecta reaches, and each ridge, dune field and sand
/// patch at every pixel. Computed from the craters as drawn (cheap: no pixel is generated), so
/// a recipe can be refused before its generation starts.
#[must_use]
pub fn landform_evaluations(params: &TerrainSettings) -> u64 {
    Landforms::evaluations(&params.sanitized())
}

/// Rows [`generate_observed`] reports: each of its three passes over the map's rows.
#[must_use]
pub fn progress_rows(params: &TerrainSettings) -> u64 {
    3 * params.sanitized().height_px as u64
}

/// Generates the three layers of a map from `params`, deterministically.
///
/// All layers share `params.geo` and size. A zero width or height gives empty layers.
/// 1500 × 1500 px takes well under a second in release builds.
#[must_use]
pub fn generate(params: &TerrainSettings) -> MapLayers {
    generate_observed(params, &|| {})
}

/// [`generate`], calling `on_row` as each row of each of its three passes is done
/// ([`progress_rows`] calls in all, from any thread; for a progress bar).
#[must_use]
pub fn generate_observed(params: &TerrainSettings, on_row: &(dyn Fn() + Sync)) -> MapLayers {
    let p = params.sanitized();
    let (w, h) = (p.width_px, p.height_px);
    let geo = p.geo;
    if w == 0 || h == 0 {
        return MapLayers {
            appearance: Raster::filled(w, h, geo, 0),
            dem: Raster::filled(w, h, geo, 0.0),
            terrain: Raster::filled(w, h, geo, 0),
        };
    }
    let res = geo.resolution_m_per_px;

    // 1. DEM and forced sand. Pixel-centre x is the same on every row.
    let landforms = Landforms::new(&p);
    let xs: Vec<f64> = (0..w).map(|col| geo.center_of(col, 0).0).collect();
    let y_of = |row: usize| geo.center_of(0, row).1;
    let mut dem = vec![0.0f32; w * h];
    let mut forced = vec![false; w * h];
    dem.par_chunks_mut(w)
        .zip(forced.par_chunks_mut(w))
        .enumerate()
        .for_each(|(row, (dem_row, forced_row))| {
            landforms.fill_row(row, &xs, y_of(row), clamp_height, dem_row, forced_row);
            on_row();
        });

    // 2. Per-pixel class scores and illumination.
    let radius_px = ((LOCAL_MEAN_RADIUS_M / res).round() as usize).clamp(1, w.max(h));
    let local_mean = box_mean(&dem, w, h, radius_px);
    let sand_noise = Fbm::new(sub_seed(p.seed, SALT_SAND), CLASS_NOISE_WAVELENGTH_M, 2);
    let rock_noise = Fbm::new(sub_seed(p.seed, SALT_ROCK), CLASS_NOISE_WAVELENGTH_M, 2);
    let sun = sun_vector(p.sun_azimuth_deg, p.sun_elevation_deg);
    let mut pixels = vec![PixelScore::default(); w * h];
    pixels.par_chunks_mut(w).enumerate().for_each(|(row, out)| {
        let y = y_of(row);
        let (mut sand_row, mut rock_row) = (vec![0.0; w], vec![0.0; w]);
        sand_noise.row(&xs, y, &mut sand_row);
        rock_noise.row(&xs, y, &mut rock_row);
        let (north, south) = (row.saturating_sub(1), (row + 1).min(h - 1));
        for (col, px) in out.iter_mut().enumerate() {
            let (west, east) = (col.saturating_sub(1), (col + 1).min(w - 1));
            let z = |c: usize, r: usize| f64::from(dem[r * w + c]);
            let dz_dx = (z(east, row) - z(west, row)) / ((east - west).max(1) as f64 * res);
            let dz_dy = (z(col, north) - z(col, south)) / ((south - north).max(1) as f64 * res);
            let grad = (dz_dx * dz_dx + dz_dy * dz_dy).sqrt();
            let above_mean_m = z(col, row) - f64::from(local_mean[row * w + col]);
            px.sand = (above_mean_m + 3.0 * grad + 1.5 * sand_row[col]) as f32;
            px.rock = (above_mean_m + 5.0 * grad + 1.5 * rock_row[col]) as f32;
            px.light = light(dz_dx, dz_dy, sun) as f32;
        }
        on_row();
    });

    // 3. Classes and appearance.
    let (sand_below, rock_above) =
        class_thresholds(&pixels, &forced, w, h, p.sand_fraction, p.bedrock_fraction);
    let albedo_noise = Fbm::new(sub_seed(p.seed, SALT_ALBEDO), 40.0, 2);
    let texture_noise = Fbm::new(sub_seed(p.seed, SALT_TEXTURE), 3.0, 1);
    let grain_seed = sub_seed(p.seed, SALT_GRAIN);
    let mut terrain = vec![0u8; w * h];
    let mut appearance = vec![0u8; w * h];
    terrain
        .par_chunks_mut(w)
        .zip(appearance.par_chunks_mut(w))
        .enumerate()
        .for_each(|(row, (t_row, a_row))| {
            let y = y_of(row);
            let (mut mottle_row, mut texture_row) = (vec![0.0; w], vec![0.0; w]);
            albedo_noise.row(&xs, y, &mut mottle_row);
            texture_noise.row(&xs, y, &mut texture_row);
            for (col, (t, a)) in t_row.iter_mut().zip(a_row.iter_mut()).enumerate() {
                let i = row * w + col;
                let px = &pixels[i];
                let class = if forced[i] || px.sand < sand_below {
                    TerrainClass::Sand
                } else if px.rock > rock_above {
                    TerrainClass::Bedrock
                } else {
                    TerrainClass::Soil
                };
                *t = class.code();
                let (albedo, texture_gray) = match class {
                    TerrainClass::Sand => (0.62, 3.0),
                    TerrainClass::Soil => (0.80, 7.0),
                    TerrainClass::Bedrock => (1.0, 12.0),
                };
                let mottle = 1.0 + 0.08 * mottle_row[col];
                let grain = white(grain_seed, col as i64, row as i64);
                let texture = texture_gray * (0.6 * grain + 0.4 * texture_row[col]);
                let gray = FLAT_BEDROCK_GRAY * albedo * mottle * f64::from(px.light) + texture;
                // Adding ½ and truncating rounds without a libm call.
                *a = (gray.clamp(0.0, 255.0) + 0.5) as u8;
            }
            on_row();
        });

    MapLayers {
        appearance: Raster {
            width: w,
            height: h,
            geo,
            data: appearance,
        },
        dem: Raster {
            width: w,
            height: h,
            geo,
            data: dem,
        },
        terrain: Raster {
            width: w,
            height: h,
            geo,
            data: terrain,
        },
    }
}

/// Scores of one pixel: low `sand` = sandy, high `rock` = rocky; `light` = shading factor
/// (1 for flat ground).
#[derive(Clone, Copy, Debug, Default)]
struct PixelScore {
    sand: f32,
    rock: f32,
    light: f32,
}

/// Clamps a height into [`HEIGHT_RANGE_M`]; NaN becomes the lower bound.
fn clamp_height(z: f64) -> f64 {
    if z >= HEIGHT_RANGE_M.0 {
        z.min(HEIGHT_RANGE_M.1)
    } else {
        HEIGHT_RANGE_M.0
    }
}

/// Unit vector towards the sun in (east, north, up).
fn sun_vector(azimuth_deg: f64, elevation_deg: f64) -> [f64; 3] {
    let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
    [az.sin() * el.cos(), az.cos() * el.cos(), el.sin()]
}

/// Lambertian shading factor of a surface with slopes `dz_dx` (east) and `dz_dy` (north) under
/// the unit sun vector `sun`: 1 for flat ground, [`AMBIENT`] for faces turned from the sun.
fn light(dz_dx: f64, dz_dy: f64, sun: [f64; 3]) -> f64 {
    let cos_incidence =
        (sun[2] - dz_dx * sun[0] - dz_dy * sun[1]) / (1.0 + dz_dx * dz_dx + dz_dy * dz_dy).sqrt();
    AMBIENT + (1.0 - AMBIENT) * cos_incidence.max(0.0) / sun[2]
}

/// Mean of each pixel's (2r+1)² neighbourhood, clipped at the raster edges.
fn box_mean(data: &[f32], w: usize, h: usize, r: usize) -> Vec<f32> {
    // Row window sums (parallel over rows), then a running column sum down the rows.
    let mut row_sums = vec![0.0f64; w * h];
    row_sums
        .par_chunks_mut(w)
        .zip(data.par_chunks(w))
        .for_each(|(out, src)| {
            let mut prefix = Vec::with_capacity(w + 1);
            prefix.push(0.0f64);
            let mut acc = 0.0f64;
            for &v in src {
                acc += f64::from(v);
                prefix.push(acc);
            }
            for (c, o) in out.iter_mut().enumerate() {
                let (a, b) = (c.saturating_sub(r), (c + r + 1).min(w));
                *o = (prefix[b] - prefix[a]) / (b - a) as f64;
            }
        });
    let mut out = vec![0.0f32; w * h];
    let mut col_sum = vec![0.0f64; w];
    for row in row_sums.chunks(w).take(r.min(h)) {
        col_sum.iter_mut().zip(row).for_each(|(s, v)| *s += v);
    }
    for row in 0..h {
        if row + r < h {
            let add = &row_sums[(row + r) * w..(row + r + 1) * w];
            col_sum.iter_mut().zip(add).for_each(|(s, v)| *s += v);
        }
        if row > r {
            let sub = &row_sums[(row - r - 1) * w..(row - r) * w];
            col_sum.iter_mut().zip(sub).for_each(|(s, v)| *s -= v);
        }
        let n = ((row + r + 1).min(h) - row.saturating_sub(r)) as f64;
        out[row * w..(row + 1) * w]
            .iter_mut()
            .zip(&col_sum)
            .for_each(|(o, s)| *o = (s / n) as f32);
    }
    out
}

/// Score thresholds `(sand_below, rock_above)` that make the requested shares of the pixels
/// outside forced sand sand and bedrock, from a regular sample of at most
/// [`THRESHOLD_SAMPLE_PX`] pixels (so the result does not depend on threads).
fn class_thresholds(
    pixels: &[PixelScore],
    forced: &[bool],
    w: usize,
    h: usize,
    sand_fraction: f64,
    bedrock_fraction: f64,
) -> (f32, f32) {
    let step = ((w * h) as f64 / THRESHOLD_SAMPLE_PX as f64)
        .sqrt()
        .ceil()
        .max(1.0) as usize;
    let sample: Vec<PixelScore> = (0..h)
        .step_by(step)
        .flat_map(|r| (0..w).step_by(step).map(move |c| r * w + c))
        .filter(|&i| !forced[i])
        .map(|i| pixels[i])
        .collect();
    let mut sand: Vec<f32> = sample.iter().map(|p| p.sand).collect();
    let sand_below = quantile(&mut sand, sand_fraction).unwrap_or(f32::NEG_INFINITY);
    let mut rock: Vec<f32> = sample
        .iter()
        .filter(|p| p.sand >= sand_below)
        .map(|p| p.rock)
        .collect();
    let rock_share = (bedrock_fraction / (1.0 - sand_fraction).max(1e-9)).min(1.0);
    let rock_above = quantile(&mut rock, 1.0 - rock_share).unwrap_or(f32::INFINITY);
    (sand_below, rock_above)
}

/// The value with a share `q` of `values` strictly below it (±∞ at the ends), or `None` for
/// an empty slice.
fn quantile(values: &mut [f32], q: f64) -> Option<f32> {
    if values.is_empty() {
        return None;
    }
    let k = (q * values.len() as f64).round() as usize;
    if k == 0 {
        return Some(f32::NEG_INFINITY);
    }
    if k >= values.len() {
        return Some(f32::INFINITY);
    }
    let (_, v, _) = values.select_nth_unstable_by(k, f32::total_cmp);
    Some(*v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_mean_matches_brute_force_at_edges_and_inside() {
        let (w, h) = (13, 7);
        let data: Vec<f32> = (0..w * h).map(|i| ((i * 37) % 11) as f32 - 3.5).collect();
        for r in [1, 2, 6, 20] {
            let fast = box_mean(&data, w, h, r);
            for row in 0..h {
                for col in 0..w {
                    let (mut sum, mut n) = (0.0f64, 0.0f64);
                    for rr in row.saturating_sub(r)..(row + r + 1).min(h) {
                        for cc in col.saturating_sub(r)..(col + r + 1).min(w) {
                            sum += f64::from(data[rr * w + cc]);
                            n += 1.0;
                        }
                    }
                    let slow = (sum / n) as f32;
                    assert!(
                        (fast[row * w + col] - slow).abs() < 1e-5,
                        "r={r} ({col}, {row})"
                    );
                }
            }
        }
    }

    #[test]
    fn quantile_ends_and_middle() {
        assert_eq!(quantile(&mut [], 0.5), None);
        let mut v = [5.0, 1.0, 4.0, 2.0, 3.0];
        assert_eq!(quantile(&mut v, 0.0), Some(f32::NEG_INFINITY));
        assert_eq!(quantile(&mut v, 1.0), Some(f32::INFINITY));
        assert_eq!(quantile(&mut v, 0.4), Some(3.0));
    }

    #[test]
    fn slopes_facing_the_sun_are_brighter() {
        // Sun from the west (azimuth 270°): a face rising to the east looks west, at the sun.
        let sun = sun_vector(270.0, 35.0);
        assert!((light(0.0, 0.0, sun) - 1.0).abs() < 1e-12);
        assert!(light(0.5, 0.0, sun) > 1.2);
        assert!(light(-0.5, 0.0, sun) < 0.8);
        assert!(
            (light(-10.0, 0.0, sun) - AMBIENT).abs() < 1e-12,
            "faces away get ambient only"
        );
        // North-south slopes are symmetric under a western sun.
        assert!((light(0.0, 0.3, sun) - light(0.0, -0.3, sun)).abs() < 1e-9);
    }

    #[test]
    fn heights_clamp_into_the_centimetre_range() {
        assert_eq!(clamp_height(-5.0), 0.0);
        assert_eq!(clamp_height(f64::NAN), 0.0);
        assert_eq!(clamp_height(1e6), 655.0);
        assert_eq!(clamp_height(123.25), 123.25);
    }

    #[test]
    fn sanitized_params_are_finite_and_in_range() {
        let p = TerrainSettings {
            relief_m: f64::NAN,
            crater_density_per_km2: -4.0,
            sun_elevation_deg: 120.0,
            bedrock_fraction: 7.0,
            geo: GeoTransform::new(f64::INFINITY, 0.0, 0.0),
            ..TerrainSettings::default()
        }
        .sanitized();
        assert_eq!(p.relief_m, 15.0);
        assert_eq!(p.crater_density_per_km2, 0.0);
        assert_eq!(p.sun_elevation_deg, 90.0);
        assert_eq!(p.bedrock_fraction, 1.0);
        assert_eq!(p.geo, GeoTransform::new(0.0, 0.0, 1.0));
    }
}
