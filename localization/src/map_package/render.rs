//! One render block of a map package: the orbital products of a block of the corridor, with
//! the sensor and DEM noise added by world pixel so that blocks join without seams.

use maps::package::{BlockRequest, RENDER_RESOLUTION_M};
use maps::{GeoTransform, MapLayers, Raster};

use crate::synthetic::{OrbitalSettings, SyntheticError, gaussian, render_orbital, truth_patch};

/// Side of a render block, metres: small enough that blocks follow the corridor closely, large
/// enough that the margin costs little ((128 + 2 × 24)² / 128² ≈ 1.9× the block area).
pub const BLOCK_M: usize = 128;
/// Terrain rendered around each block and cropped off, metres (see the module docs of
/// [`crate::map_package`]).
pub const MARGIN_M: usize = 24;

/// Seeds and orbital settings of one package: everything a block's pixels depend on besides
/// the map and the position.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RenderSettings {
    /// Seed of [`truth_patch`].
    pub truth_seed: u64,
    /// Seed of [`render_orbital`].
    pub orbital_seed: u64,
    /// Seed of the sensor noise, per world 25 cm pixel.
    pub sensor_noise_seed: u64,
    /// Seed of the DEM noise, per world 1 m cell.
    pub dem_noise_seed: u64,
    /// The orbital camera and DEM ([`OrbitalSettings::default`] with dust devil tracks off; its
    /// `noise_sigma_dn` and `dem_noise_sigma_m` are applied per world pixel, see the docs of
    /// [`crate::map_package`]).
    pub orbital: OrbitalSettings,
    /// Terrain rendered around each block and cropped, metres.
    pub margin_m: usize,
}

impl RenderSettings {
    /// The settings for the four seeds of a package (a scenario's: `study::map_package`), with
    /// the default orbital camera without dust devil tracks and a margin of [`MARGIN_M`].
    #[must_use]
    pub fn with_seeds(
        truth_seed: u64,
        orbital_seed: u64,
        sensor_noise_seed: u64,
        dem_noise_seed: u64,
    ) -> Self {
        Self {
            truth_seed,
            orbital_seed,
            sensor_noise_seed,
            dem_noise_seed,
            orbital: OrbitalSettings {
                dust_devil_tracks_per_ha: 0.0,
                ..OrbitalSettings::default()
            },
            margin_m: MARGIN_M,
        }
    }
}

/// Adds the sensor noise and the DEM noise of `s` to a rendered block, by world pixel index
/// (pixels counted from `lattice_origin_m`, the map DEM's north-west corner): the sensor noise
/// of σ `noise_sigma_dn` (linear DN) scaled by the local slope of the response
/// `255 × (v / 255)^gamma`, the DEM noise of σ `dem_noise_sigma_m`.
pub fn add_world_noise(
    appearance: &mut Raster<u8>,
    dem: &mut Raster<f32>,
    s: &RenderSettings,
    lattice_origin_m: [f64; 2],
) {
    let world = |geo: &GeoTransform| {
        let res = geo.resolution_m_per_px;
        (
            ((geo.origin_m[0] - lattice_origin_m[0]) / res).round() as i64,
            ((lattice_origin_m[1] - geo.origin_m[1]) / res).round() as i64,
        )
    };
    let p = &s.orbital;
    let (gx0, gy0) = world(&appearance.geo);
    let w = appearance.width;
    if p.noise_sigma_dn > 0.0 {
        // Output DN per linear DN at output level u: gamma × (u / 255)^((gamma − 1) / gamma).
        let slope: Vec<f64> = (0..=255u32)
            .map(|u| {
                let level = f64::from(u).max(0.5) / 255.0;
                p.gamma * level.powf((p.gamma - 1.0) / p.gamma)
            })
            .collect();
        for (i, v) in appearance.data.iter_mut().enumerate() {
            let (col, row) = ((i % w) as i64, (i / w) as i64);
            let g = gaussian(s.sensor_noise_seed, gx0 + col, gy0 + row);
            let noisy = f64::from(*v) + p.noise_sigma_dn * slope[usize::from(*v)] * g;
            *v = noisy.round().clamp(0.0, 255.0) as u8;
        }
    }
    let (dx0, dy0) = world(&dem.geo);
    let dw = dem.width;
    if p.dem_noise_sigma_m > 0.0 {
        for (i, h) in dem.data.iter_mut().enumerate() {
            let (col, row) = ((i % dw) as i64, (i / dw) as i64);
            let g = gaussian(s.dem_noise_seed, dx0 + col, dy0 + row);
            *h = (f64::from(*h) + p.dem_noise_sigma_m * g) as f32;
        }
    }
}

/// Renders one block: the 25 cm appearance and the 1 m DEM of the rectangle `req`, a pure
/// function of (`s`, map position) up to shadows longer than the margin.
///
/// The block is rendered inside a square patch of the block plus [`RenderSettings::margin_m`]
/// on every side. Near the map's edge the patch is shifted inwards to stay on the map (the
/// block stays inside it: the layout puts blocks on the map), and on a map smaller than the
/// patch it shrinks to the map, down to the block itself.
///
/// # Errors
/// A [`SyntheticError`] from the renderer, e.g. `PatchOutsideMap` for a block that does not fit
/// in a square patch on the map (a map narrower in one direction than the block is long in the
/// other), or `RegionOutsidePatch` if the block is not on its rendered patch.
pub fn render_block(
    layers: &MapLayers,
    req: &BlockRequest,
    s: &RenderSettings,
) -> Result<(Raster<u8>, Raster<f32>), SyntheticError> {
    let [bw, bh] = req.size_m;
    let lattice = layers.dem.geo.origin_m;
    let (x0, y0, x1, y1) = map_extent(layers);
    // Whole metres from the lattice origin (east, south), the map rounded inwards: the patch
    // grid is the package grid.
    let (west, east) = (
        (x0 - lattice[0] - 1e-9).ceil(),
        (x1 - lattice[0] + 1e-9).floor(),
    );
    let (north, south) = (
        (lattice[1] - y1 - 1e-9).ceil(),
        (lattice[1] - y0 + 1e-9).floor(),
    );
    let margin_m = s.margin_m as f64;
    let block_side_m = bw.max(bh) as f64;
    let side_m = (block_side_m + 2.0 * margin_m)
        .min(east - west)
        .min(south - north)
        .max(block_side_m);
    // North-west corner of the patch: the margin around the block, shifted inwards at the map
    // edge.
    let px = ((req.origin_m[0] - lattice[0]).round() - margin_m)
        .min(east - side_m)
        .max(west);
    let py = ((lattice[1] - req.origin_m[1]).round() - margin_m)
        .min(south - side_m)
        .max(north);
    let center = [
        lattice[0] + px + 0.5 * side_m,
        lattice[1] - py - 0.5 * side_m,
    ];
    let patch = truth_patch(layers, center, 0.5 * side_m, s.truth_seed)?;
    // The patch-indexed noises off: [`add_world_noise`] adds them by world pixel.
    let quiet = OrbitalSettings {
        noise_sigma_dn: 0.0,
        dem_noise_sigma_m: 0.0,
        ..s.orbital
    };
    let orbital = render_orbital(&patch, &quiet, s.orbital_seed)?;
    let k = (1.0 / RENDER_RESOLUTION_M).round() as usize;
    let pgeo = patch.height_m.geo;
    let c0 = (req.origin_m[0] - pgeo.origin_m[0]).round();
    let r0 = (pgeo.origin_m[1] - req.origin_m[1]).round();
    let outside = || {
        let [x, y] = req.origin_m;
        let (px0, py0, px1, py1) = patch.height_m.extent_m();
        SyntheticError::RegionOutsidePatch {
            region_extent_m: [x, y - bh as f64, x + bw as f64, y],
            patch_extent_m: [px0, py0, px1, py1],
        }
    };
    if !(c0 >= 0.0 && r0 >= 0.0) {
        return Err(outside());
    }
    let (c0, r0) = (c0 as usize, r0 as usize);
    let mut app = orbital
        .appearance
        .try_crop(c0 * k, r0 * k, bw * k, bh * k)
        .ok_or_else(outside)?;
    let mut dem = orbital.dem.try_crop(c0, r0, bw, bh).ok_or_else(outside)?;
    add_world_noise(&mut app, &mut dem, s, lattice);
    Ok((app, dem))
}

/// Where both the DEM and the terrain layer exist, `(x0, y0, x1, y1)` metres.
pub(super) fn map_extent(layers: &MapLayers) -> (f64, f64, f64, f64) {
    let (a0, b0, a1, b1) = layers.dem.extent_m();
    let (c0, d0, c1, d1) = layers.terrain.extent_m();
    (a0.max(c0), b0.max(d0), a1.min(c1), b1.min(d1))
}
