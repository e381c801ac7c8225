//! The truth terrain patch: a 0.25 m grid of heights and albedos around a point of a map.

use maps::{GeoTransform, MapLayers, Raster};
use rayon::prelude::*;

use super::bedforms::{RippleField, SandCoverField};
use super::ground_look::ClassLook;
use super::noise::{ValueFbm, floor_i64, gaussian, sub_seed};
use super::rocks::stamp_rocks;
use super::statics::PatchStatics;
use super::{ORBITAL_DEM_RESOLUTION_M_PER_PX, SyntheticError, TRUTH_RESOLUTION_M_PER_PX};

/// Truth pixels per orbital DEM block along each axis (1 m / 0.25 m).
const BLOCK_PX: usize = 4;
/// Wavelength of the fine height detail, metres.
const DETAIL_WAVELENGTH_M: f64 = 3.0;
/// Wavelength of the albedo texture, metres.
const TEXTURE_WAVELENGTH_M: f64 = 2.0;

const SALT_DETAIL: u64 = 1;
const SALT_TEXTURE: u64 = 2;
const SALT_GRAIN: u64 = 3;
const SALT_ROCKS: u64 = 4;
const SALT_COVER: u64 = 5;

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

/// Builds the truth patch around `center_m` from the map `layers`, deterministically.
///
/// The grid has [`TRUTH_RESOLUTION_M_PER_PX`] pixels and covers a square of side
/// `2 × half_size_m` rounded up to whole metres; its north-west corner is snapped to the 1 m
/// lattice of the map DEM's origin so that its 1 m blocks line up with 1 m map pixels.
/// Heights are the bilinear map DEM plus fine fBm detail (±3 cm on sand to ±20 cm on bedrock)
/// plus rocks (ellipsoidal domes 0.1–1.5 m across, 0.3–0.8 × their diameter high; about 0.4
/// per m² on bedrock, 0.08 on soil, 0.04 on coarse interdune lag, 0.004 on loose sand; one in
/// twenty is over 0.5 m across), plus on loose sand aeolian ripples (three trains 40° apart
/// with 2.4–3.7 m mean spacing, wavy, forking crests, 10 cm crest to trough; see
/// `RIPPLE_TRAINS`), weighted by the loose-sand share that [`TruthPatch::sand`] records.
/// The sand class is loose sand on the bedform bodies and armoured lag or bedrock in the
/// troughs between them (`sand_cover`).
/// Albedo follows the terrain class (loose sand 0.15 and smooth, lag 0.20, soil 0.22, bedrock
/// 0.29 and textured; rocks 0.19–0.27) with seeded texture; classes blend over one map pixel. The map's
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
    let (geo, n) = patch_grid(layers, center_m, half_size_m)?;
    Ok(truth_patch_on(layers, geo, n, seed, None, None))
}

/// The grid of [`truth_patch`]: its transform and its side, pixels.
///
/// # Errors
/// As [`truth_patch`].
pub(crate) fn patch_grid(
    layers: &MapLayers,
    center_m: [f64; 2],
    half_size_m: f64,
) -> Result<(GeoTransform, usize), SyntheticError> {
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
    Ok((GeoTransform::new(ox, oy, TRUTH_RESOLUTION_M_PER_PX), n))
}

/// The truth patch of [`truth_patch`] on its grid (`geo`, `n`: see [`patch_grid`]), with the
/// seed-independent fields taken from `statics` when given: the same values, computed once per
/// map (see [`super::statics`]).
///
/// `donor`, when given, is a patch of the same map and `seed` on the same pixel lattice (from
/// [`truth_patch`] or this function): every pixel is a pure function of (`seed`, map position),
/// and with lattice coordinates exact (the caller's guarantee, as for `statics`) the same bits,
/// so the pixels it covers are copied and only the rest is computed.
pub(crate) fn truth_patch_on(
    layers: &MapLayers,
    geo: GeoTransform,
    n: usize,
    seed: u64,
    statics: Option<&PatchStatics<'_>>,
    donor: Option<&TruthPatch>,
) -> TruthPatch {
    let statics = statics.filter(|s| s.n() == n);
    let overlap = donor.and_then(|d| Overlap::of(d, geo, n));
    let detail = ValueFbm::new(sub_seed(seed, SALT_DETAIL), DETAIL_WAVELENGTH_M, 4);
    let texture = ValueFbm::new(sub_seed(seed, SALT_TEXTURE), TEXTURE_WAVELENGTH_M, 3);
    let grain_seed = sub_seed(seed, SALT_GRAIN);
    let cover_seed = sub_seed(seed, SALT_COVER);
    let xs: Vec<f64> = (0..n).map(|col| geo.center_of(col, 0).0).collect();
    let mut height = vec![0.0f32; n * n];
    let mut albedo = vec![0.0f32; n * n];
    let mut sand = vec![0.0f32; n * n];
    height
        .par_chunks_mut(n)
        .zip(albedo.par_chunks_mut(n))
        .zip(sand.par_chunks_mut(n))
        .enumerate()
        .for_each_init(
            || {
                let rows = (vec![0.0; n], vec![0.0; n]);
                let static_rows = (vec![0.0f32; n], vec![0.0; n], vec![0.0; n]);
                let fields = (RippleField::new(), SandCoverField::new(cover_seed));
                (fields, rows, static_rows)
            },
            |((ripple, cover), (detail_row, texture_row), (ground_row, depth_row, ripple_row)),
             (row, ((h_row, a_row), s_row))| {
                // The columns the donor covers on this row, copied; the rest computed.
                let copied = match (&overlap, donor) {
                    (Some(o), Some(d)) if o.rows.contains(&row) => {
                        let cols = o.cols.clone();
                        // Donor pixel (row + dj, col + di), both inside the donor here.
                        let start = (row as isize + o.dj) as usize * d.height_m.width;
                        let (c0, c1) = (
                            (cols.start as isize + o.di) as usize,
                            (cols.end as isize + o.di) as usize,
                        );
                        let take = |dst: &mut [f32], data: &[f32]| {
                            dst[cols.clone()].copy_from_slice(&data[start + c0..start + c1]);
                        };
                        take(h_row, &d.height_m.data);
                        take(a_row, &d.albedo.data);
                        take(s_row, &d.sand.data);
                        cols
                    }
                    _ => 0..0,
                };
                let y = geo.center_of(0, row).1;
                if let Some(st) = statics {
                    st.truth_row(row, ground_row, depth_row, ripple_row);
                }
                for span in [0..copied.start, copied.end.max(copied.start)..n] {
                    if span.is_empty() {
                        continue;
                    }
                    detail.row(&xs[span.clone()], y, &mut detail_row[span.clone()]);
                    texture.row(&xs[span.clone()], y, &mut texture_row[span.clone()]);
                    for col in span {
                        let x = xs[col];
                        // Pixel centres lie inside the DEM (checked above); the fallback is never
                        // used.
                        let (ground, depth) = match statics {
                            Some(_) => (f64::from(ground_row[col]), Some(depth_row[col])),
                            None => {
                                let g = layers.dem.sample_bilinear(x, y).unwrap_or(0.0);
                                (f64::from(g), None)
                            }
                        };
                        let look = ClassLook::blended(layers, cover, x, y, ground, depth);
                        let ripples = if look.sand > 0.0 {
                            match statics {
                                Some(_) => look.sand * ripple_row[col],
                                None => {
                                    let weights = ripple.weights(x, y);
                                    look.sand * ripple.height_m(x, y, 0.0, &weights)
                                }
                            }
                        } else {
                            0.0
                        };
                        h_row[col] = (ground + look.detail_m * detail_row[col] + ripples) as f32;
                        s_row[col] = look.sand as f32;
                        // World pixel indices, so the grain does not depend on where the patch
                        // starts.
                        let (gx, gy) = (
                            floor_i64(x / TRUTH_RESOLUTION_M_PER_PX),
                            floor_i64(y / TRUTH_RESOLUTION_M_PER_PX),
                        );
                        let grain = 0.35 * gaussian(grain_seed, gx, gy).clamp(-3.0, 3.0);
                        let mottle = texture_row[col] + grain;
                        a_row[col] =
                            (look.albedo * (1.0 + look.texture * mottle)).clamp(0.02, 0.6) as f32;
                    }
                }
            },
        );

    // Rocks on the computed pixels only (the copied ones carry theirs).
    let rocks_seed = sub_seed(seed, SALT_ROCKS);
    let full = [0..n, 0..n];
    let rects = match &overlap {
        Some(o) => o.rest(n),
        None => vec![full],
    };
    for [rows, cols] in rects {
        stamp_rocks(
            rocks_seed,
            cover_seed,
            layers,
            geo,
            n,
            [rows, cols],
            &mut height,
            &mut albedo,
        );
    }

    TruthPatch {
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
    }
}

/// Where a donor patch covers a new patch grid: the new grid's rows and columns it covers, and
/// the donor's pixel offset (`donor (row + dj, col + di)` is the new `(row, col)`).
#[derive(Clone, Debug, PartialEq)]
struct Overlap {
    rows: std::ops::Range<usize>,
    cols: std::ops::Range<usize>,
    di: isize,
    dj: isize,
}

impl Overlap {
    /// The overlap of `donor` with the `n × n` grid `geo`, or `None` if it is not on the same
    /// pixel lattice (an exact whole number of pixels away) or covers nothing.
    fn of(donor: &TruthPatch, geo: GeoTransform, n: usize) -> Option<Self> {
        let dg = donor.height_m.geo;
        let res = geo.resolution_m_per_px;
        if dg.resolution_m_per_px.to_bits() != res.to_bits() {
            return None;
        }
        let (fi, fj) = (
            (geo.origin_m[0] - dg.origin_m[0]) / res,
            (dg.origin_m[1] - geo.origin_m[1]) / res,
        );
        if !(fi.fract() == 0.0 && fj.fract() == 0.0 && fi.abs() < 1e9 && fj.abs() < 1e9) {
            return None;
        }
        let (di, dj) = (fi as isize, fj as isize);
        let (dw, dh) = (
            donor.height_m.width as isize,
            donor.height_m.height as isize,
        );
        let span = |d: isize, len: isize| {
            let lo = (-d).clamp(0, n as isize) as usize;
            let hi = (len - d).clamp(0, n as isize) as usize;
            lo..hi.max(lo)
        };
        let (rows, cols) = (span(dj, dh), span(di, dw));
        (!rows.is_empty() && !cols.is_empty()).then_some(Self { rows, cols, di, dj })
    }

    /// The rectangles `[rows, cols]` of the `n × n` grid outside the overlap.
    fn rest(&self, n: usize) -> Vec<[std::ops::Range<usize>; 2]> {
        let mut out = Vec::new();
        for cols in [0..self.cols.start, self.cols.end..n] {
            if !cols.is_empty() {
                out.push([0..n, cols]);
            }
        }
        for rows in [0..self.rows.start, self.rows.end..n] {
            if !rows.is_empty() {
                out.push([rows, self.cols.clone()]);
            }
        }
        out
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    use super::super::bedforms::SandCoverField;
    use super::super::rocks::{ROCK_CELL_M, rocks_in_cell};

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
        let mut cover = SandCoverField::new(8);
        for iy in 5..45 {
            for ix in 5..45 {
                rocks_in_cell(7, &mut cover, ix, iy, l, &mut rocks);
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
        // Flat sand (no bedform troughs): almost all loose sand (0.004 per m²), a few patches
        // of lag; the troughs' armour is tested below.
        assert!(
            sand < 0.02 && (0.06..0.10).contains(&soil) && (0.33..0.47).contains(&rock),
            "{sand} {soil} {rock}"
        );
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
