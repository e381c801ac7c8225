//! Issue 26, finding 8: 100 000 waypoints took 4 min 39 s in `validate` and 5 min 8 s in `run`
//! (3.4 ms per leg) without a word. Each leg's passage clearance is a bottleneck search over
//! the leg's box and 150 m around it, and it expanded every cell that tied with the goal.
//!
//! Now a goal-directed walk answers the legs whose goal is their own bottleneck (the same
//! value and cell, held to the full search by a property test in `sim::grid::widest_path`), the legs
//! run in parallel, and a route is refused over `sim::run::MAX_WAYPOINTS` (10 000) or when
//! its legs' search windows cover more than `MAX_LEG_SEARCH_CELLS` (3e8) grid cells together,
//! before any search runs. `validate`, `run` and `compare` draw a bar over the legs on a
//! terminal.
//!
//! Stated bound: a route at the cells cap through open ground (3200 short legs on the 1 m grid
//! of the crater-floor map) validates in under 4 s (0.1 s measured; 12 s before). The worst
//! route at the cap, whose every leg needs the full search (2000 legs through the sol 383-386
//! passage), takes 8 s on two cores and 16 s on one: too slow for the suite.

use crate::common;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use common::{assert_bad_input, output_within, replace_line, scenario_copy, solsim, stderr};
use rand::{RngExt, SeedableRng};

/// A copy of `scenarios/crater-floor-passage.toml` without zones (open ground) whose route is a seeded
/// random walk of `legs` steps of at most 3 m, kept 160 m inside the 1200 m map so every leg's
/// search window is whole.
fn walk(legs: usize) -> (PathBuf, tempfile::TempDir) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(26);
    let (mut x, mut y) = (600.0f64, 600.0f64);
    let mut points = Vec::with_capacity(legs + 1);
    for _ in 0..=legs {
        points.push(format!("[{x:.2}, {y:.2}]"));
        x = (x + rng.random_range(-3.0..3.0)).clamp(160.0, 1040.0);
        y = (y + rng.random_range(-3.0..3.0)).clamp(160.0, 1040.0);
    }
    let route = format!("waypoints = [{}]", points.join(", "));
    let (path, dir) = scenario_copy("crater-floor-passage.toml", |t| {
        let t = replace_line(&t, "zones = ", "zones = \"none.geojson\"");
        replace_line(&t, "waypoints = ", &route)
    });
    std::fs::write(
        dir.path().join("none.geojson"),
        r#"{"type": "FeatureCollection", "features": []}"#,
    )
    .expect("write");
    (path, dir)
}

#[test]
fn a_route_at_the_search_cap_validates_in_seconds() {
    let (scenario, _dir) = walk(3200);
    let started = Instant::now();
    let o = solsim()
        .args(["validate", "--json"])
        .arg(&scenario)
        .output()
        .expect("runs");
    let took = started.elapsed();
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(report["legs"].as_array().map(Vec::len), Some(3200));
    assert!(
        took < Duration::from_secs(4),
        "validate of 3200 legs took {took:?}; stderr: {}",
        stderr(&o)
    );
}

#[test]
fn routes_over_the_caps_are_refused_before_their_searches() {
    // 10 001 waypoints: refused from their count (they took 70 s to search before).
    let (scenario, _dir) = walk(10_000);
    let o = output_within(
        solsim().arg("validate").arg(&scenario),
        Duration::from_secs(30),
    );
    assert_bad_input(
        &o,
        &[
            "case.toml: route.waypoints: expected 2 ..= 10000 waypoints",
            "got 10001",
        ],
    );
    // 3400 legs of the 1 m grid: 3.1e8 cells of search windows, over the 3e8 cap.
    let (scenario, _dir) = walk(3400);
    let o = output_within(
        solsim().args(["run", "--no-files"]).arg(&scenario),
        Duration::from_secs(30),
    );
    assert_bad_input(
        &o,
        &[
            "case.toml: route.waypoints: expected a route whose legs' passage searches",
            "cover at most 300000000 grid cells together, got 3400 legs covering",
        ],
    );
}

#[test]
fn validate_and_run_draw_a_bar_over_the_legs_on_a_terminal_only() {
    let (scenario, _dir) = walk(3200);
    let path = scenario.to_string_lossy().into_owned();
    for (command, label) in [
        (vec!["validate", path.as_str()], "validate "),
        (vec!["run", "--no-files", path.as_str()], "run "),
    ] {
        if let Some(tty) = common::on_a_terminal(&command) {
            assert!(
                tty.contains(label) && tty.contains("/3200 legs"),
                "{command:?}: {tty:.2000}"
            );
        }
        let o = solsim().args(&command).output().expect("runs");
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        assert_eq!(stderr(&o), "", "nothing on a piped stderr");
    }
}
