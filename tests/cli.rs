//! The command line end to end: the main job, determinism (byte-identical JSON for the same seed,
//! on one thread and on two), `regress` exit codes and JUnit output, and bad input — every bad
//! file gets exactly one clear line naming the file and the field, and exit code 2, never a panic.

use crate::common;

use common::{assert_bad_input, root, solsim, stderr};
use std::path::{Path, PathBuf};
use std::process::Output;

fn scenario(name: &str) -> PathBuf {
    root().join("scenarios").join(name)
}

#[test]
fn compare_runs_the_main_job_and_writes_outputs() {
    let out = tempfile::tempdir().expect("tempdir");
    let o = solsim()
        .args([
            "compare",
            scenario("rapid-traverse-379-409.toml")
                .to_str()
                .expect("utf8"),
            "--out",
        ])
        .arg(out.path())
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    for s in [
        "replay",
        "ground",
        "onboard",
        "extension",
        "extension+onboard",
        "NO_PATH",
        "max_r_m",
    ] {
        assert!(text.contains(s), "compare output lacks {s}:\n{text}");
    }
    for strategy in [
        "replay",
        "ground",
        "onboard",
        "extension",
        "extension+onboard",
    ] {
        for ext in ["json", "sols.csv", "geojson"] {
            let f = out
                .path()
                .join(format!("rapid-traverse-379-409.{strategy}.{ext}"));
            assert!(f.is_file(), "missing {}", f.display());
        }
    }
    // The JSON carries the documented fields.
    let doc: serde_json::Value = serde_json::from_slice(
        &std::fs::read(out.path().join("rapid-traverse-379-409.replay.json")).expect("read"),
    )
    .expect("json");
    assert_eq!(doc["strategy"], "replay");
    let sol = &doc["sols"][0];
    for key in ["sol", "distance_m", "end_uncertainty_m", "fault"] {
        assert!(sol.get(key).is_some(), "sols[0] lacks {key}");
    }
    assert!(doc["totals"]["distance_m"].as_f64().is_some());
    // GeoJSON: a FeatureCollection with drive lines and sol-end points carrying the ellipse.
    let gj: serde_json::Value = serde_json::from_slice(
        &std::fs::read(out.path().join("rapid-traverse-379-409.onboard.geojson")).expect("read"),
    )
    .expect("json");
    assert_eq!(gj["type"], "FeatureCollection");
    let features = gj["features"].as_array().expect("features");
    assert!(
        features
            .iter()
            .any(|f| f["geometry"]["type"] == "LineString")
    );
    assert!(
        features
            .iter()
            .any(|f| f["properties"]["uncertainty_semi_major_m"].is_number())
    );
}

#[test]
fn fault_json_has_kind_after_and_uncertainty() {
    let o = solsim()
        .args(["replay", "--json", "--no-files"])
        .arg(scenario("crater-floor-passage.toml"))
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: serde_json::Value = serde_json::from_slice(&o.stdout).expect("json");
    let sol385 = doc["sols"]
        .as_array()
        .expect("sols")
        .iter()
        .find(|s| s["sol"] == 385)
        .expect("sol 385");
    assert_eq!(sol385["fault"]["kind"], "NO_PATH");
    assert!(
        sol385["fault"]["after_m"]
            .as_f64()
            .is_some_and(|m| (12.0..16.0).contains(&m))
    );
    assert!(
        sol385["fault"]["uncertainty_m"]
            .as_f64()
            .is_some_and(|r| (26.8..27.0).contains(&r))
    );
    let sol386 = doc["sols"]
        .as_array()
        .expect("sols")
        .iter()
        .find(|s| s["sol"] == 386)
        .expect("sol 386");
    assert!(sol386["fault"].is_null());
}

/// Same scenario and seed → byte-identical JSON, whatever the thread count.
#[test]
fn same_seed_gives_byte_identical_json_on_one_and_two_threads() {
    for file in [
        "rapid-traverse-379-409.toml",
        "crater-floor-passage.toml",
        "self-reliant-campaign.toml",
    ] {
        let run = |threads: &str| {
            let o = solsim()
                .env("RAYON_NUM_THREADS", threads)
                .args(["compare", "--json", "--no-files"])
                .arg(scenario(file))
                .output()
                .expect("runs");
            assert!(o.status.success(), "{}", stderr(&o));
            o.stdout
        };
        let a = run("1");
        let b = run("2");
        let c = run("2");
        assert!(!a.is_empty());
        assert!(a == b, "{file}: 1 thread and 2 threads differ");
        assert!(b == c, "{file}: two runs on 2 threads differ");
    }
}

#[test]
fn regress_passes_on_the_bundled_scenarios_and_writes_junit() {
    let dir = tempfile::tempdir().expect("tempdir");
    let junit = dir.path().join("junit.xml");
    let o = solsim()
        .arg("regress")
        .arg(root().join("scenarios"))
        .arg("--junit")
        .arg(&junit)
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}\n{}", stderr(&o));
    assert!(text.contains(" passed, 0 failed"), "{text}");
    let xml = std::fs::read_to_string(&junit).expect("junit written");
    assert!(
        xml.contains("<testsuite") && xml.contains("failures=\"0\""),
        "{xml}"
    );
}

#[test]
fn regress_exits_1_with_a_diff_on_a_mismatch() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = std::fs::read_to_string(scenario("crater-floor-717.toml")).expect("read");
    let text = common::rebase(&text).replace(
        "end_uncertainty_m = [32.82, 33.02]",
        "end_uncertainty_m = [10.0, 11.0]",
    );
    std::fs::write(dir.path().join("broken.toml"), text).expect("write");
    let o = solsim()
        .arg("regress")
        .arg(dir.path())
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("FAIL")
            && out.contains("expected: [10, 11]")
            && out.contains("+ got:      32.920"),
        "{out}"
    );
}

/// Write a modified copy of a bundled scenario and run `validate` on it.
fn validate_modified(
    base: &str,
    edit: impl Fn(String) -> String,
) -> (Output, PathBuf, tempfile::TempDir) {
    let (path, dir) = common::scenario_copy(base, edit);
    let o = solsim().arg("validate").arg(&path).output().expect("runs");
    (o, path, dir)
}

#[test]
fn missing_scenario_file() {
    let o = solsim()
        .args(["run", "no/such/scenario.toml"])
        .output()
        .expect("runs");
    assert_bad_input(&o, &["no/such/scenario.toml", "cannot read"]);
}

#[test]
fn unknown_toml_field_names_the_line() {
    let (o, path, _d) = validate_modified("crater-floor-passage.toml", |t| {
        t.replace("drive_rate_m_per_h = 100.0", "drive_rate_m_per_hr = 100.0")
    });
    assert_bad_input(
        &o,
        &[
            path.to_str().expect("utf8"),
            "drive_rate_m_per_hr",
            "unknown field",
        ],
    );
}

#[test]
fn wrong_type_names_the_line() {
    let (o, path, _d) = validate_modified("crater-floor-passage.toml", |t| {
        t.replace("step_m = 2.0", "step_m = \"two\"")
    });
    assert_bad_input(&o, &[path.to_str().expect("utf8"), "step_m"]);
}

#[test]
fn negative_rate_is_rejected() {
    let (o, path, _d) = validate_modified("crater-floor-passage.toml", |t| {
        t.replace("drive_rate_m_per_h = 100.0", "drive_rate_m_per_h = -100.0")
    });
    assert_bad_input(
        &o,
        &[
            path.to_str().expect("utf8"),
            "rover.drive_rate_m_per_h",
            "1 ..= 1000",
            "-100",
        ],
    );
}

#[test]
fn nan_is_rejected() {
    let (o, path, _d) = validate_modified("crater-floor-passage.toml", |t| {
        t.replace("k_vo = 0.05", "k_vo = nan")
    });
    assert_bad_input(
        &o,
        &[path.to_str().expect("utf8"), "uncertainty.k_vo", "NaN"],
    );
}

#[test]
fn unknown_localizer_is_rejected() {
    let (o, path, _d) = validate_modified("crater-floor-passage.toml", |t| {
        t.replace("localizer = \"census\"", "localizer = \"sextant\"")
    });
    assert_bad_input(
        &o,
        &[
            path.to_str().expect("utf8"),
            "onboard_localization.localizer",
            "\"census\"",
            "sextant",
        ],
    );
}

#[test]
fn statistical_settings_with_an_image_localizer_are_rejected() {
    let (o, path, _d) = validate_modified("crater-floor-passage.toml", |t| {
        t.replace(
            "localizer = \"census\"",
            "localizer = \"census\"\nmean_error_m = 0.5",
        )
    });
    assert_bad_input(
        &o,
        &[
            path.to_str().expect("utf8"),
            "onboard_localization.mean_error_m",
            "statistical localizer only",
        ],
    );
}

#[test]
fn census_onboard_localization_is_logged_with_hbs_steps_and_timeline() {
    let o = solsim()
        .args(["run", "--strategy", "onboard", "--json", "--no-files"])
        .arg(scenario("crater-floor-passage.toml"))
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("json");
    let sols = v["sols"].as_array().expect("sols");
    let mut applied = 0;
    for s in sols.iter().filter(|s| s["drove"] == true) {
        let l = &s["onboard_localization"];
        assert_eq!(l["localizer"], "census", "{l}");
        let steps: Vec<&str> = l["steps"]
            .as_array()
            .expect("steps")
            .iter()
            .map(|e| e["step"].as_str().expect("step"))
            .collect();
        assert_eq!(
            steps.first(),
            Some(&"MOB_WRITE_ONBD_INPUT_FILE"),
            "{steps:?}"
        );
        assert!(
            steps.contains(&"RUN_1") && steps.contains(&"REBOOT"),
            "{steps:?}"
        );
        // The activity starts after the drive, imaging and SunFind; it lasts transfer + 2 runs
        // + reboot.
        let start = l["start_lmst"].as_str().expect("start");
        assert!(("11:30".."17:00").contains(&start), "{start}");
        let d = l["duration_s"].as_f64().expect("duration");
        assert!((120.0 + 2.0 * 32.0..3600.0).contains(&d), "{d}");
        if l["applied"] == true {
            applied += 1;
            assert_eq!(steps.last(), Some(&"MOB_APPLY_ONBD_LOCALIZATION"));
            assert!(l["error_m"].as_f64().expect("error") < 2.0, "{l}");
            assert!(l["uncertainty_after_m"].as_f64().expect("r") < 3.0, "{l}");
        } else {
            assert!(l["reason"].is_string(), "{l}");
        }
    }
    assert!(applied >= 2, "{applied} applied");
}

#[test]
fn nan_waypoint_is_rejected() {
    let (o, _path, _d) = validate_modified("crater-floor-passage.toml", |t| {
        t.replace("[[600.0, 60.0],", "[[nan, 60.0],")
    });
    assert_bad_input(
        &o,
        &[
            "route.waypoints[0][0]",
            "-11000000 ..= 11000000 map metres, got NaN",
        ],
    );
}

#[test]
fn waypoint_off_the_map_is_rejected() {
    let (o, path, _d) = validate_modified("crater-floor-passage.toml", |t| {
        t.replace("[600.0, 821.0]]", "[600.0, 5000.0]]")
    });
    assert_bad_input(
        &o,
        &[
            path.to_str().expect("utf8"),
            "route.waypoints[4]",
            "a point on the map",
            "5000",
        ],
    );
}

#[test]
fn negative_historic_distance_is_rejected() {
    let (o, _p, _d) = validate_modified("crater-floor-717.toml", |t| {
        t.replace(
            "historic_distance_m = 226.1",
            "historic_distance_m = -226.1",
        )
    });
    assert_bad_input(&o, &["sols[1].historic_distance_m", "0 ..= 10000 metres"]);
}

#[test]
fn missing_map_file_is_rejected() {
    let (o, _p, _d) = validate_modified("crater-floor-717.toml", |t| {
        t.replace("crater-floor/dem.tif", "crater-floor/nope.tif")
    });
    assert_bad_input(&o, &["map.dem", "nope.tif", "an existing regular file"]);
}

#[test]
fn self_intersecting_zone_is_rejected() {
    let dir = tempfile::tempdir().expect("tempdir");
    let zones = dir.path().join("bowtie.geojson");
    std::fs::write(
        &zones,
        r#"{"type": "FeatureCollection", "features": [{"type": "Feature",
            "properties": {"kind": "keep_out", "name": "bow tie"},
            "geometry": {"type": "Polygon", "coordinates": [[[100, 100], [200, 200], [200, 100], [100, 200], [100, 100]]]}}]}"#,
    )
    .expect("write");
    let (o, _p, _d) = validate_modified("crater-floor-717.toml", |t| {
        let scen = root().join("scenarios");
        t.replace(
            &format!(
                "zones = \"{}/crater-floor-717.zones.geojson\"",
                scen.display()
            ),
            &format!("zones = {:?}", zones.display().to_string()),
        )
    });
    assert_bad_input(&o, &["bowtie.geojson", "features[0]", "bow tie"]);
}

#[test]
fn unknown_strategy_is_rejected() {
    let o = solsim()
        .args(["run", "--strategy", "teleport"])
        .arg(scenario("crater-floor-passage.toml"))
        .output()
        .expect("runs");
    assert_bad_input(&o, &["--strategy", "teleport", "extension+onboard"]);
}

#[test]
fn outputs_are_not_half_written_when_the_directory_is_unwritable() {
    // A file where the output directory should be: writing fails cleanly, exit 2, no temp files.
    let dir = tempfile::tempdir().expect("tempdir");
    let blocker = dir.path().join("out");
    std::fs::write(&blocker, "not a directory").expect("write");
    let o = solsim()
        .args(["run", "--out"])
        .arg(&blocker)
        .arg(scenario("crater-floor-717.toml"))
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .expect("ls")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name())
        .collect();
    assert_eq!(leftovers.len(), 1, "{leftovers:?}");
    assert!(Path::new(&blocker).is_file());
}

#[test]
fn localize_bench_prints_the_accuracy_table() {
    let o = solsim()
        .args(["localize-bench", "--cases", "3", "--methods", "census"])
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    for s in [
        "method: census",
        "mean_m",
        "median_m",
        "p99_m",
        ">1_m",
        ">2_m",
        "rocky",
        "plain",
        "dunes",
    ] {
        assert!(text.contains(s), "lacks {s}:\n{text}");
    }
}

#[test]
fn localize_bench_rejects_an_unknown_method() {
    let o = solsim()
        .args(["localize-bench", "--cases", "3", "--methods", "sift"])
        .output()
        .expect("runs");
    assert_bad_input(&o, &["--methods", "sift"]);
}

#[test]
fn seu_campaign_counts_and_never_applies_a_corrupted_result() {
    let o = solsim()
        .args([
            "seu-campaign",
            "--runs",
            "20",
            "--p-memory",
            "0.5",
            "--p-output",
            "0.2",
        ])
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("upsets injected:") && text.contains("localizations lost:"),
        "{text}"
    );
    assert!(
        text.contains("corrupted results applied:        0"),
        "{text}"
    );
}

#[test]
fn bad_science_sections_name_the_field() {
    let cases: [(&str, &str, &[&str]); 10] = [
        (
            "done = [9, 11]",
            "done = [11, 9]",
            &["expect[1].science.done", "low ≤ high"],
        ),
        (
            "utility = 4.0\n[science.campaigns.template]",
            "utility = 4.0\nmax_count = 3\n[science.campaigns.template]",
            &["science.campaigns[2].max_count", "counts every instance"],
        ),
        (
            "name = \"Navcam mid-drive survey\"",
            "name = \"Navcam mid-drive survey\"\npreconditions = [\"mastcam-start\"]",
            &["science.campaigns[2].template.preconditions", "none"],
        ),
        (
            "position_m = [606.0, 574.0]",
            "position_m = [5000.0, 574.0]",
            &["science.targets[2].position_m", "a point on the map"],
        ),
        (
            "revealed_lmst = \"15:30\"",
            "",
            &["science.targets[2].revealed_lmst", "with revealed_sol"],
        ),
        (
            "duration_min = 15\npower_w = 35.0",
            "duration_min = -15\npower_w = 35.0",
            &["science.targets[0].duration_min", "positive"],
        ),
        (
            "intent = \"goal_set\"",
            "intent = \"goalset\"",
            &["science.campaigns[0].intent", "goal_set"],
        ),
        (
            "first_due_lmst = \"09:30\"",
            "",
            &["science.campaigns[1].first_due_lmst", "first due time"],
        ),
        (
            "id = \"mastcam-start\"",
            "id = \"drive\"",
            &[
                "science.targets[0].id",
                "not used by the sol's own activities",
            ],
        ),
        (
            "science = { campaign = \"survey\"",
            "science = { campaign = \"surveys\"",
            &["expect[1].science.campaign", "\"surveys\""],
        ),
    ];
    for (from, to, needles) in cases {
        let (o, path, _d) = validate_modified("self-reliant-campaign.toml", |t| {
            assert!(t.contains(from), "{from}");
            t.replacen(from, to, 1)
        });
        let mut all = vec![path.to_str().expect("utf8")];
        all.extend_from_slice(needles);
        assert_bad_input(&o, &all);
    }
}

/// The README's science table is what `compare` prints for the bundled self-reliant campaign.
#[test]
fn readme_science_table_is_what_compare_prints() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let cmd = "$ solsim compare scenarios/self-reliant-campaign.toml --no-files\n";
    let start = readme.find(cmd).expect("the README shows the command") + cmd.len();
    let block = &readme[start..start + readme[start..].find("```").expect("block end")];
    assert!(
        block.contains("plan_replans") && block.contains("onboard"),
        "{block}"
    );
    let o = solsim()
        .current_dir(root())
        .args([
            "compare",
            "scenarios/self-reliant-campaign.toml",
            "--no-files",
        ])
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains(block),
        "README:\n{block}\ncompare printed:\n{out}"
    );
}
