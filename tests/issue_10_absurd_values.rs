//! Issue 10: finite but absurd values passed the loaders — a zone vertex at x = 1e20 gave
//! wrong keep-out distances in the unsafe direction with exit 0; `k_vo = 1e300` and
//! `grid.resolution_m = 1e9` ran to nonsense. Every parameter now has a physical range and
//! every coordinate a bound (±11 000 km of map metres: off Mars beyond it): exit 2, one line
//! naming the field and what is allowed, the number printed readably.

use crate::common;

use common::{assert_bad_input, root, scenario_copy, solsim};

fn validate(edit: impl Fn(String) -> String) -> std::process::Output {
    let (path, _d) = scenario_copy("crater-floor-passage.toml", edit);
    solsim().arg("validate").arg(&path).output().expect("runs")
}

#[test]
fn k_vo_of_1e300_is_refused() {
    let o = validate(|t| t.replace("k_vo = 0.05", "k_vo = 1e300"));
    assert_bad_input(
        &o,
        &[
            "uncertainty.k_vo",
            "expected 0 ..= 1 metres per metre",
            "got 1e300",
        ],
    );
}

#[test]
fn a_grid_cell_of_1e9_m_is_refused() {
    let o = validate(|t| t.replace("resolution_m = 1.0", "resolution_m = 1e9"));
    assert_bad_input(
        &o,
        &[
            "grid.resolution_m",
            "expected 0.01 ..= 50 metres",
            "got 1e9",
        ],
    );
}

#[test]
fn a_waypoint_at_1e20_is_refused_with_its_index() {
    let o = validate(|t| {
        let at = t.find("waypoints = [").expect("route") + "waypoints = [".len();
        format!("{}[1e20, 5.0], {}", &t[..at], &t[at..])
    });
    assert_bad_input(&o, &["route.waypoints[0][0]", "map metres", "got 1e20"]);
}

#[test]
fn a_zone_vertex_at_1e20_is_refused_not_measured() {
    let dir = tempfile::tempdir().expect("tempdir");
    let zones = dir.path().join("zones.geojson");
    std::fs::write(
        &zones,
        r#"{"type": "FeatureCollection", "features": [{"type": "Feature",
            "properties": {"name": "far", "kind": "keep_out"},
            "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1e20, 0], [0, 10], [0, 0]]]}}]}"#,
    )
    .expect("write");
    let o = solsim()
        .args(["zones", "check", "--zones"])
        .arg(&zones)
        .arg("--points")
        .arg(root().join("peers/zones_fixtures/points.csv"))
        .output()
        .expect("runs");
    assert_bad_input(
        &o,
        &[
            "features[0] (\"far\").geometry.coordinates[0][1][0]",
            "expected x within ±11000000 m",
            "got 1e20",
        ],
    );
}

#[test]
fn points_beyond_mars_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let points = dir.path().join("points.csv");
    std::fs::write(&points, "x_m,y_m\n1e300,5\n").expect("write");
    let o = solsim()
        .args(["zones", "check", "--zones"])
        .arg(root().join("peers/zones_fixtures/zones.geojson"))
        .arg("--points")
        .arg(&points)
        .output()
        .expect("runs");
    assert_bad_input(
        &o,
        &["line 2, column x_m", "within ±11000000", "got \"1e300\""],
    );
}

#[test]
fn recipe_values_have_physical_ranges() {
    let dir = tempfile::tempdir().expect("tempdir");
    let recipe = dir.path().join("recipe.toml");
    let text =
        std::fs::read_to_string(root().join("maps/assets/crater-floor/recipe.toml")).expect("read");
    std::fs::write(&recipe, text.replace("relief_m = 12.0", "relief_m = 1e300")).expect("write");
    let o = solsim()
        .args(["map", "generate"])
        .arg(&recipe)
        .arg("--out")
        .arg(dir.path().join("map"))
        .output()
        .expect("runs");
    assert_bad_input(
        &o,
        &["terrain.relief_m", "0 ..= 100000 metres", "got 1e300"],
    );
    assert!(!dir.path().join("map").exists(), "nothing written");
}
