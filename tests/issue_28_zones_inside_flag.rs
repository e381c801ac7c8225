//! Issue 28: `solsim zones check` printed `max_uncertainty_m −1.650` for a point inside a
//! keep-out, with nothing saying the point was inside: −1.65 read as "1.65 m into the zone",
//! while it is the distance 0 minus the footprint radius, however deep the point lies. Each
//! point now has a status — clear, footprint touches a zone, inside keep-out (its names),
//! outside keep-in — in the table and, with the flags `inside_keep_out` and `outside_keep_in`,
//! in the JSON; a line under the table says what the sign of the number means.

use crate::common;

use common::{root, run_ok};

fn check(json: bool) -> String {
    let zones = root().join("peers/zones_fixtures/zones.geojson");
    let points = root().join("peers/zones_fixtures/points.csv");
    let mut args = vec!["zones", "check", "--footprint-radius-m", "1.65"];
    if json {
        args.push("--json");
    }
    run_ok(
        &args,
        &[
            std::path::Path::new("--zones"),
            &zones,
            std::path::Path::new("--points"),
            &points,
        ],
    )
}

#[test]
fn a_point_inside_a_keep_out_is_flagged_in_the_table() {
    let text = check(false);
    let row = |name: &str| {
        text.lines()
            .find(|l| l.starts_with(&format!("{name}  ")))
            .unwrap_or_else(|| panic!("{name} in\n{text}"))
            .to_string()
    };
    let inside = row("L inside");
    assert!(
        inside.contains("-1.650") && inside.ends_with("  inside keep-out (L ridge)"),
        "{inside}"
    );
    assert!(row("spur overlap").ends_with("  inside keep-out (L ridge, dune spur)"));
    assert!(row("L notch").ends_with("  clear"), "{}", row("L notch"));
    assert!(text.lines().next().is_some_and(|h| h.ends_with("  status")));
    let last = text.lines().last().expect("lines");
    assert!(
        last.starts_with("max_uncertainty_m = min(keep_out_distance_m, keep_in_edge_distance_m) − footprint radius")
            && last.contains("not a depth"),
        "the sign convention under the table: {last}"
    );
}

#[test]
fn the_json_flags_agree_with_the_distances() {
    let rows: Vec<serde_json::Value> = serde_json::from_str(&check(true)).expect("JSON");
    let mut kinds = std::collections::BTreeSet::new();
    for r in &rows {
        let inside = r["inside_keep_out"].as_bool().expect("inside_keep_out");
        let outside = r["outside_keep_in"].as_bool().expect("outside_keep_in");
        let status = r["status"].as_str().expect("status");
        let keep_out = r["keep_out_distance_m"].as_f64();
        let keep_in = r["keep_in_edge_distance_m"].as_f64();
        let max = r["max_uncertainty_m"].as_f64().expect("finite here");
        // Inside a keep-out the distance is 0; outside the keep-in area its edge distance is.
        if inside {
            assert_eq!(keep_out, Some(0.0), "{r}");
            assert!(status.starts_with("inside keep-out ("), "{r}");
        }
        if outside {
            assert_eq!(keep_in, Some(0.0), "{r}");
            assert!(status.contains("outside keep-in"), "{r}");
        }
        if inside || outside {
            assert!((max + 1.65).abs() < 1e-9, "minus the footprint radius: {r}");
        } else if max < 0.0 {
            assert_eq!(status, "footprint touches a zone", "{r}");
        } else {
            assert_eq!(status, "clear", "{r}");
        }
        kinds.insert(status.split(" (").next().unwrap_or(status).to_string());
    }
    assert!(
        kinds.contains("clear")
            && kinds.contains("inside keep-out")
            && kinds.contains("outside keep-in"),
        "the fixtures cover each status: {kinds:?}"
    );
}
