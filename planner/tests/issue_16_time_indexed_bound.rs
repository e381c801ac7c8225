//! Issue 16: the time-indexed bound (`bound::indexed`). The knapsacks see how much time the
//! candidates need before a deadline or after a release, not when they can run; the
//! time-indexed path sees two windows that collide. Checked here: it closes a gap neither the
//! knapsacks nor the LP relaxation can, it stays admissible on random partial plans of small
//! instances against the exhaustive optimum, and the proof phase that uses it (from the first
//! node, `dive_nodes: 0`) finds the exhaustive optimum from the start and from partial plans.
//! Two timelines: `timelines.rs` runs the proof phase on random link problems.

#![allow(clippy::unwrap_used)]

mod common;

use common::{exhaustive, random_states};
use planner::{
    Activity, BoundKind, GeneratorSettings, Instance, PlanStatus, Problem, SearchSettings, State,
    b6_problem, generate, optimistic_bound, plan, plan_from,
};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

const H: i64 = 3600;

/// Two one-hour tasks that must both start at 10:00, in a day with room for both.
fn colliding() -> Problem {
    let fixed = |id: &str| Activity::task(id, H, [10 * H, 10 * H], 10.0, 5.0);
    Problem {
        start_s: 9 * H,
        end_s: 17 * H,
        battery_capacity_wh: 1000.0,
        initial_energy_wh: 1000.0,
        recharge_w: 0.0,
        data_capacity_mb: 100.0,
        initial_data_mb: 0.0,
        activities: vec![fixed("a"), fixed("b")],
        campaigns: Vec::new(),
    }
}

#[test]
fn colliding_windows_are_bounded_at_one_task() {
    let p = colliding();
    let inst = Instance::new(&p).unwrap();
    let root = State::initial(&inst);
    let points = |kind| {
        optimistic_bound(&inst, &root, kind)
            .unwrap()
            .unwrap()
            .to_points()[0]
    };
    // Both fit every deadline row (two hours by 11:00) and every release row (two hours
    // after 10:00): the LP relaxation of those rows counts both.
    assert_eq!(points(BoundKind::Lp), 10.0);
    // The path runs one at 10:00; the other cannot start in its window.
    assert_eq!(points(BoundKind::Knapsack), 5.0);
    assert_eq!(points(BoundKind::Both), 5.0);
    let out = plan(&p, &SearchSettings::default()).unwrap();
    assert_eq!(out.status, PlanStatus::Optimal);
    assert_eq!(out.value.to_points()[0], 5.0);
}

/// Small instances with windows, precedences, mandatory passes, campaigns and split drives
/// (the generator's), and B6 instances (windows, precedences, two tiers).
fn small_instances() -> Vec<(String, Instance)> {
    let mut out = Vec::new();
    let mut rng = ChaCha8Rng::seed_from_u64(16);
    for seed in 0..240u64 {
        let settings = GeneratorSettings {
            n_optional: 4 + (seed % 3) as usize,
            n_precedences: 2,
            with_drive: seed % 2 == 0,
            with_campaign: seed % 3 == 0,
            ..GeneratorSettings::default()
        };
        let p = generate(rand::RngExt::random(&mut rng), &settings);
        if let Ok(inst) = Instance::new(&p)
            && inst.tasks().len() <= 8
        {
            out.push((format!("generated {seed}"), inst));
        }
    }
    for seed in 0..160u64 {
        let n = 4 + (seed % 4) as usize;
        out.push((
            format!("b6 n{n} seed {seed}"),
            Instance::new(&b6_problem(n, 500 + seed)).unwrap(),
        ));
    }
    out
}

#[test]
fn the_bound_is_admissible_on_random_partial_plans() {
    let mut rng = ChaCha8Rng::seed_from_u64(1616);
    let mut cases = 0;
    let mut tighter = 0;
    for (name, inst) in small_instances() {
        let mut states = vec![State::initial(&inst)];
        states.extend(random_states(&inst, &mut rng, 3));
        for state in states {
            let Some((best, _)) = exhaustive(&inst, &state) else {
                continue;
            };
            cases += 1;
            let b = optimistic_bound(&inst, &state, BoundKind::Knapsack).unwrap();
            let b = b.unwrap_or_else(|| panic!("{name}: a feasible node killed"));
            for tier in 0..planner::MAX_TIERS {
                assert!(
                    b.tiers_micro[tier] >= best.tiers_micro[tier],
                    "{name} tier {}: bound {b} < optimum {best}",
                    tier + 1
                );
            }
            let lp = optimistic_bound(&inst, &state, BoundKind::Lp)
                .unwrap()
                .unwrap();
            if b.tiers_micro[0] < lp.tiers_micro[0] {
                tighter += 1;
            }
        }
    }
    eprintln!("{cases} cases, {tighter} tighter than the LP in tier 1");
    assert!(cases >= 700, "only {cases} cases");
    // Not a property, a sign the bound is doing something on these small instances.
    assert!(
        tighter > 0,
        "never tighter than the LP in tier 1 on {cases} cases"
    );
}

/// From the start of the sol and from random partial plans (multipliers tuned at a node that
/// is not the sol's start, coupled tiers tuned where they first tie).
#[test]
fn the_proof_phase_from_the_first_node_finds_the_exhaustive_optimum() {
    let mut rng = ChaCha8Rng::seed_from_u64(161);
    let (mut optimal, mut from_partial) = (0, 0);
    for (name, inst) in small_instances() {
        let settings = SearchSettings {
            node_budget: None,
            dive_nodes: 0,
            ..SearchSettings::default()
        };
        let mut states = vec![State::initial(&inst)];
        states.extend(random_states(&inst, &mut rng, 2));
        for (i, start) in states.iter().enumerate() {
            let out = plan_from(&inst, start, &settings).unwrap();
            match exhaustive(&inst, start) {
                None => assert_eq!(out.status, PlanStatus::Infeasible, "{name} state {i}"),
                Some((best, _)) => {
                    assert_eq!(out.status, PlanStatus::Optimal, "{name} state {i}");
                    assert_eq!(out.value, best, "{name} state {i}");
                    optimal += 1;
                    from_partial += usize::from(i > 0);
                }
            }
        }
    }
    eprintln!("{optimal} feasible starts, {from_partial} of them partial plans");
    assert!(optimal >= 600, "only {optimal} feasible starts");
    assert!(from_partial >= 300, "only {from_partial} partial plans");
}
