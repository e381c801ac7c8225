//! `solsim map generate RECIPE --out DIR`: a procedural map from a recipe file.
//!
//! A recipe is a TOML file holding a `[terrain]` table with the fields of
//! [`maps::procedural::TerrainSettings`] (seed, size, placement, craters, ridges, dune fields,
//! sand patches, sun), an optional `dem_datum_m` and an optional `[georeference]` (where the map
//! lies on Mars: see [`study::recipe`]). The bundled scenario maps each keep their recipe beside
//! them (`maps/assets/<map>/recipe.toml`), so `solsim map generate` rebuilds them byte for byte.

use std::path::PathBuf;

use anyhow::Context as _;
use maps::procedural;
use study::generated_map::GeneratedMap;
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
    files: Vec<outputs::sweep_text::WrittenFile>,
    /// The map's size, extent, seed, datum and CRS.
    #[serde(flatten)]
    map: GeneratedMap,
}

/// Run `solsim map generate`.
pub fn generate(
    args: &GenerateArgs,
    budget: maps::MemoryBudget,
    out: &mut dyn std::io::Write,
) -> anyhow::Result<()> {
    let recipe = load_recipe(&args.recipe, budget)?;
    let progress = crate::progress::Progress::new(
        false,
        "map generate",
        "rows",
        procedural::progress_rows(&recipe.terrain),
    );
    let layers = procedural::generate_observed(&recipe.terrain, &|| progress.inc());
    progress.finish();
    layers
        .write_dir(&args.out, recipe.dem_datum_m, &recipe.crs)
        .with_context(|| format!("{}: cannot write the map", args.out.display()))?;
    let map = GeneratedMap::of(&recipe, &layers);
    if args.json {
        use maps::raster_io::MapLayers;
        let files = [
            MapLayers::APPEARANCE_FILE,
            MapLayers::DEM_FILE,
            MapLayers::TERRAIN_FILE,
        ]
        .iter()
        .map(|f| outputs::sweep_text::WrittenFile::of(&args.out, f, None))
        .collect::<Result<_, _>>()?;
        let doc = GenerateJson {
            dir: args.out.display().to_string(),
            files,
            map,
        };
        writeln!(out, "{}", serde_json::to_string_pretty(&doc)?)?;
    } else {
        write!(out, "{}", map.text(&args.out))?;
    }
    Ok(())
}
