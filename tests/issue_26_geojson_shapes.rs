//! Issue 26, finding 12: 3-D waypoints and an empty MultiPolygon were accepted. A zone vertex
//! `[x, y, z]` and a route waypoint `[x, y, z]` lost their third number without a word (serde's
//! `[f64; 2]` reads the first two numbers of a longer array), and a keep-out whose MultiPolygon
//! held no polygon loaded as a zone with no area. Each is refused: a zone with the feature
//! index and the position named, a waypoint with its line and column.

use crate::common::{assert_bad_input, root, scenario_copy, solsim};

fn zones_check(features: &str) -> std::process::Output {
    let dir = tempfile::tempdir().expect("tempdir");
    let zones = dir.path().join("zones.geojson");
    std::fs::write(
        &zones,
        format!(r#"{{"type": "FeatureCollection", "features": [{features}]}}"#),
    )
    .expect("write");
    solsim()
        .args(["zones", "check", "--zones"])
        .arg(&zones)
        .arg("--points")
        .arg(root().join("peers/zones_fixtures/points.csv"))
        .output()
        .expect("runs")
}

const SQUARE: &str = r#"{"type": "Feature", "properties": {"name": "ok", "kind": "keep_out"},
    "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]]]}}"#;

#[test]
fn a_zone_vertex_with_an_altitude_is_refused_with_its_feature() {
    let o = zones_check(&format!(
        r#"{SQUARE}, {{"type": "Feature", "properties": {{"name": "rock", "kind": "keep_out"}},
        "geometry": {{"type": "Polygon", "coordinates":
        [[[20, 20, 0], [30, 20, 0], [30, 30, 5], [20, 30, 0], [20, 20, 0]]]}}}}"#
    ));
    assert_bad_input(
        &o,
        &[
            "features[1] (\"rock\").geometry.coordinates[0][0]",
            "position has 3 number(s)",
            "expected [x, y]",
        ],
    );
    // One 3-D vertex among 2-D ones, in a MultiPolygon.
    let o = zones_check(
        r#"{"type": "Feature", "properties": {"name": "dune", "kind": "keep_in"},
        "geometry": {"type": "MultiPolygon", "coordinates":
        [[[[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]]],
         [[[20, 20], [30, 20], [30, 30, 1.5], [20, 30], [20, 20]]]]}}"#,
    );
    assert_bad_input(
        &o,
        &[
            "features[0] (\"dune\").geometry.coordinates[1][0][2]",
            "position has 3 number(s)",
        ],
    );
}

#[test]
fn an_empty_multipolygon_is_refused_with_its_feature() {
    let o = zones_check(&format!(
        r#"{SQUARE}, {SQUARE}, {{"type": "Feature", "properties": {{"name": "nothing", "kind": "keep_out"}},
        "geometry": {{"type": "MultiPolygon", "coordinates": []}}}}"#
    ));
    assert_bad_input(
        &o,
        &[
            "features[2] (\"nothing\").geometry.coordinates",
            "MultiPolygon has no polygons",
        ],
    );
    // A Polygon without rings, as before.
    let o = zones_check(
        r#"{"type": "Feature", "properties": {"kind": "keep_out"},
        "geometry": {"type": "Polygon", "coordinates": []}}"#,
    );
    assert_bad_input(
        &o,
        &["features[0] (\"zone-0\").geometry.coordinates: polygon has no rings"],
    );
}

#[test]
fn a_3d_waypoint_or_map_origin_is_refused() {
    let o = {
        let (path, _d) = scenario_copy("crater-floor-passage.toml", |t| {
            t.replace("[590.0, 320.0]", "[590.0, 320.0, 12.5]")
        });
        solsim().arg("validate").arg(&path).output().expect("runs")
    };
    assert_bad_input(
        &o,
        &[
            "case.toml: line ",
            "waypoints = [",
            "invalid length 3, expected [x, y]: exactly two numbers",
        ],
    );
    // A waypoint of one number, and a map origin of three.
    for (from, to) in [
        ("[590.0, 320.0]", "[590.0]"),
        (
            "zones = ",
            "resolution_m_per_px = 2.0\norigin_m = [0.0, 1200.0, 0.0]\nzones = ",
        ),
    ] {
        let (path, _d) = scenario_copy("crater-floor-passage.toml", |t| t.replacen(from, to, 1));
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        assert_bad_input(
            &o,
            &["invalid length", "expected [x, y]: exactly two numbers"],
        );
    }
}

#[test]
fn a_3d_science_target_is_refused() {
    let path = root().join("scenarios/self-reliant-campaign.toml");
    let text = std::fs::read_to_string(&path).expect("read");
    let at = text.find("position_m = [").expect("a target") + "position_m = [".len();
    let edited = format!("{}7.0, {}", &text[..at], &text[at..]);
    let e = study::scenario::ScenarioSpec::from_toml_str(&path, &edited)
        .expect_err("three numbers")
        .to_string();
    assert!(e.contains("invalid length 3, expected [x, y]"), "{e}");
}
