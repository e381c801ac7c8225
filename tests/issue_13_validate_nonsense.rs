//! Issue 13: `validate` said `ok` to a scenario whose fields were each well formed but whose
//! whole was nonsense — a route or zones in longitude/latitude degrees, a waypoint inside a
//! keep-out (every leg then "closed at r = −1.65 m" and `compare` reported the goal reached in
//! one sol), a start outside the keep-in, a leg closed at r = 0. Each is now an error (exit 2,
//! listed by `validate`, refused by every other command with one line) or a warning where an
//! operator may mean it (issue 26: a waypoint whose footprint overlaps a zone is no longer one
//! of those; its legs are closed at r = 0).

use crate::common;

use std::path::PathBuf;
use std::process::Output;

use common::{assert_bad_input, rebase, root, solsim, stderr};

/// sols 383-386 (a 1200 × 1200 m map of 1 m cells; route (600, 60) → (600, 821)), with its
/// route and zones replaced when given, written with its zones into a new temporary directory.
struct Case {
    dir: tempfile::TempDir,
}

impl Case {
    fn new(waypoints: Option<&str>, zones: Option<&str>) -> Case {
        let dir = tempfile::tempdir().expect("tempdir");
        let mut text = rebase(
            &std::fs::read_to_string(root().join("scenarios/crater-floor-passage.toml"))
                .expect("read"),
        );
        if let Some(w) = waypoints {
            let start = text.find("waypoints = [").expect("waypoints");
            let end = start + text[start..].find('\n').expect("line end");
            text.replace_range(start..end, &format!("waypoints = {w}"));
        }
        if let Some(features) = zones {
            let path = dir.path().join("zones.geojson");
            std::fs::write(
                &path,
                format!(r#"{{"type": "FeatureCollection", "features": [{features}]}}"#),
            )
            .expect("zones");
            let start = text.find("zones = \"").expect("zones line");
            let end = start + text[start..].find('\n').expect("line end");
            text.replace_range(
                start..end,
                &format!("zones = {:?}", path.display().to_string()),
            );
        }
        std::fs::write(dir.path().join("case.toml"), text).expect("write");
        Case { dir }
    }

    fn path(&self) -> PathBuf {
        self.dir.path().join("case.toml")
    }

    fn validate(&self, json: bool) -> Output {
        let mut cmd = solsim();
        cmd.arg("validate").arg(self.path());
        if json {
            cmd.arg("--json");
        }
        cmd.output().expect("runs")
    }

    /// `compare` refuses the scenario with one error line naming it.
    fn compare_refuses(&self, must_contain: &[&str]) {
        let o = solsim()
            .arg("compare")
            .arg(self.path())
            .arg("--no-files")
            .output()
            .expect("runs");
        assert_bad_input(&o, must_contain);
        assert!(stderr(&o).contains("case.toml"), "{}", stderr(&o));
        assert!(o.stdout.is_empty(), "nothing printed on a refused scenario");
    }
}

fn polygon(kind: &str, name: &str, ring: &[[f64; 2]]) -> String {
    let coords: Vec<String> = ring
        .iter()
        .chain(std::iter::once(&ring[0]))
        .map(|p| format!("[{}, {}]", p[0], p[1]))
        .collect();
    format!(
        r#"{{"type": "Feature", "properties": {{"kind": "{kind}", "name": "{name}"}},
            "geometry": {{"type": "Polygon", "coordinates": [[{}]]}}}}"#,
        coords.join(", ")
    )
}

fn square(kind: &str, name: &str, x0: f64, y0: f64, x1: f64, y1: f64) -> String {
    polygon(kind, name, &[[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
}

/// `validate` exits 2 and lists an `error:` line holding every string of `must_contain`.
fn assert_validate_error(case: &Case, must_contain: &[&str]) -> String {
    let o = case.validate(false);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(o.status.code(), Some(2), "{out}{}", stderr(&o));
    let line = out
        .lines()
        .find(|l| l.contains(": error: ") && must_contain.iter().all(|s| l.contains(s)))
        .unwrap_or_else(|| panic!("no error line with {must_contain:?}:\n{out}"));
    assert!(out.contains("every other command refuses"), "{out}");
    line.to_string()
}

const DEGREES: &str = "[[77.4503, 18.4447], [77.4511, 18.4452], [77.4520, 18.4460]]";

#[test]
fn a_route_in_degrees_is_an_error() {
    let case = Case::new(Some(DEGREES), None);
    let line = assert_validate_error(&case, &["route.waypoints", "longitude/latitude degrees"]);
    assert!(line.contains("map metres"), "says what to do: {line}");
    case.compare_refuses(&["route.waypoints", "degrees"]);
}

#[test]
fn zones_in_degrees_are_an_error() {
    let zones = [
        square("keep_out", "crater", 77.450, 18.444, 77.451, 18.445),
        square("keep_out", "ridge", 77.452, 18.446, 77.4525, 18.4465),
    ]
    .join(",");
    let case = Case::new(None, Some(&zones));
    assert_validate_error(&case, &["map.zones", "2 zones within one cell", "degrees"]);
    case.compare_refuses(&["map.zones"]);
}

#[test]
fn a_zone_off_the_map_is_an_error() {
    let zones = square("keep_out", "far crater", 5000.0, 5000.0, 5100.0, 5100.0);
    let case = Case::new(None, Some(&zones));
    assert_validate_error(&case, &["\"far crater\"", "entirely off the map"]);
}

#[test]
fn a_waypoint_inside_a_keep_out_is_an_error() {
    // Waypoint 2, (600, 545), inside a keep-out around it; before, every leg "closed at
    // r = −1.65 m" and compare reported the goal reached in one sol.
    let zones = square("keep_out", "boulder field", 580.0, 530.0, 620.0, 560.0);
    let case = Case::new(None, Some(&zones));
    let line = assert_validate_error(
        &case,
        &["route.waypoints[2]", "inside keep-out \"boulder field\""],
    );
    assert!(line.contains("AutoNav can never reach it"), "{line}");
    case.compare_refuses(&["route.waypoints[2]", "boulder field"]);
}

#[test]
fn a_start_outside_the_keep_in_is_an_error() {
    let zones = square("keep_in", "corridor", 500.0, 100.0, 700.0, 1000.0);
    let case = Case::new(None, Some(&zones));
    let line = assert_validate_error(
        &case,
        &["route.waypoints[0]", "the start inside the keep-in"],
    );
    assert!(line.contains("KEEP_IN fault"), "{line}");
}

#[test]
fn a_waypoint_outside_the_keep_in_is_an_error() {
    let zones = square("keep_in", "corridor", 500.0, 0.0, 700.0, 700.0);
    let case = Case::new(None, Some(&zones));
    assert_validate_error(&case, &["route.waypoints[3]", "outside every keep-in"]);
}

#[test]
fn a_leg_closed_at_zero_radius_is_an_error() {
    // A keep-out wall across the whole map between waypoints 1 (y 320) and 2 (y 545).
    let zones = square("keep_out", "scarp", 0.0, 400.0, 1200.0, 420.0);
    let case = Case::new(None, Some(&zones));
    let line = assert_validate_error(&case, &["route.waypoints[1..=2]", "r = 0"]);
    assert!(line.contains("NO_PATH"), "{line}");
    case.compare_refuses(&["route.waypoints[1..=2]"]);
}

/// A waypoint whose footprint overlaps a zone was a warning ("the rover stops short of it"),
/// but AutoNav plans to the waypoint's cell, closed there even at r = 0: every strategy drove
/// 0 m. Issue 26 made its legs the "no path at r = 0" error, with the overlap as the cause
/// (`tests/issue_26_keep_in_sliver.rs`). A zone smaller than a cell is still a warning.
#[test]
fn a_waypoint_touching_a_zone_closes_its_legs_and_a_tiny_zone_is_a_warning() {
    // Waypoint 1 is (590, 320): a keep-out 1 m east of it overlaps the 1.5 m footprint. A
    // 0.5 m keep-out is smaller than a 1 m cell.
    let zones = [
        square("keep_out", "rock", 591.0, 300.0, 600.0, 340.0),
        square("keep_out", "pebble", 900.0, 900.0, 900.5, 900.5),
    ]
    .join(",");
    let case = Case::new(None, Some(&zones));
    let o = case.validate(false);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(2), "{out}{}", stderr(&o));
    assert!(out.contains("2 errors, 1 warning"), "{out}");
    for leg in ["[0..=1]", "[1..=2]"] {
        assert!(
            out.lines()
                .any(|l| l.contains(&format!(": error: route.waypoints{leg}"))
                    && l.contains("at waypoint 1 [590, 320] the footprint overlaps a zone")),
            "{out}"
        );
    }
    assert!(
        out.lines()
            .any(|l| l.contains(": warning: map.zones: keep_out \"pebble\"")),
        "{out}"
    );
    // A warning refuses nothing: the pebble and a rock clear of the route.
    let zones = [
        square("keep_out", "rock", 100.0, 300.0, 110.0, 340.0),
        square("keep_out", "pebble", 900.0, 900.0, 900.5, 900.5),
    ]
    .join(",");
    let case = Case::new(None, Some(&zones));
    let o = solsim()
        .arg("run")
        .arg(case.path())
        .args(["--strategy", "ground", "--no-files"])
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn validate_json_lists_every_finding() {
    let zones = [
        square("keep_out", "boulder field", 580.0, 530.0, 620.0, 560.0),
        square("keep_out", "far crater", 5000.0, 5000.0, 5100.0, 5100.0),
        square("keep_out", "pebble", 900.0, 900.0, 900.5, 900.5),
    ]
    .join(",");
    let case = Case::new(None, Some(&zones));
    let o = case.validate(true);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(v["ok"], false);
    assert_eq!(v["errors"], 2, "{v:#}");
    assert_eq!(v["warnings"], 1, "{v:#}");
    let findings = v["findings"].as_array().expect("findings");
    let fields: Vec<&str> = findings
        .iter()
        .map(|f| f["field"].as_str().expect("field"))
        .collect();
    assert!(
        fields.iter().any(|f| f.contains("far crater")),
        "{fields:?}"
    );
    assert!(fields.contains(&"route.waypoints[2]"), "{fields:?}");
    for f in findings {
        for key in ["severity", "field", "expected", "got", "hint"] {
            assert!(f[key].is_string(), "{key} in {f}");
        }
    }
    // Errors come before warnings.
    assert_eq!(findings[2]["severity"], "warning");
    assert_eq!(v["scenario"]["waypoints"], 5);
    assert_eq!(v["legs"].as_array().map(Vec::len), Some(4));
}

#[test]
fn every_bundled_scenario_is_free_of_errors_and_warnings() {
    for entry in std::fs::read_dir(root().join("scenarios")).expect("scenarios") {
        let path = entry.expect("entry").path();
        if path.extension().and_then(|e| e.to_str()) != Some("toml") {
            continue;
        }
        let o = solsim()
            .arg("validate")
            .arg(&path)
            .arg("--json")
            .output()
            .expect("runs");
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}: {}",
            path.display(),
            stderr(&o)
        );
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
        assert_eq!(v["findings"], serde_json::json!([]), "{}", path.display());
    }
}
