//! Issue 13: outputs printed Rust debug text — `localize-bench` its rejections as
//! `[("Ambiguous", 1), ("OnWindowEdge", 1)]`, the sol plans their violations and replans as
//! `WrongDuration { step: 3, … }` and `(Battery)`, scenario errors `at_most Some(-1.0)`. Each
//! now prints words.

use crate::common;

use common::{root, solsim, stderr, validate_edited_sol717};

/// Fragments only Rust's `{:?}` produces.
const DEBUG_TEXT: [&str; 7] = [
    "Some(",
    "None",
    "[(\"",
    "\", ",
    "{ step",
    "TaskId(",
    "Rejection",
];

fn assert_no_debug_text(what: &str, text: &str) {
    for d in DEBUG_TEXT {
        assert!(
            !text.contains(d),
            "{what} prints Rust debug text {d:?}:\n{text}"
        );
    }
}

#[test]
fn localize_bench_prints_rejections_in_words() {
    let o = solsim()
        .args(["localize-bench", "--cases", "24", "--methods", "ncc"])
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("rejected by validity checks:"), "{out}");
    assert!(
        out.lines().any(|l| l.trim_start().starts_with("rocky ")),
        "terrain rows by name: {out}"
    );
    assert_no_debug_text("localize-bench", &out);
}

#[test]
fn sol_plan_changes_and_violations_are_sentences() {
    // The self-reliant campaign replans around its co-processor runs and science.
    let o = solsim()
        .current_dir(root())
        .args([
            "run",
            "scenarios/self-reliant-campaign.toml",
            "--strategy",
            "onboard",
            "--json",
            "--no-files",
        ])
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let mut texts = Vec::new();
    for sol in v["sols"].as_array().expect("sols") {
        for key in ["changes", "violations"] {
            if let Some(list) = sol["activity_plan"][key].as_array() {
                texts.extend(list.iter().filter_map(|t| t.as_str().map(str::to_owned)));
            }
        }
    }
    let all = texts.join("\n");
    assert!(
        all.contains("no longer fits ("),
        "a replan with its reason: {all}"
    );
    assert_no_debug_text("the sol plans' change logs", &all);
}

#[test]
fn a_paired_share_error_names_the_values_in_words() {
    let o = validate_edited_sol717(|t| {
        t + "\n[[expect]]\nstrategy = \"onboard\"\nruns = 10\npaired = { baseline = \"ground\", figure = \"sols_to_goal\", at_most = -1.0 }\n"
    });
    let err = stderr(&o);
    assert!(err.contains("at_most -1, share none"), "{err}");
    assert_no_debug_text("the error", &err);
}
