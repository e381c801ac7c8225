//! A map package tile by tile: the layout of a route's corridor, each tile's PNGs and their
//! georeference files as names and bytes, and the manifest.

use std::fmt::Write as _;
use std::path::Path;

use maps::package::{CorridorLayout, PACKAGE_DEM_RESOLUTION_M, RENDER_RESOLUTION_M, TileSpec};
use maps::raster_io::{encode_png, pam_aux_xml, world_file};
use maps::{GeoTransform, MapCrs, MapLayers, MarsEquirectangular, MemoryBudget};

use super::error::MapPackageError;
use super::manifest::{ManifestTile, PackageFile, PackageSummary};
use super::render::{MARGIN_M, RenderSettings, map_extent, render_block};
use crate::hbs::HbsFile;

/// The options of a package, named as on the command line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PackageOptions {
    /// Corridor half-width: pixels farther than this from the route are masked, metres.
    pub corridor_m: f64,
    /// Appearance pixel size, metres: 0.25 (the orthoimage), 0.5 or 1 (binned).
    pub resolution_m: f64,
    /// Side of the output tiles, metres.
    pub tile_m: usize,
    /// Side of the render blocks, metres.
    pub block_m: usize,
}

impl PackageOptions {
    /// Checks the options before anything is read: a positive corridor, and tiles that fit
    /// `budget` — one output tile is held at a time (appearance u8, DEM f32 and its 16-bit
    /// copy) with the render blocks that fill it (each with its margin, rendered at 25 cm).
    ///
    /// # Errors
    /// [`MapPackageError::Option`] naming `--corridor-m` or `--tile-m`.
    pub fn check(&self, budget: MemoryBudget) -> Result<(), MapPackageError> {
        if !(self.corridor_m.is_finite() && self.corridor_m > 0.0) {
            return Err(MapPackageError::Option {
                option: "--corridor-m",
                expected: "a positive number of metres".to_owned(),
                got: self.corridor_m.to_string(),
            });
        }
        let res_m = if self.resolution_m >= RENDER_RESOLUTION_M {
            self.resolution_m
        } else {
            RENDER_RESOLUTION_M
        };
        let tile_px = (self.tile_m as f64 / res_m).ceil();
        let block_px = (self.block_m + 2 * MARGIN_M) as f64 / RENDER_RESOLUTION_M;
        let need =
            tile_px * tile_px + 6.0 * (self.tile_m as f64).powi(2) + 16.0 * block_px * block_px;
        if need.is_nan() || need > budget.limit_bytes as f64 {
            return Err(MapPackageError::Option {
                option: "--tile-m",
                expected: format!(
                    "tiles that fit the memory budget ({}; --memory-budget-mib)",
                    maps::input_file::human_bytes(budget.limit_bytes)
                ),
                got: format!(
                    "{} m ({})",
                    self.tile_m,
                    maps::input_file::human_bytes(need.min(u64::MAX as f64) as u64)
                ),
            });
        }
        Ok(())
    }
}

/// Where a package comes from, as its manifest names it: the scenario.
#[derive(Clone, Copy, Debug)]
pub struct PackageSource<'a> {
    /// The scenario's name.
    pub name: &'a str,
    /// The scenario file.
    pub file: &'a Path,
    /// SHA-256 of the scenario file, hex.
    pub sha256: &'a str,
    /// The scenario's seed.
    pub seed: u64,
    /// The CRS of the map (a map without one is placed at the default anchor).
    pub map_crs: &'a MapCrs,
}

/// A package being made: laid out, then rendered tile by tile ([`MapPackage::render_tile`]),
/// then described ([`MapPackage::manifest`], [`MapPackage::summary`]).
#[derive(Debug)]
pub struct MapPackage<'a> {
    layers: &'a MapLayers,
    source: PackageSource<'a>,
    layout: CorridorLayout,
    settings: RenderSettings,
    datum_m: f64,
    crs: MarsEquirectangular,
    /// The GDAL PAM file of every PNG (the same CRS for all).
    aux: String,
    tiles: Vec<ManifestTile>,
    sidecar_bytes: u64,
}

impl<'a> MapPackage<'a> {
    /// Lays out the package of `route` on `layers`.
    ///
    /// # Errors
    /// [`MapPackageError::Layout`] naming the scenario file: an empty route, a bad option, a
    /// corridor off the map.
    pub fn new(
        layers: &'a MapLayers,
        route: &[[f64; 2]],
        options: &PackageOptions,
        settings: RenderSettings,
        source: PackageSource<'a>,
    ) -> Result<Self, MapPackageError> {
        let layout = CorridorLayout::new(
            route,
            options.corridor_m,
            options.resolution_m,
            map_extent(layers),
            layers.dem.geo.origin_m,
            options.tile_m,
            options.block_m,
        )
        .map_err(|e| MapPackageError::Layout {
            file: source.file.to_path_buf(),
            source: Box::new(e),
        })?;
        let datum_m = datum_for(layers, &layout);
        let crs = source.map_crs.mars_or_default();
        Ok(Self {
            layers,
            source,
            layout,
            settings,
            datum_m,
            crs,
            aux: pam_aux_xml(&crs),
            tiles: Vec::new(),
            sidecar_bytes: 0,
        })
    }

    /// The layout: the corridor, its bounding box and the tiles to render.
    #[must_use]
    pub fn layout(&self) -> &CorridorLayout {
        &self.layout
    }

    /// Renders `tile` (one of [`CorridorLayout::tiles`]) and returns its files, name and bytes:
    /// the appearance PNG, the DEM PNG, then each one's world file and PAM file. `dir` is
    /// where they will be written, for error messages.
    ///
    /// # Errors
    /// A block that cannot be rendered or assembled, a PNG that cannot be encoded.
    pub fn render_tile(
        &mut self,
        tile: &TileSpec,
        dir: &Path,
    ) -> Result<Vec<(String, Vec<u8>)>, MapPackageError> {
        let tag = format!("r{:02}_c{:03}", tile.row, tile.col);
        let app_name = format!("appearance_{tag}.png");
        let dem_name = format!("dem_cm_{tag}.png");
        let dem_path = dir.join(&dem_name);
        let (layers, settings) = (self.layers, &self.settings);
        let rasters = self
            .layout
            .assemble_tile(tile, self.datum_m, &dem_path, |req| {
                render_block(layers, req, settings).map_err(MapPackageError::from)
            })?;
        let app_bytes = encode_png(&rasters.appearance, &dir.join(&app_name))?;
        let dem_bytes = encode_png(&rasters.dem_cm, &dem_path)?;
        let describe = |file: HbsFile, geo: GeoTransform, size_px, kept_px| {
            let [world_file, aux_file] = sidecar_names(&file.name);
            let described = PackageFile {
                file: file.name,
                size_px,
                origin_m: geo.origin_m,
                resolution_m: geo.resolution_m_per_px,
                kept_px,
                bytes: file.bytes.len() as u64,
                md5: hex(&file.md5),
                world_file,
                aux_file,
            };
            (described, file.bytes)
        };
        let (appearance, app_bytes) = describe(
            HbsFile::new(app_name, app_bytes),
            rasters.appearance.geo,
            [rasters.appearance.width, rasters.appearance.height],
            rasters.kept_px[0],
        );
        let (dem, dem_bytes) = describe(
            HbsFile::new(dem_name, dem_bytes),
            rasters.dem_cm.geo,
            [rasters.dem_cm.width, rasters.dem_cm.height],
            rasters.kept_px[1],
        );
        let mut files = vec![
            (appearance.file.clone(), app_bytes),
            (dem.file.clone(), dem_bytes),
        ];
        for f in [&appearance, &dem] {
            let geo = GeoTransform::new(f.origin_m[0], f.origin_m[1], f.resolution_m);
            for (name, text) in [
                (&f.world_file, world_file(&geo)),
                (&f.aux_file, self.aux.clone()),
            ] {
                self.sidecar_bytes += text.len() as u64;
                files.push((name.clone(), text.into_bytes()));
            }
        }
        self.tiles.push(ManifestTile {
            spec: *tile,
            appearance,
            dem,
        });
        Ok(files)
    }

    /// Pixels inside the corridor over the tiles rendered so far: appearance, DEM.
    fn kept_px(&self) -> [usize; 2] {
        self.tiles.iter().fold([0, 0], |acc, t| {
            [acc[0] + t.appearance.kept_px, acc[1] + t.dem.kept_px]
        })
    }

    /// The corridor's area on the map (appearance pixels × pixel area), km².
    fn corridor_km2(&self) -> f64 {
        let res = self.layout.appearance_resolution_m;
        self.kept_px()[0] as f64 * res * res / 1e6
    }

    /// The PNGs' bytes: what is uplinked.
    fn png_bytes(&self) -> u64 {
        self.tiles
            .iter()
            .map(|t| t.appearance.bytes + t.dem.bytes)
            .sum()
    }

    /// The text of `manifest.json` for the tiles rendered so far (see the module docs).
    #[must_use]
    pub fn manifest(&self) -> String {
        let (layout, crs, kept_px) = (&self.layout, &self.crs, self.kept_px());
        let manifest = serde_json::json!({
            "format": "solsim-map-package/1",
            "scenario": {
                "name": self.source.name,
                "file": self.source.file.display().to_string(),
                "sha256": self.source.sha256,
                "seed": self.source.seed,
            },
            "georeference": {
                "frame": "the scenario map's metres: x east, y north; origin_m is the north-west \
                          corner of pixel (0, 0), row 0 is the north edge",
                "lattice_origin_m": self.layers.dem.geo.origin_m,
                "bbox_origin_m": layout.origin_m,
                "bbox_size_m": layout.size_m,
                "crs": crs.name(),
                "crs_wkt2": crs.wkt2(),
                "crs_from_map": self.source.map_crs.is_mars(),
                "bbox_lonlat_deg": bbox_lonlat_deg(crs, layout),
                "sidecars": "each PNG has <name>.pgw (world file: pixel size and the centre of its \
                             top-left pixel, map metres) and <name>.png.aux.xml (its CRS, GDAL PAM)",
            },
            "corridor": {
                "half_width_m": layout.half_width_m,
                "route": layout.route,
                "area_km2": self.corridor_km2(),
                "appearance_px": kept_px[0],
                "dem_px": kept_px[1],
            },
            "appearance": {
                "resolution_m": layout.appearance_resolution_m,
                "format": "PNG, 8-bit gray",
                "no_data": 0,
            },
            "dem": {
                "resolution_m": PACKAGE_DEM_RESOLUTION_M,
                "format": "PNG, 16-bit gray",
                "units": "centimetres above datum_m",
                "datum_m": self.datum_m,
                "no_data": 0,
            },
            "tile_m": layout.tile_m,
            "tiles": self.tiles,
            "png_bytes": self.png_bytes(),
            "render": {
                "block_m": layout.block_m,
                "settings": self.settings,
            },
        });
        format!("{manifest:#}\n")
    }

    /// What was made: the tiles rendered, with the size of the manifest written beside them
    /// and the wall time `seconds` it took.
    #[must_use]
    pub fn summary(&self, manifest_bytes: u64, seconds: f64) -> PackageSummary {
        PackageSummary {
            corridor_km2: self.corridor_km2(),
            kept_px: self.kept_px(),
            manifest_bytes,
            sidecar_bytes: self.sidecar_bytes,
            total_bytes: self.png_bytes() + self.sidecar_bytes + manifest_bytes,
            tiles: self.tiles.clone(),
            datum_m: self.datum_m,
            seconds,
        }
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    })
}

/// The world file and PAM file names of a PNG `name`: `x.png` → `x.pgw`, `x.png.aux.xml`.
fn sidecar_names(name: &str) -> [String; 2] {
    let stem = name.strip_suffix(".png").unwrap_or(name);
    [format!("{stem}.pgw"), format!("{name}.aux.xml")]
}

/// The corridor's bounding box in Mars longitude/latitude, degrees: `[west, south, east,
/// north]`, rounded to 1e-9°.
fn bbox_lonlat_deg(crs: &MarsEquirectangular, layout: &CorridorLayout) -> [f64; 4] {
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
