//! `solsim record import` and `solsim record baseline` on the bundled public record
//! (data/m20/M20_traverse.json), end to end: the scenario written for a sol range replays the
//! record's drive sols exactly, each sol's distance within 0.1 m of its stated source (the
//! written `[[expect]]` entries, run by `solsim regress`), and `ground` drives every sol the
//! record drove. Sols 379-409 and 383-386 and 717-719 (the paper's), and 1000-1015, a range no
//! bundled scenario uses. Every drive landing on its filed sol is `study::record`'s unit test
//! `bundled_record_lands_on_its_sols`.

use crate::common::{assert_bad_input, root, solsim};

use serde_json::Value;
use std::path::Path;

/// Import `sols` into a new directory; the scenario's path and the directory guard.
fn import(sols: &str) -> (std::path::PathBuf, tempfile::TempDir) {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("imported");
    let o = solsim()
        .current_dir(root())
        .args(["record", "import", "--sols", sols, "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (out.join(format!("record-{sols}.toml")), dir)
}

/// `solsim regress` on the imported directory: every written expectation holds.
fn regress(dir: &Path) -> String {
    let o = solsim().arg("regress").arg(dir).output().expect("runs");
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "regress failed:\n{text}");
    assert!(text.contains(" 0 failed"), "{text}");
    text
}

fn baseline(scenario: &Path) -> Value {
    let o = solsim()
        .args(["record", "baseline", "--runs", "5", "--json"])
        .arg(scenario)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).expect("JSON")
}

fn drove(b: &Value, key: &str) -> Vec<u64> {
    b["rows"]
        .as_array()
        .expect("rows")
        .iter()
        .filter(|r| r[key].as_f64().is_some_and(|m| m > 0.0))
        .map(|r| r["sol"].as_u64().expect("sol"))
        .collect()
}

#[test]
fn rapid_traverse_from_the_record() {
    let (scenario, _guard) = import("379-409");
    let text = std::fs::read_to_string(&scenario).expect("scenario");
    let checks = regress(scenario.parent().expect("dir"));
    // 24 drive sols at their distances, 7 idle sols without a drive, the fault on 385.
    assert!(checks.contains("31 passed"), "{checks}");
    assert!(
        text.contains("historic_source = \"paper 000 §8: 183 m on sol 402"),
        "402's source"
    );
    assert!(text.contains("[calendar]\n"), "computed calendar");
    for stop in [381, 390, 391, 392, 393] {
        assert!(
            text.contains(&format!("[[sols]]\nsol = {stop}\ndrive = false\n")),
            "science stop {stop}"
        );
    }
    let b = baseline(&scenario);
    let record = drove(&b, "record_m");
    assert_eq!(record.len(), 24);
    // Ground drives every sol the record drove, in every run.
    for row in b["rows"].as_array().expect("rows") {
        if row["record_m"].as_f64() > Some(0.0) {
            assert_eq!(row["ground_drove_share"].as_f64(), Some(1.0), "{row}");
        }
    }
    // And skips 403 and 406 for paper 000 §8's reasons, from the computed calendar.
    let row = |sol: u64| {
        b["rows"]
            .as_array()
            .expect("rows")
            .iter()
            .find(|r| r["sol"] == sol)
            .cloned()
            .expect("row")
    };
    let r403 = row(403);
    assert_eq!(r403["ground_drove_share"].as_f64(), Some(0.0));
    assert!(
        r403["ground_reason"]
            .as_str()
            .is_some_and(|r| r.contains("too late for a later plan")),
        "{r403}"
    );
    assert_eq!(r403["planning_day"], "2022-04-07 Thu");
    let r406 = row(406);
    assert_eq!(r406["ground_drove_share"].as_f64(), Some(0.0));
    assert!(
        r406["ground_reason"]
            .as_str()
            .is_some_and(|r| r.contains("would not reach Earth")),
        "{r406}"
    );
    assert_eq!(row(404)["planning_day"], "2022-04-08 Fri");
}

#[test]
fn papers_other_ranges_and_one_no_scenario_uses() {
    for (sols, drive_sols) in [("383-386", 4), ("717-719", 3), ("1000-1015", 6)] {
        let (scenario, _guard) = import(sols);
        regress(scenario.parent().expect("dir"));
        let b = baseline(&scenario);
        assert_eq!(drove(&b, "record_m").len(), drive_sols, "{sols}");
        for row in b["rows"].as_array().expect("rows") {
            if row["record_m"].as_f64() > Some(0.0) {
                assert_eq!(row["agreement"], "both", "{sols}: {row}");
            }
        }
    }
    // 717-719: paper 000 Fig. 2's 655.8 m and r from 0 to 32.92 m emerge in the replay.
    let (scenario, _guard) = import("717-719");
    let o = solsim()
        .args(["run", "--strategy", "replay", "--json"])
        .arg(&scenario)
        .output()
        .expect("runs");
    let run: Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let last = &run["sols"][2];
    assert!(
        (last["end_uncertainty_m"].as_f64().expect("r") - 32.92).abs() < 0.01,
        "{last}"
    );
}

#[test]
fn bad_ranges_and_files_are_one_clear_error() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("never");
    let run = |args: &[&str]| {
        solsim()
            .current_dir(root())
            .args(["record", "import"])
            .args(args)
            .arg("--out")
            .arg(&out)
            .output()
            .expect("runs")
    };
    assert_bad_input(
        &run(&["--sols", "1900-1910"]),
        &["sols: expected a range within the sols this record covers, 14-1840"],
    );
    assert_bad_input(
        &run(&["--sols", "390-393"]),
        &["expected a range in which the rover drove at least once"],
    );
    assert_bad_input(
        &run(&["--sols", "409-379"]),
        &["--sols: expected a sol range"],
    );
    assert_bad_input(
        &run(&[
            "--sols",
            "379-409",
            "--record",
            "scenarios/sol383-386.zones.geojson",
        ]),
        &["features[0].properties.sol: expected a sol number"],
    );
    assert!(!out.exists(), "nothing written");
}
