//! `solsim schema scenario|campaign` (issue 13, item 6): the JSON Schemas of the file formats,
//! checked by an independent validator — Python's `jsonschema` on the TOML read as JSON
//! (`peers/schema_check.py`) — against every bundled scenario and campaign file, and against
//! broken ones, which the loaders refuse too.
//!
//! The validator runs from `peers/.venv`; without it the check is skipped with a message on
//! stderr, unless `CI` is set (`.ci/run` creates the venv), then it fails.

use crate::common;

use std::path::{Path, PathBuf};

use common::{root, solsim, stderr};
use serde_json::Value;

fn schema(format: &str, dir: &Path) -> PathBuf {
    let o = solsim().args(["schema", format]).output().expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).expect("the schema is JSON");
    assert_eq!(
        v["$schema"], "https://json-schema.org/draft/2020-12/schema",
        "{format}"
    );
    assert_eq!(
        v["additionalProperties"], false,
        "unknown fields are refused"
    );
    let path = dir.join(format!("{format}.schema.json"));
    std::fs::write(&path, &o.stdout).expect("write");
    path
}

/// `(file, valid, errors)` per file, from `peers/schema_check.py`.
fn check(python: &Path, schema: &Path, files: &[PathBuf]) -> Vec<(String, bool, Vec<String>)> {
    let o = std::process::Command::new(python)
        .arg(root().join("peers/schema_check.py"))
        .arg(schema)
        .args(files)
        .output()
        .expect("python runs");
    assert!(o.status.success(), "schema_check.py: {}", stderr(&o));
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| {
            let v: Value = serde_json::from_str(l).expect("a JSON line");
            let errors = v["errors"]
                .as_array()
                .expect("errors")
                .iter()
                .map(|e| e.as_str().expect("text").to_owned())
                .collect();
            (
                v["file"].as_str().expect("file").to_owned(),
                v["valid"].as_bool().expect("valid"),
                errors,
            )
        })
        .collect()
}

fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_bundled_file_validates_and_broken_ones_do_not() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scenario_schema = schema("scenario", dir.path());
    let campaign_schema = schema("campaign", dir.path());
    let scenarios = toml_files(&root().join("scenarios"));
    let campaigns = toml_files(&root().join("scenarios/plans"));
    assert!(scenarios.len() >= 5 && !campaigns.is_empty());

    // Broken scenarios, each also refused by the loader: a misspelled field, a wrong type, a
    // missing section.
    let text = common::rebase(
        &std::fs::read_to_string(root().join("scenarios/crater-floor-passage.toml")).expect("read"),
    );
    let broken = [
        (
            "misspelled.toml",
            text.replace("max_slope_deg", "max_slope_degrees"),
        ),
        (
            "wrong-type.toml",
            text.replace("seed = 385", "seed = \"385\""),
        ),
        (
            "no-route.toml",
            text.replace("[route]", "[unused]")
                .replace("waypoints = [[", "# waypoints = [["),
        ),
    ];
    let mut broken_files = Vec::new();
    for (name, t) in &broken {
        assert_ne!(t, &text, "{name}: the edit applies");
        let path = dir.path().join(name);
        std::fs::write(&path, t).expect("write");
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        common::assert_bad_input(&o, &[name]);
        broken_files.push(path);
    }
    let Some(python) = common::peers_python("the jsonschema check of the file formats") else {
        return;
    };

    for (file, valid, errors) in check(&python, &scenario_schema, &scenarios) {
        assert!(valid, "{file}: {errors:?}");
    }
    for (file, valid, errors) in check(&python, &campaign_schema, &campaigns) {
        assert!(valid, "{file}: {errors:?}");
    }
    let verdicts = check(&python, &scenario_schema, &broken_files);
    assert_eq!(verdicts.len(), broken.len());
    for (file, valid, errors) in verdicts {
        assert!(!valid, "{file} validated");
        assert!(!errors.is_empty(), "{file}");
    }
    // A scenario is not a campaign file, nor the other way round.
    for (file, valid, _) in check(&python, &campaign_schema, &scenarios[..1]) {
        assert!(!valid, "{file} validated as a campaign file");
    }
}
