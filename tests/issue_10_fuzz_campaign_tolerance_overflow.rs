//! Issue 10, found by `tests/fuzz_parsers.rs`: a periodic science campaign with
//! `tolerance_min = 1e20` (finite, non-negative, so it passed the field check) panicked in
//! `study/src/campaign_file/campaign_entry.rs` with `attempt to multiply with overflow`: the
//! tolerance converts to `i64::MAX` seconds and the overlap check computed `2 * tolerance_s`
//! (in a release build the product wrapped negative and the absurd tolerance was accepted). The
//! check now saturates: the file is refused with one error naming `tolerance_min`. Both readers
//! of campaign entries are covered: `solsim plan` campaign files and a scenario's `[science]`.

use std::path::Path;

use study::scenario::ScenarioSpec;
use study::{CampaignFile, PlanFileError, ScenarioError};

fn bundled(relative: &str) -> (std::path::PathBuf, String) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    let text = std::fs::read_to_string(&path).expect("bundled file");
    (path, text)
}

fn assert_tolerance_error(err: &ScenarioError) {
    match err {
        ScenarioError::Field { field, .. } => {
            assert!(field.ends_with(".tolerance_min"), "{err}");
        }
        other => panic!("expected a field error, got {other}"),
    }
}

#[test]
fn a_huge_periodic_tolerance_in_a_campaign_file_is_an_error_not_a_panic() {
    let (path, text) = bundled("scenarios/plans/self-reliant-campaign.toml");
    assert!(text.contains("tolerance_min = 20\n"));
    for huge in ["1e20", "1e300", "1.7976931348623157e308"] {
        let edited = text.replace("tolerance_min = 20\n", &format!("tolerance_min = {huge}\n"));
        match CampaignFile::from_toml_str(&path, &edited) {
            Err(PlanFileError::File(e)) => assert_tolerance_error(&e),
            Err(other) => panic!("tolerance_min = {huge}: expected a field error, got {other}"),
            Ok(_) => panic!("tolerance_min = {huge} accepted"),
        }
    }
    CampaignFile::from_toml_str(&path, &text).expect("the bundled campaign file is valid");
}

#[test]
fn a_huge_periodic_tolerance_in_a_scenario_science_section_is_an_error_not_a_panic() {
    let (path, text) = bundled("scenarios/self-reliant-campaign.toml");
    assert!(text.contains("tolerance_min = 20\n"));
    let edited = text.replace("tolerance_min = 20\n", "tolerance_min = 1e20\n");
    let err = ScenarioSpec::from_toml_str(&path, &edited).expect_err("an absurd tolerance");
    assert_tolerance_error(&err);
    ScenarioSpec::from_toml_str(&path, &text).expect("the bundled scenario is valid");
}
