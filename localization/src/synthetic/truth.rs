//! The truth terrain patch: a 0.25 m grid of heights and albedos around a point of a map.

use maps::{GeoTransform, MapLayers, Raster, TerrainClass};
use rayon::prelude::*;

use super::noise::{SplitMix, ValueFbm, floor_i64, gaussian, hash2, sub_seed};
use super::{ORBITAL_DEM_RESOLUTION_M_PER_PX, SyntheticError, TRUTH_RESOLUTION_M_PER_PX};

/// Truth pixels per orbital DEM block along each axis (1 m / 0.25 m).
const BLOCK_PX: usize = 4;
/// Side of the square cells rocks are drawn in, metres. Rocks are a pure function of
/// (seed, cell), so two overlapping patches share their rocks.
const ROCK_CELL_M: f64 = 2.0;
/// Rock diameters, metres: a truncated power law N(>D) ∝ D^(−ROCK_SIZE_EXPONENT).
const ROCK_DIAMETER_M: (f64, f64) = (0.1, 1.5);
/// Exponent of the cumulative rock size–frequency law (more small rocks than large).
const ROCK_SIZE_EXPONENT: f64 = 1.8;
/// Rock height as a fraction of its diameter.
const ROCK_HEIGHT_RATIO: (f64, f64) = (0.3, 0.8);
/// Rock albedo (a little darker than bedrock, brighter than sand).
const ROCK_ALBEDO: (f64, f64) = (0.19, 0.27);
/// Wavelength of the fine height detail, metres.
const DETAIL_WAVELENGTH_M: f64 = 3.0;
/// Wavelength of the albedo texture, metres.
const TEXTURE_WAVELENGTH_M: f64 = 2.0;

/// Crest-to-crest spacing of the aeolian ripples on sand, metres. Large (decimetre-high)
/// ripples on Martian sand have 1–5 m spacing (Lapotre et al., Science 353, 2016); 3 m is a
/// judgement in that range.
pub(super) const RIPPLE_WAVELENGTH_M: f64 = 3.0;
/// Half the crest-to-trough height of the ripples, metres (judgement: 10 cm crest to trough).
pub(super) const RIPPLE_AMPLITUDE_M: f64 = 0.05;
/// Direction the ripple crests run, degrees clockwise from north. One regional wind sets every
/// ripple's orientation (judgement: the value is arbitrary, the uniformity is the physics).
pub(super) const RIPPLE_CREST_AZIMUTH_DEG: f64 = 20.0;

/// Height of the ripple field (before the sand weight) at map point `(x, y)` after the ripples
/// migrated `migration_m` downwind (perpendicular to the crests), metres.
#[inline]
pub(super) fn ripple_height_m(x: f64, y: f64, migration_m: f64) -> f64 {
    // Unit vector across the crests: the crest direction turned 90° clockwise.
    let across = (RIPPLE_CREST_AZIMUTH_DEG + 90.0).to_radians();
    let s = x * across.sin() + y * across.cos() - migration_m;
    RIPPLE_AMPLITUDE_M * (std::f64::consts::TAU * s / RIPPLE_WAVELENGTH_M).sin()
}

const SALT_DETAIL: u64 = 1;
const SALT_TEXTURE: u64 = 2;
const SALT_GRAIN: u64 = 3;
const SALT_ROCKS: u64 = 4;

/// The true terrain around a point: what the orbital and rover renderers image.
///
/// All rasters share one 0.25 m grid ([`TRUTH_RESOLUTION_M_PER_PX`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TruthPatch {
    /// Surface height, metres (map DEM + fine detail + sand ripples + rocks).
    pub height_m: Raster<f32>,
    /// Lambertian albedo, 0..1 (dimensionless).
    pub albedo: Raster<f32>,
    /// Share of loose sand at each pixel, 0..1 (the sand class blended across class borders):
    /// where the ripples are, and where they move between the orbital and the rover epoch.
    pub sand: Raster<f32>,
}

impl TruthPatch {
    /// A hand-built patch with no sand (so nothing moves between epochs).
    #[must_use]
    pub fn from_rasters(height_m: Raster<f32>, albedo: Raster<f32>) -> Self {
        let sand = Raster {
            width: height_m.width,
            height: height_m.height,
            geo: height_m.geo,
            data: vec![0.0; height_m.data.len()],
        };
        Self {
            height_m,
            albedo,
            sand,
        }
    }

    /// Checks a (possibly hand-built) patch before rendering: both rasters the same size with
    /// width × height samples, and a positive finite pixel size.
    pub(super) fn check(&self) -> Result<(), SyntheticError> {
        let (h, a) = (&self.height_m, &self.albedo);
        if h.width != a.width
            || h.height != a.height
            || h.data.len() != h.width * h.height
            || a.data.len() != a.width * a.height
        {
            return Err(SyntheticError::MalformedPatch {
                height_px: [h.width, h.height],
                height_samples: h.data.len(),
                albedo_px: [a.width, a.height],
                albedo_samples: a.data.len(),
            });
        }
        let sd = &self.sand;
        if sd.width != h.width || sd.height != h.height || sd.data.len() != h.data.len() {
            return Err(SyntheticError::InvalidParameter {
                field: "patch.sand",
                value: sd.data.len() as f64,
                expected: "as many sand samples as height samples, on the same grid",
            });
        }
        let res = h.geo.resolution_m_per_px;
        if !(res.is_finite() && res > 0.0) {
            return Err(SyntheticError::InvalidParameter {
                field: "patch.height_m.geo.resolution_m_per_px",
                value: res,
                expected: "a positive finite pixel size in metres",
            });
        }
        Ok(())
    }
}

/// Surface properties of one terrain class.
#[derive(Clone, Copy, Debug, Default)]
struct ClassLook {
    /// Mean albedo.
    albedo: f64,
    /// Relative albedo texture amplitude.
    texture: f64,
    /// Amplitude of the fine height detail, metres.
    detail_m: f64,
    /// Rocks per square metre.
    rocks_per_m2: f64,
    /// Share of loose sand (1 on the sand class, 0 elsewhere).
    sand: f64,
}

impl ClassLook {
    /// Sand is dark and smooth, bedrock bright, textured and rocky; no-data reads as soil.
    fn of_code(code: u8) -> Self {
        match TerrainClass::from_code(code) {
            Some(TerrainClass::Sand) => Self {
                albedo: 0.15,
                texture: 0.04,
                detail_m: 0.03,
                rocks_per_m2: 0.004,
                sand: 1.0,
            },
            Some(TerrainClass::Bedrock) => Self {
                albedo: 0.29,
                texture: 0.16,
                detail_m: 0.20,
                rocks_per_m2: 0.4,
                sand: 0.0,
            },
            Some(TerrainClass::Soil) | None => Self {
                albedo: 0.22,
                texture: 0.09,
                detail_m: 0.08,
                rocks_per_m2: 0.08,
                sand: 0.0,
            },
        }
    }

    fn add_scaled(&mut self, o: Self, k: f64) {
        self.albedo += k * o.albedo;
        self.texture += k * o.texture;
        self.detail_m += k * o.detail_m;
        self.sand += k * o.sand;
    }

    /// The look at map point `(x, y)`: classes blended bilinearly between terrain pixel centres,
    /// so class borders are not staircases of map pixels.
    fn blended(terrain: &Raster<u8>, x: f64, y: f64) -> Self {
        let (c, r) = terrain.geo.pixel_of(x, y);
        let (w, h) = (terrain.width, terrain.height);
        let c = (c - 0.5).clamp(0.0, (w - 1) as f64);
        let r = (r - 0.5).clamp(0.0, (h - 1) as f64);
        let (c0, r0) = (c as usize, r as usize);
        let (c1, r1) = ((c0 + 1).min(w - 1), (r0 + 1).min(h - 1));
        let (tx, ty) = (c - c0 as f64, r - r0 as f64);
        let mut look = Self::default();
        for (cc, rr, k) in [
            (c0, r0, (1.0 - tx) * (1.0 - ty)),
            (c1, r0, tx * (1.0 - ty)),
            (c0, r1, (1.0 - tx) * ty),
            (c1, r1, tx * ty),
        ] {
            look.add_scaled(Self::of_code(terrain.data[rr * w + cc]), k);
        }
        look
    }
}

/// One rock: an ellipsoidal dome sitting on the ground.
#[derive(Clone, Copy, Debug)]
struct Rock {
    center_m: [f64; 2],
    /// Semi-axes, metres.
    semi_axes_m: [f64; 2],
    /// Orientation of the first axis, radians counter-clockwise from east.
    angle_rad: f64,
    height_m: f64,
    albedo: f64,
}

/// The rocks whose centres fall in world cell `(ix, iy)`: a Poisson number at the densest
/// class's rate, thinned by the density of the class under each rock.
fn rocks_in_cell(seed: u64, ix: i64, iy: i64, terrain: &Raster<u8>, out: &mut Vec<Rock>) {
    let max_density = ClassLook::of_code(TerrainClass::Bedrock.code()).rocks_per_m2;
    let lambda = max_density * ROCK_CELL_M * ROCK_CELL_M;
    let mut rng = SplitMix(hash2(seed, ix, iy));
    // Poisson by multiplying uniforms (Knuth); λ is under 2.
    let limit = (-lambda).exp();
    let mut n = 0;
    let mut prod = rng.next_f64();
    while prod > limit && n < 32 {
        n += 1;
        prod *= rng.next_f64();
    }
    let (d_min, d_max) = ROCK_DIAMETER_M;
    let (a_min, a_max) = (
        d_min.powf(-ROCK_SIZE_EXPONENT),
        d_max.powf(-ROCK_SIZE_EXPONENT),
    );
    for _ in 0..n {
        let x = (ix as f64 + rng.next_f64()) * ROCK_CELL_M;
        let y = (iy as f64 + rng.next_f64()) * ROCK_CELL_M;
        let keep = rng.next_f64();
        let u = rng.next_f64();
        let diameter = (a_min - u * (a_min - a_max)).powf(-1.0 / ROCK_SIZE_EXPONENT);
        let aspect = rng.range(0.6, 1.0);
        let angle_rad = rng.range(0.0, std::f64::consts::PI);
        let height_m = diameter * rng.range(ROCK_HEIGHT_RATIO.0, ROCK_HEIGHT_RATIO.1);
        let albedo = rng.range(ROCK_ALBEDO.0, ROCK_ALBEDO.1);
        let density = terrain
            .sample_nearest(x, y)
            .map_or(0.0, |code| ClassLook::of_code(code).rocks_per_m2);
        if keep * max_density < density {
            out.push(Rock {
                center_m: [x, y],
                semi_axes_m: [0.5 * diameter, 0.5 * diameter * aspect],
                angle_rad,
                height_m,
                albedo,
            });
        }
    }
}

/// Builds the truth patch around `center_m` from the map `layers`, deterministically.
///
/// The grid has [`TRUTH_RESOLUTION_M_PER_PX`] pixels and covers a square of side
/// `2 × half_size_m` rounded up to whole metres; its north-west corner is snapped to the 1 m
/// lattice of the map DEM's origin so that its 1 m blocks line up with 1 m map pixels.
/// Heights are the bilinear map DEM plus fine fBm detail (±3 cm on sand to ±20 cm on bedrock)
/// plus rocks (ellipsoidal domes 0.1–1.5 m across, 0.3–0.8 × their diameter high; about 0.4
/// per m² on bedrock, 0.08 on soil, 0.004 on sand; one in twenty is over 0.5 m across), plus
/// on sand aeolian ripples (3 m crest spacing, 10 cm crest to trough, crests all running 20°
/// east of north), weighted by the blended sand share that [`TruthPatch::sand`] records.
/// Albedo follows the terrain class (sand 0.15 and smooth, soil 0.22, bedrock 0.29 and
/// textured; rocks 0.19–0.27) with seeded texture; classes blend over one map pixel. The map's
/// appearance layer is not used: [`render_orbital`](super::render_orbital) makes its own.
/// Every value is a pure function of (`seed`, map position), so overlapping patches agree where
/// they overlap and the thread count does not matter.
///
/// # Errors
/// [`SyntheticError::InvalidParameter`] for a non-finite centre or a `half_size_m` that is not
/// a positive finite number; [`SyntheticError::PatchOutsideMap`] if the square leaves the DEM or
/// the terrain layer of the map.
pub fn truth_patch(
    layers: &MapLayers,
    center_m: [f64; 2],
    half_size_m: f64,
    seed: u64,
) -> Result<TruthPatch, SyntheticError> {
    for (field, value) in [("center_m[0]", center_m[0]), ("center_m[1]", center_m[1])] {
        if !value.is_finite() {
            return Err(SyntheticError::InvalidParameter {
                field,
                value,
                expected: "a finite map coordinate",
            });
        }
    }
    if !(half_size_m.is_finite() && half_size_m > 0.0) {
        return Err(SyntheticError::InvalidParameter {
            field: "half_size_m",
            value: half_size_m,
            expected: "a positive finite number of metres",
        });
    }
    let block_m = ORBITAL_DEM_RESOLUTION_M_PER_PX;
    let blocks = ((2.0 * half_size_m / block_m) - 1e-9).ceil().max(1.0);
    let side_m = blocks * block_m;
    let [dem_ox, dem_oy] = layers.dem.geo.origin_m;
    let ox = dem_ox + ((center_m[0] - 0.5 * side_m - dem_ox) / block_m).round() * block_m;
    let oy = dem_oy + ((center_m[1] + 0.5 * side_m - dem_oy) / block_m).round() * block_m;
    let patch_extent_m = [ox, oy - side_m, ox + side_m, oy];
    for (layer, raster_extent) in [
        ("dem", layers.dem.extent_m()),
        ("terrain", layers.terrain.extent_m()),
    ] {
        let (x0, y0, x1, y1) = raster_extent;
        let tol = 1e-9 * (1.0 + x0.abs().max(y1.abs()));
        if patch_extent_m[0] < x0 - tol
            || patch_extent_m[1] < y0 - tol
            || patch_extent_m[2] > x1 + tol
            || patch_extent_m[3] > y1 + tol
        {
            return Err(SyntheticError::PatchOutsideMap {
                layer,
                patch_extent_m,
                map_extent_m: [x0, y0, x1, y1],
            });
        }
    }

    let n = blocks as usize * BLOCK_PX;
    let geo = GeoTransform::new(ox, oy, TRUTH_RESOLUTION_M_PER_PX);
    let detail = ValueFbm::new(sub_seed(seed, SALT_DETAIL), DETAIL_WAVELENGTH_M, 4);
    let texture = ValueFbm::new(sub_seed(seed, SALT_TEXTURE), TEXTURE_WAVELENGTH_M, 3);
    let grain_seed = sub_seed(seed, SALT_GRAIN);
    let xs: Vec<f64> = (0..n).map(|col| geo.center_of(col, 0).0).collect();
    let mut height = vec![0.0f32; n * n];
    let mut albedo = vec![0.0f32; n * n];
    let mut sand = vec![0.0f32; n * n];
    height
        .par_chunks_mut(n)
        .zip(albedo.par_chunks_mut(n))
        .zip(sand.par_chunks_mut(n))
        .enumerate()
        .for_each(|(row, ((h_row, a_row), s_row))| {
            let y = geo.center_of(0, row).1;
            let (mut detail_row, mut texture_row) = (vec![0.0; n], vec![0.0; n]);
            detail.row(&xs, y, &mut detail_row);
            texture.row(&xs, y, &mut texture_row);
            for (col, ((h, a), sd)) in h_row
                .iter_mut()
                .zip(a_row.iter_mut())
                .zip(s_row.iter_mut())
                .enumerate()
            {
                let x = xs[col];
                let look = ClassLook::blended(&layers.terrain, x, y);
                // Pixel centres lie inside the DEM (checked above); the fallback is never used.
                let ground = f64::from(layers.dem.sample_bilinear(x, y).unwrap_or(0.0));
                let ripples = if look.sand > 0.0 {
                    look.sand * ripple_height_m(x, y, 0.0)
                } else {
                    0.0
                };
                *h = (ground + look.detail_m * detail_row[col] + ripples) as f32;
                *sd = look.sand as f32;
                // World pixel indices, so the grain does not depend on where the patch starts.
                let (gx, gy) = (
                    floor_i64(x / TRUTH_RESOLUTION_M_PER_PX),
                    floor_i64(y / TRUTH_RESOLUTION_M_PER_PX),
                );
                let grain = 0.35 * gaussian(grain_seed, gx, gy).clamp(-3.0, 3.0);
                let mottle = texture_row[col] + grain;
                *a = (look.albedo * (1.0 + look.texture * mottle)).clamp(0.02, 0.6) as f32;
            }
        });

    stamp_rocks(
        sub_seed(seed, SALT_ROCKS),
        &layers.terrain,
        geo,
        n,
        &mut height,
        &mut albedo,
    );

    Ok(TruthPatch {
        height_m: Raster {
            width: n,
            height: n,
            geo,
            data: height,
        },
        albedo: Raster {
            width: n,
            height: n,
            geo,
            data: albedo,
        },
        sand: Raster {
            width: n,
            height: n,
            geo,
            data: sand,
        },
    })
}

/// Adds the rocks of every cell that can reach the `n × n` grid at `geo`. Where rocks overlap
/// the tallest wins, so the result does not depend on the order they are stamped in.
fn stamp_rocks(
    seed: u64,
    terrain: &Raster<u8>,
    geo: GeoTransform,
    n: usize,
    height: &mut [f32],
    albedo: &mut [f32],
) {
    let res = geo.resolution_m_per_px;
    let [ox, oy] = geo.origin_m;
    let side_m = n as f64 * res;
    let reach_m = 0.5 * ROCK_DIAMETER_M.1;
    let cell = |v: f64| floor_i64(v / ROCK_CELL_M);
    let (ix0, ix1) = (cell(ox - reach_m), cell(ox + side_m + reach_m));
    let (iy0, iy1) = (cell(oy - side_m - reach_m), cell(oy + reach_m));
    let mut rocks = Vec::new();
    for iy in iy0..=iy1 {
        for ix in ix0..=ix1 {
            rocks_in_cell(seed, ix, iy, terrain, &mut rocks);
        }
    }
    let mut rock_h = vec![0.0f32; n * n];
    let mut rock_albedo = vec![0.0f32; n * n];
    for rock in &rocks {
        let [rx, ry] = rock.center_m;
        let a = rock.semi_axes_m[0];
        let px = |v: f64| v.floor().clamp(0.0, n as f64) as usize;
        let (c0, c1) = (px((rx - a - ox) / res), px((rx + a - ox) / res + 1.0));
        let (r0, r1) = (px((oy - ry - a) / res), px((oy - ry + a) / res + 1.0));
        let (cos, sin) = (rock.angle_rad.cos(), rock.angle_rad.sin());
        for row in r0..r1 {
            for col in c0..c1 {
                let (x, y) = geo.center_of(col, row);
                let (dx, dy) = (x - rx, y - ry);
                let u = (dx * cos + dy * sin) / rock.semi_axes_m[0];
                let v = (-dx * sin + dy * cos) / rock.semi_axes_m[1];
                let q = 1.0 - u * u - v * v;
                if q <= 0.0 {
                    continue;
                }
                let z = (rock.height_m * q.sqrt()) as f32;
                let i = row * n + col;
                if z > rock_h[i] || (z == rock_h[i] && (rock.albedo as f32) > rock_albedo[i]) {
                    rock_h[i] = z;
                    rock_albedo[i] = rock.albedo as f32;
                }
            }
        }
    }
    for i in 0..n * n {
        if rock_h[i] > 0.0 {
            height[i] += rock_h[i];
            // Keep a little of the ground's texture on the rock surface.
            albedo[i] = 0.85 * rock_albedo[i] + 0.15 * albedo[i];
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn layers(code: u8) -> MapLayers {
        let geo = GeoTransform::new(0.0, 100.0, 1.0);
        MapLayers {
            appearance: Raster::filled(100, 100, geo, 0),
            dem: Raster::filled(100, 100, geo, 10.0),
            terrain: Raster::filled(100, 100, geo, code),
        }
    }

    fn rocks_per_m2(l: &MapLayers) -> f64 {
        let mut rocks = Vec::new();
        for iy in 5..45 {
            for ix in 5..45 {
                rocks_in_cell(7, ix, iy, &l.terrain, &mut rocks);
            }
        }
        rocks.len() as f64 / (40.0 * 40.0 * ROCK_CELL_M * ROCK_CELL_M)
    }

    #[test]
    fn rock_cover_follows_the_terrain_class() {
        let (sand, soil, rock) = (
            rocks_per_m2(&layers(1)),
            rocks_per_m2(&layers(2)),
            rocks_per_m2(&layers(3)),
        );
        assert!(sand < 0.01 && (0.06..0.10).contains(&soil) && (0.33..0.47).contains(&rock));
        let sand = truth_patch(&layers(1), [50.0, 50.0], 20.0, 3).unwrap();
        let rock = truth_patch(&layers(3), [50.0, 50.0], 20.0, 3).unwrap();
        let mean = |p: &TruthPatch| p.albedo.data.iter().sum::<f32>() / p.albedo.data.len() as f32;
        assert!(mean(&sand) < mean(&rock));
    }

    #[test]
    fn overlapping_patches_agree() {
        let l = layers(3);
        let a = truth_patch(&l, [40.0, 40.0], 10.0, 9).unwrap();
        let b = truth_patch(&l, [45.0, 37.0], 10.0, 9).unwrap();
        // Pixel (0, 0) of b lies inside a at an integer offset (grids share the 1 m lattice).
        let (dc, dr) = (
            ((b.height_m.geo.origin_m[0] - a.height_m.geo.origin_m[0]) / 0.25).round() as usize,
            ((a.height_m.geo.origin_m[1] - b.height_m.geo.origin_m[1]) / 0.25).round() as usize,
        );
        for (r, c) in [(0, 0), (5, 7), (30, 12)] {
            assert_eq!(
                b.height_m.get(c, r).to_bits(),
                a.height_m.get(c + dc, r + dr).to_bits()
            );
            assert_eq!(
                b.albedo.get(c, r).to_bits(),
                a.albedo.get(c + dc, r + dr).to_bits()
            );
        }
    }

    #[test]
    fn bad_sizes_and_off_map_patches_are_errors() {
        let l = layers(2);
        assert!(matches!(
            truth_patch(&l, [50.0, 50.0], 0.0, 1),
            Err(SyntheticError::InvalidParameter { .. })
        ));
        assert!(matches!(
            truth_patch(&l, [f64::NAN, 50.0], 5.0, 1),
            Err(SyntheticError::InvalidParameter { .. })
        ));
        assert!(matches!(
            truth_patch(&l, [95.0, 50.0], 10.0, 1),
            Err(SyntheticError::PatchOutsideMap { .. })
        ));
        let p = truth_patch(&l, [50.0, 50.0], 50.0, 1).unwrap();
        assert_eq!(p.height_m.width, 400);
    }
}
