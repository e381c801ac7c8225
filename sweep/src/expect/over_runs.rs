//! Statistical `[[expect]]` entries (`runs = N`), checked over an in-memory sweep: one sweep per
//! distinct (runs, error model, pre-emptive shortening) the entries need ([`check_statistical`]),
//! each entry checked against its rows ([`check`]).

use std::collections::BTreeMap;

use sim::Strategy;
use sim::rover::errors::ErrorPreset;
use study::expect::{Mismatch, StatCheck, StatisticalExpectation};
use study::{Scenario, metric::Metric};

use crate::engine::{SweepSpec, run_in_memory};
use crate::rows::RunRow;
use crate::stats;
use crate::summary::{self, CONFIDENCE, counts_for, metric_of};

/// The outcome of one statistical expectation.
#[derive(Debug, Clone, PartialEq)]
pub struct StatResult {
    /// Failed checks (empty = it holds).
    pub mismatches: Vec<Mismatch>,
    /// What was measured, one phrase per check, e.g. `no_path_rate 0.050 [0.017, 0.139]
    /// over 200 runs`.
    pub measured: Vec<String>,
    /// Wall-clock seconds this expectation cost: its share of the sweep it needed (a sweep
    /// shared by several expectations is split equally among them) plus its own check.
    /// Filled in by [`check_statistical`]; 0 from [`check`].
    pub seconds: f64,
}

/// Sweeps what the scenario's statistical expectations need — runs `0..runs` under the
/// scenario's seed, one sweep per distinct `runs`, over the strategies they name — and checks
/// each one, in file order.
#[must_use]
pub fn check_statistical(scenario: &Scenario) -> Vec<StatResult> {
    let mut by_runs: BTreeMap<SweepKey, Vec<Strategy>> = BTreeMap::new();
    for e in &scenario.statistical_expectations {
        let v = by_runs.entry(key(e)).or_default();
        for s in e.strategies() {
            if !v.contains(&s) {
                v.push(s);
            }
        }
    }
    let swept: BTreeMap<SweepKey, (Vec<RunRow>, f64)> = by_runs
        .into_iter()
        .map(|((runs, errors, shortening), mut strategies)| {
            strategies.sort_by_key(|s| s.stream_id());
            // One copy of the scenario, and only when an override needs it.
            let owned;
            let sc = if errors.is_none() && shortening.is_none() {
                scenario
            } else {
                let mut s = scenario.clone();
                if let Some(p) = errors.and_then(ErrorPreset::from_name) {
                    s.settings.rover.errors = p.model();
                }
                if let Some(on) = shortening {
                    s.settings.rules.preemptive_shortening = on;
                }
                owned = s;
                &owned
            };
            let start = std::time::Instant::now();
            let spec = SweepSpec {
                strategies,
                baseline: None,
                shard: None,
                ..SweepSpec::new(sc, runs)
            };
            let rows = run_in_memory(sc, &spec, 0..runs);
            let seconds = start.elapsed().as_secs_f64();
            ((runs, errors, shortening), (rows, seconds))
        })
        .collect();
    let sharing = |k: &SweepKey| {
        let n = scenario
            .statistical_expectations
            .iter()
            .filter(|e| key(e) == *k)
            .count();
        n.max(1) as f64
    };
    scenario
        .statistical_expectations
        .iter()
        .map(|e| {
            let start = std::time::Instant::now();
            let (rows, sweep_s) = &swept[&key(e)];
            let mut r = check(e, rows, scenario.seed(), SolBounds::of(scenario));
            r.seconds = sweep_s / sharing(&key(e)) + start.elapsed().as_secs_f64();
            r
        })
        .collect()
}

/// The sweep an expectation needs: its run count, error preset and pre-emptive shortening
/// (each `None`: the scenario's own).
type SweepKey = (u64, Option<&'static str>, Option<bool>);

fn key(e: &StatisticalExpectation) -> SweepKey {
    (
        e.runs,
        e.errors.map(ErrorPreset::name),
        e.preemptive_shortening,
    )
}

/// Checks one expectation against the run rows of a sweep (which must include its strategies).
///
/// A paired share on a sol count (`sols_to_goal`, `segment_sols`) counts a pair as
/// `≤ at_most` when its difference is provably so: both have the count and their difference
/// is, or only the strategy has it and it is ≤ at_most against `calendar`'s bound (a run that
/// did not reach the goal or cover the segment needs more sols than the calendar has left).
/// A pair where the strategy lacks the count never counts.
#[must_use]
pub fn check(
    e: &StatisticalExpectation,
    rows: &[RunRow],
    sweep_seed: u64,
    calendar: SolBounds,
) -> StatResult {
    let mine: Vec<&RunRow> = rows.iter().filter(|r| r.strategy == e.strategy).collect();
    let n = mine.len() as u64;
    let mut out = StatResult {
        mismatches: Vec::new(),
        measured: Vec::new(),
        seconds: 0.0,
    };
    for c in &e.checks {
        let (holds, check, expected, text) = match *c {
            StatCheck::Rate { rate, lo, hi } => {
                let count = mine.iter().filter(|r| counts_for(rate, r)).count() as u64;
                let got = count as f64 / n.max(1) as f64;
                let ci = stats::wilson(count, n, CONFIDENCE);
                let text = format!(
                    "{} {got:.3} [{}] ({count} of {n} runs)",
                    rate.name(),
                    ci.map_or("-".into(), |i| format!("{:.3}, {:.3}", i.lo, i.hi))
                );
                (
                    n > 0 && within(got, lo, hi),
                    rate.name().to_string(),
                    format!("[{lo}, {hi}]"),
                    text,
                )
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
                (
                    cov.is_some_and(|r| within(r.rate, lo, hi)),
                    "disc_coverage".to_string(),
                    format!("[{lo}, {hi}]"),
                    text,
                )
            }
            StatCheck::PairedShare {
                baseline,
                figure,
                at_most,
                lo,
                hi,
            } => {
                let censor = calendar.sols_left(figure);
                let bounds = paired_upper_bounds(rows, &mine, baseline, figure, censor);
                let n = bounds.len() as u64;
                let count = bounds
                    .iter()
                    .filter(|d| d.is_some_and(|d| d <= at_most + 1e-9))
                    .count() as u64;
                let got = count as f64 / n.max(1) as f64;
                let ci = stats::wilson(count, n, CONFIDENCE);
                let censored = censor.map_or(String::new(), |c| {
                    format!(
                        "; a run without {} counts as needing more than the {c} sols the \
                         calendar has",
                        name(figure)
                    )
                });
                let text = format!(
                    "share of runs with {} − {} ≤ {at_most}: {got:.3} [{}] ({count} of {n} \
                     pairs{censored})",
                    name(figure),
                    baseline.name(),
                    ci.map_or("-".into(), |i| format!("{:.3}, {:.3}", i.lo, i.hi))
                );
                (
                    n > 0 && within(got, lo, hi),
                    format!("paired {} − {} ≤ {at_most}", name(figure), baseline.name()),
                    format!("share in [{lo}, {hi}]"),
                    text,
                )
            }
            StatCheck::Paired {
                baseline,
                figure,
                lo,
                hi,
            } => {
                let diffs: Vec<f64> = paired_upper_bounds(rows, &mine, baseline, figure, None)
                    .into_iter()
                    .flatten()
                    .collect();
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
                (
                    d.is_some_and(|d| within(d.mean, lo, hi)),
                    format!("paired {} − {}", name(figure), baseline.name()),
                    format!("mean in [{lo}, {hi}]"),
                    text,
                )
            }
        };
        if !holds {
            out.mismatches.push(Mismatch {
                check: format!("{} {check} over {} runs", e.strategy.name(), e.runs),
                expected,
                got: text.clone(),
            });
        }
        out.measured.push(text);
    }
    out
}

/// What a sol count is bounded by when a run has none: the calendar's sols.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SolBounds {
    /// Sols in the calendar (`sols_to_goal` counts from its first sol).
    pub sols: u32,
    /// Sols from the study segment's first sol to the calendar's end (`segment_sols`).
    pub segment_sols: Option<u32>,
}

impl SolBounds {
    /// The bounds of `scenario`'s calendar.
    #[must_use]
    pub fn of(scenario: &Scenario) -> Self {
        let cal = &scenario.settings.calendar;
        SolBounds {
            sols: cal.sols.len() as u32,
            segment_sols: scenario.study_segment.map(|g| cal.sols_from(g.from_sol)),
        }
    }

    /// The sols a run lacking `figure` needs more than (`None`: not a sol count).
    #[must_use]
    pub fn sols_left(self, figure: Metric) -> Option<u32> {
        match figure {
            Metric::SolsToGoal => Some(self.sols),
            Metric::SegmentSols => self.segment_sols,
            _ => None,
        }
    }
}

/// Per run index both strategies ran: an upper bound on (strategy − baseline) on `figure`, or
/// `None` where none is known. Without `censor` the bound is the difference itself where both
/// have the figure. With `censor` (a sol count: the sols the calendar has left), a baseline
/// without the figure needs at least `censor + 1`.
fn paired_upper_bounds(
    rows: &[RunRow],
    mine: &[&RunRow],
    baseline: Strategy,
    figure: Metric,
    censor: Option<u32>,
) -> Vec<Option<f64>> {
    let base: BTreeMap<u64, &RunRow> = rows
        .iter()
        .filter(|r| r.strategy == baseline)
        .map(|r| (r.run_index, r))
        .collect();
    mine.iter()
        .filter_map(|r| {
            let b = base.get(&r.run_index)?;
            let m = metric_of(figure, r);
            let least_b = metric_of(figure, b).or(censor.map(|c| f64::from(c) + 1.0));
            Some(m.zip(least_b).map(|(m, b)| m - b))
        })
        .collect()
}

/// `x` within `[lo, hi]`, allowing for the rounding of a written range.
fn within(x: f64, lo: f64, hi: f64) -> bool {
    x >= lo - 1e-12 && x <= hi + 1e-12
}

fn name(f: Metric) -> &'static str {
    f.name()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(run_index: u64, strategy: Strategy, segment_sols: Option<u32>) -> RunRow {
        RunRow {
            run_index,
            strategy,
            run_seed: run_index,
            sols_to_goal: None,
            goal_reached: false,
            drive_sols: 0,
            distance_m: 0.0,
            route_remaining_m: 0.0,
            no_path_faults: 0,
            keep_out_faults: 0,
            keep_in_faults: 0,
            faults: 0,
            max_uncertainty_m: 0.0,
            onboard_localizations_applied: 0,
            onboard_localizations_rejected: 0,
            ground_localizations: 0,
            truth_outside_disc_sols: 0,
            max_truth_error_m: 0.0,
            segment_sols,
            segment_distance_m: None,
            drive_time_s: 0.0,
            drive_plan_uplinks: 0,
        }
    }

    fn share_at_most(at_most: f64) -> StatisticalExpectation {
        StatisticalExpectation {
            index: 0,
            what: String::new(),
            strategy: Strategy::ExtensionOnboard,
            runs: 4,
            errors: None,
            preemptive_shortening: None,
            checks: vec![StatCheck::PairedShare {
                baseline: Strategy::Ground,
                figure: Metric::SegmentSols,
                at_most,
                lo: 0.0,
                hi: 1.0,
            }],
        }
    }

    /// Run 0: both covered (6 against 8). Run 1: only the strategy did, in 7 sols of the 8 the
    /// calendar has left, so the baseline needs 9 or more. Run 2: only the baseline did. Run 3:
    /// neither did.
    fn rows() -> Vec<RunRow> {
        let g = Strategy::Ground;
        let e = Strategy::ExtensionOnboard;
        vec![
            row(0, e, Some(6)),
            row(0, g, Some(8)),
            row(1, e, Some(7)),
            row(1, g, None),
            row(2, e, None),
            row(2, g, Some(8)),
            row(3, e, None),
            row(3, g, None),
        ]
    }

    fn measured(at_most: f64, segment_sols: Option<u32>) -> String {
        let bounds = SolBounds {
            sols: 31,
            segment_sols,
        };
        let r = check(&share_at_most(at_most), &rows(), 1, bounds);
        r.measured.join("; ")
    }

    #[test]
    fn a_baseline_that_did_not_cover_the_segment_needs_more_than_the_sols_left() {
        // Run 1 is −2 or less (7 − 9), so it counts for at_most −2 but not −3; run 0 (−2)
        // counts for both −2; runs 2 and 3 never count, and all four are pairs.
        assert!(
            measured(-2.0, Some(8)).contains("(2 of 4 pairs"),
            "{}",
            measured(-2.0, Some(8))
        );
        assert!(
            measured(-3.0, Some(8)).contains("(0 of 4 pairs"),
            "{}",
            measured(-3.0, Some(8))
        );
        // With 7 sols left run 1's baseline needs 8 or more: 7 − 8 = −1, not ≤ −2.
        assert!(
            measured(-2.0, Some(7)).contains("(1 of 4 pairs"),
            "{}",
            measured(-2.0, Some(7))
        );
        assert!(
            measured(-1.0, Some(7)).contains("(2 of 4 pairs"),
            "{}",
            measured(-1.0, Some(7))
        );
    }

    #[test]
    fn without_a_segment_only_pairs_where_both_have_the_count_can_count() {
        assert!(
            measured(-2.0, None).contains("(1 of 4 pairs)"),
            "{}",
            measured(-2.0, None)
        );
    }
}
