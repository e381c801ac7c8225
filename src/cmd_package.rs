//! `solsim map package SCENARIO --out DIR`: the onboard map package of a scenario's route — the
//! 25 cm orthoimage and the 1 m DEM, masked to a corridor around the strategic route, the DEM as
//! 16-bit centimetres, compressed losslessly (paper 000 §5: "any parts of the map that are not
//! within a 100m radius of the upcoming strategic route are masked out", "the DEM elevations are
//! discretized to 1cm resolution and converted to a 16-bit image", "the appearance map
//! resolution is optionally reduced, for example to 50cm", "the total file size is on the order
//! of a few megabytes").
//!
//! ## What is rendered
//! The scenario maps are coarse (the bundled ones 4 m/px), so the orbital products are rendered
//! with [`localization::synthetic`]: [`truth_patch`] (map DEM plus fine detail, ripples and rocks
//! at 25 cm) and [`render_orbital`] (the HiRISE stand-in: 25 cm u8 image, 1 m DEM), block by
//! block along the corridor (the layout is [`maps::package::CorridorLayout`]: output tiles of
//! `--tile-m`, render blocks of [`BLOCK_M`], only those the corridor touches).
//!
//! ## Seamless blocks
//! Every value is a pure function of (seed, map position), so blocks join without seams and the
//! package does not depend on the block size, the tile size, the order or the thread count:
//!
//! - one truth seed and one orbital seed for the whole package, the same the simulator's onboard
//!   localizer matches against ([`sim::seeds`]: one world per scenario seed):
//!   the truth terrain, the between-epoch albedo change, the ripple migration and the
//!   orthorectification displacement are fields of map position under those seeds;
//! - [`render_orbital`] draws its sensor noise and DEM noise by *patch* pixel index, so the
//!   blocks are rendered with both at 0 and the same noise is added here by *world* pixel index
//!   ([`add_world_noise`]; the sensor noise is applied after the gamma with the response's local
//!   slope, which differs from noise before quantisation by the extra rounding, < 0.3 DN rms);
//! - dust devil tracks are off: [`render_orbital`] draws them per patch, so they would stop at
//!   block edges (they are smooth, low-contrast bands: leaving them out changes the compressed
//!   size negligibly);
//! - each block is rendered with [`MARGIN_M`] of terrain around it and cropped, so cast shadows,
//!   the PSF and the ortho displacement near a block edge see the same terrain as in the middle
//!   (shadows longer than the margin would be cut; at 35° sun elevation the margin covers
//!   obstacles up to 0.7 × [`MARGIN_M`] high). At the map's own edge the patch is shifted
//!   inwards, so the outermost pixels lack that context.
//!
//! ## Package format (directory DIR)
//! - `appearance_rRR_cCCC.png`: 8-bit gray, `--resolution-m` pixels, 0 = outside the corridor
//!   (a rendered 0 inside is stored as 1);
//! - `dem_cm_rRR_cCCC.png`: 16-bit gray, 1 m pixels, centimetres above `datum_m`, 0 = outside
//!   (a height exactly at the datum is stored as 1 cm);
//! - beside each PNG, its georeference for GDAL and QGIS (ground-side aids, not part of the
//!   uplinked bytes in `png_bytes`): `<name>.pgw`, a world file placing its pixels in map
//!   metres ([`maps::raster_io::world_file`]), and `<name>.png.aux.xml`, a GDAL PAM file naming
//!   the map's Mars CRS ([`maps::raster_io::pam_aux_xml`]; a map without one is placed at
//!   [`maps::mars_crs::DEFAULT_ANCHOR`]), so `gdalinfo` reports each tile's CRS and extent;
//! - `manifest.json`: georeference (map metres, x east, y north; each tile's north-west
//!   corner; the CRS those metres are projected coordinates of, and the bounding box in Mars
//!   longitude/latitude), corridor, route, datum, sizes, pixel counts and the MD5 of every PNG,
//!   and the render seeds and parameters.
//!
//! The package is an [`OutputSet`]: written into a staging directory and swapped into place
//! whole, so DIR holds an earlier package or this one, never a mix, and no tile of an earlier
//! package is left beside a new manifest. DIR must be new, empty or an earlier solsim output.
//!
//! PNG, because no lossless JPEG-XL encoder is in the dependency set (the paper's JPEG-XL is
//! "typically half the size of PNG").

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context as _;

use localization::hbs::HbsFile;
use localization::synthetic::{OrbitalParams, render_orbital, truth_patch};
use maps::package::{
    BlockRequest, CorridorLayout, PACKAGE_DEM_RESOLUTION_M, RENDER_RESOLUTION_M, TileSpec,
};
use maps::procedural::noise::hash2;
use maps::raster_io::{encode_png, pam_aux_xml, world_file};
use maps::{GeoTransform, MapLayers, Raster};
use sim::seeds::{Purpose, stream_seed};

use crate::output_set::OutputSet;
use study::Scenario;

/// Side of a render block, metres: small enough that blocks follow the corridor closely, large
/// enough that the margin costs little ((128 + 2 × 24)² / 128² ≈ 1.9× the block area).
pub const BLOCK_M: usize = 128;
/// Terrain rendered around each block and cropped off, metres (see the module docs).
pub const MARGIN_M: usize = 24;
/// The manifest's file name.
pub const MANIFEST_FILE: &str = "manifest.json";

/// Arguments of `solsim map package`.
#[derive(Debug, clap::Args)]
pub struct PackageArgs {
    /// Scenario file (TOML): its map and its route.
    pub scenario: PathBuf,
    /// Output directory for the tiles (PNG, each with a .pgw world file and a .png.aux.xml
    /// naming its CRS) and manifest.json.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Corridor half-width: pixels farther than this from the route are masked, metres.
    #[arg(long, default_value_t = 100.0, value_name = "M")]
    pub corridor_m: f64,
    /// Appearance pixel size, metres: 0.25 (the orthoimage), 0.5 or 1 (binned). The DEM is 1 m.
    #[arg(long, default_value_t = 0.25, value_name = "M")]
    pub resolution_m: f64,
    /// Side of the output tiles, metres (each tile is one appearance and one DEM PNG).
    #[arg(long, default_value_t = 1024, value_name = "M")]
    pub tile_m: usize,
    /// Side of the render blocks, metres (a check of seamlessness: the package must not change
    /// with it).
    #[arg(long, default_value_t = BLOCK_M, value_name = "M", hide = true)]
    pub block_m: usize,
    /// Print what was written as JSON (corridor area, pixels, tiles with their files, sizes
    /// and MD5s, total bytes, datum, seconds) instead of the text summary.
    #[arg(long)]
    pub json: bool,
}

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
    /// The orbital camera and DEM ([`OrbitalParams::default`] with dust devil tracks off; its
    /// `noise_sigma_dn` and `dem_noise_sigma_m` are applied per world pixel, see the module
    /// docs).
    pub orbital: OrbitalParams,
    /// Terrain rendered around each block and cropped, metres.
    pub margin_m: usize,
}

impl RenderSettings {
    /// The settings for a scenario seed.
    #[must_use]
    pub fn for_seed(seed: u64) -> Self {
        Self {
            truth_seed: stream_seed(seed, Purpose::WorldTruth, 0).seed,
            orbital_seed: stream_seed(seed, Purpose::WorldOrbital, 0).seed,
            sensor_noise_seed: stream_seed(seed, Purpose::PackageSensorNoise, 0).seed,
            dem_noise_seed: stream_seed(seed, Purpose::PackageDemNoise, 0).seed,
            orbital: OrbitalParams {
                dust_devil_tracks_per_ha: 0.0,
                ..OrbitalParams::default()
            },
            margin_m: MARGIN_M,
        }
    }
}

/// An approximately standard normal value for world cell `(ix, iy)` (Irwin–Hall sum of four
/// 16-bit uniforms from one hash; integer arithmetic only, so platform independent).
fn gaussian(seed: u64, ix: i64, iy: i64) -> f64 {
    let h = hash2(seed, ix, iy);
    let sum = (h & 0xFFFF) + ((h >> 16) & 0xFFFF) + ((h >> 32) & 0xFFFF) + (h >> 48);
    const SCALE: f64 = 1.0 / 37_837.226_5; // 1 / √(4 × (65536² − 1) / 12)
    (sum as f64 - 4.0 * 32_767.5) * SCALE
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
/// A [`SyntheticError`](localization::synthetic::SyntheticError) from the renderer, e.g.
/// `PatchOutsideMap` for a block that does not fit in a square patch on the map (a map
/// narrower in one direction than the block is long in the other), or `RegionOutsidePatch` if
/// the block is not on its rendered patch.
pub fn render_block(
    layers: &MapLayers,
    req: &BlockRequest,
    s: &RenderSettings,
) -> Result<(Raster<u8>, Raster<f32>), localization::synthetic::SyntheticError> {
    use localization::synthetic::SyntheticError;
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
    let quiet = OrbitalParams {
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
fn map_extent(layers: &MapLayers) -> (f64, f64, f64, f64) {
    let (a0, b0, a1, b1) = layers.dem.extent_m();
    let (c0, d0, c1, d1) = layers.terrain.extent_m();
    (a0.max(c0), b0.max(d0), a1.min(c1), b1.min(d1))
}

/// One written file of the package.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PackageFile {
    /// File name inside the package directory.
    pub file: String,
    /// Width and height, pixels.
    pub size_px: [usize; 2],
    /// North-west corner of pixel (0, 0), map metres.
    pub origin_m: [f64; 2],
    /// Pixel size, metres.
    pub resolution_m: f64,
    /// Pixels inside the corridor.
    pub kept_px: usize,
    /// File size, bytes.
    pub bytes: u64,
    /// MD5 of the file, hex.
    pub md5: String,
    /// Its world file (`.pgw`, map metres), for GDAL and QGIS.
    pub world_file: String,
    /// Its GDAL PAM file (`.png.aux.xml`) naming the map's CRS.
    pub aux_file: String,
}

/// One tile of the manifest: its place and its two files.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ManifestTile {
    /// The tile's place in the grid.
    #[serde(flatten)]
    pub spec: TileSpec,
    /// The 8-bit appearance PNG.
    pub appearance: PackageFile,
    /// The 16-bit centimetre DEM PNG.
    pub dem: PackageFile,
}

/// What `solsim map package` measured.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PackageSummary {
    /// Corridor area on the map (appearance pixels × pixel area), km².
    pub corridor_km2: f64,
    /// Pixels inside the corridor: appearance, DEM.
    pub kept_px: [usize; 2],
    /// The tiles written.
    pub tiles: Vec<ManifestTile>,
    /// Size of manifest.json, bytes.
    pub manifest_bytes: u64,
    /// Size of the world files and PAM files beside the PNGs, bytes.
    pub sidecar_bytes: u64,
    /// All files, bytes.
    pub total_bytes: u64,
    /// DEM datum, metres.
    pub datum_m: f64,
    /// Wall time, seconds.
    pub seconds: f64,
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    })
}

/// Writes `bytes` as `name` into the package's output set and describes it.
fn write_file(
    set: &OutputSet,
    name: String,
    bytes: Vec<u8>,
) -> anyhow::Result<(String, u64, String)> {
    set.write(&name, &bytes)?;
    let len = bytes.len() as u64;
    let md5 = hex(&HbsFile::new(name.clone(), bytes).md5);
    Ok((name, len, md5))
}

/// The world file and PAM file names of a PNG `name`: `x.png` → `x.pgw`, `x.png.aux.xml`.
fn sidecar_names(name: &str) -> [String; 2] {
    let stem = name.strip_suffix(".png").unwrap_or(name);
    [format!("{stem}.pgw"), format!("{name}.aux.xml")]
}

/// The corridor's bounding box in Mars longitude/latitude, degrees: `[west, south, east,
/// north]`, rounded to 1e-9°.
fn bbox_lonlat_deg(crs: &maps::MarsEquirectangular, layout: &CorridorLayout) -> [f64; 4] {
    let [ox, oy] = layout.origin_m;
    let [w, h] = layout.size_m.map(|v| v as f64);
    let [west, south] = crs.lonlat_from_map([ox, oy - h]);
    let [east, north] = crs.lonlat_from_map([ox + w, oy]);
    [west, south, east, north].map(|v| (v * 1e9).round() / 1e9)
}

/// The datum of the package DEM: a whole metre 2 m below the lowest map height in the
/// bounding box (fine detail, rocks and noise stay within ±1 m of the map DEM's bilinear
/// surface, and bilinear never undershoots the samples).
fn datum_for(layers: &MapLayers, layout: &CorridorLayout) -> f64 {
    let [ox, oy] = layout.origin_m;
    let (x1, y0) = (ox + layout.size_m[0] as f64, oy - layout.size_m[1] as f64);
    let dem = &layers.dem;
    let mut lo = f64::INFINITY;
    for row in 0..dem.height {
        for col in 0..dem.width {
            let (x, y) = dem.geo.center_of(col, row);
            let half = 0.5 * dem.geo.resolution_m_per_px;
            if x + half >= ox && x - half <= x1 && y + half >= y0 && y - half <= oy {
                lo = lo.min(f64::from(dem.get(col, row)));
            }
        }
    }
    if lo.is_finite() {
        lo.floor() - 2.0
    } else {
        0.0
    }
}

/// Run `solsim map package`: render, mask, write, and print the sizes.
pub fn run(
    args: &PackageArgs,
    budget: maps::MemoryBudget,
    out: &mut dyn std::io::Write,
) -> anyhow::Result<()> {
    let start = Instant::now();
    if !(args.corridor_m.is_finite() && args.corridor_m > 0.0) {
        anyhow::bail!(
            "--corridor-m: expected a positive number of metres, got {}",
            args.corridor_m
        );
    }
    // One output tile at a time is held (appearance u8, DEM f32 and its 16-bit copy) with
    // the render blocks that fill it (each with its margin, rendered at 25 cm).
    let res_m = if args.resolution_m >= RENDER_RESOLUTION_M {
        args.resolution_m
    } else {
        RENDER_RESOLUTION_M
    };
    let tile_px = (args.tile_m as f64 / res_m).ceil();
    let block_px = (args.block_m + 2 * MARGIN_M) as f64 / RENDER_RESOLUTION_M;
    let need = tile_px * tile_px + 6.0 * (args.tile_m as f64).powi(2) + 16.0 * block_px * block_px;
    if need.is_nan() || need > budget.limit_bytes as f64 {
        anyhow::bail!(
            "--tile-m: expected tiles that fit the memory budget ({}; --memory-budget-mib), got {} m ({})",
            maps::input_file::human_bytes(budget.limit_bytes),
            args.tile_m,
            maps::input_file::human_bytes(need.min(u64::MAX as f64) as u64)
        );
    }
    let scenario = Scenario::load_within(&args.scenario, budget)?;
    let layers = &*scenario.layers;
    // The package is written aside and swapped into place whole (fails before rendering if
    // the directory cannot take it).
    let set = OutputSet::begin(&args.out)?;

    let route = &scenario.campaign.route;
    let layout = CorridorLayout::new(
        route,
        args.corridor_m,
        args.resolution_m,
        map_extent(layers),
        layers.dem.geo.origin_m,
        args.tile_m,
        args.block_m,
    )
    .with_context(|| format!("{}", args.scenario.display()))?;
    let settings = RenderSettings::for_seed(scenario.campaign.seed);
    let datum_m = datum_for(layers, &layout);

    let crs = scenario.map_crs.mars_or_default();
    let aux = pam_aux_xml(&crs);
    let mut sidecar_bytes = 0u64;
    let mut tiles = Vec::new();
    let progress =
        crate::progress::Progress::new(false, "map package", "tiles", layout.tiles.len() as u64);
    for tile in &layout.tiles {
        let tag = format!("r{:02}_c{:03}", tile.row, tile.col);
        let app_name = format!("appearance_{tag}.png");
        let dem_name = format!("dem_cm_{tag}.png");
        let dem_path = args.out.join(&dem_name);
        let rasters = layout.assemble_tile(tile, datum_m, &dem_path, |req| {
            render_block(layers, req, &settings).map_err(anyhow::Error::from)
        })?;
        let app_bytes = encode_png(&rasters.appearance, &args.out.join(&app_name))?;
        let dem_bytes = encode_png(&rasters.dem_cm, &dem_path)?;
        let describe =
            |(file, bytes, md5): (String, u64, String), r_geo: GeoTransform, size_px, kept_px| {
                let [world_file, aux_file] = sidecar_names(&file);
                PackageFile {
                    file,
                    size_px,
                    origin_m: r_geo.origin_m,
                    resolution_m: r_geo.resolution_m_per_px,
                    kept_px,
                    bytes,
                    md5,
                    world_file,
                    aux_file,
                }
            };
        let appearance = describe(
            write_file(&set, app_name, app_bytes)?,
            rasters.appearance.geo,
            [rasters.appearance.width, rasters.appearance.height],
            rasters.kept_px[0],
        );
        let dem = describe(
            write_file(&set, dem_name, dem_bytes)?,
            rasters.dem_cm.geo,
            [rasters.dem_cm.width, rasters.dem_cm.height],
            rasters.kept_px[1],
        );
        for f in [&appearance, &dem] {
            let geo = GeoTransform::new(f.origin_m[0], f.origin_m[1], f.resolution_m);
            for (name, text) in [
                (&f.world_file, world_file(&geo)),
                (&f.aux_file, aux.clone()),
            ] {
                set.write(name, text.as_bytes())?;
                sidecar_bytes += text.len() as u64;
            }
        }
        tiles.push(ManifestTile {
            spec: *tile,
            appearance,
            dem,
        });
        progress.inc();
    }
    progress.finish();

    let kept_px = tiles.iter().fold([0, 0], |acc, t| {
        [acc[0] + t.appearance.kept_px, acc[1] + t.dem.kept_px]
    });
    let res = layout.appearance_resolution_m;
    let corridor_km2 = kept_px[0] as f64 * res * res / 1e6;
    let png_bytes: u64 = tiles.iter().map(|t| t.appearance.bytes + t.dem.bytes).sum();
    let manifest = serde_json::json!({
        "format": "solsim-map-package/1",
        "scenario": {
            "name": scenario.name,
            "file": args.scenario.display().to_string(),
            "sha256": scenario.sha256,
            "seed": scenario.campaign.seed,
        },
        "georeference": {
            "frame": "the scenario map's metres: x east, y north; origin_m is the north-west \
                      corner of pixel (0, 0), row 0 is the north edge",
            "lattice_origin_m": layers.dem.geo.origin_m,
            "bbox_origin_m": layout.origin_m,
            "bbox_size_m": layout.size_m,
            "crs": crs.name(),
            "crs_wkt2": crs.wkt2(),
            "crs_from_map": scenario.map_crs.is_mars(),
            "bbox_lonlat_deg": bbox_lonlat_deg(&crs, &layout),
            "sidecars": "each PNG has <name>.pgw (world file: pixel size and the centre of its \
                         top-left pixel, map metres) and <name>.png.aux.xml (its CRS, GDAL PAM)",
        },
        "corridor": {
            "half_width_m": layout.half_width_m,
            "route": layout.route,
            "area_km2": corridor_km2,
            "appearance_px": kept_px[0],
            "dem_px": kept_px[1],
        },
        "appearance": {
            "resolution_m": res,
            "format": "PNG, 8-bit gray",
            "no_data": 0,
        },
        "dem": {
            "resolution_m": PACKAGE_DEM_RESOLUTION_M,
            "format": "PNG, 16-bit gray",
            "units": "centimetres above datum_m",
            "datum_m": datum_m,
            "no_data": 0,
        },
        "tile_m": layout.tile_m,
        "tiles": tiles,
        "png_bytes": png_bytes,
        "render": {
            "block_m": layout.block_m,
            "settings": settings,
        },
    });
    let text = format!("{}\n", serde_json::to_string_pretty(&manifest)?);
    set.write(MANIFEST_FILE, text.as_bytes())?;
    set.commit()?;
    let summary = PackageSummary {
        corridor_km2,
        kept_px,
        manifest_bytes: text.len() as u64,
        sidecar_bytes,
        total_bytes: png_bytes + sidecar_bytes + text.len() as u64,
        tiles,
        datum_m,
        seconds: start.elapsed().as_secs_f64(),
    };
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&summary)?)?;
    } else {
        write!(
            out,
            "{}",
            summary_text(&scenario.name, &args.out, &layout, &summary)
        )?;
    }
    Ok(())
}

/// The printed report.
#[must_use]
pub fn summary_text(name: &str, dir: &Path, layout: &CorridorLayout, s: &PackageSummary) -> String {
    let mut t = String::new();
    let res = layout.appearance_resolution_m;
    let _ = writeln!(
        t,
        "map package of {name}: route of {} waypoints, corridor ±{} m, appearance {res} m/px, DEM {} m/px (16-bit cm above {} m)",
        layout.route.len(),
        layout.half_width_m,
        PACKAGE_DEM_RESOLUTION_M,
        s.datum_m
    );
    let _ = writeln!(
        t,
        "corridor: {:.3} km², {} appearance px, {} DEM px (bounding box {} × {} m, {} tiles of {} m)",
        s.corridor_km2,
        s.kept_px[0],
        s.kept_px[1],
        layout.size_m[0],
        layout.size_m[1],
        s.tiles.len(),
        layout.tile_m
    );
    let _ = writeln!(t, "files in {}/:", dir.display());
    for tile in &s.tiles {
        for f in [&tile.appearance, &tile.dem] {
            let _ = writeln!(
                t,
                "  {:<28} {:>10} B  {:>5} × {:<5} px  {:>9} in corridor",
                f.file, f.bytes, f.size_px[0], f.size_px[1], f.kept_px
            );
        }
    }
    let _ = writeln!(
        t,
        "  {:<28} {:>10} B  (.pgw world file and .png.aux.xml CRS beside each PNG)",
        format!("{} georeference files", 4 * s.tiles.len()),
        s.sidecar_bytes
    );
    let _ = writeln!(t, "  {MANIFEST_FILE:<28} {:>10} B", s.manifest_bytes);
    let app: u64 = s.tiles.iter().map(|f| f.appearance.bytes).sum();
    let dem: u64 = s.tiles.iter().map(|f| f.dem.bytes).sum();
    let per_px = |bytes: u64, px: usize| 8.0 * bytes as f64 / px.max(1) as f64;
    let _ = writeln!(
        t,
        "appearance: {app} B ({:.2} bit/px in corridor); DEM: {dem} B ({:.2} bit/px)",
        per_px(app, s.kept_px[0]),
        per_px(dem, s.kept_px[1])
    );
    let _ = writeln!(
        t,
        "total: {} B = {:.3} MB (10^6 B) in {} files; {:.1} s",
        s.total_bytes,
        s.total_bytes as f64 / 1e6,
        6 * s.tiles.len() + 1,
        s.seconds
    );
    t
}
