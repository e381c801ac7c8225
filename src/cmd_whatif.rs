//! `solsim whatif BASE VARIANT --runs N`: one strategy on two versions of a scenario that differ
//! in a setting (slip-aware routing on or off, a slip limit, a localizer), run over the same run
//! indices with the same seed, so run `i` of both sees the same world (common random numbers) and
//! the difference is paired run by run.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use maps::MemoryBudget;
use serde::Serialize;
use sim::Strategy;
use study::Scenario;
use sweep::engine::SweepSpec;
use sweep::rows::RunRow;
use sweep::stats::{Interval, PairedDifference};
use sweep::summary::{BOOTSTRAP_RESAMPLES, CONFIDENCE, RateKind};

use crate::progress::Progress;

/// Arguments of `solsim whatif`.
#[derive(clap::Args, Debug)]
pub struct WhatifArgs {
    /// The scenario as it is.
    pub base: PathBuf,
    /// The scenario with the setting changed: the same seed (so the runs pair), the same
    /// sols and route.
    pub variant: PathBuf,
    /// Run indices 0..N (2 to 100000).
    #[arg(long, value_parser = clap::value_parser!(u64).range(2..=100_000))]
    pub runs: u64,
    /// The strategy both run under.
    #[arg(long, default_value = "ground")]
    pub strategy: String,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

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

/// Run `solsim whatif`.
///
/// # Errors
/// A scenario that does not load, different seeds, a strategy that does not apply.
pub fn run(a: &WhatifArgs, budget: MemoryBudget, stdout: &mut dyn Write) -> anyhow::Result<()> {
    let strategy = Strategy::from_name(&a.strategy).ok_or_else(|| {
        anyhow::anyhow!(
            "--strategy {}: expected one of replay, ground, onboard, extension, extension+onboard",
            a.strategy
        )
    })?;
    let base = Scenario::load_within(&a.base, budget)?;
    let variant = Scenario::load_within(&a.variant, budget)?;
    if base.seed() != variant.seed() {
        anyhow::bail!(
            "{}: seed {}: expected the base's seed ({}), so that run i of both sees the same world",
            a.variant.display(),
            variant.seed(),
            base.seed()
        );
    }
    let spec = |s: &Scenario| -> anyhow::Result<SweepSpec> {
        let mut spec = SweepSpec::new(s, a.runs);
        spec.strategies = vec![strategy];
        spec.baseline = None;
        spec.validate(s, budget)?;
        Ok(spec)
    };
    let (spec_base, spec_variant) = (spec(&base)?, spec(&variant)?);
    let progress = Progress::new(false, "whatif", "runs", 2 * a.runs);
    let rows_base = sweep::engine::run_in_memory(&base, &spec_base, 0..a.runs);
    progress.update(a.runs, 2 * a.runs);
    let rows_variant = sweep::engine::run_in_memory(&variant, &spec_variant, 0..a.runs);
    progress.finish();
    let w = compare(&base, &variant, strategy, a.runs, &rows_base, &rows_variant);
    if a.json {
        writeln!(stdout, "{}", serde_json::to_string_pretty(&w)?)?;
    } else {
        write!(stdout, "{}", table(&w))?;
    }
    Ok(())
}

/// Pair the two run tables (same run indices, one strategy) figure by figure.
#[must_use]
pub fn compare(
    base: &Scenario,
    variant: &Scenario,
    strategy: Strategy,
    runs: u64,
    rows_base: &[RunRow],
    rows_variant: &[RunRow],
) -> Whatif {
    let has_segment = sweep::engine::segment_of(base).is_some();
    let figures = sweep::summary::figures(has_segment)
        .into_iter()
        .filter_map(|f| {
            let pairs: Vec<(f64, f64)> = rows_base
                .iter()
                .zip(rows_variant)
                .filter_map(|(b, v)| {
                    Some((
                        sweep::summary::figure_of(f, b)?,
                        sweep::summary::figure_of(f, v)?,
                    ))
                })
                .collect();
            let diffs: Vec<f64> = pairs.iter().map(|(b, v)| v - b).collect();
            let seed = sweep::summary::bootstrap_seed(base.seed(), strategy, f);
            let difference =
                sweep::stats::paired_bootstrap(&diffs, BOOTSTRAP_RESAMPLES, CONFIDENCE, seed)?;
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
                    .filter(|r| sweep::summary::counts_for(k, r))
                    .count() as u64
            };
            let (cb, cv) = (count(rows_base), count(rows_variant));
            Some(RateComparison {
                rate: k.name(),
                base_count: cb,
                base_interval: sweep::stats::wilson(cb, runs, CONFIDENCE)?,
                variant_count: cv,
                variant_interval: sweep::stats::wilson(cv, runs, CONFIDENCE)?,
            })
        })
        .collect();
    Whatif {
        base: base.name.clone(),
        variant: variant.name.clone(),
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
