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
