//! Expected outcomes in scenario files (`[[expect]]`): what an entry holds once validated
//! ([`Expectation`] of one run, [`StatisticalExpectation`] over runs, each a list of checks)
//! and how a failed check is told ([`Mismatch`]). [`raw`] parses and validates the entries as
//! written. The checking itself is `sweep::expect`, the one module that checks both kinds
//! (a check over runs needs the sweep engine, which this crate sits below); `solsim regress`
//! runs it over a directory.
//!
//! ```toml
//! [[expect]]
//! what = "sol 385 faults NO_PATH after ~14 m at r ≈ 26.9 m"   # printed on failure
//! strategy = "replay"
//! sol = 385                        # per-sol checks below need a sol
//! fault = "NO_PATH"                # or "none"
//! fault_after_m = [12.0, 16.0]     # closed ranges [low, high]
//! fault_uncertainty_m = [26.8, 27.0]
//! distance_m = [240.0, 250.0]
//! end_uncertainty_m = [32.82, 33.02]
//! drove = true
//!
//! [[expect]]                       # totals of a run
//! strategy = "onboard"
//! no_path_faults = [0, 0]
//! sols_to_goal = [1, 3]
//! goal_sooner_than = { strategy = "replay", by_at_least_sols = 1 }
//! covers = { from_sol = 402, distance_m = 1411.0, sols = [6, 6] }
//!
//! [[expect]]                       # over a sweep: runs 0..200 of each strategy named
//! what = "onboard rarely faults; it reaches the goal sooner than ground"
//! strategy = "onboard"
//! runs = 200                       # statistical checks below need runs
//! no_path_rate = [0.0, 0.10]       # the rate over the runs within [low, high]; also
//!                                  # fault_rate, truth_outside_disc_rate, goal_reached_rate
//! paired = { baseline = "ground", figure = "sols_to_goal", mean = [-2.0, -0.5] }
//!                                  # or the share of runs with a difference ≤ at_most:
//!                                  # paired = { …, at_most = -1, share = [0.95, 1.0] }
//!
//! [[expect]]                       # the disc's coverage: drive sols ending with the truth
//! strategy = "ground"              # inside it, pooled over the runs
//! runs = 200
//! errors = "stress"                # under another error model than the scenario's
//! disc_coverage = [0.0, 0.99]
//!
//! [[expect]]                       # what-if: ground without paper 000 §2's pre-emptive
//! strategy = "ground"              # shortening (the scenario's [operations] otherwise)
//! runs = 200
//! preemptive_shortening = false
//! no_path_rate = [0.05, 1.0]
//! ```
//!
//! A statistical entry checks the point estimate (a rate, or the mean paired difference over
//! the run indices where both strategies have the figure) against its range; `solsim regress`
//! prints the 95 % interval beside it. The figures are the columns of a sweep's `runs.parquet`
//! ([`crate::metric::Metric`]).

use crate::metric::{Metric, RateKind};
use sim::{FaultKind, Strategy};

pub mod raw;

/// Most runs a statistical expectation may ask for.
pub const MAX_EXPECT_RUNS: u64 = 100_000;

/// One check of a statistical expectation.
#[derive(Debug, Clone, PartialEq)]
pub enum StatCheck {
    /// The rate of runs with the outcome within `[lo, hi]`.
    Rate {
        /// Which rate.
        rate: RateKind,
        /// Bounds (fractions).
        lo: f64,
        /// Bounds (fractions).
        hi: f64,
    },
    /// The disc's coverage within `[lo, hi]`: the fraction of drive sols, pooled over the
    /// runs, that ended with the truth inside the uncertainty disc.
    DiscCoverage {
        /// Bounds (fractions).
        lo: f64,
        /// Bounds (fractions).
        hi: f64,
    },
    /// The mean over runs of (strategy − baseline) on `figure` within `[lo, hi]`.
    Paired {
        /// The other strategy.
        baseline: Strategy,
        /// The figure.
        figure: Metric,
        /// Bounds.
        lo: f64,
        /// Bounds.
        hi: f64,
    },
    /// The share of paired runs with (strategy − baseline) on `figure` at most `at_most`
    /// within `[lo, hi]` (for instance the goal at least one sol sooner in ≥ 95 % of runs).
    PairedShare {
        /// The other strategy.
        baseline: Strategy,
        /// The figure.
        figure: Metric,
        /// The difference counted.
        at_most: f64,
        /// Bounds (fractions).
        lo: f64,
        /// Bounds (fractions).
        hi: f64,
    },
}

/// A validated `[[expect]]` entry that holds over a sweep (`runs = N`).
#[derive(Debug, Clone, PartialEq)]
pub struct StatisticalExpectation {
    /// Index in the file.
    pub index: usize,
    /// Human description.
    pub what: String,
    /// Strategy run.
    pub strategy: Strategy,
    /// Run indices `0..runs`.
    pub runs: u64,
    /// The error model the sweep runs under, when not the scenario's own (`errors = "stress"`).
    pub errors: Option<sim::rover::errors::ErrorPreset>,
    /// `[operations] preemptive_shortening` for the sweep, when not the scenario's
    /// (`preemptive_shortening = false`).
    pub preemptive_shortening: Option<bool>,
    /// The checks.
    pub checks: Vec<StatCheck>,
}

impl StatisticalExpectation {
    /// The strategies this expectation needs swept.
    #[must_use]
    pub fn strategies(&self) -> Vec<Strategy> {
        let mut v = vec![self.strategy];
        for c in &self.checks {
            if let StatCheck::Paired { baseline, .. } | StatCheck::PairedShare { baseline, .. } = c
            {
                v.push(*baseline);
            }
        }
        v
    }
}

/// An `[[expect]]` entry: of one seeded run, or over a sweep.
#[derive(Debug, Clone, PartialEq)]
pub enum Resolved {
    /// Checks of one run per strategy under the scenario's seed.
    Run(Expectation),
    /// Checks over runs `0..runs`.
    Sweep(StatisticalExpectation),
}

/// One check on one quantity of a run.
#[derive(Debug, Clone, PartialEq)]
pub enum Check {
    /// The sol's fault kind (`None` = no fault).
    Fault(Option<FaultKind>),
    /// A real quantity of the sol or the run within `[lo, hi]`.
    Range {
        /// Name of the quantity as printed.
        quantity: &'static str,
        /// Bounds.
        lo: f64,
        /// Bounds.
        hi: f64,
    },
    /// Whether the sol drove.
    Drove(bool),
    /// The goal is reached at least `by` sols sooner than under `than`.
    Sooner {
        /// The other strategy.
        than: Strategy,
        /// Sols.
        by: u32,
    },
    /// Sols needed to drive `distance_m` from `from_sol`, within `[lo, hi]`.
    Covers {
        /// First sol counted.
        from_sol: u32,
        /// Metres.
        distance_m: f64,
        /// Bounds.
        lo: u32,
        /// Bounds.
        hi: u32,
    },
    /// A science campaign's members done (or failed) over the run, within `[lo, hi]`.
    Science {
        /// Campaign id.
        campaign: String,
        /// Count the members that failed rather than those done.
        failed: bool,
        /// Bounds.
        lo: u32,
        /// Bounds.
        hi: u32,
    },
}

/// A validated `[[expect]]` entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Expectation {
    /// Index in the file.
    pub index: usize,
    /// Human description.
    pub what: String,
    /// Strategy run.
    pub strategy: Strategy,
    /// Sol for per-sol checks.
    pub sol: Option<u32>,
    /// The checks.
    pub checks: Vec<Check>,
}

/// One failed check.
#[derive(Debug, Clone, PartialEq)]
pub struct Mismatch {
    /// What was checked, e.g. `replay sol 385 fault_after_m`.
    pub check: String,
    /// What the file expects.
    pub expected: String,
    /// What the run gave.
    pub got: String,
}

impl Expectation {
    /// The strategies this expectation needs run.
    #[must_use]
    pub fn strategies(&self) -> Vec<Strategy> {
        let mut v = vec![self.strategy];
        for c in &self.checks {
            if let Check::Sooner { than, .. } = c {
                v.push(*than);
            }
        }
        v
    }
}
