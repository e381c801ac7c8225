//! Simulating a sweep's runs: each run index under every strategy, in parallel, to the rows of
//! its tables ([`crate::rows`]), and a sweep without files ([`run_in_memory`],
//! [`summary_in_memory`]). Every strategy of one run sees the same world; the rows do not
//! depend on the thread count.

use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};

use rayon::prelude::*;
use study::Scenario;

use crate::manifest::Manifest;
use crate::rows::{self, RunRow, SolRow};
use crate::spec::SweepSpec;
use crate::summary::{Summary, summarise};

/// Runs run `run` under every strategy: the rows, in strategy order.
pub(crate) fn run_rows(
    scenario: &Scenario,
    spec: &SweepSpec,
    run: u64,
) -> Vec<(RunRow, Vec<SolRow>)> {
    let segment = scenario.study_segment;
    let seeds = sim::seeds::RunSeeds::new(spec.seed, run);
    spec.strategies
        .par_iter()
        .map(|&s| rows::rows_of(run, seeds.master(), &scenario.run(s, seeds), segment))
        .collect()
}

/// Runs `runs` under every strategy, in parallel over runs and strategies, and returns the
/// run rows in run order (strategies in `spec` order): a sweep without files, for the
/// statistical `[[expect]]` checks (`solsim regress`) and `sweep::whatif`.
#[must_use]
pub fn run_in_memory(scenario: &Scenario, spec: &SweepSpec, runs: Range<u64>) -> Vec<RunRow> {
    rows_in_memory(scenario, spec, runs, &|_, _| {})
}

/// [`run_in_memory`], calling `progress(done, total)` with the run indices done after each.
fn rows_in_memory(
    scenario: &Scenario,
    spec: &SweepSpec,
    runs: Range<u64>,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Vec<RunRow> {
    let total = runs.end - runs.start;
    let done = AtomicU64::new(0);
    runs.into_par_iter()
        .flat_map_iter(|run| {
            let rows: Vec<RunRow> = run_rows(scenario, spec, run)
                .into_iter()
                .map(|(r, _)| r)
                .collect();
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            rows
        })
        .collect()
}

/// Runs the sweep `spec` in memory — no directory, no Parquet files, no sol rows kept — and
/// returns its [`Summary`]: the one [`crate::run`] writes to `summary.json` for the same scenario and
/// spec, equal once serialised (row order and arithmetic are the same; the thread count changes
/// neither). `progress(done, total)` is called with the run indices done after each one. This
/// is what `solsim compare --runs N` reports. Check the spec with [`SweepSpec::validate`] first:
/// the run table is held in memory.
#[must_use]
pub fn summary_in_memory(
    scenario: &Scenario,
    spec: &SweepSpec,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Summary {
    let rows = rows_in_memory(scenario, spec, spec.run_range(), progress);
    summarise(&rows, &Manifest::fresh(scenario, spec))
}
