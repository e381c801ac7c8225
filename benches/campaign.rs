//! Whole-job benchmark: `solsim compare` on the rapid traverse (sols 379-409, ≈5 km, all five
//! strategies), exactly what the README's first command runs minus printing and file output.
//!
//! Three stages are timed separately so a regression points at its stage:
//! - `load`: parse the scenario, read the GeoTIFF maps and the zones, build the planning grid
//!   (two exact EDTs over 4800 × 1000 cells of 2 m, slope and terrain sampling) and the per-leg
//!   passage clearances (computed once per scenario since issue 10);
//! - `strategies`: the five campaign runs (rayon over strategies, as the CLI does);
//! - `compare_total`: both, end to end. Target (issue 2): under 2 s on this 2-core machine.
//!
//! And a Monte Carlo sweep's inner loop (`monte_carlo_sweep`): the scenario loaded once, then
//! run indices under every strategy, in parallel over (run, strategy) pairs, as `solsim sweep`
//! does; each iteration takes the next runs, so the shared caches (A* scratch, the census
//! localizer's terrain tiles) are warm as in a long sweep but the runs are new. Times are per
//! iteration of `RUNS_PER_ITER` runs × 5 strategies. Targets on this 2-core machine at 2 threads:
//! rapid traverse ≤ 45 ms per run (1000 runs in ≤ 90 s), sols 383-386 with the census localizer
//! ≤ 225 ms per run (200 runs in ≤ 45 s).

use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use study::Scenario;

fn scenario_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/rapid-traverse-379-409.toml")
}

fn bench_compare(c: &mut Criterion) {
    let path = scenario_path();
    let mut group = c.benchmark_group("rapid_traverse_compare");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    group.bench_function("load", |b| {
        b.iter(|| Scenario::load(&path).expect("bundled scenario loads"))
    });
    let scenario = Scenario::load(&path).expect("bundled scenario loads");
    let strategies = scenario.strategies();
    group.bench_function("strategies", |b| {
        b.iter(|| scenario.compare(&strategies, scenario.seeds()))
    });
    group.bench_function("compare_total", |b| {
        b.iter(|| {
            let s = Scenario::load(&path).expect("bundled scenario loads");
            let runs = s.compare(&s.strategies(), s.seeds());
            assert_eq!(runs.len(), 5);
            runs
        });
    });
    group.finish();
}

/// Runs per iteration of the sweep benchmarks.
const RUNS_PER_ITER: u64 = 4;

fn bench_sweep(c: &mut Criterion) {
    use rayon::prelude::*;
    let mut group = c.benchmark_group("monte_carlo_sweep");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(20));
    for (name, file) in [
        ("rapid_traverse_4_runs", "rapid-traverse-379-409.toml"),
        ("sol383_386_census_4_runs", "sol383-386.toml"),
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenarios")
            .join(file);
        let scenario = Scenario::load(&path).expect("bundled scenario loads");
        let strategies = scenario.strategies();
        let mut next_run = 0;
        group.bench_function(name, |b| {
            b.iter(|| {
                let pairs: Vec<(u64, sim::Strategy)> = (next_run..next_run + RUNS_PER_ITER)
                    .flat_map(|r| strategies.iter().map(move |&s| (r, s)))
                    .collect();
                next_run += RUNS_PER_ITER;
                pairs
                    .par_iter()
                    .map(|&(r, s)| scenario.run_index(s, r).totals.distance_m)
                    .sum::<f64>()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_compare, bench_sweep);
criterion_main!(benches);
