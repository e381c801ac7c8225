//! The `[errors]` section and the statistical `errors = "…"` / `disc_coverage` checks: bad values
//! are one line naming the field; `solsim calibrate vo` explains a scenario it cannot use.

use crate::common;

use common::{assert_bad_input, root, solsim};

use common::validate_edited_sol717 as validate;

fn with_errors(section: &str) -> impl Fn(String) -> String + '_ {
    move |t: String| t.replacen("[map]", &format!("[errors]\n{section}\n\n[map]"), 1)
}

#[test]
fn an_unknown_error_model_is_refused() {
    let o = validate(with_errors("model = \"pessimistic\""));
    assert_bad_input(
        &o,
        &[
            "errors.model",
            "\"calibrated\" or \"stress\"",
            "pessimistic",
        ],
    );
}

#[test]
fn a_heading_error_of_100_degrees_is_refused() {
    let o = validate(with_errors("heading_sigma_deg = 100.0"));
    assert_bad_input(&o, &["errors.heading_sigma_deg", "degrees", "got 100"]);
}

#[test]
fn a_vo_failure_probability_above_one_is_refused() {
    let o = validate(with_errors("vo_failure = { sand = 1.5 }"));
    assert_bad_input(&o, &["errors.vo_failure.sand", "fraction", "got 1.5"]);
}

#[test]
fn a_nan_slip_is_refused() {
    let o = validate(with_errors("slip_fraction = { soil = nan }"));
    assert_bad_input(&o, &["errors.slip_fraction.soil"]);
}

#[test]
fn the_stress_preset_and_overrides_load() {
    let o = validate(with_errors("model = \"stress\"\nheading_sigma_deg = 1.0"));
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn a_statistical_expectation_under_an_unknown_error_model_is_refused() {
    let o = validate(|t| {
        t + "\n[[expect]]\nstrategy = \"ground\"\nruns = 10\nerrors = \"worst\"\ndisc_coverage = [0.0, 1.0]\n"
    });
    assert_bad_input(
        &o,
        &["expect[3].errors", "\"calibrated\" or \"stress\"", "worst"],
    );
}

#[test]
fn a_disc_coverage_range_outside_zero_one_is_refused() {
    let o = validate(|t| {
        t + "\n[[expect]]\nstrategy = \"ground\"\nruns = 10\ndisc_coverage = [0.5, 1.5]\n"
    });
    assert_bad_input(&o, &["expect[3].disc_coverage", "fractions"]);
}

#[test]
fn calibrate_vo_explains_a_scenario_without_a_record() {
    let o = solsim()
        .args(["calibrate", "vo"])
        .arg(root().join("scenarios/self-reliant-campaign.toml"))
        .output()
        .expect("runs");
    assert_bad_input(
        &o,
        &[
            "self-reliant-campaign",
            "no historic record to calibrate to",
        ],
    );
}

#[test]
fn calibrate_vo_prints_the_solved_and_shipped_values() {
    let o = solsim()
        .args(["calibrate", "vo", "--runs", "20"])
        .arg(root().join("scenarios/crater-floor-717.toml"))
        .output()
        .expect("runs");
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for text in [
        "record: 0.289 m without VO in 655.8 m",
        "solved VO failure probability per step on soil",
        "shipped: 3.160e-4",
    ] {
        assert!(out.contains(text), "{text:?} missing from:\n{out}");
    }
}
