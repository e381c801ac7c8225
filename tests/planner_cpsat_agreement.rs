//! The planner's proven optima against an independent model: OR-Tools CP-SAT
//! (`peers/planner_cpsat.py`, run from `peers/.venv`) on
//! - the simulator's own sol problems (`peers/planner_fixtures/sol_problems`: drives split at
//!   survey distances, goal-set / periodic / state-based campaigns, the HBS link timeline),
//! - issue 16's `weak.toml` with 0, 12 and 20 tier-2 fillers (a drive that can never run),
//! - small B6 instances (`planner::b6_problem`, n = 6–18).
//!
//! Each is also planned with `dive_nodes: 0` (the proof phase's time-indexed bounds from the
//! first node), which must prove the same optimum.
//!
//! Wherever both prove an optimum the per-tier values must be equal, and wherever the planner
//! proves a problem infeasible CP-SAT must too. This is the CP-SAT half of issue 16's
//! admissibility check (the exhaustive half is `planner/tests/issue_16_propagated_bounds.rs`):
//! a bound that cut off a better plan would show here as a lower planner optimum.

use crate::common;
use planner::{PlanStatus, Problem, SearchSettings, plan};
use std::path::Path;

/// Writes `problem` as `dir/<stem>.json` and the planner's proof as `<stem>.planner.json`
/// (the format `planner/examples/dump_instances.rs` writes and the script compares).
fn write_with_proof(dir: &Path, stem: &str, problem: &Problem) -> PlanStatus {
    let out = plan(
        problem,
        &SearchSettings {
            node_budget: Some(2_000_000),
            ..SearchSettings::default()
        },
    )
    .expect("valid problem");
    // The proof phase (time-indexed bounds, best-first) from the first node proves the same.
    let proof_only = plan(
        problem,
        &SearchSettings {
            node_budget: Some(2_000_000),
            dive_nodes: 0,
            ..SearchSettings::default()
        },
    )
    .expect("valid problem");
    assert_eq!(
        (proof_only.status, proof_only.value),
        (out.status, out.value),
        "{stem}: dive_nodes 0"
    );
    let status = format!("{:?}", out.status);
    std::fs::write(
        dir.join(format!("{stem}.json")),
        serde_json::to_string(problem).expect("problem JSON"),
    )
    .expect("write problem");
    std::fs::write(
        dir.join(format!("{stem}.planner.json")),
        serde_json::json!({ "status": status, "value_micro": out.value.tiers_micro }).to_string(),
    )
    .expect("write planner result");
    out.status
}

#[test]
fn planner_and_cp_sat_prove_the_same_optima() {
    let Some(python) = common::peers_python("the planner / CP-SAT agreement") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let mut stems = Vec::new();
    let fixtures = common::root().join("peers/planner_fixtures/sol_problems");
    let mut files: Vec<_> = std::fs::read_dir(&fixtures)
        .expect("fixtures")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 14, "the 14 distinct sol problems");
    for f in &files {
        let problem: Problem =
            serde_json::from_str(&std::fs::read_to_string(f).expect("read")).expect("Problem");
        let stem = f.file_stem().expect("stem").to_string_lossy().into_owned();
        let status = write_with_proof(dir.path(), &stem, &problem);
        assert_eq!(status, PlanStatus::Optimal, "{stem}");
        stems.push(stem);
    }
    for n in [0, 12, 20] {
        let text = super::issue_16_unreachable_drive_bound::weak_with_fillers(n);
        let file = study::CampaignFile::from_toml_str(Path::new("weak.toml"), &text)
            .expect("weak.toml loads");
        let stem = format!("weak_{n}_fillers");
        let status = write_with_proof(dir.path(), &stem, &file.problem);
        assert_eq!(status, PlanStatus::Optimal, "{stem}");
        stems.push(stem);
    }
    for n in [6, 10, 14, 18] {
        for seed in 1..=3 {
            let stem = format!("b6_n{n}_seed{seed}");
            write_with_proof(dir.path(), &stem, &planner::b6_problem(n, seed));
            stems.push(stem);
        }
    }
    let out_json = dir.path().join("cpsat.json");
    let mut cmd = std::process::Command::new(python);
    cmd.arg(common::root().join("peers/planner_cpsat.py"))
        .arg("solve")
        .args(stems.iter().map(|s| dir.path().join(format!("{s}.json"))))
        .args([
            "--workers",
            "1",
            "--repeat",
            "1",
            "--time-limit",
            "60",
            "--out",
        ])
        .arg(&out_json);
    let o = cmd.output().expect("runs planner_cpsat.py");
    assert_eq!(
        o.status.code(),
        Some(0),
        "planner_cpsat.py: {}",
        common::stderr(&o)
    );
    let results: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(&out_json).expect("cpsat.json"))
            .expect("cpsat.json is JSON");
    assert_eq!(results.len(), stems.len(), "one result per problem");
    let mut proven = 0;
    for r in &results {
        let file = r["file"].as_str().expect("file");
        let cp = r["status"][0].as_str().expect("status");
        match r["planner_status"].as_str().expect("planner status") {
            "Optimal" => {
                assert_eq!(cp, "OPTIMAL", "{file}: CP-SAT did not prove it in 60 s");
                assert_eq!(r["value_micro"], r["planner_value_micro"], "{file}");
                proven += 1;
            }
            "Infeasible" => assert_eq!(cp, "INFEASIBLE", "{file}"),
            other => panic!("{file}: planner status {other}"),
        }
    }
    assert!(proven >= 25, "only {proven} proven optima compared");
    // The weak family's optimum: nothing in tier 1.
    for r in results
        .iter()
        .filter(|r| r["file"].as_str().is_some_and(|f| f.starts_with("weak_")))
    {
        assert_eq!(r["value_micro"][0], 0, "{}", r["file"]);
    }
}

/// The fixtures are a snapshot of what the simulator builds. Re-capture the self-reliant
/// campaign's sol problems (the 11 of the 14 that exercise the search; the rapid traverse's 3
/// are mandatory-only and take a minute to re-run in a debug build) under every strategy and
/// require them to be exactly the committed files, so a change to the sol problems shows here
/// (regenerate with `cargo run --release -p study --example dump_sol_problems -- DIR`).
#[test]
fn the_fixtures_are_the_sol_problems_the_simulator_builds() {
    let dir = common::root().join("peers/planner_fixtures/sol_problems");
    let scenario =
        study::Scenario::load(&common::root().join("scenarios/self-reliant-campaign.toml"))
            .expect("the bundled scenario loads");
    let mut built = std::collections::BTreeSet::new();
    for strategy in scenario.strategies() {
        let (_, problems) = sim::operations::sol_plan::capture_sol_problems(|| {
            scenario.run(strategy, scenario.seeds())
        });
        assert!(!problems.is_empty(), "{}: no sol planned", strategy.name());
        for (_, problem) in problems {
            built.insert(serde_json::to_string_pretty(&problem).expect("problem JSON"));
        }
    }
    let mut fixtures = std::collections::BTreeSet::new();
    for entry in std::fs::read_dir(&dir).expect("fixtures") {
        let path = entry.expect("entry").path();
        let name = path
            .file_name()
            .expect("name")
            .to_string_lossy()
            .into_owned();
        if name.starts_with("self-reliant-campaign_") && name.ends_with(".json") {
            fixtures.insert(std::fs::read_to_string(&path).expect("read fixture"));
        }
    }
    assert_eq!(
        fixtures.len(),
        11,
        "the self-reliant campaign's distinct sol problems"
    );
    assert!(
        built == fixtures,
        "the simulator's sol problems changed: {} built, {} committed, {} in common; regenerate \
         peers/planner_fixtures/sol_problems",
        built.len(),
        fixtures.len(),
        built.intersection(&fixtures).count()
    );
}
