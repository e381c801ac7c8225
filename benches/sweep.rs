//! Monte Carlo sweep benchmarks: where a sweep's time goes.
//!
//! - `runs_rapid_traverse_5_strategies/10`: 10 run indices × the five strategies of the rapid
//!   traverse (statistical localizer) through `sweep::engine::run_in_memory` — the simulation
//!   itself, parallel over runs and strategies as `solsim sweep` runs it, scenario loaded once;
//! - `parquet_sols_table`: the rows of those 10 runs (one per run × strategy × sol) written as
//!   `sols.parquet` by `sweep::parquet_io::TableWriter` (the peer is pyarrow's
//!   `pq.write_table`, `peers/bench_sweep.py`);
//! - `paired_bootstrap_1000_x_10000`: one paired difference's 95 % interval, 10 000 resamples
//!   of 1000 runs (the peer is `scipy.stats.bootstrap`, `peers/bench_sweep.py`).
//!
//! - `runs_dune_crossing_ground/{slip_aware,slip_unaware}`: 10 run indices of
//!   `scenarios/dune-crossing.toml` and its slip-blind twin under `ground` (issue 15): slip
//!   from the rapier rover's profile every step; the slip-aware one plans with
//!   direction-dependent move costs (`AStar::plan_edges`);
//! - `runs_rapid_traverse_5_strategies_slip_profile/10`: the first benchmark with the rapid
//!   traverse's `[rover]` switched to `slip_model = "profile"` (slip-aware routing), what the
//!   slip model costs a sweep on the 4800 × 1000 grid.
//!
//! `SOLSIM_SWEEP_DUMP=DIR` also writes the benchmark's `sols.parquet` and the bootstrap input
//! there, for the peer script to time the same data.

use std::path::Path;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use study::Scenario;
use sweep::engine::{SweepSpec, run_in_memory};

fn scenario() -> Scenario {
    bundled("rapid-traverse-379-409.toml")
}

fn bundled(name: &str) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(name);
    Scenario::load(&path).expect("bundled scenario loads")
}

/// The rapid traverse with `slip_model = "profile"`, written with absolute map paths into `dir`.
fn rapid_traverse_slip_profile(dir: &Path) -> Scenario {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("scenarios/rapid-traverse-379-409.toml"))
        .expect("read")
        .replace("\"../maps/", &format!("\"{}/maps/", root.display()))
        .replace(
            "zones = \"",
            &format!("zones = \"{}/scenarios/", root.display()),
        )
        .replacen("\n[rover]\n", "\n[rover]\nslip_model = \"profile\"\n", 1);
    let path = dir.join("rapid-traverse-slip-profile.toml");
    std::fs::write(&path, text).expect("write");
    Scenario::load(&path).expect("the slip-profile rapid traverse loads")
}

fn sol_rows(scenario: &Scenario, runs: u64) -> Vec<sweep::rows::SolRow> {
    let seg = scenario.study_segment;
    let mut rows = Vec::new();
    for run in 0..runs {
        let seeds = sim::seeds::RunSeeds::new(scenario.seed(), run);
        for s in scenario.strategies() {
            rows.extend(sweep::rows::rows_of(run, seeds.master(), &scenario.run(s, seeds), seg).1);
        }
    }
    rows
}

fn bench_sweep(c: &mut Criterion) {
    let scenario = scenario();
    let mut group = c.benchmark_group("sweep");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(15));
    let spec = SweepSpec::new(&scenario, 10);
    group.bench_with_input(
        BenchmarkId::new("runs_rapid_traverse_5_strategies", 10),
        &spec,
        |b, spec| b.iter(|| run_in_memory(&scenario, spec, 0..spec.runs)),
    );

    for (name, file) in [
        ("slip_aware", "dune-crossing.toml"),
        ("slip_unaware", "dune-crossing-slip-unaware.toml"),
    ] {
        let dune = bundled(file);
        let mut spec = SweepSpec::new(&dune, 10);
        spec.strategies = vec![sim::Strategy::Ground];
        spec.baseline = None;
        group.bench_with_input(
            BenchmarkId::new("runs_dune_crossing_ground", name),
            &spec,
            |b, spec| b.iter(|| run_in_memory(&dune, spec, 0..spec.runs)),
        );
    }
    let tmp = tempfile::tempdir().expect("tempdir");
    let profile = rapid_traverse_slip_profile(tmp.path());
    let spec_profile = SweepSpec::new(&profile, 10);
    group.bench_with_input(
        BenchmarkId::new("runs_rapid_traverse_5_strategies_slip_profile", 10),
        &spec_profile,
        |b, spec| b.iter(|| run_in_memory(&profile, spec, 0..spec.runs)),
    );

    let rows = sol_rows(&scenario, 10);
    let batch = sweep::rows::sols_batch(&rows).expect("rows fit the schema");
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("sols.parquet");
    group.bench_function("parquet_sols_table", |b| {
        b.iter(|| {
            let mut w =
                sweep::parquet_io::TableWriter::create(&out, sweep::rows::sols_schema(), &[])
                    .expect("create");
            w.push(&batch).expect("push");
            w.finish().expect("finish");
        })
    });

    // Paired differences like a sweep's: small integers with a few outliers, fixed.
    let diffs: Vec<f64> = (0..1000_u64)
        .map(|i| -2.0 + ((i * 2_654_435_761) % 7) as f64 / 3.0)
        .collect();
    group.bench_function("paired_bootstrap_1000_x_10000", |b| {
        b.iter(|| sweep::stats::paired_bootstrap(&diffs, 10_000, 0.95, 7))
    });
    group.finish();

    if let Some(dump) = std::env::var_os("SOLSIM_SWEEP_DUMP") {
        let dump = Path::new(&dump);
        std::fs::create_dir_all(dump).expect("dump dir");
        std::fs::copy(&out, dump.join("sols.parquet")).expect("copy sols.parquet");
        let text: Vec<String> = diffs.iter().map(|d| format!("{d:?}")).collect();
        std::fs::write(dump.join("diffs.txt"), text.join("\n")).expect("write diffs");
    }
}

criterion_group!(benches, bench_sweep);
criterion_main!(benches);
