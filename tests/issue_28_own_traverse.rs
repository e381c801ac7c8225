//! Issue 28, "your own scenario in minutes": there was no way from a track in Mars longitude and
//! latitude to a `compare` run but writing a scenario, a map recipe and a route in map metres
//! by hand. `solsim route import TRACK --out S.toml` and `solsim init S.toml` now write them.
//!
//! These tests run the README's three commands ("Your own traverse") on the bundled example
//! track, check the route comes back from `compare`'s longitude/latitude GIS output within
//! `study::starter::ROUND_TRIP_TOLERANCE_DEG`, read the same track as CSV, refuse each kind of
//! bad track with one line naming the file and the place (exit 2, nothing written), and run
//! `init`'s starter as written.

use std::path::Path;
use std::process::Output;

use crate::common::{assert_bad_input, root, solsim};

/// The example track, relative to the repository (and to the test's working directory).
const TRACK: &str = "scenarios/tracks/jezero-example.geojson";

/// The example track's points, degrees.
fn track_points() -> Vec<[f64; 2]> {
    let text = std::fs::read_to_string(root().join(TRACK)).expect("track");
    let v: serde_json::Value = serde_json::from_str(&text).expect("json");
    v["features"][0]["geometry"]["coordinates"]
        .as_array()
        .expect("coordinates")
        .iter()
        .map(|p| [p[0].as_f64().expect("lon"), p[1].as_f64().expect("lat")])
        .collect()
}

/// A temporary working directory holding a copy of the example track at `TRACK`.
fn workdir() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("tempdir");
    let to = dir.path().join(TRACK);
    std::fs::create_dir_all(to.parent().expect("parent")).expect("mkdir");
    std::fs::copy(root().join(TRACK), &to).expect("copy");
    dir
}

/// `solsim ARGS` in `dir`.
fn run_in(dir: &Path, args: &[&str]) -> Output {
    solsim().current_dir(dir).args(args).output().expect("runs")
}

fn ok(o: &Output) -> String {
    assert_eq!(
        o.status.code(),
        Some(0),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout.clone()).expect("utf-8")
}

/// The README's three commands, as its "Your own traverse" section gives them.
const COMMANDS: [&str; 3] = [
    "solsim route import scenarios/tracks/jezero-example.geojson --out my-traverse.toml",
    "solsim validate my-traverse.toml",
    "solsim compare my-traverse.toml",
];

#[test]
fn three_commands_from_a_track_to_compare() {
    let dir = workdir();
    let mut outputs = Vec::new();
    for c in COMMANDS {
        let args: Vec<&str> = c.split(' ').skip(1).collect();
        outputs.push(ok(&run_in(dir.path(), &args)));
    }
    let [import, validate, compare] = [&outputs[0], &outputs[1], &outputs[2]];
    assert!(
        import.contains("wrote my-traverse.toml (+ my-traverse.map/"),
        "{import}"
    );
    for next in &COMMANDS[1..] {
        assert!(import.contains(&format!("  {next}\n")), "{import}");
    }
    assert!(
        validate.starts_with("my-traverse.toml: ok — my-traverse"),
        "{validate}"
    );
    // Every strategy of a scenario without history (no replay), in the table and against ground.
    for s in ["ground", "onboard", "extension", "extension+onboard"] {
        assert!(
            compare
                .lines()
                .any(|l| l.split_whitespace().next() == Some(s)
                    && l.split_whitespace().count() == 10),
            "no table row for {s}:\n{compare}"
        );
    }
    for s in ["onboard", "extension", "extension+onboard"] {
        assert!(compare.contains(&format!("\n  {s}:\n")), "{compare}");
    }
    assert!(!compare.contains("\nreplay "), "{compare}");

    // The README shows the commands and what they print.
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let section = readme
        .split("## Your own traverse")
        .nth(1)
        .expect("a README section \"Your own traverse\"");
    for (c, out) in COMMANDS.iter().zip(&outputs) {
        assert!(
            section.contains(&format!("$ {c}\n")),
            "README lacks `$ {c}`"
        );
        for l in out.lines().take(12) {
            assert!(
                section.contains(l),
                "README lacks the output line {l:?} of `{c}`"
            );
        }
    }

    // The route comes back from compare's longitude/latitude layer.
    let layer = dir
        .path()
        .join("solsim-out/my-traverse/gis/my-traverse.route.geojson");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&layer).expect("route layer")).expect("json");
    let back = v["features"][0]["geometry"]["coordinates"]
        .as_array()
        .expect("coordinates")
        .clone();
    let want = track_points();
    assert_eq!(back.len(), want.len());
    for (b, w) in back.iter().zip(&want) {
        for k in 0..2 {
            let got = b[k].as_f64().expect("number");
            assert!(
                (got - w[k]).abs() <= study::starter::ROUND_TRIP_TOLERANCE_DEG,
                "{got} against {} (tolerance {:e}°)",
                w[k],
                study::starter::ROUND_TRIP_TOLERANCE_DEG
            );
        }
    }
}

/// The `[route]` table of a scenario file.
fn route_of(path: &Path) -> String {
    let text = std::fs::read_to_string(path).expect("scenario");
    let start = text.find("[route]").expect("route");
    let end = start + text[start..].find("\n]\n").expect("end of waypoints");
    text[start..end].to_owned()
}

#[test]
fn the_same_track_as_csv_gives_the_same_route() {
    let dir = workdir();
    let mut csv = String::from("name,lon,lat\n");
    for (i, p) in track_points().iter().enumerate() {
        csv.push_str(&format!("p{i},{},{}\n", p[0], p[1]));
    }
    std::fs::write(dir.path().join("track.csv"), csv).expect("write");
    ok(&run_in(
        dir.path(),
        &["route", "import", "track.csv", "--out", "csv.toml"],
    ));
    ok(&run_in(
        dir.path(),
        &["route", "import", TRACK, "--out", "geo.toml"],
    ));
    assert_eq!(
        route_of(&dir.path().join("csv.toml")),
        route_of(&dir.path().join("geo.toml"))
    );
    ok(&run_in(dir.path(), &["validate", "csv.toml"]));
}

/// Files and folders in `dir` besides the track copy.
fn written(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n != "scenarios" && n != "bad.geojson" && n != "bad.csv")
        .collect();
    names.sort();
    names
}

#[test]
fn bad_tracks_are_refused_naming_the_place() {
    let dir = workdir();
    let import = |file: &str, text: &str, extra: &[&str]| {
        std::fs::write(dir.path().join(file), text).expect("write");
        let mut args = vec!["route", "import", file, "--out", "s.toml"];
        args.extend_from_slice(extra);
        let o = run_in(dir.path(), &args);
        assert!(written(dir.path()).is_empty(), "{:?}", written(dir.path()));
        o
    };
    let line = |coords: &str| format!(r#"{{"type": "LineString", "coordinates": [{coords}]}}"#);
    assert_bad_input(
        &import("bad.geojson", "{\"type\": \"LineString\", ", &[]),
        &["bad.geojson: expected a GeoJSON track (JSON), got malformed JSON"],
    );
    assert_bad_input(
        &import("bad.geojson", &line("[77.45, NaN], [77.46, 18.45]"), &[]),
        &["bad.geojson: line 1, column", "NaN or Infinity"],
    );
    assert_bad_input(
        &import("bad.geojson", &line("[77.45, 18.44], [77.46, 95.0]"), &[]),
        &[
            "bad.geojson: (root).coordinates[1]: expected a latitude in degrees north",
            "95",
        ],
    );
    assert_bad_input(
        &import("bad.geojson", &line("[77.45, 18.44]"), &[]),
        &["bad.geojson: expected at least 2 points (a route), got 1"],
    );
    assert_bad_input(
        &import(
            "bad.geojson",
            &line("[77.45, 18.44], [77.46, 18.45], [77.46, 18.45]"),
            &[],
        ),
        &[
            "bad.geojson: (root).coordinates[2]: expected a point apart from the one before it ((root).coordinates[1])",
            "duplicate",
        ],
    );
    let points = r#"{"type": "FeatureCollection", "features": [
        {"type": "Feature", "geometry": {"type": "Point", "coordinates": [77.45, 18.44]}},
        {"type": "Feature", "geometry": {"type": "LineString", "coordinates": [[77.46, 18.45]]}}]}"#;
    assert_bad_input(
        &import("bad.geojson", points, &[]),
        &["bad.geojson: features[1].geometry.type: expected \"Point\""],
    );
    // A track so long its map would exhaust memory: refused before anything is generated.
    assert_bad_input(
        &import("bad.geojson", &line("[77.0, 18.0], [77.4, 18.3]"), &[]),
        &[
            "bad.geojson: track: expected a track whose map (margin 300 m) and planning grid fit the memory budget (2 GiB; --memory-budget-mib)",
            "got a track spanning 22.5 × 17.8 km",
        ],
    );
    assert_bad_input(
        &import(
            "bad.geojson",
            &line("[77.45, 18.44], [77.46, 18.45]"),
            &["--memory-budget-mib", "8"],
        ),
        &[
            "track: expected a track whose map (margin 300 m) and planning grid fit the memory budget (8 MiB",
        ],
    );
    assert_bad_input(
        &import(
            "bad.geojson",
            &line("[77.45, 18.44], [77.46, 18.45]"),
            &["--map-margin-m", "10"],
        ),
        &["--map-margin-m: expected 50 ..= 100000 metres", "got 10"],
    );
    assert_bad_input(
        &import("bad.csv", "77.45,18.44\n77.46,18.45\n", &[]),
        &[
            "bad.csv: line 1: expected a header row naming a lon and a lat column",
            "required",
        ],
    );
    assert_bad_input(
        &import("bad.csv", "lon,lat\n77.45,18.44\n77.46,nan\n", &[]),
        &[
            "bad.csv: line 3, column lat: expected a latitude in degrees north",
            "NaN",
        ],
    );
    assert_bad_input(
        &import("bad.csv", "lon,lat\n77.45,18.44\n77.46\n", &[]),
        &["bad.csv: line 3: expected 2 fields, as the header, got 1"],
    );
    assert_bad_input(
        &import("bad.csv", "lon,lat\n77.45,18.44\n77.45,18.44\n", &[]),
        &["bad.csv: line 3: expected a point apart from the one before it (line 2)"],
    );
}

#[test]
fn init_writes_a_starter_that_runs_as_written() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = ok(&run_in(dir.path(), &["init", "starter.toml"]));
    assert!(out.contains("zones: one example keep-out"), "{out}");
    let text = std::fs::read_to_string(dir.path().join("starter.toml")).expect("scenario");
    // Every value line has a comment line above it (or its own, for waypoints).
    let lines: Vec<&str> = text.lines().collect();
    for (i, l) in lines.iter().enumerate() {
        let is_value = l.contains(" = ") && !l.starts_with('#') && !l.starts_with("sol = ");
        if is_value {
            assert!(lines[i - 1].starts_with('#'), "no comment above {l:?}");
        }
    }
    ok(&run_in(dir.path(), &["validate", "starter.toml"]));
    let compare = ok(&run_in(
        dir.path(),
        &["compare", "starter.toml", "--no-files"],
    ));
    assert!(compare.contains("extension+onboard"), "{compare}");
    // Not replaced without --force; replaced with it.
    let again = run_in(dir.path(), &["init", "starter.toml"]);
    assert_bad_input(
        &again,
        &["starter.toml: expected a new file, but it exists; pass --force"],
    );
    ok(&run_in(dir.path(), &["init", "starter.toml", "--force"]));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("starter.toml")).expect("scenario"),
        text
    );
}
