//! Properties against the exhaustive reference planner in `common`: on small generated
//! instances the search's value equals the optimum, and every bound is admissible.
//!
//! These are seeded loops rather than proptest cases: proptest is not a workspace
//! dependency yet. Each failure message names its seed.

#![allow(clippy::unwrap_used)]

mod common;

use common::{exhaustive, random_states};
use planner::{
    BoundKind, GeneratorSettings, Instance, PlanStatus, SearchSettings, State, generate,
    optimistic_bound, plan_from, validate_plan,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A small generated instance (≤ 8 tasks after drive splitting) for `seed`.
fn small_instance(seed: u64) -> Instance {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    loop {
        let settings = GeneratorSettings {
            n_optional: rng.random_range(2..=6),
            n_comm_passes: rng.random_range(0..=2),
            n_precedences: rng.random_range(0..=2),
            energy_fraction: [0.4, 0.2, 0.7][rng.random_range(0..3usize)],
            data_fraction: [0.5, 0.3][rng.random_range(0..2usize)],
            with_drive: rng.random_bool(0.35),
            with_campaign: rng.random_bool(0.4),
        };
        let inst = Instance::new(&generate(rng.random(), &settings)).unwrap();
        if inst.tasks().len() <= 8 {
            return inst;
        }
    }
}

const KINDS: [BoundKind; 3] = [BoundKind::Both, BoundKind::Knapsack, BoundKind::Lp];

#[test]
fn search_value_equals_exhaustive_optimum() {
    let mut optimal = 0;
    for seed in 0..1000u64 {
        let inst = small_instance(seed);
        let start = State::initial(&inst);
        let settings = SearchSettings {
            node_budget: None,
            bound: KINDS[seed as usize % 3],
            dominance: (seed / 3) % 2 == 0,
            ..SearchSettings::default()
        };
        let out = plan_from(&inst, &start, &settings).unwrap();
        let reference = exhaustive(&inst, &start);
        match reference {
            None => assert_eq!(out.status, PlanStatus::Infeasible, "seed {seed}"),
            Some((best, best_plan)) => {
                assert!(
                    validate_plan(&inst, &start, &best_plan).is_empty(),
                    "seed {seed}: reference plan invalid"
                );
                assert_eq!(out.status, PlanStatus::Optimal, "seed {seed}");
                assert_eq!(
                    out.value,
                    best,
                    "seed {seed}: search {:?} vs reference {:?}",
                    out.plan.describe(&inst),
                    best_plan.describe(&inst)
                );
                assert_eq!(out.best_bound, out.value, "seed {seed}");
                let v = validate_plan(&inst, &start, &out.plan);
                assert!(v.is_empty(), "seed {seed}: {v:?}");
                let mut done = vec![false; inst.tasks().len()];
                for s in &out.plan.steps {
                    done[s.task.index()] = true;
                }
                assert_eq!(common::value_of(&inst, &done), out.value, "seed {seed}");
                optimal += 1;
            }
        }
    }
    // The generator must mostly produce feasible instances for this test to mean much.
    assert!(optimal >= 600, "only {optimal} feasible instances");
}

#[test]
fn bounds_are_admissible_and_lp_is_at_least_as_tight_on_average() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    // Sum over cases of (bound − optimum) in points, summed over tiers.
    let mut excess = [0.0f64; 3];
    let mut cases = 0;
    for seed in 0..400u64 {
        let inst = small_instance(1000 + seed);
        for state in random_states(&inst, &mut rng, 3) {
            let Some((best, _)) = exhaustive(&inst, &state) else {
                continue;
            };
            cases += 1;
            for (k, kind) in KINDS.iter().enumerate() {
                let b = optimistic_bound(&inst, &state, *kind).unwrap();
                let b = b.unwrap_or_else(|| panic!("seed {seed} {kind:?}: feasible node killed"));
                for tier in 0..planner::MAX_TIERS {
                    assert!(
                        b.tiers_micro[tier] >= best.tiers_micro[tier],
                        "seed {seed} {kind:?} tier {}: bound {b} < optimum {best}",
                        tier + 1
                    );
                }
                excess[k] +=
                    b.to_points().iter().sum::<f64>() - best.to_points().iter().sum::<f64>();
            }
        }
    }
    assert!(cases > 800, "only {cases} cases");
    eprintln!(
        "mean bound excess over the optimum (points, {cases} nodes): both {:.3}, knapsack {:.3}, lp {:.3}",
        excess[0] / cases as f64,
        excess[1] / cases as f64,
        excess[2] / cases as f64
    );
    // `Both` is the componentwise minimum of the two, so it can never be looser.
    assert!(excess[0] <= excess[1] + 1e-6 && excess[0] <= excess[2] + 1e-6);
}

/// The B6 benchmark instances (quantised for the CP-SAT peer), small enough to enumerate:
/// the search with every bound kind proves the exhaustive optimum. The CP-SAT model of
/// `peers/planner_cpsat.py` is checked against the planner on the same family at 6–18
/// optional activities (BENCHMARKS.md, "Activity planner (B6)").
#[test]
fn b6_instances_match_the_exhaustive_optimum() {
    let mut optimal = 0;
    for seed in 0..150u64 {
        let n = 3 + (seed % 4) as usize;
        let inst = Instance::new(&planner::b6_problem(n, seed)).unwrap();
        let start = State::initial(&inst);
        let reference = exhaustive(&inst, &start);
        let settings = SearchSettings {
            node_budget: None,
            bound: KINDS[seed as usize % 3],
            ..SearchSettings::default()
        };
        let out = plan_from(&inst, &start, &settings).unwrap();
        match reference {
            None => assert_eq!(out.status, PlanStatus::Infeasible, "seed {seed}"),
            Some((best, _)) => {
                assert_eq!(out.status, PlanStatus::Optimal, "seed {seed}");
                assert_eq!(out.value, best, "seed {seed}");
                optimal += 1;
            }
        }
    }
    assert!(optimal >= 100, "only {optimal} feasible instances");
}
