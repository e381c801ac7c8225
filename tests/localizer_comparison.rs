//! `solsim localize-bench --methods all`: the six onboard localizers on the same benchmark
//! cases (issue 14, item 4). The side-by-side rows agree with the matchers' own tables, are
//! the same on one and two threads (times aside), and the Markdown form is the one
//! BENCHMARKS.md holds.

use crate::common;

use common::{root, solsim};

fn bench(args: &[&str], threads: &str) -> String {
    let o = solsim()
        .current_dir(root())
        .env("RAYON_NUM_THREADS", threads)
        .arg("localize-bench")
        .args(args)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", common::stderr(&o));
    String::from_utf8(o.stdout).expect("utf-8")
}

/// The JSON document without the run times (which differ run to run).
fn without_times(json: &str) -> serde_json::Value {
    let mut doc: serde_json::Value = serde_json::from_str(json).expect("JSON");
    for row in doc["comparison"].as_array_mut().expect("rows") {
        let row = row.as_object_mut().expect("row");
        assert!(
            row.remove("mean_ms_per_case")
                .is_some_and(|v| v.as_f64().is_some())
        );
        assert!(
            row.remove("max_ms_per_case")
                .is_some_and(|v| v.as_f64().is_some())
        );
    }
    doc
}

#[test]
fn six_localizers_side_by_side_on_the_same_cases() {
    let args = ["--cases", "9", "--methods", "all", "--json"];
    let two = bench(&args, "2");
    let one = bench(&args, "1");
    assert_eq!(
        without_times(&one),
        without_times(&two),
        "1 against 2 threads"
    );
    let doc = without_times(&two);
    let rows = doc["comparison"].as_array().expect("an array");
    let names: Vec<&str> = rows
        .iter()
        .map(|r| r["localizer"].as_str().expect("a string"))
        .collect();
    assert_eq!(
        names,
        ["statistical", "census", "ncc", "mi", "particle", "ekf"]
    );
    for r in rows {
        let accepted = r["accepted"]["count"].as_u64().expect("a count");
        let rejected = r["rejected"].as_u64().expect("a count");
        let not_run = r["could_not_run"].as_u64().expect("a count");
        assert_eq!(accepted + rejected + not_run, 9, "{r}");
        assert!(!r["needs"].as_str().expect("a string").is_empty());
    }
    // The matchers' rows are their own reports' accepted statistics.
    for (k, m) in doc["matchers"]
        .as_array()
        .expect("an array")
        .iter()
        .enumerate()
    {
        assert_eq!(
            m["report"]["accepted"],
            rows[k + 1]["accepted"],
            "{}",
            m["method"]
        );
    }
    // What each needs is said: only the EKF needs an orbiter pass, only it needs no imagery
    // among the real localizers.
    assert!(
        rows[5]["needs"]
            .as_str()
            .expect("a string")
            .contains("orbiter pass")
    );
    assert!(
        rows[4]["needs"]
            .as_str()
            .expect("a string")
            .contains("imagery")
    );
}

#[test]
fn markdown_is_one_table_row_per_localizer() {
    let md = bench(
        &["--cases", "3", "--methods", "census,ekf", "--markdown"],
        "2",
    );
    let lines: Vec<&str> = md.lines().collect();
    assert_eq!(lines.len(), 4, "{md}");
    assert!(lines[0].starts_with("| localizer |") && lines[1].starts_with("|---"));
    assert!(
        lines[2].starts_with("| census | ") && lines[3].starts_with("| ekf | "),
        "{md}"
    );
}

#[test]
fn an_unknown_localizer_is_refused() {
    let o = solsim()
        .args([
            "localize-bench",
            "--cases",
            "3",
            "--methods",
            "census,kalman",
        ])
        .output()
        .expect("runs");
    common::assert_bad_input(&o, &["--methods", "kalman", "particle, ekf or all"]);
}
