//! Map recipes (TOML): a `[terrain]` table with the fields of
//! [`maps::procedural::TerrainParams`] (seed, size, georeference, craters, ridges, dune fields,
//! sand patches, sun) and an optional `dem_datum_m`. `solsim map generate` turns one into the
//! appearance, DEM and terrain-class GeoTIFFs.

use std::path::Path;

use serde::Deserialize;

use crate::error::ScenarioError;
use maps::procedural::TerrainParams;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRecipe {
    terrain: TerrainParams,
    #[serde(default)]
    dem_datum_m: f64,
}

/// Largest map side accepted, pixels.
const MAX_SIDE_PX: usize = 20_000;

/// Read and validate a recipe.
pub fn load_recipe(path: &Path) -> Result<(TerrainParams, f64), ScenarioError> {
    let (recipe, _sha256) = crate::input::read_toml::<RawRecipe>(path)?;
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
