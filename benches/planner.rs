//! B6: the activity planner's time to proven optimum on the generated 20/40/80-activity
//! instances ([`planner::b6_problem`], seeds 1–3), and the 10 ms anytime run on 80.
//!
//! `cargo bench --bench planner` (the peer comparison: `peers/run_peer_benchmarks.sh planner`).
//! With `SOLSIM_PLANNER_DUMP=<dir>` the bench writes every instance as `Problem` JSON
//! (`n{N}_seed{S}.json`) and the planner's result next to it (`n{N}_seed{S}.planner.json`:
//! status, value per tier in micro-points, bound, nodes), which `peers/planner_cpsat.py`
//! solves and checks in the same job.
//!
//! Settings: [`BoundKind::Knapsack`] (the fastest to a proof on these instances; see
//! BENCHMARKS.md), no node budget, no time budget, one thread. Criterion: 10 samples, flat
//! sampling.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode, criterion_group, criterion_main};
use planner::{
    BoundKind, Instance, PlanStatus, SearchSettings, State, b6_problem, plan, validate_plan,
};

const SIZES: [usize; 3] = [20, 40, 80];
const SEEDS: [u64; 3] = [1, 2, 3];

fn proof_settings() -> SearchSettings {
    SearchSettings {
        node_budget: None,
        time_budget: None,
        bound: BoundKind::Knapsack,
        ..SearchSettings::default()
    }
}

fn bench_planner(c: &mut Criterion) {
    let dump = std::env::var_os("SOLSIM_PLANNER_DUMP").map(std::path::PathBuf::from);
    if let Some(d) = &dump {
        std::fs::create_dir_all(d).expect("dump dir");
    }
    let mut group = c.benchmark_group("planner_b6");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for n in SIZES {
        for seed in SEEDS {
            let problem = b6_problem(n, seed);
            let out = plan(&problem, &proof_settings()).expect("valid problem");
            assert_eq!(out.status, PlanStatus::Optimal, "n{n} seed{seed}");
            let inst = Instance::new(&problem).expect("valid problem");
            assert!(validate_plan(&inst, &State::initial(&inst), &out.plan).is_empty());
            eprintln!(
                "n{n} seed{seed}: optimal {} ({} nodes expanded, {} generated, {:.1} ms once)",
                out.value,
                out.stats.nodes_expanded,
                out.stats.nodes_generated,
                out.stats.total_time.as_secs_f64() * 1e3
            );
            if let Some(d) = &dump {
                let stem = d.join(format!("n{n}_seed{seed}"));
                let json = serde_json::to_string_pretty(&problem).expect("serialise");
                std::fs::write(stem.with_extension("json"), json).expect("write problem");
                let summary = serde_json::json!({
                    "status": format!("{:?}", out.status),
                    "value_micro": out.value.tiers_micro,
                    "bound_micro": out.best_bound.tiers_micro,
                    "nodes": out.stats.nodes_expanded,
                });
                std::fs::write(stem.with_extension("planner.json"), summary.to_string())
                    .expect("write summary");
            }
            group.bench_with_input(
                BenchmarkId::new(format!("prove_n{n}"), seed),
                &problem,
                |b, p| b.iter(|| plan(black_box(p), &proof_settings()).expect("valid")),
            );
        }
    }
    // Anytime: 10 ms on each 80-activity instance.
    for seed in SEEDS {
        let problem = b6_problem(80, seed);
        let settings = SearchSettings {
            node_budget: None,
            time_budget: Some(Duration::from_millis(10)),
            bound: BoundKind::Knapsack,
            ..SearchSettings::default()
        };
        let inst = Instance::new(&problem).expect("valid problem");
        for rep in 0..5 {
            let out = plan(&problem, &settings).expect("valid problem");
            assert!(matches!(
                out.status,
                PlanStatus::Optimal | PlanStatus::Feasible
            ));
            assert!(validate_plan(&inst, &State::initial(&inst), &out.plan).is_empty());
            eprintln!(
                "anytime 10 ms n80 seed{seed} run {rep}: {:?} value {} bound {} gap {:?} \
                 ({} nodes, {:.1} ms)",
                out.status,
                out.value,
                out.best_bound,
                out.gap_points(),
                out.stats.nodes_expanded,
                out.stats.total_time.as_secs_f64() * 1e3
            );
        }
        group.bench_with_input(
            BenchmarkId::new("anytime_10ms_n80", seed),
            &problem,
            |b, p| b.iter(|| plan(black_box(p), &settings).expect("valid")),
        );
    }
    group.finish();
}

criterion_group!(benches, bench_planner);
criterion_main!(benches);
