//! Zones end to end: distances against shapely (the committed `peers/zones_fixtures` table),
//! hand-computed cases, an independent overlay cross-check for overlapping keep-ins, rasterisation,
//! validation errors, and query speed.

use maps::{GeoTransform, ZoneError, ZoneSet};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[path = "../../tests/common/external.rs"]
mod external;
use std::time::Instant;

/// Footprint radius the committed shapely table was made with (see `peers/zones_reference.py`).
const FIXTURE_FOOTPRINT_M: f64 = 0.75;

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../peers/zones_fixtures")
}

fn collection(features: &[String]) -> String {
    format!(
        r#"{{"type": "FeatureCollection", "features": [{}]}}"#,
        features.join(",\n")
    )
}

/// A feature with one polygon; `rings` are closed coordinate lists.
fn polygon_feature(kind: &str, name: &str, rings: &[&[[f64; 2]]]) -> String {
    let rings: Vec<String> = rings
        .iter()
        .map(|r| {
            let pts: Vec<String> = r
                .iter()
                .map(|p| format!("[{:?}, {:?}]", p[0], p[1]))
                .collect();
            format!("[{}]", pts.join(", "))
        })
        .collect();
    format!(
        r#"{{"type": "Feature", "properties": {{"kind": "{kind}", "name": "{name}"}},
            "geometry": {{"type": "Polygon", "coordinates": [{}]}}}}"#,
        rings.join(", ")
    )
}

fn zones(features: &[String]) -> ZoneSet {
    ZoneSet::from_geojson_str(&collection(features), Path::new("test.geojson"))
        .expect("valid zones")
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]
}

fn assert_close(actual: f64, expected: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= 1e-12,
        "{what}: got {actual}, expected {expected}"
    );
}

// ---------------------------------------------------------------------------------------------
// Against shapely

/// Parse a shapely number: `inf` or a float.
fn number(text: &str) -> f64 {
    text.parse()
        .unwrap_or_else(|e| panic!("bad number {text:?}: {e}"))
}

#[test]
fn matches_shapely_reference_table() {
    let zones = ZoneSet::load(&fixtures().join("zones.geojson")).expect("fixture zones load");
    let table = std::fs::read_to_string(fixtures().join("expected_shapely.csv"))
        .expect("expected_shapely.csv");
    let mut lines = table.lines();
    assert_eq!(
        lines.next(),
        Some("name,x_m,y_m,keep_out_distance_m,keep_in_edge_distance_m,max_uncertainty_m")
    );
    let (mut rows, mut inside_keep_in, mut worst) = (0, 0, 0.0f64);
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 6, "fixture names contain no commas: {line}");
        let p = [number(f[1]), number(f[2])];
        let expected = [number(f[3]), number(f[4]), number(f[5])];
        let c = zones.clearance(p, FIXTURE_FOOTPRINT_M);
        let actual = [
            c.keep_out_distance_m,
            c.keep_in_edge_distance_m,
            c.max_uncertainty_m,
        ];
        for (k, (a, e)) in actual.iter().zip(expected).enumerate() {
            if e.is_infinite() {
                assert_eq!(*a, e, "{}: column {k}", f[0]);
            } else {
                let diff = (a - e).abs();
                worst = worst.max(diff);
                // The brief's requirement is 1 cm; both sides are exact up to rounding.
                assert!(
                    diff <= 1e-9,
                    "{} at {p:?}: column {k}: rust {a}, shapely {e}",
                    f[0]
                );
            }
        }
        rows += 1;
        inside_keep_in += usize::from(expected[1] > 0.0);
    }
    assert_eq!(rows, 228);
    assert!(
        inside_keep_in > 60,
        "the fixture should probe the keep-in union: {inside_keep_in}"
    );
    eprintln!("shapely comparison: {rows} points, worst difference {worst:e} m");
}

/// Re-runs shapely (in `peers/.venv`, made by `python3 peers/setup_venv.py`) and checks the
/// committed table is what it prints today. Without the venv the test fails, unless the run
/// opted out of the external checks (`scripts/test.sh --skip-external`, counted).
#[test]
fn committed_shapely_table_is_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let Some(python) = external::peers_python(&root, "re-running shapely on the zones fixtures")
    else {
        return;
    };
    let output = std::process::Command::new(python)
        .arg(root.join("peers/zones_reference.py"))
        .arg(fixtures().join("zones.geojson"))
        .arg(fixtures().join("points.csv"))
        .args([
            "--footprint-radius-m",
            &FIXTURE_FOOTPRINT_M.to_string(),
            "--csv",
        ])
        .output()
        .expect("run zones_reference.py");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let committed =
        std::fs::read_to_string(fixtures().join("expected_shapely.csv")).expect("table");
    assert_eq!(
        String::from_utf8_lossy(&output.stdout),
        committed,
        "regenerate expected_shapely.csv"
    );
}

// ---------------------------------------------------------------------------------------------
// Hand-computed cases

/// Keep-out square 0..100 with a hole 30..70 (a crater rim around a drivable floor).
#[test]
fn square_with_hole_by_hand() {
    let shell = rect(0.0, 0.0, 100.0, 100.0);
    let hole = rect(30.0, 30.0, 70.0, 70.0);
    let z = zones(&[polygon_feature("keep_out", "rim", &[&shell, &hole])]);
    let d = |x, y| z.distance_to_keep_out_m([x, y]);
    assert_eq!(d(50.0, 50.0), 20.0); // hole centre: 20 m to every hole edge
    assert_eq!(d(35.0, 50.0), 5.0); // in the hole, 5 m east of x = 30
    assert_eq!(d(30.0, 50.0), 0.0); // on the hole's edge
    assert_eq!(d(20.0, 50.0), 0.0); // in the rim
    assert_eq!(d(110.0, 50.0), 10.0); // 10 m east of x = 100
    assert_eq!(d(-6.0, -8.0), 10.0); // nearest is the corner (0, 0): √(36 + 64)
    assert!(z.in_keep_out([20.0, 50.0]) && !z.in_keep_out([50.0, 50.0]));
    assert_eq!(z.max_uncertainty_m([50.0, 50.0], 1.5), 18.5); // no keep-ins: 20 − 1.5

    // The same shape as a keep-in: drivable rim, forbidden floor.
    let z = zones(&[polygon_feature("keep_in", "rim", &[&shell, &hole])]);
    let e = |x, y| z.distance_to_keep_in_edge_m([x, y]);
    assert_eq!(e(20.0, 50.0), 10.0); // 20 to x = 0, 10 to the hole's x = 30
    assert_eq!(e(50.0, 15.0), 15.0); // 15 to y = 0 and to the hole's y = 30
    assert_eq!(e(5.0, 5.0), 5.0);
    assert_eq!(e(50.0, 50.0), 0.0); // in the hole: outside the keep-in
    assert_eq!(e(150.0, 50.0), 0.0);
    assert_eq!(z.distance_to_keep_out_m([50.0, 50.0]), f64::INFINITY);
    assert_eq!(z.max_uncertainty_m([20.0, 50.0], 2.0), 8.0);
    assert!(!z.in_keep_in([50.0, 50.0]) && z.in_keep_in([100.0, 100.0]));
}

/// An L: foot 0..40 × 0..10, upright 0..10 × 0..30; re-entrant corner at (10, 10).
#[test]
fn l_shape_by_hand() {
    let l = [
        [0.0, 0.0],
        [40.0, 0.0],
        [40.0, 10.0],
        [10.0, 10.0],
        [10.0, 30.0],
        [0.0, 30.0],
        [0.0, 0.0],
    ];
    let z = zones(&[polygon_feature("keep_out", "L", &[&l])]);
    let d = |x, y| z.distance_to_keep_out_m([x, y]);
    assert_eq!(d(25.0, 20.0), 10.0); // in the notch: 10 to y = 10, 15 to x = 10
    assert_eq!(d(20.0, 25.0), 10.0); // 10 to x = 10, 15 to y = 10
    assert_eq!(d(13.0, 13.0), 3.0); // 3 to both inner edges
    assert_close(
        d(50.0, 20.0),
        200f64.sqrt(),
        "past the corner (40, 10): √(10² + 10²)",
    );
    assert_eq!(d(-3.0, -4.0), 5.0); // corner (0, 0): 3-4-5
    assert_eq!(d(5.0, 5.0), 0.0);
    assert_eq!(d(5.0, 30.0), 0.0); // on the top edge
    assert_eq!(d(10.0, 10.0), 0.0); // on the re-entrant vertex

    let z = zones(&[polygon_feature("keep_in", "L", &[&l])]);
    let e = |x, y| z.distance_to_keep_in_edge_m([x, y]);
    assert_eq!(e(5.0, 20.0), 5.0); // upright: 5 to x = 0 and x = 10
    assert_eq!(e(30.0, 5.0), 5.0); // foot: 5 to y = 0 and y = 10
    // Near the re-entrant corner the nearest edge point is the corner itself: √(2² + 2²).
    assert_close(e(8.0, 8.0), 8f64.sqrt(), "to the re-entrant corner");
    assert_eq!(e(25.0, 20.0), 0.0); // in the notch: outside
}

/// Overlapping and abutting keep-ins act as their union: inner edges do not count.
#[test]
fn keep_in_union_by_hand() {
    // [0,20]² ∪ [10,30]²: from (19, 15) the nearest edge point of the union is the concave corner
    // (20, 10), √(1² + 5²); per-polygon reasoning would say 5 (K1's right edge is inside K2).
    let z = zones(&[
        polygon_feature("keep_in", "a", &[&rect(0.0, 0.0, 20.0, 20.0)]),
        polygon_feature("keep_in", "b", &[&rect(10.0, 10.0, 30.0, 30.0)]),
    ]);
    assert_close(
        z.distance_to_keep_in_edge_m([19.0, 15.0]),
        26f64.sqrt(),
        "concave corner",
    );
    // From (15, 15) both concave corners (20, 10) and (10, 20) are √(5² + 5²) away; the nearer
    // edges x = 20 and y = 20 of `a` lie inside `b` there.
    assert_close(
        z.distance_to_keep_in_edge_m([15.0, 15.0]),
        50f64.sqrt(),
        "between the corners",
    );
    assert_eq!(z.distance_to_keep_in_edge_m([25.0, 5.0]), 0.0); // outside both

    // Two 10 × 10 squares sharing the edge x = 10: a point on it is 5 m from the union's edge.
    let z = zones(&[
        polygon_feature("keep_in", "west", &[&rect(0.0, 0.0, 10.0, 10.0)]),
        polygon_feature("keep_in", "east", &[&rect(10.0, 0.0, 20.0, 10.0)]),
    ]);
    assert_eq!(z.distance_to_keep_in_edge_m([10.0, 5.0]), 5.0);
    assert_eq!(z.distance_to_keep_in_edge_m([9.0, 4.0]), 4.0);
    assert_eq!(z.distance_to_keep_in_edge_m([10.0, 10.0]), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Cross-check: random overlapping polygons against geo's overlay

/// A random star-shaped polygon (simple by construction) around `centre`.
fn star(rng: &mut ChaCha8Rng, centre: [f64; 2], radius: f64, n: usize) -> Vec<[f64; 2]> {
    let mut ring: Vec<[f64; 2]> = (0..n)
        .map(|k| {
            let angle = (k as f64 + rng.random_range(0.0..0.8)) * std::f64::consts::TAU / n as f64;
            let r = radius * rng.random_range(0.3..1.0);
            [centre[0] + r * angle.cos(), centre[1] + r * angle.sin()]
        })
        .collect();
    ring.push(ring[0]);
    ring
}

#[test]
fn random_keep_ins_match_geo_union() {
    use geo::{Distance, Euclidean, LineString, Point, Polygon};
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    for case in 0..10 {
        let rings: Vec<Vec<[f64; 2]>> = (0..6)
            .map(|_| {
                let c = [rng.random_range(0.0..100.0), rng.random_range(0.0..100.0)];
                let n = rng.random_range(5..25);
                let radius = rng.random_range(10.0..40.0);
                star(&mut rng, c, radius, n)
            })
            .collect();
        let features: Vec<String> = rings
            .iter()
            .enumerate()
            .map(|(i, r)| polygon_feature("keep_in", &format!("s{i}"), &[r]))
            .collect();
        let z = zones(&features);
        let polys: Vec<Polygon<f64>> = rings
            .iter()
            .map(|r| Polygon::new(LineString::from(r.clone()), vec![]))
            .collect();
        let union = geo::unary_union(&polys);
        let edges: Vec<&LineString<f64>> = union
            .0
            .iter()
            .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
            .collect();
        for _ in 0..300 {
            let p = [
                rng.random_range(-20.0..120.0),
                rng.random_range(-20.0..120.0),
            ];
            let ours = z.distance_to_keep_in_edge_m(p);
            if ours == 0.0 {
                continue;
            }
            let theirs = edges
                .iter()
                .map(|e| Euclidean.distance(&Point::from(p), *e))
                .fold(f64::INFINITY, f64::min);
            // geo's overlay snaps vertices to a grid of ~2⁻²⁹ of the extent (≈ 1e-7 m here).
            assert!(
                (ours - theirs).abs() < 1e-5,
                "case {case} at {p:?}: {ours} vs geo {theirs}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Rasterisation

#[test]
fn rasterize_fixture_agrees_with_point_queries() {
    let z = ZoneSet::load(&fixtures().join("zones.geojson")).expect("fixture");
    // 0.7 m cells over the whole fixture.
    let geo = GeoTransform::new(-40.3, 450.1, 0.7);
    let (w, h) = (860, 700);
    let (keep_out, keep_in) = z.rasterize(geo, w, h);
    assert_eq!((keep_out.len(), keep_in.len()), (w * h, w * h));
    let (mut mismatches, mut on_edges) = (0, 0);
    for row in 0..h {
        for col in 0..w {
            let (x, y) = geo.center_of(col, row);
            // A centre on an edge may go either way; compare only centres clear of every edge.
            let near = [[x + 1e-6, y], [x - 1e-6, y], [x, y + 1e-6], [x, y - 1e-6]];
            if near.iter().any(|&q| {
                z.in_keep_out(q) != z.in_keep_out([x, y]) || z.in_keep_in(q) != z.in_keep_in([x, y])
            }) {
                on_edges += 1;
                continue;
            }
            mismatches += usize::from(keep_out[row * w + col] != z.in_keep_out([x, y]));
            mismatches += usize::from(keep_in[row * w + col] != z.in_keep_in([x, y]));
        }
    }
    assert_eq!(mismatches, 0);
    assert!(on_edges < 10, "{on_edges} centres on edges");
    // Same cells on one thread as on many.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    assert!(pool.install(|| z.rasterize(geo, w, h)) == (keep_out.clone(), keep_in.clone()));
    assert!(keep_out.iter().filter(|&&c| c).count() > 10_000);
}

// ---------------------------------------------------------------------------------------------
// Errors: each names the file and the field, on one line

fn load_error(text: &str) -> (String, ZoneError) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("bad_zones.geojson");
    std::fs::write(&path, text).expect("write");
    let err = ZoneSet::load(&path).expect_err("should be rejected");
    let message = err.to_string();
    assert!(
        message.contains("bad_zones.geojson"),
        "names the file: {message}"
    );
    assert!(!message.contains('\n'), "one line: {message}");
    (message, err)
}

fn raw_feature(kind: &str, geometry: &str) -> String {
    format!(
        r#"{{"type": "FeatureCollection", "features": [
  {{"type": "Feature", "properties": {{"kind": "keep_out", "name": "ok"}},
    "geometry": {{"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}}}},
  {{"type": "Feature", "properties": {{"kind": "{kind}", "name": "dune west"}},
    "geometry": {geometry}}}
]}}"#
    )
}

#[test]
fn nan_coordinate_is_rejected_with_its_position() {
    let (msg, err) = load_error(&raw_feature(
        "keep_out",
        r#"{"type": "Polygon", "coordinates": [[[0, 0], [10, 0], [NaN, 10], [0, 10], [0, 0]]]}"#,
    ));
    assert!(
        matches!(err, ZoneError::NonFiniteCoordinate { feature: 1, .. }),
        "{err:?}"
    );
    assert!(
        msg.contains(r#"features[1] ("dune west").geometry.coordinates[0][2]: x is NaN"#),
        "{msg}"
    );
    let (msg, _) = load_error(&raw_feature(
        "keep_out",
        r#"{"type": "Polygon", "coordinates": [[[0, 0], [10, 0], [10, -Infinity], [0, 10], [0, 0]]]}"#,
    ));
    assert!(
        msg.contains("geometry.coordinates[0][2]: y is -Infinity"),
        "{msg}"
    );
}

#[test]
fn bow_tie_is_rejected_with_the_crossing() {
    let (msg, err) = load_error(&raw_feature(
        "keep_out",
        r#"{"type": "Polygon", "coordinates": [[[100, 20], [141, 46], [141, 20], [100, 46], [100, 20]]]}"#,
    ));
    assert!(
        matches!(err, ZoneError::SelfIntersection { ring: 0, .. }),
        "{err:?}"
    );
    assert!(
        msg.ends_with(r#"features[1] ("dune west").geometry: ring 0 crosses itself at (120.5, 33.0); expected a simple polygon"#),
        "{msg}"
    );
}

#[test]
fn unclosed_ring_is_rejected() {
    let (msg, err) = load_error(&raw_feature(
        "keep_out",
        r#"{"type": "MultiPolygon", "coordinates": [[[[0, 0], [1, 0], [1, 1], [0, 0]]],
                                                   [[[5, 5], [6, 5], [6, 6], [5, 6]]]]}"#,
    ));
    assert!(matches!(err, ZoneError::RingNotClosed { .. }), "{err:?}");
    assert!(
        msg.contains(r#"("dune west").geometry.coordinates[1][0]: ring is not closed"#),
        "{msg}"
    );
}

#[test]
fn unknown_and_missing_kind_are_rejected() {
    let square = r#"{"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}"#;
    let (msg, err) = load_error(&raw_feature("keep_near", square));
    assert!(
        matches!(err, ZoneError::UnknownKind { feature: 1, .. }),
        "{err:?}"
    );
    assert!(
        msg.contains(r#"features[1] ("dune west").properties.kind: unknown kind "keep_near""#),
        "{msg}"
    );
    let text = raw_feature("x", square).replace(r#""kind": "x", "#, "");
    let (msg, _) = load_error(&text);
    assert!(
        msg.contains(r#"features[1] ("dune west").properties.kind: missing"#),
        "{msg}"
    );
}

#[test]
fn missing_file_is_rejected() {
    let path = Path::new("/nonexistent/dir/zones_missing.geojson");
    let err = ZoneSet::load(path).expect_err("no such file");
    assert!(matches!(err, ZoneError::Io { .. }));
    let msg = err.to_string();
    assert!(
        msg.starts_with("/nonexistent/dir/zones_missing.geojson: cannot read the file"),
        "{msg}"
    );
}

#[test]
fn other_invalid_inputs_are_rejected() {
    let cases: &[(&str, &str)] = &[
        (
            r#"{"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [0, 0]]]}"#,
            "coordinates[0]: ring has 3 positions",
        ),
        (
            r#"{"type": "Polygon", "coordinates": [[[0, 0], [1, 1], [2, 2], [0, 0]]]}"#,
            "coordinates[0]: ring encloses zero area",
        ),
        (
            r#"{"type": "LineString", "coordinates": [[0, 0], [1, 1]]}"#,
            r#"geometry.type: unsupported geometry "LineString""#,
        ),
        (r#"null"#, "geometry: missing"),
        (
            r#"{"type": "Polygon", "coordinates": []}"#,
            "geometry.coordinates: polygon has no rings",
        ),
        (
            r#"{"type": "Polygon", "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]],
                                                  [[5, 5], [15, 5], [15, 6], [5, 6], [5, 5]]]}"#,
            "geometry: ring 1 crosses ring 0 at (10.0, 5.0)",
        ),
        (
            r#"{"type": "Polygon", "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]],
                                                  [[20, 5], [25, 5], [25, 6], [20, 5]]]}"#,
            "geometry: hole (ring 1) lies outside the outer ring",
        ),
        (
            r#"{"type": "Polygon", "coordinates": [[[0, 0], [1], [1, 1], [0, 0]]]}"#,
            "geometry.coordinates[0][1]: position has 1 number(s)",
        ),
        (
            r#"{"type": "Polygon"}"#,
            r#"features[1] ("dune west"): invalid GeoJSON Feature"#,
        ),
    ];
    for (geometry, expected) in cases {
        let (msg, _) = load_error(&raw_feature("keep_out", geometry));
        assert!(msg.contains(expected), "expected {expected:?} in {msg}");
    }
    let (msg, _) = load_error(r#"{"type": "Feature", "features": []}"#);
    assert!(
        msg.contains(
            r#"type: expected a GeoJSON FeatureCollection with a "features" array, found "Feature""#
        ),
        "{msg}"
    );
    let (msg, _) = load_error("{\"type\": \"FeatureCollection\",\n \"features\": [,]}");
    assert!(
        msg.contains("invalid JSON") && msg.contains("line 2"),
        "{msg}"
    );
    let (msg, _) =
        load_error(&raw_feature("keep_in", "1").replace(r#""name": "dune west""#, r#""name": 7"#));
    assert!(
        msg.contains("features[1].properties.name: expected a string, found 7"),
        "{msg}"
    );
}

// ---------------------------------------------------------------------------------------------
// Speed

/// 50 keep-outs of 100 vertices, 1e5 query points; and a 4000 × 4000 rasterisation. The budgets
/// are loose (the test profile is opt-level 2 and the machine is shared); the times are printed.
#[test]
fn queries_are_fast() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let mut features = Vec::new();
    for i in 0..50 {
        let c = [rng.random_range(0.0..2000.0), rng.random_range(0.0..2000.0)];
        let radius = rng.random_range(20.0..120.0);
        let ring = star(&mut rng, c, radius, 100);
        let kind = if i % 10 == 0 { "keep_in" } else { "keep_out" };
        features.push(polygon_feature(kind, &format!("z{i}"), &[&ring]));
    }
    let t = Instant::now();
    let z = zones(&features);
    let load = t.elapsed();
    let points: Vec<[f64; 2]> = (0..100_000)
        .map(|_| {
            [
                rng.random_range(-100.0..2100.0),
                rng.random_range(-100.0..2100.0),
            ]
        })
        .collect();
    let t = Instant::now();
    let serial: Vec<_> = points.iter().map(|&p| z.clearance(p, 0.5)).collect();
    let serial_time = t.elapsed();
    let t = Instant::now();
    let parallel = z.clearances(&points, 0.5);
    let parallel_time = t.elapsed();
    assert_eq!(serial, parallel);
    let t = Instant::now();
    let (out, _) = z.rasterize(GeoTransform::new(0.0, 2000.0, 0.5), 4000, 4000);
    let raster_time = t.elapsed();
    assert!(out.iter().any(|&c| c));
    let mut report = String::new();
    let _ = write!(
        report,
        "load {load:?}; 1e5 points: serial {serial_time:?}, parallel {parallel_time:?}; 4000x4000 raster {raster_time:?}"
    );
    eprintln!("{report}");
    assert!(serial_time.as_secs_f64() < 2.0, "{report}");
    assert!(raster_time.as_secs_f64() < 1.0, "{report}");
}
