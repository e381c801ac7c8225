//! Synthetic imagery for onboard global localization: a seeded truth terrain, the orbital map
//! made from it, and the rover's post-drive orthomosaic of it (paper 000 §4-§5).
//!
//! The matcher needs pairs of images that differ the way a HiRISE map and a NavCam panorama
//! differ, with the rover's true position known. Three steps make them:
//!
//! 1. [`truth_patch`] — a 0.25 m [`TruthPatch`] of heights and albedos around a map point: the
//!    map DEM, fine fBm detail, and rocks whose density follows the terrain class (bedrock
//!    rocky, soil some, loose sand almost none but the coarse lag of dune troughs some); three
//!    wavy, forking ripple trains on sand; albedo by class with seeded texture.
//! 2. [`render_orbital`] — the HiRISE stand-in ([`OrbitalProducts`]): Lambertian shading under
//!    a mid-afternoon sun with cast shadows, a Gaussian PSF, noise and a gamma, quantised to a
//!    25 cm u8 image; and a 1 m DEM, the block mean of the truth.
//! 3. [`render_rover`] — the post-drive NavCam orthomosaic ([`RoverObservation`]): 3–5 stereo
//!    wedges of 96° from a 2 m mast, a 30 m range limit, the rover body masked, occlusion by
//!    line of sight over the truth heights, stereo errors growing with range², a different
//!    (late-afternoon) sun than orbit, a different monotonic response per wedge, sensor noise;
//!    and a 1 m rover DEM where enough samples were seen.
//!
//! Many runs on one map share [`TerrainStatics`]: the seed-independent parts of the truth (map
//! DEM height, interdune depth, the ripples at both epochs), built once per 16 m tile, which
//! [`crate::onboard::run_onboard_with`] takes (through [`crate::onboard::OnboardCache`]) instead
//! of recomputing them (the same bits).
//!
//! ## Error sources (why census does not localize these scenes to millimetres)
//!
//! Rendering the map and the mosaic from one truth with perfect geometry localizes to ~5 mm;
//! real data gives 0.36 m mean (paper 000 §4). Each real error source is a field of the
//! settings structs, with unit, default and source (or "judgement") in its documentation:
//!
//! - orbital effective resolution: [`OrbitalSettings::blur_sigma_px`] (σ 1 px, HiRISE MTF);
//! - a different orbital epoch: smooth albedo change ([`OrbitalSettings::albedo_change_sigma`]),
//!   dust devil tracks in the orbital image only (`dust_devil_tracks_*`), and sand ripples
//!   (part of the truth on sand) migrated between epochs
//!   ([`OrbitalSettings::ripple_migration_m`]);
//! - orthorectification / co-registration error: a smooth displacement field of the orbital
//!   image ([`OrbitalSettings::ortho_displacement_sigma_m`], `_wavelength_m`);
//! - rover side: heading error ([`RoverImagingSettings::heading_sigma_deg`]), scale error
//!   ([`RoverImagingSettings::scale_sigma`]), the mosaic centre off the rover's true position
//!   ([`RoverImagingSettings::mosaic_offset_sigma_m`]), recorded in
//!   [`RoverObservation::geometry_errors`]; stereo range and height noise, dropouts and
//!   per-wedge responses as before.
//!
//! Each can be switched off (set to 0) for ablations; see [`crate::benchmark_set`].
//!
//! Settings are plain structs ([`OrbitalSettings`], [`RoverImagingSettings`]); bad input is a
//! [`SyntheticError`]. Every pixel is a pure function of (seed, position) through hash-based
//! noise, and the few per-observation draws (sun, wedge responses) come from one
//! `ChaCha8Rng`, so a seed gives byte-identical images on any number of threads.
//!
//! ```
//! use localization::synthetic::{
//!     OrbitalSettings, RoverImagingSettings, render_orbital, render_rover, truth_patch,
//! };
//! use maps::{GeoTransform, MapLayers, Raster};
//!
//! // A flat 200 m soil map of 1 m pixels.
//! let geo = GeoTransform::new(0.0, 200.0, 1.0);
//! let layers = MapLayers {
//!     appearance: Raster::filled(200, 200, geo, 0),
//!     dem: Raster::filled(200, 200, geo, 100.0),
//!     terrain: Raster::filled(200, 200, geo, 2),
//! };
//! let patch = truth_patch(&layers, [100.0, 100.0], 40.0, 7)?;
//! let orbital = render_orbital(&patch, &OrbitalSettings::default(), 8)?;
//! let rover = render_rover(&patch, [100.3, 99.6], &RoverImagingSettings::default(), 9)?;
//! assert_eq!((orbital.appearance.width, orbital.dem.width), (320, 80));
//! assert_eq!((rover.ortho.width, rover.dem.width), (240, 60));
//! assert!(rover.valid_fraction() > 0.3);
//! # Ok::<(), localization::synthetic::SyntheticError>(())
//! ```
//!
//! ## References
//! - Paper 000 §4 (post-drive NavCam panoramas of 3–5 stereo wedges with a 96° field of view;
//!   orbital images acquired mid-afternoon; robustness to lighting differences) and §5 (the
//!   rover stereo orthomosaic gridded at 25 cm with a 1 m DEM, occlusions by rocks and the
//!   rover body, different camera responses between wedges — Fig. 13 —, the HiRISE 25 cm
//!   orthoimage and 1 m DTM).
//! - M. P. Golombek and D. Rapp, "Size-frequency distributions of rocks on Mars and Earth
//!   analog sites", J. Geophys. Res. 102, 1997 (rock populations by terrain).

mod bedforms;
mod ground_look;
mod image_ops;
mod noise;
mod orbital;
mod rocks;
mod rover;
mod rover_settings;
mod shading;
mod statics;
mod truth;

// The map package adds its sensor and DEM noise by world pixel with the same draws.
pub(crate) use noise::gaussian;
pub(crate) use orbital::render_orbital_with;
pub use orbital::{OrbitalProducts, OrbitalSettings, render_orbital};
pub use rover::{
    RoverGeometryErrors, RoverLighting, RoverObservation, WedgeResponse, render_rover,
};
pub use rover_settings::RoverImagingSettings;
pub use statics::TerrainStatics;
pub use truth::{TruthPatch, truth_patch};
pub(crate) use truth::{patch_grid, truth_patch_on};

/// Pixel size of the truth patch and of the orbital appearance image, metres (HiRISE, 25 cm).
pub const TRUTH_RESOLUTION_M_PER_PX: f64 = 0.25;
/// Pixel size of the orbital DEM, metres (the HiRISE DTM, 1 m).
pub const ORBITAL_DEM_RESOLUTION_M_PER_PX: f64 = 1.0;
/// Width and height of the rover orthomosaic, pixels (60 m at 25 cm).
pub const ORTHO_SIZE_PX: usize = 240;
/// Pixel size of the rover orthomosaic, metres.
pub const ORTHO_RESOLUTION_M_PER_PX: f64 = 0.25;
/// Ortho pixels per rover DEM cell along each axis (1 m cells).
pub const ROVER_DEM_BLOCK_PX: usize = 4;

/// Why synthetic imagery could not be made (bad input, not a bad outcome).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SyntheticError {
    /// The requested truth patch is not entirely on the map.
    #[error(
        "patch {patch_extent_m:?} leaves the map's {layer} layer {map_extent_m:?} (x0, y0, x1, y1 in m)"
    )]
    PatchOutsideMap {
        /// The map layer it leaves: `"dem"` or `"terrain"`.
        layer: &'static str,
        /// Patch extent `[min_x, min_y, max_x, max_y]`, metres.
        patch_extent_m: [f64; 4],
        /// That layer's extent `[min_x, min_y, max_x, max_y]`, metres.
        map_extent_m: [f64; 4],
    },
    /// The rover position is not on the truth patch.
    #[error(
        "rover at {rover_m:?} m is off the truth patch {patch_extent_m:?} (x0, y0, x1, y1 in m)"
    )]
    RoverOutsidePatch {
        /// Requested rover position (x east, y north), metres.
        rover_m: [f64; 2],
        /// Patch extent `[min_x, min_y, max_x, max_y]`, metres.
        patch_extent_m: [f64; 4],
    },
    /// A region to take from a rendered patch (a block of a map package) is not entirely on
    /// the patch.
    #[error(
        "region {region_extent_m:?} is not entirely on the rendered patch {patch_extent_m:?} (x0, y0, x1, y1 in m)"
    )]
    RegionOutsidePatch {
        /// Region extent `[min_x, min_y, max_x, max_y]`, metres.
        region_extent_m: [f64; 4],
        /// Patch extent `[min_x, min_y, max_x, max_y]`, metres.
        patch_extent_m: [f64; 4],
    },
    /// A hand-built truth patch whose rasters disagree: different sizes, or a sample count
    /// that is not width × height.
    #[error(
        "malformed truth patch: height {height_px:?} px with {height_samples} samples, albedo {albedo_px:?} px with {albedo_samples} samples"
    )]
    MalformedPatch {
        /// Width and height of the height raster, pixels.
        height_px: [usize; 2],
        /// Samples in the height raster.
        height_samples: usize,
        /// Width and height of the albedo raster, pixels.
        albedo_px: [usize; 2],
        /// Samples in the albedo raster.
        albedo_samples: usize,
    },
    /// A parameter is outside the range its documentation gives.
    #[error("{field} = {value} is invalid: expected {expected}")]
    InvalidParameter {
        /// Name of the argument or params field.
        field: &'static str,
        /// The value given (counts are converted to `f64`).
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
}

/// A smooth random texture for tests and benchmarks of the matchers: the sum of 24 seeded
/// plane sinusoids around grey 128, quantised to 0..255. No terrain, no sensor model; the same
/// `seed` always gives the same image.
#[must_use]
pub fn sinusoid_texture(
    width: usize,
    height: usize,
    geo: maps::GeoTransform,
    seed: u64,
) -> maps::Raster<u8> {
    let mut s = seed;
    let mut next = || {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let waves: Vec<(f64, f64, f64)> = (0..24)
        .map(|_| (next() * 1.2 - 0.6, next() * 1.2 - 0.6, next() * 6.3))
        .collect();
    let mut r = maps::Raster::filled(width, height, geo, 0u8);
    for row in 0..height {
        for col in 0..width {
            let v: f64 = waves
                .iter()
                .map(|(a, b, ph)| (a * col as f64 + b * row as f64 + ph).sin())
                .sum();
            r.set(col, row, (128.0 + 20.0 * v).clamp(0.0, 255.0) as u8);
        }
    }
    r
}

/// `Ok` if `ok(value)`, else [`SyntheticError::InvalidParameter`].
fn check_param(
    field: &'static str,
    value: f64,
    expected: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<(), SyntheticError> {
    if ok(value) {
        Ok(())
    } else {
        Err(SyntheticError::InvalidParameter {
            field,
            value,
            expected,
        })
    }
}
