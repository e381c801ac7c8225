//! A tiny map (40 × 40 px at 1 m, generated once per call) and scenarios over it: for tests that
//! run `solsim` hundreds of times, where a bundled scenario's load (0.25-3 s) would dominate.

use std::path::{Path, PathBuf};
use std::time::Duration;

/// `solsim map generate` of a flat 40 × 40 m map into `dir/map`; returns that directory.
pub fn tiny_map(dir: &Path) -> PathBuf {
    let recipe = dir.join("tiny-recipe.toml");
    std::fs::write(
        &recipe,
        "[terrain]\nseed = 1\nwidth_px = 40\nheight_px = 40\n\
         geo = { origin_m = [0.0, 40.0], resolution_m_per_px = 1.0 }\n\
         base_height_m = 100.0\nrelief_m = 1.0\ncrater_density_per_km2 = 0.0\n\
         ridge_count = 0\nsand_fraction = 0.0\nbedrock_fraction = 0.0\n\
         sun_azimuth_deg = 250.0\nsun_elevation_deg = 35.0\n",
    )
    .expect("recipe");
    let map = dir.join("map");
    let o = super::output_within(
        super::solsim()
            .args(["map", "generate"])
            .arg(&recipe)
            .arg("--out")
            .arg(&map),
        Duration::from_secs(60),
    );
    assert!(o.status.success(), "map generate: {}", super::stderr(&o));
    map
}

/// A scenario named `name` (written as a TOML string) over the map of [`tiny_map`] in `map`,
/// with the zones file `zones`, driving 30 m east in one sol, then `extra` (more TOML).
pub fn tiny_scenario(map: &Path, zones: &Path, name: &str, extra: &str) -> String {
    let m = map.display();
    format!(
        "name = {}\nseed = 1\n[map]\nappearance = \"{m}/appearance.tif\"\n\
         dem = \"{m}/dem.tif\"\nterrain = \"{m}/terrain.tif\"\nzones = \"{}\"\n\
         [route]\nwaypoints = [[5.0, 20.0], [35.0, 20.0]]\n[[sols]]\nsol = 1\nuplink = true\n{extra}",
        toml::Value::String(name.to_owned()),
        zones.display()
    )
}

/// A zones file with no zones.
pub const NO_ZONES: &str = r#"{"type": "FeatureCollection", "features": []}"#;
