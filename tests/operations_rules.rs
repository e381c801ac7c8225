//! `[operations]` planning rules (plan lengths, extension breadcrumbs, the passage margin, the
//! optional extension cap) and the statistical `paired = { at_most, share }` check: bad values
//! are one line naming the field; good ones load and act.

use crate::common;

use common::assert_bad_input;

use common::validate_edited_sol717 as validate;

fn with_operations(lines: &str) -> impl Fn(String) -> String + '_ {
    move |t: String| t.replacen("[operations]", &format!("[operations]\n{lines}"), 1)
}

#[test]
fn zero_drive_sols_per_plan_is_refused() {
    let o = validate(with_operations("max_drive_sols_per_plan = 0"));
    assert_bad_input(&o, &["operations.max_drive_sols_per_plan", "sols", "got 0"]);
}

#[test]
fn an_absurd_extension_plan_is_refused() {
    let o = validate(with_operations("extension_plan_sols = 4000000000"));
    assert_bad_input(&o, &["operations.extension_plan_sols", "sols"]);
}

#[test]
fn a_negative_or_nan_passage_margin_is_refused() {
    let o = validate(with_operations("passage_margin_m = -1.0"));
    assert_bad_input(&o, &["operations.passage_margin_m", "metres", "got -1"]);
    let o = validate(with_operations("passage_margin_m = nan"));
    assert_bad_input(&o, &["operations.passage_margin_m", "metres"]);
}

#[test]
fn the_planning_rules_load() {
    let o = validate(with_operations(
        "max_drive_sols_per_plan = 2\nextension_plan_sols = 5\npassage_margin_m = 2.5\nmax_extension_sols = 3",
    ));
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn a_paired_share_without_its_range_is_refused() {
    let o = validate(|t| {
        t + "\n[[expect]]\nstrategy = \"onboard\"\nruns = 10\npaired = { baseline = \"ground\", figure = \"sols_to_goal\", at_most = -1.0 }\n"
    });
    assert_bad_input(&o, &["expect[3].paired.share", "at_most"]);
}

#[test]
fn a_paired_share_outside_zero_one_is_refused() {
    let o = validate(|t| {
        t + "\n[[expect]]\nstrategy = \"onboard\"\nruns = 10\npaired = { baseline = \"ground\", figure = \"sols_to_goal\", at_most = -1.0, share = [0.5, 2.0] }\n"
    });
    assert_bad_input(&o, &["expect[3].paired.share", "fractions"]);
}

#[test]
fn a_paired_entry_needs_a_mean_or_a_share() {
    let o = validate(|t| {
        t + "\n[[expect]]\nstrategy = \"onboard\"\nruns = 10\npaired = { baseline = \"ground\", figure = \"sols_to_goal\" }\n"
    });
    assert_bad_input(&o, &["expect[3].paired", "mean = [low, high]"]);
}

#[test]
fn preemptive_shortening_in_an_expectation_needs_runs_and_a_check() {
    let o = validate(|t| {
        t + "\n[[expect]]\nstrategy = \"ground\"\npreemptive_shortening = false\ntotal_distance_m = [0.0, 1.0]\n"
    });
    assert_bad_input(&o, &["expect[3].runs", "number of runs"]);
    let o = validate(|t| {
        t + "\n[[expect]]\nstrategy = \"ground\"\nruns = 10\npreemptive_shortening = false\n"
    });
    assert_bad_input(&o, &["expect[3]", "at least one statistical check"]);
    let o = validate(|t| {
        t + "\n[[expect]]\nstrategy = \"ground\"\nruns = 10\npreemptive_shortening = \"no\"\nno_path_rate = [0.0, 1.0]\n"
    });
    assert_bad_input(&o, &["preemptive_shortening"]);
}

#[test]
fn an_expectation_without_preemptive_shortening_runs_the_sweep_without_it() {
    // crater-floor-passage's ground meets NO_PATH in a minority of runs with shortening (paper 000 §2)
    // and in every run without it: the override reaches the planners.
    let dir = tempfile::tempdir().expect("tempdir");
    let src = common::root().join("scenarios");
    let text = std::fs::read_to_string(src.join("crater-floor-passage.toml")).expect("scenario");
    let head = &text[..text.find("\n[[expect]]").expect("an expect")];
    let edited = common::rebase(head)
        + "\n[[expect]]\nwhat = \"without shortening ground faults in every run\"\nstrategy = \"ground\"\nruns = 20\npreemptive_shortening = false\nno_path_rate = [1.0, 1.0]\n\n[[expect]]\nwhat = \"with it, not in every run\"\nstrategy = \"ground\"\nruns = 20\nno_path_rate = [0.0, 0.9]\n";
    std::fs::write(dir.path().join("s.toml"), edited).expect("writes");
    let o = common::solsim()
        .arg("regress")
        .arg(dir.path())
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("2 passed, 0 failed"), "{out}");
}
