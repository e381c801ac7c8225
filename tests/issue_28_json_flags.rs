//! Issue 28, item 6: `sweep`, `sweep merge`, `report` and `map generate` printed only text
//! (`validate`, `regress`, `map package`, `whatif`, … take `--json`: issue 13). Each now takes
//! `--json` and prints one JSON document on standard output describing what it wrote — the
//! files with their sizes (and, for sweeps, their SHA-256 from the manifest), counts and
//! figures — and nothing else there.

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

use crate::common::{root, solsim, stderr, tiny};

/// Standard output as the one JSON document it must be (exit 0).
fn json_of(what: &str, o: &Output) -> Value {
    assert_eq!(o.status.code(), Some(0), "{what}: {}", stderr(o));
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| {
        panic!(
            "{what}: not one JSON document ({e}):\n{}",
            String::from_utf8_lossy(&o.stdout)
        )
    })
}

fn run(args: &[&str], paths: &[&Path]) -> Output {
    solsim()
        .current_dir(root())
        .args(args)
        .args(paths)
        .output()
        .expect("runs")
}

/// Each file the document lists is in `dir`, with the bytes (and SHA-256, where given) it says.
fn assert_files_as_described(what: &str, dir: &Path, v: &Value, names: &[&str]) {
    let files = v["files"].as_array().expect("files");
    let listed: Vec<&str> = files
        .iter()
        .map(|f| f["file"].as_str().expect("file"))
        .collect();
    assert_eq!(listed, names, "{what}");
    for f in files {
        let path = dir.join(f["file"].as_str().expect("file"));
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(f["bytes"].as_u64(), Some(bytes.len() as u64), "{what}: {f}");
        if let Some(sha) = f.get("sha256") {
            assert_eq!(
                sha,
                &Value::from(study::input::sha256_hex(&bytes)),
                "{what}: {f}"
            );
        }
    }
}

struct Tiny {
    _dir: tempfile::TempDir,
    root: PathBuf,
    scenario: PathBuf,
}

fn tiny() -> Tiny {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path().to_path_buf();
    let map = tiny::tiny_map(&d);
    std::fs::write(d.join("zones.geojson"), tiny::NO_ZONES).expect("zones");
    let scenario = d.join("tiny.toml");
    std::fs::write(
        &scenario,
        tiny::tiny_scenario(&map, &d.join("zones.geojson"), "tiny", ""),
    )
    .expect("scenario");
    Tiny {
        _dir: dir,
        root: d,
        scenario,
    }
}

const SWEEP_FILES: [&str; 4] = [
    "runs.parquet",
    "sols.parquet",
    "summary.json",
    "manifest.json",
];

#[test]
fn sweep_json_describes_the_sweep_and_its_files() {
    let t = tiny();
    let out = t.root.join("sweep");
    let o = run(
        &[
            "sweep",
            "--runs",
            "3",
            "--strategies",
            "ground,onboard",
            "--json",
            "--out",
        ],
        &[&out, &t.scenario],
    );
    let v = json_of("sweep --json", &o);
    assert_eq!(v["dir"], out.display().to_string());
    assert_eq!(v["scenario"]["name"], "tiny");
    assert_eq!(
        v["scenario"]["sha256"],
        study::input::sha256_hex(&std::fs::read(&t.scenario).expect("read"))
    );
    assert_eq!(v["runs"], 3);
    assert_eq!(v["run_range"], serde_json::json!([0, 3]));
    assert_eq!(v["shard"], Value::Null);
    assert_eq!(v["strategies"], serde_json::json!(["ground", "onboard"]));
    assert_eq!(v["baseline"], "ground");
    assert_eq!(v["runs_run"], 3);
    assert_eq!(v["runs_resumed"], 0);
    assert_eq!(v["already_complete"], false);
    assert!(v["seconds"].as_f64().is_some_and(|s| s > 0.0), "{v}");
    assert!(v["threads"].as_u64().is_some_and(|n| n >= 1), "{v}");
    assert_files_as_described("sweep --json", &out, &v, &SWEEP_FILES);
    // The statistics are summary.json's.
    let summary: Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).expect("summary"))
            .expect("summary JSON");
    assert_eq!(v["statistics"], summary["statistics"]);
    assert_eq!(v["statistics"]["strategies"][0]["runs"], 3);

    // Resumed on a complete directory: nothing run, said so.
    let o = run(
        &[
            "sweep",
            "--runs",
            "3",
            "--strategies",
            "ground,onboard",
            "--json",
            "--resume",
            "--out",
        ],
        &[&out, &t.scenario],
    );
    let v = json_of("sweep --resume --json", &o);
    assert_eq!(v["already_complete"], true);
    assert_eq!(v["runs_run"], 0);
}

#[test]
fn sweep_merge_json_describes_the_merged_directory() {
    let t = tiny();
    let shard = |k: u32| {
        let dir = t.root.join(format!("shard-{k}"));
        let o = run(
            &[
                "sweep",
                "--runs",
                "3",
                "--shard",
                &format!("{k}/2"),
                "--json",
                "--out",
            ],
            &[&dir, &t.scenario],
        );
        let v = json_of("sweep --shard --json", &o);
        assert_eq!(v["shard"]["index"], k);
        assert_eq!(v["shard"]["count"], 2);
        assert_eq!(
            v["run_range"],
            serde_json::json!([v["shard"]["first_run"], v["shard"]["end_run"]])
        );
        dir
    };
    let (s0, s1) = (shard(0), shard(1));
    let out = t.root.join("merged");
    let o = run(&["sweep", "merge", "--json", "--out"], &[&out, &s1, &s0]);
    let v = json_of("sweep merge --json", &o);
    assert_eq!(v["dir"], out.display().to_string());
    assert_eq!(
        v["merged_from"],
        serde_json::json!([s1.display().to_string(), s0.display().to_string()])
    );
    assert_eq!(v["runs"], 3);
    assert_eq!(v["run_range"], serde_json::json!([0, 3]));
    assert_eq!(v["shard"], Value::Null);
    // A merge runs nothing: no run counts, no timing.
    for absent in [
        "runs_run",
        "runs_resumed",
        "already_complete",
        "seconds",
        "threads",
    ] {
        assert!(v.get(absent).is_none(), "{absent}: {v}");
    }
    assert_files_as_described("sweep merge --json", &out, &v, &SWEEP_FILES);
    assert_eq!(v["statistics"]["strategies"][0]["runs"], 3);
}

#[test]
fn report_json_describes_the_page_for_a_sweep_and_a_compare_run() {
    let t = tiny();
    let sweep = t.root.join("sweep");
    let o = run(
        &["sweep", "--runs", "2", "-q", "--out"],
        &[&sweep, &t.scenario],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let compare = t.root.join("compare");
    let o = run(&["compare", "--out"], &[&compare, &t.scenario]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for (dir, kind) in [(&sweep, "sweep"), (&compare, "compare")] {
        let out = t.root.join(format!("report-{kind}"));
        let o = run(&["report", "--json", "--out"], &[&out, dir]);
        let v = json_of("report --json", &o);
        let page = out.join("report.html");
        assert_eq!(v["report"], page.display().to_string());
        assert_eq!(v["kind"], kind);
        assert_eq!(v["dir"], dir.display().to_string());
        let html = std::fs::read_to_string(&page).expect("report.html");
        assert_eq!(v["bytes"].as_u64(), Some(html.len() as u64));
        assert_eq!(
            v["figures"].as_u64(),
            Some(html.matches("<figure").count() as u64)
        );
        assert!(v["figures"].as_u64().is_some_and(|n| n > 0), "{v}");
        assert!(v["title"].as_str().is_some_and(|s| !s.is_empty()), "{v}");
    }
}

#[test]
fn map_generate_json_describes_the_rasters_and_the_crs() {
    let dir = tempfile::tempdir().expect("tempdir");
    // A bundled recipe, georeferenced on Mars.
    let out = dir.path().join("crater-floor");
    let o = run(
        &[
            "map",
            "generate",
            "maps/assets/crater-floor/recipe.toml",
            "--json",
            "--out",
        ],
        &[&out],
    );
    let v = json_of("map generate --json", &o);
    assert_eq!(v["dir"], out.display().to_string());
    assert_files_as_described(
        "map generate --json",
        &out,
        &v,
        &["appearance.tif", "dem.tif", "terrain.tif"],
    );
    assert_eq!(v["size_px"], serde_json::json!([600, 600]));
    assert_eq!(v["resolution_m_per_px"], 2.0);
    assert_eq!(v["x_m"], serde_json::json!([0.0, 1200.0]));
    assert_eq!(v["y_m"], serde_json::json!([0.0, 1200.0]));
    assert_eq!(v["seed"], 383);
    assert_eq!(v["dem_datum_m"], 0.0);
    let crs = &v["crs"];
    assert!(
        crs["name"].as_str().is_some_and(|n| n.starts_with("Mars")),
        "{crs}"
    );
    let lon = crs["lon_deg"].as_array().expect("lon");
    let lat = crs["lat_deg"].as_array().expect("lat");
    let (lon0, lon1) = (lon[0].as_f64().expect("f64"), lon[1].as_f64().expect("f64"));
    let (lat0, lat1) = (lat[0].as_f64().expect("f64"), lat[1].as_f64().expect("f64"));
    // 1200 m on the Mars sphere (r 3396.19 km) is 0.0202° of latitude; Jezero is near 18.4° N.
    assert!((lat1 - lat0 - 0.020245).abs() < 1e-4, "{lat0} {lat1}");
    assert!(lon1 > lon0 && (17.0..20.0).contains(&lat0), "{crs}");

    // A recipe without a georeference: map metres only.
    let t = tiny();
    let out = t.root.join("map-again");
    let o = run(
        &["map", "generate", "--json", "--out"],
        &[&out, &t.root.join("tiny-recipe.toml")],
    );
    let v = json_of("map generate --json (local)", &o);
    assert_eq!(v["crs"], Value::Null);
    assert_eq!(v["size_px"], serde_json::json!([40, 40]));
    assert_files_as_described(
        "map generate --json (local)",
        &out,
        &v,
        &["appearance.tif", "dem.tif", "terrain.tif"],
    );
}
