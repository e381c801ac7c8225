//! `solsim map generate RECIPE --out DIR`: a procedural map from a recipe file.
//!
//! A recipe is a TOML file holding a `[terrain]` table with the fields of
//! [`maps::procedural::TerrainParams`] (seed, size, georeference, craters, ridges, dune fields,
//! sand patches, sun) and an optional `dem_datum_m`. The bundled scenario maps each keep their
//! recipe beside them (`maps/assets/<map>/recipe.toml`), so `solsim map generate` rebuilds them
//! byte for byte.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use serde::Deserialize;

use crate::error::ScenarioError;
use maps::procedural::{self, TerrainParams};

/// Arguments of `solsim map generate`.
#[derive(Debug, clap::Args)]
pub struct GenerateArgs {
    /// Recipe file (TOML with a `[terrain]` table).
    pub recipe: PathBuf,
    /// Output directory for appearance.tif, dem.tif (16-bit cm) and terrain.tif.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Recipe {
    terrain: TerrainParams,
    #[serde(default)]
    dem_datum_m: f64,
}

/// Largest map side accepted, pixels.
const MAX_SIDE_PX: usize = 20_000;

/// Read and validate a recipe.
pub fn load_recipe(path: &Path) -> Result<(TerrainParams, f64), ScenarioError> {
    let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let recipe: Recipe =
        toml::from_str(&text).map_err(|e| ScenarioError::from_toml(path, &text, &e))?;
    let t = &recipe.terrain;
    let bad = |field: &str, expected: &str, got: String| {
        Err(ScenarioError::field(
            path,
            format!("terrain.{field}"),
            expected,
            got,
        ))
    };
    if t.width_px == 0 || t.width_px > MAX_SIDE_PX {
        return bad(
            "width_px",
            &format!("1 ..= {MAX_SIDE_PX} pixels"),
            t.width_px.to_string(),
        );
    }
    if t.height_px == 0 || t.height_px > MAX_SIDE_PX {
        return bad(
            "height_px",
            &format!("1 ..= {MAX_SIDE_PX} pixels"),
            t.height_px.to_string(),
        );
    }
    if !(t.geo.resolution_m_per_px.is_finite() && t.geo.resolution_m_per_px > 0.0) {
        return bad(
            "geo.resolution_m_per_px",
            "a positive number of metres per pixel",
            t.geo.resolution_m_per_px.to_string(),
        );
    }
    let reals = [
        ("geo.origin_m[0]", t.geo.origin_m[0]),
        ("geo.origin_m[1]", t.geo.origin_m[1]),
        ("base_height_m", t.base_height_m),
        ("relief_m", t.relief_m),
        ("crater_density_per_km2", t.crater_density_per_km2),
        ("crater_radius_min_m", t.crater_radius_min_m),
        ("crater_radius_max_m", t.crater_radius_max_m),
        ("ridge_height_m", t.ridge_height_m),
        ("sand_fraction", t.sand_fraction),
        ("bedrock_fraction", t.bedrock_fraction),
        ("sun_azimuth_deg", t.sun_azimuth_deg),
        ("sun_elevation_deg", t.sun_elevation_deg),
    ];
    for (field, v) in reals {
        if !v.is_finite() {
            return bad(field, "a finite number", v.to_string());
        }
    }
    for (i, f) in t.dune_fields.iter().enumerate() {
        let vals = [
            f.center_m[0],
            f.center_m[1],
            f.radius_m,
            f.wavelength_m,
            f.amplitude_m,
            f.crest_azimuth_deg,
        ];
        if vals.iter().any(|v| !v.is_finite()) || f.radius_m < 0.0 || f.wavelength_m <= 0.0 {
            return bad(
                &format!("dune_fields[{i}]"),
                "finite values, radius_m ≥ 0 and wavelength_m > 0",
                format!("{f:?}"),
            );
        }
    }
    if !recipe.dem_datum_m.is_finite() {
        return Err(ScenarioError::field(
            path,
            "dem_datum_m",
            "a finite number of metres",
            recipe.dem_datum_m,
        ));
    }
    Ok((recipe.terrain, recipe.dem_datum_m))
}

/// Run `solsim map generate`.
pub fn generate(args: &GenerateArgs, out: &mut dyn std::io::Write) -> anyhow::Result<()> {
    let (params, datum_m) = load_recipe(&args.recipe)?;
    let layers = procedural::generate(&params);
    layers
        .write_dir(&args.out, datum_m)
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
    Ok(())
}
