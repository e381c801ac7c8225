//! `solsim map generate RECIPE --out DIR`: a procedural map from a recipe file.
//!
//! A recipe is a TOML file holding a `[terrain]` table with the fields of
//! [`maps::procedural::TerrainParams`] (seed, size, placement, craters, ridges, dune fields,
//! sand patches, sun), an optional `dem_datum_m` and an optional `[georeference]` (where the map
//! lies on Mars: see [`study::recipe`]). The bundled scenario maps each keep their recipe beside
//! them (`maps/assets/<map>/recipe.toml`), so `solsim map generate` rebuilds them byte for byte.

use std::path::PathBuf;

use anyhow::Context as _;
use maps::procedural;
use study::recipe::load_recipe;

/// Arguments of `solsim map generate`.
#[derive(Debug, clap::Args)]
pub struct GenerateArgs {
    /// Recipe file (TOML with a `[terrain]` table).
    pub recipe: PathBuf,
    /// Output directory for appearance.tif, dem.tif (16-bit cm) and terrain.tif.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Print what was written as one JSON document instead of the text: the directory, each
    /// file with its bytes, the size in pixels, the pixel size, the extent in map metres, the
    /// seed, the DEM datum and the CRS (with the extent in longitude/latitude on Mars).
    #[arg(long)]
    pub json: bool,
}

/// `solsim map generate --json`.
#[derive(serde::Serialize)]
struct GenerateJson {
    /// The output directory.
    dir: String,
    /// appearance.tif, dem.tif (16-bit cm) and terrain.tif.
    files: Vec<crate::cmd_sweep::WrittenFile>,
    /// Width and height, pixels.
    size_px: [usize; 2],
    /// Pixel size, metres.
    resolution_m_per_px: f64,
    /// West and east edges, map metres.
    x_m: [f64; 2],
    /// South and north edges, map metres.
    y_m: [f64; 2],
    /// The recipe's seed.
    seed: u64,
    /// Height of DEM value 0, metres.
    dem_datum_m: f64,
    /// Where the map lies on Mars (`null`: map metres only).
    crs: Option<CrsJson>,
}

/// The CRS of a generated map.
#[derive(serde::Serialize)]
struct CrsJson {
    name: String,
    /// West and east edges, degrees east.
    lon_deg: [f64; 2],
    /// South and north edges, degrees north.
    lat_deg: [f64; 2],
}

/// Run `solsim map generate`.
pub fn generate(
    args: &GenerateArgs,
    budget: maps::MemoryBudget,
    out: &mut dyn std::io::Write,
) -> anyhow::Result<()> {
    let recipe = load_recipe(&args.recipe, budget)?;
    let params = &recipe.terrain;
    let progress = crate::progress::Progress::new(
        false,
        "map generate",
        "rows",
        procedural::progress_rows(params),
    );
    let layers = procedural::generate_observed(params, &|| progress.inc());
    progress.finish();
    layers
        .write_dir(&args.out, recipe.dem_datum_m, &recipe.crs)
        .with_context(|| format!("{}: cannot write the map", args.out.display()))?;
    let (x0, y0, x1, y1) = layers.dem.extent_m();
    if args.json {
        use maps::raster_io::MapLayers;
        let files = [
            MapLayers::APPEARANCE_FILE,
            MapLayers::DEM_FILE,
            MapLayers::TERRAIN_FILE,
        ]
        .iter()
        .map(|f| crate::cmd_sweep::WrittenFile::of(&args.out, f, None))
        .collect::<anyhow::Result<_>>()?;
        let crs = match &recipe.crs {
            maps::MapCrs::Mars(crs) => {
                let [lon0, lat0] = crs.lonlat_from_map([x0, y0]);
                let [lon1, lat1] = crs.lonlat_from_map([x1, y1]);
                Some(CrsJson {
                    name: crs.name().to_string(),
                    lon_deg: [lon0, lon1],
                    lat_deg: [lat0, lat1],
                })
            }
            _ => None,
        };
        let doc = GenerateJson {
            dir: args.out.display().to_string(),
            files,
            size_px: [params.width_px, params.height_px],
            resolution_m_per_px: params.geo.resolution_m_per_px,
            x_m: [x0, x1],
            y_m: [y0, y1],
            seed: params.seed,
            dem_datum_m: recipe.dem_datum_m,
            crs,
        };
        writeln!(out, "{}", serde_json::to_string_pretty(&doc)?)?;
        return Ok(());
    }
    writeln!(
        out,
        "wrote {}/{{appearance,dem,terrain}}.tif: {} × {} px at {} m/px, x {x0:.1}..{x1:.1} m, y {y0:.1}..{y1:.1} m (seed {})",
        args.out.display(),
        params.width_px,
        params.height_px,
        params.geo.resolution_m_per_px,
        params.seed
    )?;
    if let maps::MapCrs::Mars(crs) = recipe.crs {
        let [lon0, lat0] = crs.lonlat_from_map([x0, y0]);
        let [lon1, lat1] = crs.lonlat_from_map([x1, y1]);
        writeln!(
            out,
            "CRS: {} (lon {lon0:.5}..{lon1:.5}° E, lat {lat0:.5}..{lat1:.5}° N)",
            crs.name()
        )?;
    }
    Ok(())
}
