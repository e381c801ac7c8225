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

/// A setting the two scenario files give different values.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct SettingDifference {
    /// Its TOML path: `rover.slip_aware_routing`, `sols[3].drive_window_lmst`.
    pub field: String,
    /// The base's value, as TOML (`None`: not set, so the default applies).
    pub base: Option<String>,
    /// The variant's value, as TOML (`None`: not set, so the default applies).
    pub variant: Option<String>,
}

impl std::fmt::Display for SettingDifference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let shown = |v: &Option<String>| v.clone().unwrap_or_else(|| "(not set: default)".into());
        write!(
            f,
            "{}: {} → {}",
            self.field,
            shown(&self.base),
            shown(&self.variant)
        )
    }
}

/// Fields of a scenario file that do not change a run: its name, its description, per-sol
/// notes and the `[[expect]]` entries `solsim regress` checks.
fn is_setting(field: &str) -> bool {
    let top = field.split(['.', '[']).next().unwrap_or(field);
    let note = field.starts_with("sols[") && field.ends_with("].note");
    !(note || matches!(top, "name" | "description" | "expect"))
}

/// Every setting whose value differs between two scenario files' TOML, in field order: the
/// tables flattened to dotted paths, arrays of tables indexed (`sols[3].distance_m`), other
/// arrays compared whole. A field one file sets and the other leaves to its default is a
/// difference (`None` on the side that does not set it). The name, the description, per-sol
/// notes and `[[expect]]` entries are left out: they do not change a run.
///
/// # Errors
/// Text that is not TOML (the scenario loader has read it already, so this is not expected).
pub fn setting_differences(
    base_toml: &str,
    variant_toml: &str,
) -> Result<Vec<SettingDifference>, toml::de::Error> {
    fn flatten(
        prefix: &str,
        v: &toml::Value,
        out: &mut std::collections::BTreeMap<String, String>,
    ) {
        let key = |k: &str| {
            if prefix.is_empty() {
                k.to_string()
            } else {
                format!("{prefix}.{k}")
            }
        };
        match v {
            toml::Value::Table(t) => {
                for (k, v) in t {
                    flatten(&key(k), v, out);
                }
            }
            toml::Value::Array(a) if !a.is_empty() && a.iter().all(toml::Value::is_table) => {
                for (i, v) in a.iter().enumerate() {
                    flatten(&format!("{prefix}[{i}]"), v, out);
                }
            }
            other => {
                out.insert(prefix.to_string(), other.to_string());
            }
        }
    }
    let flat = |text: &str| -> Result<_, toml::de::Error> {
        let table: toml::Table = toml::from_str(text)?;
        let mut out = std::collections::BTreeMap::new();
        flatten("", &toml::Value::Table(table), &mut out);
        Ok(out)
    };
    let (b, v) = (flat(base_toml)?, flat(variant_toml)?);
    let mut fields: Vec<&String> = b.keys().chain(v.keys()).collect();
    fields.sort();
    fields.dedup();
    Ok(fields
        .into_iter()
        .filter(|f| is_setting(f) && b.get(*f) != v.get(*f))
        .map(|f| SettingDifference {
            field: f.clone(),
            base: b.get(f).cloned(),
            variant: v.get(f).cloned(),
        })
        .collect())
}

/// The settings that differ between the loaded `base` and `variant`, read from their files; a
/// map file named by a different path but with the same contents (SHA-256) is not a
/// difference.
fn differences_of(base: &Scenario, variant: &Scenario) -> anyhow::Result<Vec<SettingDifference>> {
    let read = |s: &Scenario| {
        maps::input_file::read_text_file(&s.path)
            .map_err(|e| anyhow::anyhow!("{}: cannot read it again: {e}", s.path.display()))
    };
    let all = setting_differences(&read(base)?, &read(variant)?).map_err(|e| {
        anyhow::anyhow!("{} or {}: {e}", base.path.display(), variant.path.display())
    })?;
    let sha = |s: &Scenario, field: &str| {
        s.inputs_sha256
            .iter()
            .find(|(f, _, _)| *f == field)
            .map(|(_, _, sha)| sha.clone())
    };
    Ok(all
        .into_iter()
        .filter(|d| {
            let same_file = sha(base, &d.field).is_some_and(|b| sha(variant, &d.field) == Some(b));
            !same_file
        })
        .collect())
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
    let mut w = compare(&base, &variant, strategy, a.runs, &rows_base, &rows_variant);
    w.differences = differences_of(&base, &variant)?;
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
