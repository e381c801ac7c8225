//! Determinism goldens: for fixed seeds and node budgets the plan must be identical on every
//! platform and run.
//!
//! A mismatch means the search order, a tie-break, the generator or the model's arithmetic
//! changed. If the change is intended, check the new plans with the validator and the
//! exhaustive tests, then update the constants; if not, something now depends on timing,
//! hash order or platform floating point (the LP bound's clarabel arithmetic feeds pruning,
//! so a different CPU or BLAS-free build flag could legitimately change a plan of equal value;
//! these constants are for x86-64 Linux).

#![allow(clippy::unwrap_used)]

use planner::{
    GeneratorSettings, Instance, PlanStatus, SearchSettings, State, generate, plan, validate_plan,
};
use std::time::Duration;

/// FNV-1a, enough to fingerprint a JSON string.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn fingerprint(seed: u64, n_optional: usize, budget: u64) -> (usize, u64) {
    let problem = generate(
        seed,
        &GeneratorSettings {
            n_optional,
            with_drive: true,
            with_campaign: true,
            ..GeneratorSettings::default()
        },
    );
    let settings = SearchSettings {
        node_budget: Some(budget),
        ..SearchSettings::default()
    };
    let out = plan(&problem, &settings).unwrap();
    let json = serde_json::to_string(&(&out.plan, out.value, out.best_bound)).unwrap();
    (json.len(), fnv1a(json.as_bytes()))
}

#[test]
fn plans_match_their_goldens() {
    let got = [fingerprint(1, 12, 500), fingerprint(2, 40, 30)];
    assert_eq!(got, GOLDEN);
}

// The second golden changed on 2026-11-25 with the B6 knapsack bound (nested rows, grain
// rounding, tier coupling): a tighter bound prunes differently within the 30-node budget.
// The exhaustive tests pass with the new bound. It changed again when `Knapsack` became the
// default bound (it was `Both`): within the 30 nodes the plan is valid and better (tier 1
// 64.52 as before, tier 2 22 instead of 19), and the tier-2 bound is 79 instead of the LP's 76.
const GOLDEN: [(usize, u64); 2] = [
    (422, 2_065_107_230_192_391_087),
    (721, 13_148_233_000_144_486_288),
];

#[test]
fn a_zero_time_budget_still_returns_an_honest_outcome() {
    let problem = generate(5, &GeneratorSettings::default());
    let inst = Instance::new(&problem).unwrap();
    let out = plan(
        &problem,
        &SearchSettings {
            node_budget: None,
            time_budget: Some(Duration::ZERO),
            ..SearchSettings::default()
        },
    )
    .unwrap();
    assert!(out.best_bound >= out.value);
    match out.status {
        PlanStatus::Feasible | PlanStatus::Optimal => {
            assert!(validate_plan(&inst, &State::initial(&inst), &out.plan).is_empty());
        }
        PlanStatus::NoPlanFound | PlanStatus::Infeasible => assert!(out.plan.steps.is_empty()),
    }
}
