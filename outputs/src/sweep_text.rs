//! What `solsim sweep` and `sweep merge` print: the rates, spreads and paired differences of a
//! sweep as a table ([`sweep_table`]), the line a merge prints ([`merge_line`]), and the
//! `--json` document of either ([`SweepJson`], with each file written as a [`WrittenFile`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use study::Scenario;
use sweep::engine::SweepResult;
use sweep::summary::{Metric, RateKind, Statistics};

use crate::over_runs::signed;

/// A written file that cannot be read back.
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot read what was written", path.display())]
pub struct WrittenFileError {
    /// The file.
    pub path: PathBuf,
    /// What the operating system said.
    #[source]
    pub source: std::io::Error,
}

/// A file a command wrote, as its `--json` describes it.
#[derive(serde::Serialize)]
pub struct WrittenFile {
    /// Name inside the output directory.
    pub file: String,
    /// Size, bytes.
    pub bytes: u64,
    /// SHA-256 of its bytes, hex, where the command records it (a sweep's manifest).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sha256: Option<String>,
}

impl WrittenFile {
    /// `dir/file`'s size as written, with `sha256` if known.
    ///
    /// # Errors
    /// The file cannot be read (it was just written: a race with something else).
    pub fn of(dir: &Path, file: &str, sha256: Option<String>) -> Result<Self, WrittenFileError> {
        let path = dir.join(file);
        let bytes = std::fs::metadata(&path)
            .map_err(|source| WrittenFileError { path, source })?
            .len();
        Ok(WrittenFile {
            file: file.to_owned(),
            bytes,
            sha256,
        })
    }
}

/// `sweep --json` and `sweep merge --json`: what the command wrote and the statistics.
#[derive(serde::Serialize)]
pub struct SweepJson<'a> {
    /// The output directory.
    pub dir: String,
    /// `sweep merge`: the shard directories, as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub merged_from: Option<Vec<String>>,
    /// The scenario swept.
    pub scenario: &'a sweep::manifest::ScenarioId,
    /// The sweep's seed.
    pub seed: u64,
    /// Run indices 0..runs of the whole sweep.
    pub runs: u64,
    /// The run indices this directory holds, [first, end).
    pub run_range: [u64; 2],
    /// The shard this directory holds, if it is one.
    pub shard: Option<sweep::manifest::ShardInfo>,
    /// The strategies swept.
    pub strategies: &'a [String],
    /// The strategy the paired differences are taken against.
    pub baseline: Option<&'a str>,
    /// Run indices simulated by this command (`sweep`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub runs_run: Option<u64>,
    /// Run indices found committed by an interrupted sweep (`sweep --resume`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub runs_resumed: Option<u64>,
    /// The directory held the complete sweep already (`sweep --resume`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub already_complete: Option<bool>,
    /// Wall time, seconds (`sweep`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seconds: Option<f64>,
    /// Worker threads (`sweep`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub threads: Option<usize>,
    /// Every file in the directory: the outputs with their SHA-256, then manifest.json.
    pub files: Vec<WrittenFile>,
    /// As in summary.json.
    pub statistics: &'a Statistics,
}

impl<'a> SweepJson<'a> {
    /// The document of `r`, the files in its directory listed with their sizes; the fields
    /// only `sweep` or only `merge` has are set by the caller.
    ///
    /// # Errors
    /// A file of the directory that cannot be read back.
    pub fn of(r: &'a SweepResult) -> Result<Self, WrittenFileError> {
        let m = &r.manifest;
        let mut files = m
            .files
            .iter()
            .map(|(name, sha)| WrittenFile::of(&r.dir, name, Some(sha.clone())))
            .collect::<Result<Vec<_>, _>>()?;
        files.push(WrittenFile::of(&r.dir, sweep::manifest::MANIFEST, None)?);
        let range = m.shard.map_or([0, m.runs], |sh| [sh.first_run, sh.end_run]);
        Ok(SweepJson {
            dir: r.dir.display().to_string(),
            merged_from: None,
            scenario: &m.scenario,
            seed: m.seed,
            runs: m.runs,
            run_range: range,
            shard: m.shard,
            strategies: &m.strategies,
            baseline: m.baseline.as_deref(),
            runs_run: Some(r.runs_run),
            runs_resumed: Some(r.runs_resumed),
            already_complete: Some(r.already_complete),
            seconds: None,
            threads: None,
            files,
            statistics: &r.summary.statistics,
        })
    }
}

/// The line `sweep merge` prints: `merged 2 shard directories into OUT/ (40 runs × 5
/// strategies)`.
#[must_use]
pub fn merge_line(shards: usize, out: &Path, r: &SweepResult) -> String {
    format!(
        "merged {} into {}/ ({} × {})",
        plural(shards as u64, "shard directory").replace("directorys", "directories"),
        out.display(),
        plural(r.manifest.runs, "run"),
        plural(r.manifest.strategies.len() as u64, "strategy")
    )
}

fn plural(n: u64, what: &str) -> String {
    match (n, what) {
        (1, _) => format!("1 {what}"),
        (_, "strategy") => format!("{n} strategies"),
        _ => format!("{n} {what}s"),
    }
}

fn pct(x: f64) -> String {
    format!("{:.1}", 100.0 * x)
}

/// The printed report of a sweep that took `seconds` on `threads` worker threads: what ran, where
/// the files are, then per strategy the rates with their Wilson intervals, the disc's coverage
/// and the figures' means and spreads, and each strategy's paired differences from the
/// baseline.
#[must_use]
pub fn sweep_table(r: &SweepResult, scenario: &Scenario, seconds: f64, threads: usize) -> String {
    let m = &r.manifest;
    let st: &Statistics = &r.summary.statistics;
    let mut s = String::new();
    let range = m.shard.map_or(0..m.runs, |sh| sh.first_run..sh.end_run);
    let _ = writeln!(
        s,
        "{} — {} × {} (runs {}..{} of {}, seed {}){}",
        scenario.name,
        plural(range.end - range.start, "run"),
        plural(m.strategies.len() as u64, "strategy"),
        range.start,
        range.end,
        m.runs,
        m.seed,
        m.shard.map_or(String::new(), |sh| format!(
            ", shard {}/{}",
            sh.index, sh.count
        ))
    );
    let how = if r.already_complete {
        "already complete".to_string()
    } else if r.runs_resumed > 0 {
        format!(
            "{} run indices resumed from committed chunks, {} run",
            r.runs_resumed, r.runs_run
        )
    } else {
        format!("{} run indices", r.runs_run)
    };
    let _ = writeln!(
        s,
        "{how} in {seconds:.1} s on {threads} threads; files in {}/ (runs.parquet, sols.parquet, summary.json, manifest.json)\n",
        r.dir.display()
    );
    let _ = writeln!(
        s,
        "Rates: % of runs [95 % Wilson interval]. Disc coverage: % of drive sols, pooled over the runs,\n\
         that ended with the truth inside the uncertainty disc [Wilson]. Figures: mean (p5–p95) over\n\
         the runs that have them (n = how many, when not all)."
    );
    let mut figs = vec![Metric::SolsToGoal];
    if m.segment.is_some() {
        figs.push(Metric::SegmentSols);
    }
    figs.extend([Metric::DistanceM, Metric::MaxUncertaintyM]);
    let rates = [
        RateKind::NoPath,
        RateKind::Fault,
        RateKind::TruthOutsideDisc,
        RateKind::GoalReached,
    ];
    let head_rate = |k: RateKind| match k {
        RateKind::NoPath => "NO_PATH",
        RateKind::Fault => "any fault",
        RateKind::TruthOutsideDisc => "truth outside r",
        RateKind::GoalReached => "goal reached",
    };
    let _ = write!(s, "{:<18}", "strategy");
    for k in rates {
        let _ = write!(s, " {:>19}", head_rate(k));
    }
    let _ = write!(s, " {:>22}", "disc coverage (sols)");
    for f in &figs {
        let _ = write!(s, " {:>19}", f.name());
    }
    let _ = writeln!(s);
    for ss in &st.strategies {
        let _ = write!(s, "{:<18}", ss.strategy);
        for k in rates {
            let cell = ss.rate(k.name()).map_or("-".into(), |r| {
                format!(
                    "{} [{}, {}]",
                    pct(r.rate),
                    pct(r.interval.lo),
                    pct(r.interval.hi)
                )
            });
            let _ = write!(s, " {cell:>19}");
        }
        let cell = ss.disc_coverage.as_ref().map_or("-".into(), |r| {
            format!(
                "{:.2} [{:.2}, {:.2}]",
                100.0 * r.rate,
                100.0 * r.interval.lo,
                100.0 * r.interval.hi
            )
        });
        let _ = write!(s, " {cell:>22}");
        for f in &figs {
            let cell = ss.figure(f.name()).map_or("-".into(), |sp| {
                let d = if sp.mean.abs() >= 100.0 { 0 } else { 2 };
                let n = if sp.n as u64 == ss.runs {
                    String::new()
                } else {
                    format!(" n={}", sp.n)
                };
                format!("{:.d$} ({:.d$}–{:.d$}){n}", sp.mean, sp.p5, sp.p95)
            });
            let _ = write!(s, " {cell:>19}");
        }
        let _ = writeln!(s);
    }
    if let Some(b) = &st.baseline {
        let mut paired = vec![Metric::SolsToGoal];
        if m.segment.is_some() {
            paired.extend([Metric::SegmentSols, Metric::SegmentDistanceM]);
        }
        paired.extend([Metric::NoPathFaults, Metric::DistanceM]);
        let _ = writeln!(
            s,
            "\nPaired difference from {b}: mean of (strategy − {b}) over the run indices where both have the\n\
             figure [95 % bootstrap interval, {} resamples].",
            st.bootstrap_resamples
        );
        for ss in st.strategies.iter().filter(|x| &x.strategy != b) {
            for (i, f) in paired.iter().enumerate() {
                let name = if i == 0 { ss.strategy.as_str() } else { "" };
                let cell = st
                    .paired(&ss.strategy, f.name())
                    .and_then(|p| p.difference)
                    .map_or("- (no run where both have it)".into(), |d| {
                        let dec = if f.name().ends_with("_m") { 1 } else { 2 };
                        format!(
                            "{:>8} [{}, {}]  {} pairs",
                            signed(d.mean, dec),
                            signed(d.interval.lo, dec),
                            signed(d.interval.hi, dec),
                            d.n
                        )
                    });
                let _ = writeln!(s, "{name:<18} {:<20} {cell}", f.name());
            }
        }
    }
    s
}
