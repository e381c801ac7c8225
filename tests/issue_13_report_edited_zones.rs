//! Regression (issue 13 review): `solsim report --scenario` drew a zones file the run never
//! used — the provenance hashed only the scenario TOML. Runs now record the SHA-256 of the map
//! rasters and the zones file (`provenance.inputs_sha256`) and `report` names the edited one.

use crate::common;

use std::path::Path;

use common::{assert_bad_input, root, run_ok, solsim};

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).expect("readable")
}

#[test]
fn report_names_a_zones_file_edited_since_the_run() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = dir.path().join("run");
    run_ok(
        &["compare", "scenarios/crater-floor-passage.toml", "--out"],
        &[&run],
    );
    let out = dir.path().join("report");
    let report = |d: &Path, extra: &[&str]| common::report(d, &out, extra);
    // A zones file edited since the run (the scenario itself unchanged): named.
    let zones_dir = tempfile::tempdir().expect("tempdir");
    let zones_copy = zones_dir.path().join("zones.geojson");
    let zones_text = read(&root().join("scenarios/crater-floor-passage.zones.geojson"));
    std::fs::write(&zones_copy, zones_text.replacen("[", "[ ", 1)).expect("write");
    let (moved, _keep2) = common::scenario_copy("crater-floor-passage.toml", |t| {
        common::replace_line(
            &t,
            "zones = ",
            &format!("zones = \"{}\"", zones_copy.display()),
        )
    });
    // (Its own SHA-256 differs too, so the run's scenario check is skipped by giving the run's
    // recorded one: rewrite the run's provenance to the copy's.)
    let copy_sha = {
        let o = solsim()
            .args(["compare", "--json", "--no-files"])
            .arg(&moved)
            .output()
            .expect("runs");
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
        v[0]["provenance"]["scenario_sha256"]
            .as_str()
            .expect("sha")
            .to_string()
    };
    let edited_run = dir.path().join("edited-run");
    std::fs::create_dir(&edited_run).expect("mkdir");
    for e in std::fs::read_dir(&run).expect("list") {
        let p = e.expect("entry").path();
        if p.extension().is_some_and(|x| x == "json") {
            let t = read(&p);
            let sha = serde_json::from_str::<serde_json::Value>(&t).expect("JSON")["provenance"]
                ["scenario_sha256"]
                .as_str()
                .expect("sha")
                .to_string();
            std::fs::write(
                edited_run.join(p.file_name().expect("name")),
                t.replace(&sha, &copy_sha),
            )
            .expect("write");
        }
    }
    let o = report(&edited_run, &["--scenario", moved.to_str().expect("utf-8")]);
    assert_bad_input(&o, &["zones.geojson", "map.zones", "edited since the run"]);
    assert!(!out.exists(), "nothing written");
}
