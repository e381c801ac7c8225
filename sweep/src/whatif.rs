//! One strategy on two versions of a scenario that differ in a setting (slip-aware routing on
//! or off, a slip limit, a localizer), run over the same run indices with the same seed, so run
//! `i` of both sees the same world (common random numbers) and the difference is paired run by
//! run (`solsim whatif`): each figure's paired difference with a bootstrap interval, each
//! rate's Wilson interval, and the settings that differ ([`crate::setting_diff`]).

use std::fmt::Write as _;

use maps::MemoryBudget;
use serde::Serialize;
use sim::Strategy;
use study::Scenario;

use crate::engine::SweepSpec;
use crate::error::SweepError;
use crate::rows::RunRow;
use crate::setting_diff::{SettingDifference, differences_of};
use crate::stats::{Interval, PairedDifference};
use crate::summary::{BOOTSTRAP_RESAMPLES, CONFIDENCE, RateKind};

/// One figure of both versions and their paired difference.
#[derive(Debug, Serialize)]
pub struct FigureComparison {
    /// The figure (`drive_time_s`, `sols_to_goal`, ...).
    pub figure: &'static str,
    /// Runs where both versions have a value (e.g. both reached the goal).
    pub paired_runs: usize,
    /// Mean over those runs, base.
    pub base_mean: f64,
    /// Mean over those runs, variant.
    pub variant_mean: f64,
    /// Variant − base, run by run, with its 95 % percentile bootstrap interval.
    pub difference: PairedDifference,
}

/// One rate of both versions, % of runs with 95 % Wilson intervals.
#[derive(Debug, Serialize)]
pub struct RateComparison {
    /// The rate (`fault_rate`, `goal_reached_rate`, ...).
    pub rate: &'static str,
    /// Runs counted, base.
    pub base_count: u64,
    /// Wilson interval, base.
    pub base_interval: Interval,
    /// Runs counted, variant.
    pub variant_count: u64,
    /// Wilson interval, variant.
    pub variant_interval: Interval,
}

/// What `solsim whatif` prints.
#[derive(Debug, Serialize)]
pub struct Whatif {
    /// Base scenario name.
    pub base: String,
    /// Variant scenario name.
    pub variant: String,
    /// The settings that differ between the two files (map files compared by contents; name,
    /// description, notes and `[[expect]]` entries left out).
    pub differences: Vec<SettingDifference>,
    /// The strategy.
    pub strategy: &'static str,
    /// The shared seed.
    pub seed: u64,
    /// Runs of each.
    pub runs: u64,
    /// Figures.
    pub figures: Vec<FigureComparison>,
    /// Rates.
    pub rates: Vec<RateComparison>,
}

/// A what-if study checked and ready to run: both versions, the strategy and the sweeps.
#[derive(Debug)]
pub struct WhatifRun<'a> {
    base: &'a Scenario,
    variant: &'a Scenario,
    strategy: Strategy,
    runs: u64,
    specs: [SweepSpec; 2],
}

impl<'a> WhatifRun<'a> {
    /// `strategy` over run indices `0..runs` on `base` and on `variant`.
    ///
    /// # Errors
    /// Different seeds (the runs would not pair), a sweep the scenarios refuse (a strategy
    /// that does not apply, runs over the memory budget).
    pub fn new(
        base: &'a Scenario,
        variant: &'a Scenario,
        strategy: Strategy,
        runs: u64,
        budget: MemoryBudget,
    ) -> Result<Self, SweepError> {
        if base.seed() != variant.seed() {
            return Err(SweepError::SeedMismatch {
                variant: variant.path.clone(),
                seed: variant.seed(),
                base_seed: base.seed(),
            });
        }
        let spec = |s: &Scenario| -> Result<SweepSpec, SweepError> {
            let mut spec = SweepSpec::new(s, runs);
            spec.strategies = vec![strategy];
            spec.baseline = None;
            spec.validate(s, budget)?;
            Ok(spec)
        };
        let specs = [spec(base)?, spec(variant)?];
        Ok(Self {
            base,
            variant,
            strategy,
            runs,
            specs,
        })
    }

    /// Runs both, pairs them and lists the settings that differ between the two files
    /// ([`differences_of`]); `progress(done, total)` is called with the runs done of both.
    ///
    /// # Errors
    /// A file that cannot be read again for its settings.
    pub fn run(&self, progress: &dyn Fn(u64, u64)) -> Result<Whatif, SweepError> {
        let (runs, [spec_base, spec_variant]) = (self.runs, &self.specs);
        let rows_base = crate::engine::run_in_memory(self.base, spec_base, 0..runs);
        progress(runs, 2 * runs);
        let rows_variant = crate::engine::run_in_memory(self.variant, spec_variant, 0..runs);
        let mut w = compare(
            self.base,
            self.variant,
            self.strategy,
            runs,
            &rows_base,
            &rows_variant,
        );
        w.differences = differences_of(self.base, self.variant)?;
        Ok(w)
    }
}

/// Pair the two run tables (same run indices, one strategy) figure by figure; the settings
/// that differ are filled in by [`WhatifRun::run`].
fn compare(
    base: &Scenario,
    variant: &Scenario,
    strategy: Strategy,
    runs: u64,
    rows_base: &[RunRow],
    rows_variant: &[RunRow],
) -> Whatif {
    let has_segment = base.study_segment.is_some();
    let figures = crate::summary::metrics(has_segment)
        .into_iter()
        .filter_map(|f| {
            let pairs: Vec<(f64, f64)> = rows_base
                .iter()
                .zip(rows_variant)
                .filter_map(|(b, v)| {
                    Some((
                        crate::summary::metric_of(f, b)?,
                        crate::summary::metric_of(f, v)?,
                    ))
                })
                .collect();
            let diffs: Vec<f64> = pairs.iter().map(|(b, v)| v - b).collect();
            let seed = crate::summary::bootstrap_seed(base.seed(), strategy, f);
            let difference =
                crate::stats::paired_bootstrap(&diffs, BOOTSTRAP_RESAMPLES, CONFIDENCE, seed)?;
            let n = pairs.len() as f64;
            Some(FigureComparison {
                figure: f.name(),
                paired_runs: pairs.len(),
                base_mean: pairs.iter().map(|p| p.0).sum::<f64>() / n,
                variant_mean: pairs.iter().map(|p| p.1).sum::<f64>() / n,
                difference,
            })
        })
        .collect();
    let rates = RateKind::ALL
        .into_iter()
        .filter_map(|k| {
            let count = |rows: &[RunRow]| {
                rows.iter()
                    .filter(|r| crate::summary::counts_for(k, r))
                    .count() as u64
            };
            let (cb, cv) = (count(rows_base), count(rows_variant));
            Some(RateComparison {
                rate: k.name(),
                base_count: cb,
                base_interval: crate::stats::wilson(cb, runs, CONFIDENCE)?,
                variant_count: cv,
                variant_interval: crate::stats::wilson(cv, runs, CONFIDENCE)?,
            })
        })
        .collect();
    Whatif {
        base: base.name.clone(),
        variant: variant.name.clone(),
        differences: Vec::new(),
        strategy: strategy.name(),
        seed: base.seed(),
        runs,
        figures,
        rates,
    }
}

/// The printed table.
#[must_use]
pub fn table(w: &Whatif) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "what-if: {} against {} under {}, {} runs (seed {}; run i of both sees the same world)",
        w.variant, w.base, w.strategy, w.runs, w.seed
    );
    const LISTED: usize = 8;
    match w.differences.as_slice() {
        [] => {
            let _ = writeln!(
                s,
                "  no setting differs: the two files set the same values (name, description, \
                 notes and [[expect]] aside), so the runs are the same"
            );
        }
        [one] => {
            let _ = writeln!(s, "  the setting that differs: {one}");
        }
        many => {
            let _ = writeln!(s, "  the {} settings that differ:", many.len());
            for d in many.iter().take(LISTED) {
                let _ = writeln!(s, "    {d}");
            }
            if many.len() > LISTED {
                let _ = writeln!(
                    s,
                    "    … and {} more (`--json` lists every one)",
                    many.len() - LISTED
                );
            }
        }
    }
    let _ = writeln!(
        s,
        "  {:<32} {:>6} {:>12} {:>12} {:>12}  95 % bootstrap",
        "figure (runs where both have it)", "runs", "base", "variant", "difference"
    );
    for f in &w.figures {
        let _ = writeln!(
            s,
            "  {:<32} {:>6} {:>12.2} {:>12.2} {:>+12.2}  [{:+.2}, {:+.2}]",
            f.figure,
            f.paired_runs,
            f.base_mean,
            f.variant_mean,
            f.difference.mean,
            f.difference.interval.lo,
            f.difference.interval.hi
        );
    }
    let _ = writeln!(s, "  rates, % of runs [95 % Wilson]");
    for r in &w.rates {
        let pct = |c: u64| 100.0 * c as f64 / w.runs as f64;
        let _ = writeln!(
            s,
            "  {:<32} base {:>6.1} [{:.1}, {:.1}]   variant {:>6.1} [{:.1}, {:.1}]",
            r.rate,
            pct(r.base_count),
            100.0 * r.base_interval.lo,
            100.0 * r.base_interval.hi,
            pct(r.variant_count),
            100.0 * r.variant_interval.lo,
            100.0 * r.variant_interval.hi
        );
    }
    s
}
