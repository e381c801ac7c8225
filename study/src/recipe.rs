//! Map recipes (TOML): a `[terrain]` table with the fields of
//! [`maps::procedural::TerrainSettings`] (seed, size, placement in map metres, craters, ridges,
//! dune fields, sand patches, sun), an optional `dem_datum_m`, and an optional
//! `[georeference]` table, a [`MapAnchor`]: the map point `anchor_m` lies at planetocentric
//! `lon_deg` east, `lat_deg` north on Mars. With it the GeoTIFFs carry the Jezero equirectangular
//! CRS through that point ([`MarsEquirectangular::jezero`]); without it they carry only local
//! metres. `solsim map generate` turns a recipe into the appearance, DEM and terrain-class
//! GeoTIFFs.
//!
//! Every field has a physical range (below), and the map's size is held to the command's
//! [`MemoryBudget`] before anything is generated.

use std::path::Path;

use serde::Deserialize;

use crate::check::FieldCheck;
use crate::error::ScenarioError;
use maps::procedural::TerrainSettings;
use maps::zone::MAX_COORDINATE_M;
use maps::{MapAnchor, MapCrs, MarsEquirectangular, MemoryBudget};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRecipe {
    terrain: TerrainSettings,
    #[serde(default)]
    dem_datum_m: f64,
    georeference: Option<MapAnchor>,
}

/// A validated recipe.
#[derive(Clone, Debug, PartialEq)]
pub struct Recipe {
    /// What to generate.
    pub terrain: TerrainSettings,
    /// The DEM files' datum: heights are stored as centimetres above it, metres.
    pub dem_datum_m: f64,
    /// Where the map lies on Mars: [`MapCrs::Mars`] from `[georeference]`, else
    /// [`MapCrs::Local`].
    pub crs: MapCrs,
}

/// Largest map side accepted, pixels.
pub const MAX_SIDE_PX: usize = 20_000;
/// Memory the generator holds per map pixel, bytes: measured (peak RSS of `solsim map
/// generate` at 1000² and 2000² px: 22 B per extra pixel) and rounded up.
pub const BYTES_PER_PX: u64 = 24;
/// Most craters, ridges, dune fields or sand patches one map may ask for (the generator's
/// time grows with each).
pub const MAX_FEATURES: f64 = 1.0e6;
/// Heights, reliefs and datums, metres: Mars spans about −8 km to +22 km.
const MAX_HEIGHT_M: f64 = 100_000.0;
/// Map pixel size, metres.
const MAX_RESOLUTION_M: f64 = 1_000.0;

/// Read and validate a recipe within `budget`: the terrain, its datum and its georeference.
///
/// # Errors
/// A [`ScenarioError`] naming the file and the first `terrain.…` or `georeference.…` field at
/// fault.
pub fn load_recipe(path: &Path, budget: MemoryBudget) -> Result<Recipe, ScenarioError> {
    let (recipe, _sha256) = crate::input::read_toml::<RawRecipe>(path)?;
    validate(path, recipe, budget)
}

/// [`load_recipe`] of recipe text (`path` names it in errors; nothing is read).
///
/// # Errors
/// As [`load_recipe`].
pub fn recipe_from_toml_str(
    path: &Path,
    text: &str,
    budget: MemoryBudget,
) -> Result<Recipe, ScenarioError> {
    validate(path, crate::input::parse_toml(path, text)?, budget)
}

fn validate(path: &Path, recipe: RawRecipe, budget: MemoryBudget) -> Result<Recipe, ScenarioError> {
    let c = FieldCheck { path };
    let t = &recipe.terrain;
    for (field, v) in [
        ("terrain.width_px", t.width_px),
        ("terrain.height_px", t.height_px),
    ] {
        if v == 0 || v > MAX_SIDE_PX {
            return Err(c.err(field, format!("1 ..= {MAX_SIDE_PX} pixels"), v));
        }
    }
    let need_bytes =
        maps::memory_budget::bytes_of(&[t.width_px as u64, t.height_px as u64, BYTES_PER_PX]);
    if !budget.allows(need_bytes) {
        return Err(c.err(
            "terrain.width_px",
            format!(
                "a map whose generation fits the memory budget ({}; --memory-budget-mib)",
                maps::input_file::human_bytes(budget.limit_bytes)
            ),
            format!(
                "{} × {} px, which needs {}",
                t.width_px,
                t.height_px,
                maps::input_file::human_bytes(need_bytes)
            ),
        ));
    }
    let res = c.positive_at_most(
        "terrain.geo.resolution_m_per_px",
        t.geo.resolution_m_per_px,
        MAX_RESOLUTION_M,
        "metres per pixel",
    )?;
    let coordinate = |field: &str, v: f64| c.range(crate::ranges::COORDINATE_M, field, v);
    coordinate("terrain.geo.origin_m[0]", t.geo.origin_m[0])?;
    coordinate("terrain.geo.origin_m[1]", t.geo.origin_m[1])?;
    let height = |field: &str, v: f64| c.in_range(field, v, -MAX_HEIGHT_M, MAX_HEIGHT_M, "metres");
    height("terrain.base_height_m", t.base_height_m)?;
    height("dem_datum_m", recipe.dem_datum_m)?;
    c.in_range("terrain.relief_m", t.relief_m, 0.0, MAX_HEIGHT_M, "metres")?;
    c.in_range(
        "terrain.ridge_height_m",
        t.ridge_height_m,
        0.0,
        MAX_HEIGHT_M,
        "metres",
    )?;
    let area_km2 = t.width_px as f64 * t.height_px as f64 * res * res / 1e6;
    let density = c.in_range(
        "terrain.crater_density_per_km2",
        t.crater_density_per_km2,
        0.0,
        1e6,
        "craters per km²",
    )?;
    if density * area_km2 > MAX_FEATURES {
        return Err(c.err(
            "terrain.crater_density_per_km2",
            format!("at most {MAX_FEATURES:e} craters over the map ({area_km2:.1} km²)"),
            density,
        ));
    }
    let r_min = c.in_range(
        "terrain.crater_radius_min_m",
        t.crater_radius_min_m,
        0.0,
        MAX_HEIGHT_M,
        "metres",
    )?;
    c.in_range(
        "terrain.crater_radius_max_m",
        t.crater_radius_max_m,
        r_min,
        MAX_HEIGHT_M,
        "metres (at least crater_radius_min_m)",
    )?;
    for (field, n) in [
        ("terrain.ridge_count", t.ridge_count),
        ("terrain.dune_fields", t.dune_fields.len()),
        ("terrain.sand_patches", t.sand_patches.len()),
    ] {
        if n as f64 > MAX_FEATURES {
            return Err(c.err(field, format!("at most {MAX_FEATURES:e} entries"), n));
        }
    }
    c.fraction("terrain.sand_fraction", t.sand_fraction)?;
    c.fraction("terrain.bedrock_fraction", t.bedrock_fraction)?;
    c.in_range(
        "terrain.sun_azimuth_deg",
        t.sun_azimuth_deg,
        -360.0,
        360.0,
        "degrees",
    )?;
    c.in_range(
        "terrain.sun_elevation_deg",
        t.sun_elevation_deg,
        0.0,
        90.0,
        "degrees",
    )?;
    for (i, f) in t.dune_fields.iter().enumerate() {
        let field = |name: &str| format!("terrain.dune_fields[{i}].{name}");
        coordinate(&field("center_m[0]"), f.center_m[0])?;
        coordinate(&field("center_m[1]"), f.center_m[1])?;
        c.in_range(
            &field("radius_m"),
            f.radius_m,
            0.0,
            MAX_COORDINATE_M,
            "metres",
        )?;
        c.positive_at_most(
            &field("wavelength_m"),
            f.wavelength_m,
            MAX_HEIGHT_M,
            "metres",
        )?;
        c.in_range(
            &field("amplitude_m"),
            f.amplitude_m,
            0.0,
            MAX_HEIGHT_M,
            "metres",
        )?;
        c.in_range(
            &field("crest_azimuth_deg"),
            f.crest_azimuth_deg,
            -360.0,
            360.0,
            "degrees",
        )?;
    }
    for (i, (center, radius)) in t.sand_patches.iter().enumerate() {
        coordinate(&format!("terrain.sand_patches[{i}][0][0]"), center[0])?;
        coordinate(&format!("terrain.sand_patches[{i}][0][1]"), center[1])?;
        c.in_range(
            &format!("terrain.sand_patches[{i}][1]"),
            *radius,
            0.0,
            MAX_COORDINATE_M,
            "metres",
        )?;
    }
    // Generation time: refused from the landforms' evaluations before any pixel is made,
    // naming the field that asks for the most of them.
    let evaluations = maps::procedural::landform_evaluations(t);
    if evaluations > maps::procedural::MAX_LANDFORM_EVALUATIONS {
        let sane = t.sanitized();
        let px = (t.width_px as u64).saturating_mul(t.height_px as u64);
        let per_px = |n: usize| px.saturating_mul(n as u64);
        let others = [
            ("terrain.ridge_count", per_px(sane.ridge_count)),
            ("terrain.dune_fields", per_px(sane.dune_fields.len())),
            ("terrain.sand_patches", per_px(sane.sand_patches.len())),
        ];
        let craters = others
            .iter()
            .fold(evaluations, |e, o| e.saturating_sub(o.1));
        let (field, _) =
            others
                .into_iter()
                .fold(("terrain.crater_density_per_km2", craters), |a, b| {
                    if b.1 > a.1 { b } else { a }
                });
        return Err(c.err(
            field,
            format!(
                "landforms that generate in bounded time: at most {:e} evaluations of a crater, \
                 ridge, dune field or sand patch at a pixel (craters count at every pixel their \
                 ejecta reaches, 3 radii)",
                maps::procedural::MAX_LANDFORM_EVALUATIONS as f64
            ),
            format!(
                "{:.3e} evaluations over {} × {} px",
                evaluations as f64, t.width_px, t.height_px
            ),
        ));
    }
    let crs = match &recipe.georeference {
        None => MapCrs::Local,
        Some(a) => {
            coordinate("georeference.anchor_m[0]", a.anchor_m[0])?;
            coordinate("georeference.anchor_m[1]", a.anchor_m[1])?;
            c.in_range(
                "georeference.lon_deg",
                a.lon_deg,
                -180.0,
                360.0,
                "degrees east (planetocentric)",
            )?;
            c.in_range(
                "georeference.lat_deg",
                a.lat_deg,
                -89.0,
                89.0,
                "degrees north (planetocentric)",
            )?;
            MapCrs::Mars(MarsEquirectangular::jezero(a))
        }
    };
    Ok(Recipe {
        terrain: recipe.terrain,
        dem_datum_m: recipe.dem_datum_m,
        crs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TERRAIN: &str = "[terrain]\nwidth_px = 10\nheight_px = 10\n";

    fn load(text: &str) -> Result<Recipe, ScenarioError> {
        recipe_from_toml_str(Path::new("r.toml"), text, MemoryBudget::default())
    }

    #[test]
    fn a_georeference_gives_the_jezero_crs_through_the_anchor() {
        let r = load(&format!(
            "{TERRAIN}[georeference]\nanchor_m = [5.0, 5.0]\nlon_deg = 77.45\nlat_deg = 18.44\n"
        ))
        .expect("a valid recipe");
        let MapCrs::Mars(crs) = r.crs else {
            panic!("{:?}", r.crs)
        };
        let [lon, lat] = crs.lonlat_from_map([5.0, 5.0]);
        assert!((lon - 77.45).abs() < 1e-7 && (lat - 18.44).abs() < 1e-7);
        assert_eq!(load(TERRAIN).expect("valid").crs, MapCrs::Local);
    }

    #[test]
    fn a_bad_georeference_names_its_field() {
        for (bad, field) in [
            ("lon_deg = 77.45\nlat_deg = 95.0", "georeference.lat_deg"),
            ("lon_deg = 400.0\nlat_deg = 18.0", "georeference.lon_deg"),
            ("lon_deg = nan\nlat_deg = 18.0", "georeference.lon_deg"),
        ] {
            let e = load(&format!(
                "{TERRAIN}[georeference]\nanchor_m = [0.0, 0.0]\n{bad}\n"
            ))
            .expect_err("refused");
            assert!(e.to_string().contains(field), "{e}");
        }
        let e = load(&format!(
            "{TERRAIN}[georeference]\nanchor_m = [0.0, 0.0]\nlon_deg = 77.0\nlat_deg = 18.0\nlat = 1\n"
        ))
        .expect_err("an unknown key is refused");
        assert!(e.to_string().contains("lat"), "{e}");
    }
}
