//! Issue 13: each JUnit testcase of `solsim regress --junit` repeated its scenario's whole time
//! (31.6 s reported for a 4.7 s run). A case's time is now its own share: the checks of one
//! run split their scenario's load and runs, statistical entries split the sweep they share.
//! The cases sum to no more than the command took, and the suite's time is their sum.

use crate::common;

use common::{rebase, root, solsim, stderr};

/// The `time="…"` attribute of one XML tag, seconds.
fn time_attribute(tag: &str) -> f64 {
    let t = &tag[tag.find("time=\"").expect("time") + 6..];
    t[..t.find('"').expect("quote")].parse().expect("seconds")
}

#[test]
fn junit_testcase_times_are_each_cases_share() {
    let dir = tempfile::tempdir().expect("tempdir");
    let read =
        |f: &str| rebase(&std::fs::read_to_string(root().join("scenarios").join(f)).expect("read"));
    // Three checks of one run.
    std::fs::write(dir.path().join("a.toml"), read("crater-floor-717.toml")).expect("write");
    // Two statistical entries sharing one 10-run sweep, one with a sweep of its own.
    let text = read("crater-floor-passage.toml");
    let head = &text[..text.find("\n[[expect]]").expect("an expect")];
    let stat = |what: &str, extra: &str| {
        format!(
            "\n[[expect]]\nwhat = \"{what}\"\nstrategy = \"ground\"\nruns = 10\n{extra}no_path_rate = [0.0, 1.0]\n"
        )
    };
    let b = format!(
        "{head}{}{}{}",
        stat("shared 1", ""),
        stat("shared 2", ""),
        stat("own sweep", "preemptive_shortening = false\n")
    );
    std::fs::write(dir.path().join("b.toml"), b).expect("write");
    let junit = dir.path().join("junit.xml");
    let start = std::time::Instant::now();
    let o = solsim()
        .arg("regress")
        .arg(dir.path())
        .arg("--junit")
        .arg(&junit)
        .output()
        .expect("runs");
    let wall_s = start.elapsed().as_secs_f64();
    assert!(o.status.success(), "{}", stderr(&o));
    let xml = std::fs::read_to_string(&junit).expect("junit written");
    let cases: Vec<(&str, f64)> = xml
        .lines()
        .filter(|l| l.contains("<testcase"))
        .map(|l| (l, time_attribute(l)))
        .collect();
    assert_eq!(cases.len(), 6, "{xml}");
    let sum: f64 = cases.iter().map(|c| c.1).sum();
    assert!(
        sum > 0.0 && sum <= wall_s,
        "cases sum to {sum} s in a {wall_s} s run:\n{xml}"
    );
    let suite = &xml[xml.find("<testsuite").expect("suite")..];
    let suite_s = time_attribute(&suite[..suite.find('>').expect("tag end")]);
    assert!(
        (suite_s - sum).abs() < 0.01,
        "suite {suite_s} s, cases {sum} s:\n{xml}"
    );
    // The checks of one run split it equally; so do the entries sharing a sweep (to within
    // their own checks' microseconds).
    let time_of = |name: &str| {
        cases
            .iter()
            .find(|c| c.0.contains(name))
            .unwrap_or_else(|| panic!("{name} in {xml}"))
            .1
    };
    let one_run = time_of("crater-floor-717/expect[0]");
    assert!(
        (time_of("crater-floor-717/expect[1]") - one_run).abs() < 0.002,
        "{xml}"
    );
    assert!(
        (time_of("shared 1") - time_of("shared 2")).abs() < 0.01,
        "{xml}"
    );
}
