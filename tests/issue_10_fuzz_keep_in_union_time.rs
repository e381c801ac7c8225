//! Issue 10 (found by the fuzzer): the keep-in union's boundary is computed on load in time
//! quadratic in overlapping keep-in edges, so a zones file of many overlapping keep-in copies,
//! far below the 16 MiB cap on text inputs, ran for minutes (8 000 copies, 1.7 MB: past 5 min;
//! 64 × 1 000 vertices: 29 s). Keep-in polygons are now limited to 10 000 vertices together
//! (the worst overlapping case at the limit loads in about a second): over it, exit 2 with one
//! line naming the file, while the limit itself still loads.

use crate::common;

use std::time::Duration;

use common::{assert_bad_input, output_within, solsim};

/// A FeatureCollection of `copies` keep-in circles of `vertices` vertices, nearly coincident.
fn overlapping_keep_ins(copies: usize, vertices: usize) -> String {
    let features: Vec<String> = (0..copies)
        .map(|i| {
            let r = 100.0 + 0.01 * i as f64;
            let mut ring: Vec<String> = (0..vertices)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / vertices as f64;
                    format!("[{}, {}]", 500.0 + r * a.cos(), 500.0 + r * a.sin())
                })
                .collect();
            ring.push(ring[0].clone());
            format!(
                r#"{{"type": "Feature", "properties": {{"name": "k{i}", "kind": "keep_in"}},
                    "geometry": {{"type": "Polygon", "coordinates": [[{}]]}}}}"#,
                ring.join(", ")
            )
        })
        .collect();
    format!(
        r#"{{"type": "FeatureCollection", "features": [{}]}}"#,
        features.join(", ")
    )
}

fn zones_check(zones: &str) -> std::process::Output {
    let dir = tempfile::tempdir().expect("tempdir");
    let z = dir.path().join("zones.geojson");
    let p = dir.path().join("points.csv");
    std::fs::write(&z, zones).expect("write");
    std::fs::write(&p, "x_m,y_m\n500,500\n").expect("write");
    output_within(
        solsim()
            .args(["zones", "check", "--zones"])
            .arg(&z)
            .arg("--points")
            .arg(&p),
        Duration::from_secs(60),
    )
}

#[test]
fn many_overlapping_keep_ins_are_refused_at_once() {
    // 64 × 1 000 vertices: 29 s before the limit.
    let o = zones_check(&overlapping_keep_ins(64, 1000));
    assert_bad_input(
        &o,
        &[
            "keep_in zones: expected at most 10000 vertices",
            "got 64000",
        ],
    );
}

#[test]
fn keep_ins_at_the_limit_still_load() {
    // 99 × 100 = 9 900 vertices (the closing point of a ring is not counted): under the limit.
    let o = zones_check(&overlapping_keep_ins(99, 100));
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
}
