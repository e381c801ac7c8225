//! Issue 13: `validate`, `regress`, `seu-campaign` and `map package` printed only text. Each
//! now takes `--json` (validate's is tested in `issue_13_validate_nonsense.rs`).

use crate::common;

use common::{rebase, root, solsim, stderr};
use serde_json::Value;

fn json_of(o: &std::process::Output) -> Value {
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| {
        panic!(
            "not JSON ({e}):\n{}\n{}",
            String::from_utf8_lossy(&o.stdout),
            stderr(o)
        )
    })
}

/// `solsim regress DIR --json`, which must exit `code`.
fn regress_json(dir: &std::path::Path, code: i32) -> Value {
    let o = solsim()
        .arg("regress")
        .arg(dir)
        .arg("--json")
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(code), "{}", stderr(&o));
    json_of(&o)
}

#[test]
fn regress_json_lists_each_case_and_keeps_the_exit_code() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = rebase(
        &std::fs::read_to_string(root().join("scenarios/crater-floor-717.toml")).expect("read"),
    );
    std::fs::write(dir.path().join("a.toml"), &text).expect("write");
    let v = regress_json(dir.path(), 0);
    assert_eq!(v["passed"], 3);
    assert_eq!(v["failed"], 0);
    let cases = v["cases"].as_array().expect("cases");
    assert_eq!(cases.len(), 3);
    assert!(
        cases
            .iter()
            .all(|c| c["ok"] == true && c["seconds"].is_number())
    );

    let broken = text.replace(
        "end_uncertainty_m = [32.82, 33.02]",
        "end_uncertainty_m = [10.0, 11.0]",
    );
    assert_ne!(broken, text);
    std::fs::write(dir.path().join("a.toml"), broken).expect("write");
    let v = regress_json(dir.path(), 1);
    assert_eq!(v["failed"], 1);
    let failed: Vec<&Value> = v["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .filter(|c| c["ok"] == false)
        .collect();
    assert_eq!(failed.len(), 1);
    let m = &failed[0]["mismatches"][0];
    assert!(
        m["expected"].as_str().is_some_and(|e| e.contains("10")),
        "{m}"
    );
}

#[test]
fn seu_campaign_json_has_the_counts() {
    let o = solsim()
        .args(["seu-campaign", "--runs", "20", "--json"])
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json_of(&o);
    assert_eq!(v["runs"], 20);
    assert_eq!(v["counts"]["runs"], 20);
    assert_eq!(v["counts"]["corrupted_applied"], 0);
    assert!(v["probabilities"]["memory"].is_number());
}

#[test]
fn map_package_json_describes_the_files_written() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("pkg");
    let o = solsim()
        .current_dir(root())
        .args([
            "map",
            "package",
            "scenarios/crater-floor-717.toml",
            "--resolution-m",
            "1",
        ])
        .args(["--corridor-m", "30", "--json", "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json_of(&o);
    let tiles = v["tiles"].as_array().expect("tiles");
    assert!(!tiles.is_empty());
    for t in tiles {
        let file = t["appearance"]["file"].as_str().expect("file");
        let len = std::fs::metadata(out.join(file)).expect("on disk").len();
        assert_eq!(Some(len), t["appearance"]["bytes"].as_u64(), "{file}");
    }
    assert!(v["total_bytes"].as_u64().is_some_and(|b| b > 0));
}
