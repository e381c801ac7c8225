//! The Parquet files of `solsim sweep` are what `docs/sweep-schema.md` documents, read back by
//! an independent reader (pyarrow).
//!
//! `tests/sweep_schema.json` is the documented schema: per file, the columns in order with
//! their arrow type and nullability, and the manifest format. Two tests check the Rust schemas
//! (`sweep::rows::runs_schema`, `sols_schema`) equal it, and the column tables of
//! `docs/sweep-schema.md` equal it, so neither the file nor the document can drift from the
//! code unnoticed: a change to a column must update all three. Another runs small sweeps and
//! `peers/sweep_schema_check.py` on them, which reads the files with pyarrow and checks
//! columns, row counts, null patterns, key-value metadata, manifest and summary. It needs
//! `peers/.venv` (any peer script creates it); without it that check is skipped with a message
//! on stderr — unless the environment variable `CI` is set, then it fails (CI creates the venv
//! first). The last checks the checker: it must report a schema or a summary that differs.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::Duration;

use common::{output_within, root, solsim, stderr};
use serde_json::{Value, json};

/// How long one small sweep may take (a hang is a bug).
const SWEEP_LIMIT: Duration = Duration::from_secs(120);

fn documented() -> Value {
    let path = root().join("tests/sweep_schema.json");
    serde_json::from_str(&std::fs::read_to_string(&path).expect("read tests/sweep_schema.json"))
        .expect("tests/sweep_schema.json is JSON")
}

/// pyarrow's name of an arrow type (`str(pyarrow.DataType)`), from the Rust type's `Debug`.
fn pyarrow_type(data_type: &impl std::fmt::Debug) -> String {
    let rust = format!("{data_type:?}");
    match rust.as_str() {
        "Boolean" => "bool",
        "UInt32" => "uint32",
        "UInt64" => "uint64",
        "Int32" => "int32",
        "Int64" => "int64",
        "Float64" => "double",
        "Utf8" => "string",
        other => panic!("no pyarrow name for the arrow type {other}: add it here"),
    }
    .to_string()
}

/// A Rust schema's columns as `tests/sweep_schema.json` lists them (a macro: the schema type
/// lives in `arrow-schema`, which this package does not name).
macro_rules! columns {
    ($schema:expr) => {
        $schema
            .fields()
            .iter()
            .map(|f| {
                json!({
                    "name": f.name(),
                    "type": pyarrow_type(f.data_type()),
                    "nullable": f.is_nullable(),
                })
            })
            .collect::<Value>()
    };
}

/// The Rust schemas as `tests/sweep_schema.json` writes them.
fn rust_schema() -> Value {
    json!({
        "format": sweep::manifest::FORMAT,
        "runs.parquet": columns!(sweep::rows::runs_schema()),
        "sols.parquet": columns!(sweep::rows::sols_schema()),
    })
}

#[test]
fn rust_schema_equals_the_documented_schema() {
    let mut want = documented();
    if let Some(doc) = want.as_object_mut() {
        doc.remove("$comment");
    }
    let got = rust_schema();
    let code = serde_json::to_string_pretty(&got).expect("json");
    for key in ["format", "runs.parquet", "sols.parquet"] {
        assert_eq!(
            got[key], want[key],
            "{key}: sweep::rows differs from tests/sweep_schema.json; update that file and \
             docs/sweep-schema.md with the code. The code's schema is:\n{code}"
        );
    }
    assert_eq!(got, want, "tests/sweep_schema.json has other entries");
}

/// The column tables of `docs/sweep-schema.md` (`| `name` | type | meaning | null when |` under
/// `## runs.parquet` and `## sols.parquet`) as `tests/sweep_schema.json` lists columns, with
/// nullable = "null when" is not `never`.
fn doc_tables() -> Value {
    let path = root().join("docs/sweep-schema.md");
    let text = std::fs::read_to_string(&path).expect("read docs/sweep-schema.md");
    let mut tables = serde_json::Map::new();
    for section in text.split("\n## ").skip(1) {
        let (title, body) = section.split_once('\n').unwrap_or((section, ""));
        if !title.ends_with(".parquet") {
            continue;
        }
        let columns: Vec<Value> = body
            .lines()
            .filter(|l| l.starts_with("| `"))
            .map(|l| {
                let cells: Vec<&str> = l.trim_matches('|').split('|').map(str::trim).collect();
                json!({
                    "name": cells[0].trim_matches('`'),
                    "type": cells[1],
                    "nullable": cells[cells.len() - 1] != "never",
                })
            })
            .collect();
        tables.insert(title.trim().to_string(), Value::Array(columns));
    }
    Value::Object(tables)
}

#[test]
fn the_documented_tables_equal_the_schema_file() {
    let want = documented();
    let doc = doc_tables();
    for key in ["runs.parquet", "sols.parquet"] {
        assert_eq!(
            doc[key], want[key],
            "docs/sweep-schema.md's {key} table differs from tests/sweep_schema.json (column \
             order, type, or whether its \"null when\" is `never`)"
        );
    }
}

/// The venv's Python, or `None` (with the skip said on stderr) when there is none outside CI.
fn python() -> Option<PathBuf> {
    common::peers_python(
        "the pyarrow check of the sweep files (only the Rust schema was compared with \
         tests/sweep_schema.json)",
    )
}

/// `peers/sweep_schema_check.py DIR --schema SCHEMA`.
fn check(python: &Path, dir: &Path, schema: &Path) -> Output {
    output_within(
        std::process::Command::new(python)
            .arg(root().join("peers/sweep_schema_check.py"))
            .arg(dir)
            .arg("--schema")
            .arg(schema),
        Duration::from_secs(120),
    )
}

fn assert_ok(o: &Output, what: &str) {
    assert!(
        o.status.success(),
        "{what}: {}\nstdout:\n{}\nstderr:\n{}",
        o.status,
        String::from_utf8_lossy(&o.stdout),
        stderr(o)
    );
}

/// Runs `solsim sweep SCENARIO --runs RUNS --strategies STRATEGIES --out DIR EXTRA…`.
fn sweep(scenario: &str, runs: &str, strategies: &str, dir: &Path, extra: &[&str]) {
    let o = output_within(
        solsim()
            .current_dir(root())
            .args([
                "sweep",
                scenario,
                "--runs",
                runs,
                "--strategies",
                strategies,
            ])
            .args(["--quiet", "--out"])
            .arg(dir)
            .args(extra),
        SWEEP_LIMIT,
    );
    assert_ok(&o, &format!("solsim sweep {scenario}"));
}

/// Two sweeps pyarrow reads as documented: rapid traverse (a study segment, onboard
/// localizations; two chunks, so the files are assembled from pieces) and crater-floor-passage (NO_PATH
/// faults, goals reached, no segment: the nullable columns hold values and nulls).
#[test]
fn pyarrow_reads_sweeps_as_documented() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let rapid = tmp.path().join("rapid");
    sweep(
        "scenarios/rapid-traverse-379-409.toml",
        "6",
        "ground,onboard,extension+onboard",
        &rapid,
        &["--chunk-runs", "4"],
    );
    let sol383 = tmp.path().join("sol383");
    sweep(
        "scenarios/crater-floor-passage.toml",
        "3",
        "ground,extension+onboard",
        &sol383,
        &[],
    );
    let Some(python) = python() else { return };
    let schema = root().join("tests/sweep_schema.json");
    for dir in [&rapid, &sol383] {
        let o = check(&python, dir, &schema);
        assert_ok(&o, "peers/sweep_schema_check.py");
        assert!(
            String::from_utf8_lossy(&o.stdout).starts_with("ok: "),
            "{}",
            String::from_utf8_lossy(&o.stdout)
        );
    }
}

/// The checker is no rubber stamp: a schema with one type and one nullability changed, and a
/// summary.json with one count changed, are each reported, naming the column or field.
#[test]
fn the_pyarrow_check_reports_differences() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path().join("sweep");
    sweep(
        "scenarios/rapid-traverse-379-409.toml",
        "2",
        "ground,onboard",
        &dir,
        &[],
    );
    let Some(python) = python() else { return };

    let mut schema = documented();
    schema["runs.parquet"][6]["type"] = json!("float");
    schema["sols.parquet"][5]["nullable"] = json!(false);
    let bad_schema = tmp.path().join("schema.json");
    std::fs::write(&bad_schema, schema.to_string()).expect("write");
    let o = check(&python, &dir, &bad_schema);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    for s in [
        "runs.parquet: column 'distance_m': type: expected float, got double",
        "sols.parquet: column 'skip_reason': nullable: expected False, got True",
    ] {
        assert!(err.contains(s), "stderr lacks {s:?}:\n{err}");
    }

    let path = dir.join("summary.json");
    let mut summary: Value =
        serde_json::from_slice(&std::fs::read(&path).expect("read")).expect("json");
    let rate = &mut summary["statistics"]["strategies"][1]["rates"][0];
    assert_eq!(rate["name"], "no_path_rate");
    let count = rate["count"].as_u64().expect("count");
    rate["count"] = json!(count + 1);
    std::fs::write(&path, serde_json::to_string_pretty(&summary).expect("json")).expect("write");
    let o = check(&python, &dir, &root().join("tests/sweep_schema.json"));
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let count_line = format!(
        "summary.json (strategy onboard): no_path_rate.count (no_path_faults): expected {count}, \
         got {}",
        count + 1
    );
    for s in [
        count_line.as_str(),
        "manifest.json: files.summary.json: lists SHA-256",
    ] {
        assert!(err.contains(s), "stderr lacks {s:?}:\n{err}");
    }
}
