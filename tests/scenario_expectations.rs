//! The bundled scenarios are the regression suite: every `[[expect]]` in `scenarios/` must hold
//! (the historic scenarios rebuilt from the public record: sols 717-719 end at 32.92 m, sol 385
//! faults NO_PATH and onboard localization saves a sol, the rapid traverse's record and the
//! paper's claims over 200 runs; and the what-if cases). A failure prints the same diff as `solsim regress scenarios/`.

use std::path::Path;

use outputs::regress;

fn check(file: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(file);
    let results = regress::check_scenario(&path, maps::MemoryBudget::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!results.is_empty(), "{file} has no expectations");
    let failed: Vec<_> = results
        .iter()
        .filter(|r| !r.mismatches.is_empty())
        .cloned()
        .collect();
    assert!(failed.is_empty(), "\n{}", regress::text_report(&failed));
}

#[test]
fn sol717_719_ends_at_32_92_m() {
    check("sol717-719.toml");
}

#[test]
fn sol383_386_faults_no_path_on_385_and_onboard_avoids_it() {
    check("sol383-386.toml");
}

#[test]
fn crater_floor_passage_faults_no_path_and_onboard_avoids_it() {
    check("crater-floor-passage.toml");
}

#[test]
fn rapid_traverse_402_409_and_two_sols_saved() {
    check("rapid-traverse-379-409.toml");
}

#[test]
fn every_bundled_scenario_validates() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let files = regress::scenario_files(&dir).expect("scenarios/ is readable");
    assert!(files.len() >= 3);
    for f in files {
        study::Scenario::load(&f).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn self_reliant_campaign_science_and_replans() {
    check("self-reliant-campaign.toml");
}
