//! Issue 10, found by `tests/fuzz_parsers.rs`: a waypoint a hair inside the map's south edge
//! (`[600.0, 1e-60]` on the crater-floor map, whose south edge is y = 0) passed the loader's
//! on-map check (`y > y0`) but lies in no planning-grid cell (`(1200 - 1e-60) / res` rounds to
//! the grid's height), so `Scenario::load` failed with the simulator's own
//! `ScenarioError::Campaign` (`route[0]: expected a point on the planning grid, got [600,
//! 0.000…01]`), the variant that "is a bug in the loader if it ever shows". The loader now
//! checks the route against the grid it built: the error names `route.waypoints[0]`.

use crate::common;

use study::{Scenario, ScenarioError};

#[test]
fn a_waypoint_within_rounding_of_the_south_edge_is_a_field_error() {
    let (path, _dir) = common::scenario_copy("crater-floor-passage.toml", |t| {
        assert!(t.contains("waypoints = [[600.0, 60.0],"));
        t.replace(
            "waypoints = [[600.0, 60.0],",
            "waypoints = [[600.0, 1e-60],",
        )
    });
    let err = Scenario::load(&path).expect_err("a start in no grid cell");
    match &err {
        ScenarioError::Field {
            field, expected, ..
        } => {
            assert_eq!(field, "route.waypoints[0]", "{err}");
            assert!(expected.contains("a point on the map"), "{err}");
        }
        other => panic!("expected a field error naming the waypoint, got {other}"),
    }
}

#[test]
fn a_waypoint_just_inside_the_edge_still_loads() {
    let (path, dir) = common::scenario_copy("crater-floor-passage.toml", |t| {
        t.replace("waypoints = [[600.0, 60.0],", "waypoints = [[600.0, 0.5],")
    });
    // The scenario's keep-in corridor starts 20 m north of the edge, and a start outside it is
    // refused (issue 13): this case is about the map's edge, so it has no zones.
    let zones = dir.path().join("no-zones.geojson");
    std::fs::write(&zones, r#"{"type": "FeatureCollection", "features": []}"#).expect("zones");
    let text = std::fs::read_to_string(&path).expect("read");
    let start = text.find("zones = \"").expect("zones line");
    let end = start + text[start..].find('\n').expect("line end");
    let text = format!(
        "{}zones = {:?}{}",
        &text[..start],
        zones.display().to_string(),
        &text[end..]
    );
    std::fs::write(&path, text).expect("write");
    Scenario::load(&path).expect("a start half a metre inside the map");
}
