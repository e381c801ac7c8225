//! B6: the activity planner's time to proven optimum on the generated 20/40/80-activity
//! instances ([`planner::b6_problem`], seeds 1–3), a capped proof attempt on 160 and 320, and the
//! 10 ms anytime run on 80; and the proof of each of the simulator's own sol problems
//! (`peers/planner_fixtures/sol_problems`, `prove_sol/<stem>`).
//!
//! `cargo bench --bench planner` (the peer comparison: `peers/run_peer_benchmarks.sh planner`).
//! With `SOLSIM_PLANNER_DUMP=<dir>` the bench writes every instance as `Problem` JSON
//! (`n{N}_seed{S}.json`) and the planner's result next to it (`n{N}_seed{S}.planner.json`:
//! status, value per tier in micro-points, bound, nodes), which `peers/planner_cpsat.py`
//! solves and checks in the same job.
//!
//! Settings: [`BoundKind::Knapsack`] (the fastest to a proof on these instances; see
//! BENCHMARKS.md), one thread. Criterion: 10 samples, flat sampling.
//!
//! - n ≤ 80: no node or time budget; the proof must succeed, and criterion times it.
//! - n ≥ [`CAPPED_FROM`] (160, 320): a proof may take very long (n = 320 seed 2 took 4 182
//!   nodes, 14 s, once the time-indexed bound came in; before it, no proof in 20 000 nodes), so
//!   the bench makes ONE attempt capped at [`PROOF_NODE_CAP`] nodes (which makes
//!   the outcome deterministic) and [`PROOF_TIME_CAP`] (a safety net against a slow machine).
//!   A proof within the cap is then timed by criterion (`prove_n{N}`, under the same caps, so no
//!   sample can hang); otherwise the bench prints "not proven within …" with the value, bound and
//!   gap, writes them to the `.planner.json` (status `Feasible`, plus the cap), and times nothing.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode, criterion_group, criterion_main};
use planner::{
    BoundKind, Instance, PlanStatus, SearchSettings, State, b6_problem, plan, validate_plan,
};

const SIZES: [usize; 5] = [20, 40, 80, 160, 320];
const SEEDS: [u64; 3] = [1, 2, 3];
/// From this size on, the proof is one capped attempt (see the crate docs above).
const CAPPED_FROM: usize = 160;
/// Node cap of that attempt: n = 160 needs 241–475 nodes and n = 320 222–4 182 (seed 2, about
/// 300 nodes/s), so the cap binds only on a harder instance or a regression.
const PROOF_NODE_CAP: u64 = 20_000;
/// Time cap of that attempt: binds only on a machine 2–3× slower than the reference one.
const PROOF_TIME_CAP: Duration = Duration::from_secs(60);

fn proof_settings() -> SearchSettings {
    SearchSettings {
        node_budget: None,
        time_budget: None,
        bound: BoundKind::Knapsack,
        ..SearchSettings::default()
    }
}

/// The capped proof attempt for n ≥ [`CAPPED_FROM`].
fn capped_proof_settings() -> SearchSettings {
    SearchSettings {
        node_budget: Some(PROOF_NODE_CAP),
        time_budget: Some(PROOF_TIME_CAP),
        ..proof_settings()
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
            let capped = n >= CAPPED_FROM;
            let settings = if capped {
                capped_proof_settings()
            } else {
                proof_settings()
            };
            let out = plan(&problem, &settings).expect("valid problem");
            if capped {
                assert!(
                    matches!(out.status, PlanStatus::Optimal | PlanStatus::Feasible),
                    "n{n} seed{seed}: {:?}",
                    out.status
                );
            } else {
                assert_eq!(out.status, PlanStatus::Optimal, "n{n} seed{seed}");
            }
            let inst = Instance::new(&problem).expect("valid problem");
            assert!(validate_plan(&inst, &State::initial(&inst), &out.plan).is_empty());
            let proven = out.status == PlanStatus::Optimal;
            if proven {
                eprintln!(
                    "n{n} seed{seed}: optimal {} ({} nodes expanded, {} generated, {:.1} ms once)",
                    out.value,
                    out.stats.nodes_expanded,
                    out.stats.nodes_generated,
                    out.stats.total_time.as_secs_f64() * 1e3
                );
            } else {
                eprintln!(
                    "n{n} seed{seed}: NOT PROVEN within {PROOF_NODE_CAP} nodes / {} s: value {} \
                     bound {} gap {:?} ({} nodes expanded, {:.1} ms); not timed",
                    PROOF_TIME_CAP.as_secs(),
                    out.value,
                    out.best_bound,
                    out.gap_points(),
                    out.stats.nodes_expanded,
                    out.stats.total_time.as_secs_f64() * 1e3
                );
            }
            if let Some(d) = &dump {
                let stem = d.join(format!("n{n}_seed{seed}"));
                let json = serde_json::to_string_pretty(&problem).expect("serialise");
                std::fs::write(stem.with_extension("json"), json).expect("write problem");
                let mut summary = serde_json::json!({
                    "status": format!("{:?}", out.status),
                    "value_micro": out.value.tiers_micro,
                    "bound_micro": out.best_bound.tiers_micro,
                    "nodes": out.stats.nodes_expanded,
                });
                if capped {
                    summary["cap"] = serde_json::json!({
                        "nodes": PROOF_NODE_CAP,
                        "time_s": PROOF_TIME_CAP.as_secs(),
                        "search_ms": out.stats.total_time.as_secs_f64() * 1e3,
                    });
                }
                std::fs::write(stem.with_extension("planner.json"), summary.to_string())
                    .expect("write summary");
            }
            if proven {
                group.bench_with_input(
                    BenchmarkId::new(format!("prove_n{n}"), seed),
                    &problem,
                    |b, p| b.iter(|| plan(black_box(p), &settings).expect("valid")),
                );
            }
        }
    }
    // The simulator's own sol problems (peers/planner_fixtures/sol_problems, written by
    // study/examples/dump_sol_problems.rs): `prove_sol/<stem>`, dumped as `sol_<stem>.json`.
    let fixtures = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("peers/planner_fixtures/sol_problems");
    let mut files: Vec<_> = std::fs::read_dir(&fixtures)
        .expect("peers/planner_fixtures/sol_problems")
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    for f in files {
        let stem = f.file_stem().expect("stem").to_string_lossy().into_owned();
        let text = std::fs::read_to_string(&f).expect("read a sol problem");
        let problem: planner::Problem = serde_json::from_str(&text).expect("a Problem");
        let out = plan(&problem, &proof_settings()).expect("valid problem");
        assert_eq!(out.status, PlanStatus::Optimal, "{stem}");
        eprintln!(
            "sol problem {stem}: optimal {} ({} nodes expanded, {:.2} ms once)",
            out.value,
            out.stats.nodes_expanded,
            out.stats.total_time.as_secs_f64() * 1e3
        );
        if let Some(d) = &dump {
            let base = d.join(format!("sol_{stem}"));
            std::fs::write(base.with_extension("json"), &text).expect("write problem");
            let summary = serde_json::json!({
                "status": format!("{:?}", out.status),
                "value_micro": out.value.tiers_micro,
                "bound_micro": out.best_bound.tiers_micro,
                "nodes": out.stats.nodes_expanded,
            });
            std::fs::write(base.with_extension("planner.json"), summary.to_string())
                .expect("write summary");
        }
        group.bench_with_input(BenchmarkId::new("prove_sol", &stem), &problem, |b, p| {
            b.iter(|| plan(black_box(p), &proof_settings()).expect("valid"))
        });
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
