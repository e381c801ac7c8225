//! What a study reports (`summary.json` and the printed table): per strategy the mean,
//! median, p5 and p95 of each figure and the rates with 95 % Wilson intervals; against the
//! baseline strategy the paired per-run difference of each figure with a seeded 95 % percentile
//! bootstrap interval. [`Summary`] is `summary.json` itself: the statistics with the sweep they
//! come from.

use std::path::Path;

use rayon::prelude::*;
use serde::Serialize;
use sim::Strategy;
use study::scenario::StudySegment;

use crate::error::SweepError;
use crate::manifest::{Manifest, ScenarioId, ShardInfo};
use crate::rows::RunRow;
use crate::stats::{self, Interval, PairedDifference, Spread};
pub use study::metric::{Metric, RateKind};

/// Confidence of every interval.
pub const CONFIDENCE: f64 = 0.95;
/// Bootstrap resamples of a paired difference.
pub const BOOTSTRAP_RESAMPLES: usize = 10_000;
/// Salt of the bootstrap seeds under the sweep's seed (see [`bootstrap_seed`]).
const BOOTSTRAP_SALT: u64 = 0x424f_4f54_0000_0000;

/// The value of `figure` in a run (`None`: the goal or the segment was not reached).
#[must_use]
pub fn metric_of(figure: Metric, r: &RunRow) -> Option<f64> {
    match figure {
        Metric::SolsToGoal => r.sols_to_goal.map(f64::from),
        Metric::SegmentSols => r.segment_sols.map(f64::from),
        Metric::SegmentDistanceM => r.segment_distance_m,
        Metric::DriveSols => Some(f64::from(r.drive_sols)),
        Metric::DistanceM => Some(r.distance_m),
        Metric::NoPathFaults => Some(f64::from(r.no_path_faults)),
        Metric::Faults => Some(f64::from(r.faults)),
        Metric::MaxUncertaintyM => Some(r.max_uncertainty_m),
        Metric::OnboardApplied => Some(f64::from(r.onboard_localizations_applied)),
        Metric::OnboardRejected => Some(f64::from(r.onboard_localizations_rejected)),
        Metric::MaxTruthErrorM => Some(r.max_truth_error_m),
        Metric::DriveTimeS => Some(r.drive_time_s),
        Metric::DrivePlanUplinks => Some(f64::from(r.drive_plan_uplinks)),
    }
}

/// Whether a run counts towards `rate`.
#[must_use]
pub fn counts_for(rate: RateKind, r: &RunRow) -> bool {
    match rate {
        RateKind::NoPath => r.no_path_faults > 0,
        RateKind::Fault => r.faults > 0,
        RateKind::TruthOutsideDisc => r.truth_outside_disc_sols > 0,
        RateKind::GoalReached => r.goal_reached,
    }
}

/// The disc's coverage over `runs`: drive sols that ended with the truth inside the
/// uncertainty disc, pooled over the runs, with a Wilson interval (`runs` counts the drive
/// sols here). Sols of one run are not independent draws, so the interval is narrower than a
/// run-clustered one would be; the point estimate is exact. `None`: no drive sol.
#[must_use]
pub fn disc_coverage(runs: &[&RunRow]) -> Option<Rate> {
    let sols: u64 = runs.iter().map(|r| u64::from(r.drive_sols)).sum();
    let outside: u64 = runs
        .iter()
        .map(|r| u64::from(r.truth_outside_disc_sols))
        .sum();
    let inside = sols.saturating_sub(outside);
    stats::wilson(inside, sols, CONFIDENCE).map(|interval| Rate {
        name: "disc_coverage".into(),
        count: inside,
        runs: sols,
        rate: inside as f64 / sols as f64,
        interval,
    })
}

/// A rate with its Wilson interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Rate {
    /// `no_path_rate`, `fault_rate`, `truth_outside_disc_rate`, `goal_reached_rate`
    /// (or `disc_coverage`, see [`disc_coverage`]).
    pub name: String,
    /// Runs that count (drive sols inside the disc, for `disc_coverage`).
    pub count: u64,
    /// Runs (drive sols, for `disc_coverage`).
    pub runs: u64,
    /// `count / runs`.
    pub rate: f64,
    /// 95 % Wilson score interval.
    pub interval: Interval,
}

/// A figure's spread over the runs where it has a value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FigureSummary {
    /// The `runs.parquet` column.
    pub name: String,
    /// Mean, median, p5, p95 and the number of runs with a value (`None`: no run has one).
    pub spread: Option<Spread>,
}

/// One strategy's figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrategySummary {
    /// The strategy.
    pub strategy: String,
    /// Runs.
    pub runs: u64,
    /// Rates.
    pub rates: Vec<Rate>,
    /// The disc's coverage over the drive sols ([`disc_coverage`]; `None`: no drive sol).
    pub disc_coverage: Option<Rate>,
    /// Figures.
    pub figures: Vec<FigureSummary>,
}

/// A strategy's paired difference from the baseline on one figure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairedSummary {
    /// The strategy.
    pub strategy: String,
    /// The `runs.parquet` column.
    pub figure: String,
    /// Mean of (strategy − baseline) over the run indices where both have a value, with its
    /// 95 % bootstrap interval (`None`: no such run).
    pub difference: Option<PairedDifference>,
}

/// The statistics of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Statistics {
    /// Confidence of the intervals.
    pub confidence: f64,
    /// Wilson score intervals for rates.
    pub rate_interval: String,
    /// Bootstrap resamples of each paired difference.
    pub bootstrap_resamples: usize,
    /// The strategy the paired differences are taken against.
    pub baseline: Option<String>,
    /// Per strategy, in the sweep's order.
    pub strategies: Vec<StrategySummary>,
    /// Paired differences from the baseline, per strategy and figure.
    pub paired: Vec<PairedSummary>,
}

/// The seed of the bootstrap of `strategy` against the baseline on `figure`: a fixed function
/// of the sweep's seed, so the intervals are as reproducible as the runs.
#[must_use]
pub fn bootstrap_seed(sweep_seed: u64, strategy: Strategy, figure: Metric) -> u64 {
    let k = Metric::ALL.iter().position(|f| *f == figure).unwrap_or(0) as u64;
    maps::procedural::noise::sub_seed(sweep_seed, BOOTSTRAP_SALT + 16 * k + strategy.stream_id())
}

/// The figures of a sweep with or without a study segment.
#[must_use]
pub fn metrics(has_segment: bool) -> Vec<Metric> {
    Metric::ALL
        .into_iter()
        .filter(|f| has_segment || !matches!(f, Metric::SegmentSols | Metric::SegmentDistanceM))
        .collect()
}

/// Per-strategy rates and spreads, and paired differences against `baseline` (when it is one
/// of `strategies`). `rows` are in run order, strategies in sweep order within a run.
#[must_use]
pub fn statistics(
    rows: &[RunRow],
    strategies: &[Strategy],
    baseline: Option<Strategy>,
    has_segment: bool,
    sweep_seed: u64,
) -> Statistics {
    let figures = metrics(has_segment);
    let of = |s: Strategy| -> Vec<&RunRow> { rows.iter().filter(|r| r.strategy == s).collect() };
    let per: Vec<StrategySummary> = strategies
        .iter()
        .map(|&s| {
            let runs = of(s);
            let n = runs.len() as u64;
            StrategySummary {
                strategy: s.name().into(),
                runs: n,
                rates: RateKind::ALL
                    .iter()
                    .filter_map(|k| {
                        let count = runs.iter().filter(|r| counts_for(*k, r)).count() as u64;
                        stats::wilson(count, n, CONFIDENCE).map(|interval| Rate {
                            name: k.name().into(),
                            count,
                            runs: n,
                            rate: count as f64 / n as f64,
                            interval,
                        })
                    })
                    .collect(),
                disc_coverage: disc_coverage(&runs),
                figures: figures
                    .iter()
                    .map(|f| {
                        let values: Vec<f64> =
                            runs.iter().filter_map(|r| metric_of(*f, r)).collect();
                        FigureSummary {
                            name: f.name().into(),
                            spread: stats::spread(&values),
                        }
                    })
                    .collect(),
            }
        })
        .collect();
    let paired = match baseline.filter(|b| strategies.contains(b)) {
        None => Vec::new(),
        Some(b) => {
            let base: std::collections::BTreeMap<u64, &RunRow> =
                of(b).into_iter().map(|r| (r.run_index, r)).collect();
            let jobs: Vec<(Strategy, Metric)> = strategies
                .iter()
                .filter(|&&s| s != b)
                .flat_map(|&s| figures.iter().map(move |&f| (s, f)))
                .collect();
            jobs.par_iter()
                .map(|&(s, f)| {
                    let diffs: Vec<f64> = of(s)
                        .iter()
                        .filter_map(|r| {
                            let mine = metric_of(f, r)?;
                            let theirs = metric_of(f, base.get(&r.run_index)?)?;
                            Some(mine - theirs)
                        })
                        .collect();
                    PairedSummary {
                        strategy: s.name().into(),
                        figure: f.name().into(),
                        difference: stats::paired_bootstrap(
                            &diffs,
                            BOOTSTRAP_RESAMPLES,
                            CONFIDENCE,
                            bootstrap_seed(sweep_seed, s, f),
                        ),
                    }
                })
                .collect()
        }
    };
    Statistics {
        confidence: CONFIDENCE,
        rate_interval: "wilson".into(),
        bootstrap_resamples: BOOTSTRAP_RESAMPLES,
        baseline: baseline.map(|b| b.name().into()),
        strategies: per,
        paired,
    }
}

impl Statistics {
    /// The summary of `strategy`.
    #[must_use]
    pub fn strategy(&self, strategy: &str) -> Option<&StrategySummary> {
        self.strategies.iter().find(|s| s.strategy == strategy)
    }

    /// The paired difference of `strategy` from the baseline on `figure`.
    #[must_use]
    pub fn paired(&self, strategy: &str, figure: &str) -> Option<&PairedSummary> {
        self.paired
            .iter()
            .find(|p| p.strategy == strategy && p.figure == figure)
    }
}

impl StrategySummary {
    /// The rate named `name`.
    #[must_use]
    pub fn rate(&self, name: &str) -> Option<&Rate> {
        self.rates.iter().find(|r| r.name == name)
    }

    /// The spread of the figure named `name`.
    #[must_use]
    pub fn figure(&self, name: &str) -> Option<&Spread> {
        self.figures
            .iter()
            .find(|f| f.name == name)
            .and_then(|f| f.spread.as_ref())
    }
}

/// `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// [`crate::manifest::FORMAT`].
    pub format: String,
    /// The scenario.
    pub scenario: ScenarioId,
    /// The sweep's seed.
    pub seed: u64,
    /// Run indices `0..runs` of the whole sweep.
    pub runs: u64,
    /// The slice summarised (`None`: all runs).
    pub shard: Option<ShardInfo>,
    /// The study segment.
    pub segment: Option<StudySegment>,
    /// The statistics.
    pub statistics: Statistics,
}

/// The [`Summary`] of the run rows `rows` of the sweep `manifest` describes.
pub(crate) fn summarise(rows: &[RunRow], manifest: &Manifest) -> Summary {
    let strategies: Vec<Strategy> = manifest
        .strategies
        .iter()
        .filter_map(|s| Strategy::from_name(s))
        .collect();
    let baseline = manifest.baseline.as_deref().and_then(Strategy::from_name);
    Summary {
        format: manifest.format.clone(),
        scenario: manifest.scenario.clone(),
        seed: manifest.seed,
        runs: manifest.runs,
        shard: manifest.shard,
        segment: manifest.segment,
        statistics: statistics(
            rows,
            &strategies,
            baseline,
            manifest.segment.is_some(),
            manifest.seed,
        ),
    }
}

/// `summary.json`'s text for `summary` (pretty JSON and a newline).
pub(crate) fn summary_text(summary: &Summary, dir: &Path) -> Result<String, SweepError> {
    let mut text = serde_json::to_string_pretty(summary)
        .map_err(|e| SweepError::io(&dir.join("summary.json"), "cannot serialise", e))?;
    text.push('\n');
    Ok(text)
}
