//! Issue 26, finding 8: a recipe of 1 000 000 large craters took 3 min 17 s in `solsim map
//! generate`, without a word. Every pixel sums the craters whose ejecta (3 radii) reaches its
//! 32-pixel bin, and every ridge, dune field and sand patch; the recipe checks capped the
//! crater count but not how far each reaches.
//!
//! A recipe is now refused when its landforms would take more than
//! `maps::procedural::MAX_LANDFORM_EVALUATIONS` (2e9, about 15 s on one core) evaluations,
//! counted from the craters as drawn before any pixel is generated, naming the field that asks
//! for most of them; and `map generate` draws a bar over its rows on a terminal.

use crate::common;

use std::time::Duration;

use common::{assert_bad_input, output_within, solsim, stderr};

/// A recipe of `width_px` × `width_px` pixels of 1 m with `extra` lines in `[terrain]`.
fn recipe(dir: &std::path::Path, width_px: usize, extra: &str) -> std::path::PathBuf {
    let path = dir.join("recipe.toml");
    let text = format!(
        "[terrain]\nseed = 26\nwidth_px = {width_px}\nheight_px = {width_px}\n\
         geo = {{ origin_m = [0.0, {width_px}.0], resolution_m_per_px = 1.0 }}\n{extra}\n"
    );
    std::fs::write(&path, text).expect("write");
    path
}

#[test]
fn recipes_over_the_landform_cap_are_refused_before_generating() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("map");
    // A million craters of 20 m (200 000 drawn, the generator's own cap): each reaches 25 bins.
    let path = recipe(
        dir.path(),
        1000,
        "crater_density_per_km2 = 1000000.0\ncrater_radius_min_m = 20.0\ncrater_radius_max_m = 20.0",
    );
    let o = output_within(
        solsim()
            .args(["map", "generate"])
            .arg(&path)
            .arg("--out")
            .arg(&out),
        Duration::from_secs(20),
    );
    assert_bad_input(
        &o,
        &[
            "recipe.toml: terrain.crater_density_per_km2: expected landforms that generate in bounded time: at most 2e9 evaluations",
            "evaluations over 1000 × 1000 px",
        ],
    );
    // 1000 ridges, each tested at every one of 9 million pixels.
    let path = recipe(
        dir.path(),
        3000,
        "crater_density_per_km2 = 0.0\nridge_count = 1000",
    );
    let o = output_within(
        solsim()
            .args(["map", "generate"])
            .arg(&path)
            .arg("--out")
            .arg(&out),
        Duration::from_secs(20),
    );
    assert_bad_input(
        &o,
        &[
            "recipe.toml: terrain.ridge_count: expected landforms that generate in bounded time",
            "got 9.000e9 evaluations over 3000 × 3000 px",
        ],
    );
    assert!(!out.exists(), "nothing written");
}

#[test]
fn map_generate_draws_a_bar_over_its_rows_on_a_terminal_only() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = recipe(
        dir.path(),
        500,
        "crater_density_per_km2 = 10000.0\ncrater_radius_min_m = 5.0\ncrater_radius_max_m = 20.0",
    );
    let (path, tty_out, piped_out) = (
        path.to_string_lossy().into_owned(),
        dir.path().join("tty").to_string_lossy().into_owned(),
        dir.path().join("piped").to_string_lossy().into_owned(),
    );
    if let Some(tty) = common::on_a_terminal(&["map", "generate", &path, "--out", &tty_out]) {
        assert!(
            tty.contains("map generate ") && tty.contains("/1500 rows"),
            "{tty:.2000}"
        );
    }
    let o = solsim()
        .args(["map", "generate", &path, "--out", &piped_out])
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "", "nothing on a piped stderr");
}
