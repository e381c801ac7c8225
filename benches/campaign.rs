//! Whole-job benchmark: `solsim compare` on the rapid traverse (sols 379-409, ≈5 km, all five
//! strategies), exactly what the README's first command runs minus printing and file output.
//!
//! Three stages are timed separately so a regression points at its stage:
//! - `load`: parse the scenario, read the GeoTIFF maps and the zones, build the planning grid
//!   (two exact EDTs over 4800 × 1000 cells of 2 m, slope and terrain sampling) and the per-leg
//!   passage clearances (computed once per scenario since issue 10);
//! - `strategies`: the five campaign runs (rayon over strategies, as the CLI does);
//! - `compare_total`: both, end to end. Target (issue 2): under 2 s on this 2-core machine.

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
        b.iter(|| scenario.compare(&strategies, scenario.seed()))
    });
    group.bench_function("compare_total", |b| {
        b.iter(|| {
            let s = Scenario::load(&path).expect("bundled scenario loads");
            let runs = s.compare(&s.strategies(), s.seed());
            assert_eq!(runs.len(), 5);
            runs
        });
    });
    group.finish();
}

criterion_group!(benches, bench_compare);
criterion_main!(benches);
