//! Issue 28: `solsim validate` said "2 expectations" for a file with six `[[expect]]` entries:
//! it counted only the checks of one run and left out the four over runs, which `solsim
//! regress` runs and counts. Both now count every entry; validate also says how they split.

use crate::common;

use common::{rebase, root, run_ok, solsim, stderr};

#[test]
fn validate_counts_every_expect_entry() {
    let text = run_ok(&["validate", "scenarios/crater-floor-passage.toml"], &[]);
    assert!(
        text.contains("6 expectations (2 on one run, 4 over runs))"),
        "{text}"
    );
    for entry in std::fs::read_dir(root().join("scenarios")).expect("scenarios/") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let file = std::fs::read_to_string(&path).expect("read");
        let entries = file.lines().filter(|l| l.trim() == "[[expect]]").count();
        let json = run_ok(&["validate", "--json"], &[path.as_path()]);
        let v: serde_json::Value = serde_json::from_str(&json).expect("JSON");
        let s = &v["scenario"];
        assert_eq!(s["expectations"], entries, "{}", path.display());
        assert_eq!(
            s["one_run_expectations"].as_u64().expect("count")
                + s["statistical_expectations"].as_u64().expect("count"),
            entries as u64,
            "{}",
            path.display()
        );
    }
}

#[test]
fn validate_and_regress_count_the_same() {
    // Two checks of one run and two over 4 runs.
    let dir = tempfile::tempdir().expect("tempdir");
    let text = rebase(
        &std::fs::read_to_string(root().join("scenarios/crater-floor-passage.toml")).expect("read"),
    );
    let head = &text[..text.find("\n[[expect]]").expect("an expect")];
    let one_run = |what: &str| {
        format!(
            "\n[[expect]]\nwhat = \"{what}\"\nstrategy = \"ground\"\nsol = 383\nfault = \"none\"\n"
        )
    };
    let over_runs = |what: &str| {
        format!(
            "\n[[expect]]\nwhat = \"{what}\"\nstrategy = \"ground\"\nruns = 4\nno_path_rate = [0.0, 1.0]\n"
        )
    };
    let file = dir.path().join("four.toml");
    std::fs::write(
        &file,
        format!(
            "{head}{}{}{}{}",
            one_run("a"),
            over_runs("b"),
            one_run("c"),
            over_runs("d")
        ),
    )
    .expect("write");
    let validate = run_ok(&["validate"], &[file.as_path()]);
    assert!(
        validate.contains("4 expectations (2 on one run, 2 over runs))"),
        "{validate}"
    );
    let o = solsim()
        .arg("regress")
        .arg(dir.path())
        .output()
        .expect("runs");
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}\n{}", stderr(&o));
    assert!(out.ends_with("4 passed, 0 failed\n"), "{out}");
}
