//! Statistical `[[expect]]` entries (`runs = N`), checked over an in-memory sweep.

use std::collections::BTreeMap;

use sim::Strategy;
use sim::errors::ErrorPreset;
use study::expect::{Mismatch, StatCheck, StatisticalExpectation};
use study::{Scenario, figure::Figure};

use crate::engine::{SweepSpec, run_in_memory};
use crate::rows::RunRow;
use crate::stats;
use crate::summary::{self, CONFIDENCE, counts_for, figure_of};

/// The outcome of one statistical expectation.
#[derive(Debug, Clone, PartialEq)]
pub struct StatResult {
    /// Failed checks (empty = it holds).
    pub mismatches: Vec<Mismatch>,
    /// What was measured, one phrase per check, e.g. `no_path_rate 0.050 [0.017, 0.139]
    /// over 200 runs`.
    pub measured: Vec<String>,
}

/// Sweeps what the scenario's statistical expectations need — runs `0..runs` under the
/// scenario's seed, one sweep per distinct `runs`, over the strategies they name — and checks
/// each one, in file order.
#[must_use]
pub fn check_statistical(scenario: &Scenario) -> Vec<StatResult> {
    let mut by_runs: BTreeMap<(u64, Option<&'static str>), Vec<Strategy>> = BTreeMap::new();
    for e in &scenario.statistical_expectations {
        let v = by_runs.entry(key(e)).or_default();
        for s in e.strategies() {
            if !v.contains(&s) {
                v.push(s);
            }
        }
    }
    let swept: BTreeMap<(u64, Option<&'static str>), Vec<RunRow>> = by_runs
        .into_iter()
        .map(|((runs, errors), mut strategies)| {
            strategies.sort_by_key(|s| s.stream_id());
            let under = errors
                .and_then(ErrorPreset::from_name)
                .map(|p| scenario.with_errors(p.model()));
            let sc = under.as_ref().unwrap_or(scenario);
            let spec = SweepSpec {
                strategies,
                baseline: None,
                shard: None,
                ..SweepSpec::new(sc, runs)
            };
            ((runs, errors), run_in_memory(sc, &spec, 0..runs))
        })
        .collect();
    scenario
        .statistical_expectations
        .iter()
        .map(|e| check(e, &swept[&key(e)], scenario.seed()))
        .collect()
}

/// The sweep an expectation needs: its run count and error preset (if not the scenario's).
fn key(e: &StatisticalExpectation) -> (u64, Option<&'static str>) {
    (e.runs, e.errors.map(ErrorPreset::name))
}

/// Checks one expectation against the run rows of a sweep (which must include its strategies).
#[must_use]
pub fn check(e: &StatisticalExpectation, rows: &[RunRow], sweep_seed: u64) -> StatResult {
    let mine: Vec<&RunRow> = rows.iter().filter(|r| r.strategy == e.strategy).collect();
    let n = mine.len() as u64;
    let mut out = StatResult {
        mismatches: Vec::new(),
        measured: Vec::new(),
    };
    for c in &e.checks {
        match *c {
            StatCheck::Rate { rate, lo, hi } => {
                let count = mine.iter().filter(|r| counts_for(rate, r)).count() as u64;
                let got = count as f64 / n.max(1) as f64;
                let ci = stats::wilson(count, n, CONFIDENCE);
                let text = format!(
                    "{} {got:.3} [{}] ({count} of {n} runs)",
                    rate.name(),
                    ci.map_or("-".into(), |i| format!("{:.3}, {:.3}", i.lo, i.hi))
                );
                if !(n > 0 && got >= lo - 1e-12 && got <= hi + 1e-12) {
                    out.mismatches.push(Mismatch {
                        check: format!(
                            "{} {} over {} runs",
                            e.strategy.name(),
                            rate.name(),
                            e.runs
                        ),
                        expected: format!("[{lo}, {hi}]"),
                        got: text.clone(),
                    });
                }
                out.measured.push(text);
            }
            StatCheck::DiscCoverage { lo, hi } => {
                let cov = summary::disc_coverage(&mine);
                let text = cov.as_ref().map_or_else(
                    || "disc_coverage: no drive sol".to_string(),
                    |r| {
                        format!(
                            "disc_coverage {:.4} [{:.4}, {:.4}] ({} of {} drive sols)",
                            r.rate, r.interval.lo, r.interval.hi, r.count, r.runs
                        )
                    },
                );
                if !cov.is_some_and(|r| r.rate >= lo - 1e-12 && r.rate <= hi + 1e-12) {
                    out.mismatches.push(Mismatch {
                        check: format!("{} disc_coverage over {} runs", e.strategy.name(), e.runs),
                        expected: format!("[{lo}, {hi}]"),
                        got: text.clone(),
                    });
                }
                out.measured.push(text);
            }
            StatCheck::PairedShare {
                baseline,
                figure,
                at_most,
                lo,
                hi,
            } => {
                let diffs = paired_diffs(rows, &mine, baseline, figure);
                let n = diffs.len() as u64;
                let count = diffs.iter().filter(|&&d| d <= at_most + 1e-9).count() as u64;
                let got = count as f64 / n.max(1) as f64;
                let ci = stats::wilson(count, n, CONFIDENCE);
                let text = format!(
                    "share of runs with {} − {} ≤ {at_most}: {got:.3} [{}] ({count} of {n} pairs)",
                    name(figure),
                    baseline.name(),
                    ci.map_or("-".into(), |i| format!("{:.3}, {:.3}", i.lo, i.hi))
                );
                if !(n > 0 && got >= lo - 1e-12 && got <= hi + 1e-12) {
                    out.mismatches.push(Mismatch {
                        check: format!(
                            "{} paired {} − {} ≤ {at_most} over {} runs",
                            e.strategy.name(),
                            name(figure),
                            baseline.name(),
                            e.runs
                        ),
                        expected: format!("share in [{lo}, {hi}]"),
                        got: text.clone(),
                    });
                }
                out.measured.push(text);
            }
            StatCheck::Paired {
                baseline,
                figure,
                lo,
                hi,
            } => {
                let diffs = paired_diffs(rows, &mine, baseline, figure);
                let d = stats::paired_bootstrap(
                    &diffs,
                    summary::BOOTSTRAP_RESAMPLES,
                    CONFIDENCE,
                    summary::bootstrap_seed(sweep_seed, e.strategy, figure),
                );
                let text = d.map_or_else(
                    || {
                        format!(
                            "{} − {}: no run where both have it",
                            name(figure),
                            baseline.name()
                        )
                    },
                    |d| {
                        format!(
                            "{} − {} {:+.3} [{:+.3}, {:+.3}] ({} pairs)",
                            name(figure),
                            baseline.name(),
                            d.mean,
                            d.interval.lo,
                            d.interval.hi,
                            d.n
                        )
                    },
                );
                if !d.is_some_and(|d| d.mean >= lo - 1e-12 && d.mean <= hi + 1e-12) {
                    out.mismatches.push(Mismatch {
                        check: format!(
                            "{} paired {} − {} over {} runs",
                            e.strategy.name(),
                            name(figure),
                            baseline.name(),
                            e.runs
                        ),
                        expected: format!("mean in [{lo}, {hi}]"),
                        got: text.clone(),
                    });
                }
                out.measured.push(text);
            }
        }
    }
    out
}

/// (strategy − baseline) on `figure` over the run indices where both have it.
fn paired_diffs(rows: &[RunRow], mine: &[&RunRow], baseline: Strategy, figure: Figure) -> Vec<f64> {
    let base: BTreeMap<u64, &RunRow> = rows
        .iter()
        .filter(|r| r.strategy == baseline)
        .map(|r| (r.run_index, r))
        .collect();
    mine.iter()
        .filter_map(|r| Some(figure_of(figure, r)? - figure_of(figure, base.get(&r.run_index)?)?))
        .collect()
}

fn name(f: Figure) -> &'static str {
    f.name()
}
