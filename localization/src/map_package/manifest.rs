//! What a map package holds and what making it measured: its files, tiles and sizes, and the
//! printed summary.

use std::fmt::Write as _;
use std::path::Path;

use maps::package::{CorridorLayout, PACKAGE_DEM_RESOLUTION_M, TileSpec};

/// The manifest's file name.
pub const MANIFEST_FILE: &str = "manifest.json";

/// One file of the package.
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

/// What making a package measured.
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

/// The printed report of package `name` written in `dir`.
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
