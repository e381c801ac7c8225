//! What to sweep: [`SweepSpec`] (runs, strategies, seed, baseline, shard, chunk size), the
//! slice of run indices one machine runs ([`Shard`]), and their checks against the scenario
//! and the memory budget.

use std::collections::BTreeSet;
use std::ops::Range;

use sim::Strategy;
use study::Scenario;

use crate::error::SweepError;

/// Default runs per committed chunk.
pub const DEFAULT_CHUNK_RUNS: u64 = 10;
/// Most runs one sweep may ask for (a run index is a `u64`; this keeps the run table and its
/// statistics within memory: 5 strategies × 10⁸ runs would be ~80 GB of rows).
pub const MAX_RUNS: u64 = 10_000_000;
/// Memory per row of the run table held for the statistics, bytes (`RunRow` with its vector
/// slot, rounded up).
pub(crate) const RUN_ROW_BYTES: u64 = 192;

/// Checks a run count (`--runs`): from `fewest` to [`MAX_RUNS`]. [`SweepSpec::validate`]
/// calls it with 1; `solsim compare --runs` with 2.
///
/// # Errors
/// `runs` outside that range: `--runs: expected a number of runs from 1 to 10000000, got 0`.
pub fn check_runs(runs: u64, fewest: u64) -> Result<(), SweepError> {
    if runs < fewest || runs > MAX_RUNS {
        return Err(SweepError::option(
            "--runs",
            format!("a number of runs from {fewest} to {MAX_RUNS}"),
            runs,
        ));
    }
    Ok(())
}

/// A slice of the run indices: `--shard INDEX/COUNT`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0..count`.
    pub index: u64,
    /// Shards in all.
    pub count: u64,
}

impl Shard {
    /// Parses `K/N` (`0 ≤ K < N`).
    ///
    /// # Errors
    /// Anything else.
    pub fn parse(text: &str) -> Result<Self, SweepError> {
        let bad = || SweepError::option("--shard", "K/N with 0 ≤ K < N (e.g. 0/4)", text);
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count): (u64, u64) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// The run indices of this shard: `index·runs/count .. (index+1)·runs/count`, so shards
    /// `0..count` tile `0..runs` in order.
    #[must_use]
    pub fn range(self, runs: u64) -> Range<u64> {
        let at = |k: u64| (u128::from(k) * u128::from(runs) / u128::from(self.count)) as u64;
        at(self.index)..at(self.index + 1)
    }
}

/// What to sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepSpec {
    /// Run indices `0..runs`.
    pub runs: u64,
    /// Strategies, each run under every one (in this order in the tables).
    pub strategies: Vec<Strategy>,
    /// The sweep's seed: run `i` runs under [`sim::seeds::RunSeeds::new`]`(seed, i)`.
    pub seed: u64,
    /// The strategy paired differences are taken against (`None`: none).
    pub baseline: Option<Strategy>,
    /// Run only this slice.
    pub shard: Option<Shard>,
    /// Runs per committed chunk.
    pub chunk_runs: u64,
}

impl SweepSpec {
    /// A sweep of `runs` runs of every strategy that makes sense for the scenario, under its
    /// own seed, against `ground`.
    #[must_use]
    pub fn new(scenario: &Scenario, runs: u64) -> Self {
        let strategies = scenario.strategies();
        Self {
            runs,
            baseline: strategies
                .contains(&Strategy::Ground)
                .then_some(Strategy::Ground),
            strategies,
            seed: scenario.seed(),
            shard: None,
            chunk_runs: DEFAULT_CHUNK_RUNS,
        }
    }

    /// The run indices this sweep runs.
    #[must_use]
    pub fn run_range(&self) -> Range<u64> {
        self.shard.map_or(0..self.runs, |s| s.range(self.runs))
    }

    /// Checks the spec against the scenario and the memory budget.
    ///
    /// # Errors
    /// No runs or strategies, too many runs, a strategy twice, `replay` without historic
    /// data, a baseline that is not one of the strategies.
    pub fn validate(
        &self,
        scenario: &Scenario,
        budget: maps::MemoryBudget,
    ) -> Result<(), SweepError> {
        check_runs(self.runs, 1)?;
        if let Some(s) = self.shard
            && s.count > self.runs
        {
            return Err(SweepError::option(
                "--shard",
                format!("at most --runs ({}) shards", self.runs),
                format!("{}/{}", s.index, s.count),
            ));
        }
        // The run table of this slice, held for the statistics, beside the scenario's maps and
        // planning grid (already checked against the budget when it was loaded).
        let r = self.run_range();
        let table = (r.end - r.start) * self.strategies.len() as u64 * RUN_ROW_BYTES;
        let grid = &scenario.settings.grid;
        let maps = maps::memory_budget::bytes_of(&[
            grid.width as u64,
            grid.height as u64,
            sim::grid::planning_grid::PlanningGrid::BYTES_PER_CELL,
        ]);
        if !budget.allows(table.saturating_add(maps)) {
            return Err(SweepError::option(
                "--runs",
                format!(
                    "a sweep whose run table fits the memory budget (--memory-budget-mib, {}) beside the planning grid ({}): {} runs × {} {} need {}",
                    maps::input_file::human_bytes(budget.limit_bytes),
                    maps::input_file::human_bytes(maps),
                    r.end - r.start,
                    self.strategies.len(),
                    if self.strategies.len() == 1 {
                        "strategy"
                    } else {
                        "strategies"
                    },
                    maps::input_file::human_bytes(table)
                ),
                self.runs,
            ));
        }
        if self.strategies.is_empty() {
            return Err(SweepError::option(
                "--strategies",
                "at least one strategy",
                "none",
            ));
        }
        let mut seen = BTreeSet::new();
        for s in &self.strategies {
            if !seen.insert(s.stream_id()) {
                return Err(SweepError::option(
                    "--strategies",
                    "each strategy once",
                    format!("{} twice", s.name()),
                ));
            }
            if *s == Strategy::Replay && !scenario.has_history {
                return Err(SweepError::option(
                    "--strategies",
                    format!(
                        "strategies without replay: {} has no historic drives",
                        scenario.path.display()
                    ),
                    "replay",
                ));
            }
        }
        if let Some(b) = self.baseline
            && !self.strategies.contains(&b)
        {
            return Err(SweepError::option(
                "--baseline",
                format!(
                    "one of the swept strategies ({})",
                    self.strategies
                        .iter()
                        .map(|s| s.name())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                b.name(),
            ));
        }
        if self.chunk_runs == 0 {
            return Err(SweepError::option("--chunk-runs", "at least 1", 0));
        }
        Ok(())
    }
}
