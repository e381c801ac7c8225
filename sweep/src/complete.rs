//! A complete sweep read back from its directory ([`read_complete`]): the files the manifest
//! lists, unchanged, and the statistics recomputed from the rows equal to `summary.json`'s —
//! what `solsim report` shows, and what a finished sweep run again checks.

use std::path::Path;

use crate::assemble::{OUTPUTS, read_run_rows};
use crate::error::SweepError;
use crate::lock::{DirLock, LockKind};
use crate::manifest::{MANIFEST, Manifest, State, sha256_file};
use crate::rows::RunRow;
use crate::spec::RUN_ROW_BYTES;
use crate::summary::{Summary, summarise, summary_text};

/// Largest `summary.json` read back, bytes (its statistics are a few kilobytes).
const MAX_SUMMARY_BYTES: u64 = 16 << 20;

/// A complete sweep read back from its directory: the manifest, every run row, and the summary
/// recomputed from the rows, which must equal the directory's `summary.json` byte for byte.
#[derive(Debug, Clone)]
pub struct CompletedSweep {
    /// `manifest.json`.
    pub manifest: Manifest,
    /// The runs this directory holds: all of the sweep's, or its shard's.
    pub runs_here: u64,
    /// `runs.parquet`, in run order.
    pub rows: Vec<RunRow>,
    /// The statistics of `rows` (as `summary.json` holds them).
    pub summary: Summary,
}

/// Reads the complete sweep in `dir` (what `solsim report` shows): the manifest must say
/// complete, `runs.parquet` and `summary.json` must have the SHA-256 it lists, and the summary
/// recomputed from the rows must be the one on disk — so a report never shows numbers the
/// rows do not give.
///
/// A shard directory is read as what it is, the shard's runs (see [`Manifest::shard`]).
///
/// The run table is held in memory: it must fit `budget` (the manifest's runs × strategies,
/// checked before anything is decoded; the table's row count is checked against it too).
///
/// # Errors
/// No manifest; a sweep still running; a file missing, changed since the sweep wrote it, or
/// not a solsim table; a run table over the budget; a directory being written.
pub fn read_complete(dir: &Path, budget: maps::MemoryBudget) -> Result<CompletedSweep, SweepError> {
    let _lock = DirLock::take(dir, LockKind::Shared, "DIR")?;
    let path = dir.join(MANIFEST);
    let manifest = Manifest::read(dir)?
        .ok_or_else(|| SweepError::format(&path, "(file)", "a sweep manifest", "no such file"))?;
    let r = manifest.run_range();
    let table = (r.end - r.start)
        .saturating_mul(manifest.strategies.len() as u64)
        .saturating_mul(RUN_ROW_BYTES);
    if !budget.allows(table) {
        return Err(SweepError::option(
            "--memory-budget-mib",
            format!(
                "room for the run table of {} ({} runs × {} strategies: {})",
                dir.display(),
                r.end - r.start,
                manifest.strategies.len(),
                maps::input_file::human_bytes(table)
            ),
            maps::input_file::human_bytes(budget.limit_bytes),
        ));
    }
    verify_complete(dir, &manifest)
}

/// [`read_complete`] on a manifest already read, with `dir` locked: every listed file has its
/// SHA-256, the run rows are the runs the manifest names, and the summary recomputed from them
/// is the one on disk.
pub(crate) fn verify_complete(
    dir: &Path,
    manifest: &Manifest,
) -> Result<CompletedSweep, SweepError> {
    let path = dir.join(MANIFEST);
    let manifest = manifest.clone();
    if manifest.state != State::Complete {
        return Err(SweepError::format(
            &path,
            "state",
            "\"complete\" (resume the sweep with --resume first)",
            "\"running\"",
        ));
    }
    for name in OUTPUTS {
        let file = dir.join(name);
        let listed = manifest.files.get(name).ok_or_else(|| {
            SweepError::format(&path, format!("files.{name}"), "its SHA-256", "nothing")
        })?;
        let actual = sha256_file(&file)?;
        if &actual != listed {
            return Err(SweepError::format(
                &file,
                "(file)",
                format!("the file the sweep wrote (SHA-256 {listed})"),
                format!("a changed file (SHA-256 {actual})"),
            ));
        }
    }
    let rows = read_run_rows(
        &dir.join("runs.parquet"),
        manifest.run_range(),
        &manifest.strategies,
    )?;
    let summary = summarise(&rows, &manifest);
    let text = summary_text(&summary, dir)?;
    let summary_path = dir.join("summary.json");
    let on_disk = maps::input_file::read_input(
        &summary_path,
        MAX_SUMMARY_BYTES,
        maps::input_file::Follow::No,
    )
    .map_err(|e| SweepError::io(&summary_path, "cannot read", e))?;
    if on_disk != text.as_bytes() {
        return Err(SweepError::format(
            dir.join("summary.json"),
            "(file)",
            "the statistics of runs.parquet as this solsim computes them",
            format!(
                "other statistics (written by solsim {})",
                manifest.solsim_version
            ),
        ));
    }
    let runs_here = manifest
        .shard
        .map_or(manifest.runs, |sh| sh.end_run - sh.first_run);
    Ok(CompletedSweep {
        manifest,
        runs_here,
        rows,
        summary,
    })
}
