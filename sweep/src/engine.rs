//! Running a sweep into a directory: chunks committed as they finish, a manifest to resume
//! from, and the output files assembled at the end; merging shard directories.
//!
//! A sweep directory holds, once complete:
//!
//! ```text
//! manifest.json   what was run (scenario, seed, runs, strategies, shard) and the files' SHA-256
//! runs.parquet    one row per run × strategy (crate::rows::RunRow)
//! sols.parquet    one row per run × strategy × sol (crate::rows::SolRow)
//! summary.json    the statistics (crate::summary)
//! ```
//!
//! While running it also holds `chunks/`. Every output byte is a function of the scenario file,
//! the seed, the runs and the strategies: not of the thread count, of where a kill interrupted
//! the sweep, or of how it was cut into shards.

use std::collections::BTreeSet;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use rayon::prelude::*;
use serde::Serialize;
use sim::Strategy;
use study::Scenario;

use crate::error::SweepError;
use crate::lock::{DirLock, LockKind};
use crate::manifest::{
    ChunkEntry, MANIFEST, Manifest, ScenarioId, SegmentInfo, ShardInfo, State, sha256_file,
};
use crate::parquet_io::{TableWriter, table_batches, tmp_path, write_durably};
use crate::rows::{self, RunRow, Segment, SolRow};
use crate::summary::{self, Statistics};

/// Default runs per committed chunk.
pub const DEFAULT_CHUNK_RUNS: u64 = 10;
/// Most runs one sweep may ask for (a run index is a `u64`; this keeps the run table and its
/// statistics within memory: 5 strategies × 10⁸ runs would be ~80 GB of rows).
pub const MAX_RUNS: u64 = 10_000_000;
/// Memory per row of the run table held for the statistics, bytes (`RunRow` with its vector
/// slot, rounded up).
const RUN_ROW_BYTES: u64 = 192;

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
    /// The sweep's seed: run `i` runs under [`sim::seeds::run_seed`]`(seed, i)`.
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
        let grid = &scenario.campaign.grid;
        let maps = maps::memory_budget::bytes_of(&[
            grid.width as u64,
            grid.height as u64,
            sim::planning_grid::PlanningGrid::BYTES_PER_CELL,
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

    fn manifest(&self, scenario: &Scenario, segment: Option<Segment>) -> Manifest {
        Manifest {
            format: crate::manifest::FORMAT.into(),
            solsim_version: env!("CARGO_PKG_VERSION").into(),
            scenario: ScenarioId {
                name: scenario.name.clone(),
                sha256: scenario.sha256.clone(),
            },
            seed: self.seed,
            runs: self.runs,
            strategies: self.strategies.iter().map(|s| s.name().into()).collect(),
            baseline: self.baseline.map(|b| b.name().into()),
            segment: segment.map(|s| SegmentInfo {
                from_sol: s.from_sol,
                distance_m: s.distance_m,
            }),
            shard: self.shard.map(|s| {
                let r = s.range(self.runs);
                ShardInfo {
                    index: s.index,
                    count: s.count,
                    first_run: r.start,
                    end_run: r.end,
                }
            }),
            state: State::Running,
            chunk_runs: Some(self.chunk_runs),
            chunks: Vec::new(),
            files: Default::default(),
        }
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
    pub segment: Option<SegmentInfo>,
    /// The statistics.
    pub statistics: Statistics,
}

/// What a finished sweep (or merge) reports.
#[derive(Debug, Clone)]
pub struct SweepResult {
    /// The directory.
    pub dir: PathBuf,
    /// The final manifest.
    pub manifest: Manifest,
    /// `summary.json`'s contents.
    pub summary: Summary,
    /// Run indices run by this call (runs × strategies were simulated).
    pub runs_run: u64,
    /// Run indices found committed by an earlier, interrupted call.
    pub runs_resumed: u64,
    /// Whether the directory already held the complete sweep.
    pub already_complete: bool,
}

/// The study segment of a scenario.
#[must_use]
pub fn segment_of(scenario: &Scenario) -> Option<Segment> {
    scenario.study_segment.map(|s| Segment {
        from_sol: s.from_sol,
        distance_m: s.distance_m,
    })
}

/// Runs run `run` under every strategy: the rows, in strategy order.
fn run_rows(
    scenario: &Scenario,
    spec: &SweepSpec,
    segment: Option<Segment>,
    run: u64,
) -> Vec<(RunRow, Vec<SolRow>)> {
    let seed = sim::seeds::run_seed(spec.seed, run);
    spec.strategies
        .par_iter()
        .map(|&s| rows::rows_of(run, seed, &scenario.run(s, seed), segment))
        .collect()
}

/// Runs `runs` under every strategy, in parallel over runs and strategies, and returns the
/// run rows in run order (strategies in `spec` order): a sweep without files, for
/// `solsim regress`'s statistical expectations.
#[must_use]
pub fn run_in_memory(scenario: &Scenario, spec: &SweepSpec, runs: Range<u64>) -> Vec<RunRow> {
    rows_in_memory(scenario, spec, runs, &|_, _| {})
}

/// [`run_in_memory`], calling `progress(done, total)` with the run indices done after each.
fn rows_in_memory(
    scenario: &Scenario,
    spec: &SweepSpec,
    runs: Range<u64>,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Vec<RunRow> {
    let segment = segment_of(scenario);
    let total = runs.end - runs.start;
    let done = AtomicU64::new(0);
    runs.into_par_iter()
        .flat_map_iter(|run| {
            let rows: Vec<RunRow> = run_rows(scenario, spec, segment, run)
                .into_iter()
                .map(|(r, _)| r)
                .collect();
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            rows
        })
        .collect()
}

/// Runs the sweep `spec` in memory — no directory, no Parquet files, no sol rows kept — and
/// returns its [`Summary`]: the one [`run`] writes to `summary.json` for the same scenario and
/// spec, equal once serialised (row order and arithmetic are the same; the thread count changes
/// neither). `progress(done, total)` is called with the run indices done after each one. This
/// is what `solsim compare --runs N` reports. Check the spec with [`SweepSpec::validate`] first:
/// the run table is held in memory.
#[must_use]
pub fn summary_in_memory(
    scenario: &Scenario,
    spec: &SweepSpec,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Summary {
    let rows = rows_in_memory(scenario, spec, spec.run_range(), progress);
    summarise(&rows, &spec.manifest(scenario, segment_of(scenario)))
}

/// Largest `summary.json` read back, bytes (its statistics are a few kilobytes).
const MAX_SUMMARY_BYTES: u64 = 16 << 20;

fn io_gate(path: &Path, e: maps::input_file::InputFileError) -> SweepError {
    SweepError::Io {
        path: path.to_path_buf(),
        what: "cannot read".into(),
        message: e.to_string(),
    }
}

fn chunk_name(kind: &str, first: u64, end: u64) -> String {
    format!("{kind}-{first:010}-{end:010}.parquet")
}

fn io(path: &Path, what: &str, e: std::io::Error) -> SweepError {
    SweepError::Io {
        path: path.to_path_buf(),
        what: what.into(),
        message: e.to_string(),
    }
}

fn metadata(manifest: &Manifest) -> Vec<(String, String)> {
    let mut kv = vec![
        ("solsim.format".into(), manifest.format.clone()),
        ("solsim.version".into(), manifest.solsim_version.clone()),
        ("solsim.scenario".into(), manifest.scenario.name.clone()),
        (
            "solsim.scenario_sha256".into(),
            manifest.scenario.sha256.clone(),
        ),
        ("solsim.seed".into(), manifest.seed.to_string()),
        ("solsim.runs".into(), manifest.runs.to_string()),
        ("solsim.strategies".into(), manifest.strategies.join(",")),
    ];
    if let Some(s) = manifest.shard {
        kv.push((
            "solsim.shard".into(),
            format!(
                "{}/{} (runs {}..{})",
                s.index, s.count, s.first_run, s.end_run
            ),
        ));
    }
    kv
}

/// Prepares `dir` for the sweep: a new or empty directory gets a fresh manifest; a directory
/// holding this sweep resumes it (with `resume`), after removing what a kill left half-made.
/// Returns the manifest to continue from.
fn prepare(dir: &Path, fresh: Manifest, resume: bool) -> Result<(Manifest, DirLock), SweepError> {
    if dir.exists() && !dir.is_dir() {
        return Err(SweepError::option(
            "--out",
            "a directory",
            format!("{} (not a directory)", dir.display()),
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| io(dir, "cannot create the directory", e))?;
    let lock = DirLock::take(dir, LockKind::Exclusive, "--out")?;
    prepare_locked(dir, fresh, resume).map(|m| (m, lock))
}

/// [`prepare`], with `dir` locked.
fn prepare_locked(dir: &Path, fresh: Manifest, resume: bool) -> Result<Manifest, SweepError> {
    let Some(mut found) = Manifest::read(dir)? else {
        // A kill during the first manifest's write leaves only its temporary file: the
        // directory is this sweep's, with nothing in it yet.
        let half_written = tmp_path(&dir.join(MANIFEST));
        if half_written.is_file() {
            std::fs::remove_file(&half_written)
                .map_err(|e| io(&half_written, "cannot remove", e))?;
        }
        let mut entries = std::fs::read_dir(dir).map_err(|e| io(dir, "cannot list", e))?;
        if let Some(Ok(e)) = entries.next() {
            return Err(SweepError::option(
                "--out",
                "a new or empty directory, or one holding a sweep (manifest.json)",
                format!(
                    "{} (holds {} and no sweep manifest)",
                    dir.display(),
                    e.file_name().to_string_lossy()
                ),
            ));
        }
        fresh.write(dir)?;
        return Ok(fresh);
    };
    let path = dir.join(MANIFEST);
    if !resume {
        return Err(SweepError::option(
            "--out",
            "a new or empty directory (pass --resume to continue the sweep in it)",
            format!("{} (holds a sweep: {})", dir.display(), path.display()),
        ));
    }
    let mismatch = fresh.differs_from(&found).or_else(|| {
        (found.shard != fresh.shard).then(|| {
            let f = |s: Option<ShardInfo>| {
                s.map_or("none".into(), |s| format!("{}/{}", s.index, s.count))
            };
            ("shard", f(fresh.shard), f(found.shard))
        })
    });
    if let Some((field, this, there)) = mismatch {
        return Err(SweepError::option(
            "--resume",
            format!(
                "the scenario and options of the sweep in {} ({field} {there})",
                path.display()
            ),
            format!("{field} {this}"),
        ));
    }
    let chunks = dir.join("chunks");
    // `chunks/` is this directory's own: a link (or anything but a directory) there would have
    // the clean-up below list and remove files elsewhere.
    match std::fs::symlink_metadata(&chunks) {
        Ok(meta) if !meta.is_dir() => {
            return Err(SweepError::format(
                &chunks,
                "(file)",
                "the sweep's own chunks directory",
                if meta.file_type().is_symlink() {
                    "a symbolic link (refused: it would be cleaned up wherever it points)"
                } else {
                    "not a directory"
                },
            ));
        }
        Ok(_) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(io(&chunks, "cannot look up", e)),
    }
    if found.state == State::Complete {
        // Nothing is rewritten; `run` checks that the files are the ones the manifest lists.
        if chunks.exists() {
            std::fs::remove_dir_all(&chunks).map_err(|e| io(&chunks, "cannot remove", e))?;
        }
        return Ok(found);
    }
    // What a kill may have left: temporary files, and chunk files written before the manifest
    // that would have listed them. A listed chunk whose files are missing or changed is run
    // again; one whose checksums agree must also hold exactly the runs its entry names
    // (a file renamed under an edited entry is refused, not merged in).
    std::fs::create_dir_all(&chunks).map_err(|e| io(&chunks, "cannot create", e))?;
    let mut intact = Vec::with_capacity(found.chunks.len());
    for c in std::mem::take(&mut found.chunks) {
        let same = [("runs", &c.runs_sha256), ("sols", &c.sols_sha256)]
            .iter()
            .all(|(kind, sha)| {
                sha256_file(&chunks.join(chunk_name(kind, c.first_run, c.end_run)))
                    .is_ok_and(|got| &got == *sha)
            });
        if same {
            let runs = chunks.join(chunk_name("runs", c.first_run, c.end_run));
            read_run_rows(&runs, c.first_run..c.end_run, &found.strategies)?;
            intact.push(c);
        }
    }
    found.chunks = intact;
    let keep: BTreeSet<String> = found
        .chunks
        .iter()
        .flat_map(|c| {
            [
                chunk_name("runs", c.first_run, c.end_run),
                chunk_name("sols", c.first_run, c.end_run),
            ]
        })
        .collect();
    for d in [dir, chunks.as_path()] {
        for e in std::fs::read_dir(d).map_err(|e| io(d, "cannot list", e))? {
            let e = e.map_err(|e| io(d, "cannot list", e))?;
            let name = e.file_name().to_string_lossy().into_owned();
            let stale = name.ends_with(".tmp")
                || (d == chunks.as_path() && !keep.contains(&name))
                || (d == dir
                    && ["runs.parquet", "sols.parquet", "summary.json"].contains(&name.as_str()));
            if stale {
                std::fs::remove_file(e.path())
                    .map_err(|err| io(&e.path(), "cannot remove", err))?;
            }
        }
    }
    found.write(dir)?;
    Ok(found)
}

/// Runs the sweep into `dir`, or resumes it (`resume`), and writes the output files.
/// `progress(done, total)` is called with run indices done (including resumed ones) after each
/// committed chunk.
///
/// # Errors
/// The spec does not fit the scenario; the directory holds something else (or this sweep
/// without `resume`, or another sweep); a write fails.
pub fn run(
    scenario: &Scenario,
    spec: &SweepSpec,
    dir: &Path,
    resume: bool,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<SweepResult, SweepError> {
    let segment = segment_of(scenario);
    let (manifest, _lock) = prepare(dir, spec.manifest(scenario, segment), resume)?;
    let range = spec.run_range();
    let total = range.end - range.start;
    if manifest.state == State::Complete {
        let summary = verify_complete(dir, &manifest)?.summary;
        return Ok(SweepResult {
            dir: dir.to_path_buf(),
            manifest,
            summary,
            runs_run: 0,
            runs_resumed: total,
            already_complete: true,
        });
    }
    let chunk_runs = manifest.chunk_runs.unwrap_or(spec.chunk_runs);
    let committed: BTreeSet<u64> = manifest.chunks.iter().map(|c| c.first_run).collect();
    let pending: Vec<Range<u64>> = (range.start..range.end)
        .step_by(chunk_runs.try_into().unwrap_or(usize::MAX))
        .map(|first| first..(first + chunk_runs).min(range.end))
        .filter(|r| !committed.contains(&r.start))
        .collect();
    let resumed = total - pending.iter().map(|r| r.end - r.start).sum::<u64>();
    let done = AtomicU64::new(resumed);
    progress(resumed, total);
    let chunks_dir = dir.join("chunks");
    std::fs::create_dir_all(&chunks_dir).map_err(|e| io(&chunks_dir, "cannot create", e))?;
    // Workers simulate; one committer thread writes each finished chunk (two Parquet files and
    // the manifest, each `fsync`ed), so no worker waits on the disk. The queue is short, which
    // bounds the rows held in memory.
    let (tx, rx) = std::sync::mpsc::sync_channel::<(Range<u64>, Vec<RunRow>, Vec<SolRow>)>(2);
    let mut manifest = manifest;
    let (simulated, committed) = std::thread::scope(|scope| {
        let committer = scope.spawn(|| -> Result<Manifest, SweepError> {
            for (chunk, run_rows, sol_rows) in rx {
                commit_chunk(
                    &chunks_dir,
                    &chunk,
                    &run_rows,
                    &sol_rows,
                    &mut manifest,
                    dir,
                )?;
                let n = done.fetch_add(chunk.end - chunk.start, Ordering::Relaxed) + chunk.end
                    - chunk.start;
                progress(n, total);
            }
            Ok(manifest)
        });
        let simulated = pending.par_iter().try_for_each(|chunk| {
            let results: Vec<(RunRow, Vec<SolRow>)> = chunk
                .clone()
                .into_par_iter()
                .flat_map_iter(|run| run_rows(scenario, spec, segment, run))
                .collect();
            let run_rows: Vec<RunRow> = results.iter().map(|(r, _)| r.clone()).collect();
            let sol_rows: Vec<SolRow> = results.into_iter().flat_map(|(_, s)| s).collect();
            // A closed queue means the committer stopped on an error, reported below.
            tx.send((chunk.clone(), run_rows, sol_rows)).map_err(|_| ())
        });
        drop(tx);
        let committed = committer
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p));
        (simulated, committed)
    });
    let manifest = committed?;
    if simulated.is_err() {
        return Err(SweepError::Io {
            path: dir.to_path_buf(),
            what: "the chunk committer stopped".into(),
            message: "without an error (a bug)".into(),
        });
    }
    let sources: Vec<Source> = manifest
        .chunks
        .iter()
        .map(|c| Source {
            runs: chunks_dir.join(chunk_name("runs", c.first_run, c.end_run)),
            sols: chunks_dir.join(chunk_name("sols", c.first_run, c.end_run)),
            range: c.first_run..c.end_run,
        })
        .collect();
    let (manifest, summary) = assemble(dir, &sources, manifest)?;
    std::fs::remove_dir_all(&chunks_dir).map_err(|e| io(&chunks_dir, "cannot remove", e))?;
    Ok(SweepResult {
        dir: dir.to_path_buf(),
        manifest,
        summary,
        runs_run: total - resumed,
        runs_resumed: resumed,
        already_complete: false,
    })
}

fn commit_chunk(
    chunks_dir: &Path,
    chunk: &Range<u64>,
    run_rows: &[RunRow],
    sol_rows: &[SolRow],
    m: &mut Manifest,
    dir: &Path,
) -> Result<(), SweepError> {
    let bug = |e: arrow_schema::ArrowError| SweepError::Io {
        path: chunks_dir.to_path_buf(),
        what: "cannot build the rows of a chunk".into(),
        message: e.to_string(),
    };
    let runs_path = chunks_dir.join(chunk_name("runs", chunk.start, chunk.end));
    let sols_path = chunks_dir.join(chunk_name("sols", chunk.start, chunk.end));
    let mut w = TableWriter::create(&runs_path, rows::runs_schema(), &[])?;
    w.push(&rows::runs_batch(run_rows).map_err(bug)?)?;
    w.finish()?;
    let mut w = TableWriter::create(&sols_path, rows::sols_schema(), &[])?;
    w.push(&rows::sols_batch(sol_rows).map_err(bug)?)?;
    w.finish()?;
    let entry = ChunkEntry {
        first_run: chunk.start,
        end_run: chunk.end,
        runs_sha256: sha256_file(&runs_path)?,
        sols_sha256: sha256_file(&sols_path)?,
    };
    m.chunks.push(entry);
    m.chunks.sort_by_key(|c| c.first_run);
    m.write(dir)
}

/// The run rows of runs `range` under `strategies` read from `path`, checked as
/// [`check_run_rows`] does (the row count before anything is decoded).
fn read_run_rows(
    path: &Path,
    range: Range<u64>,
    strategies: &[String],
) -> Result<Vec<RunRow>, SweepError> {
    let want = (range.end - range.start).saturating_mul(strategies.len() as u64);
    let mut rows = Vec::new();
    for batch in table_batches(path, &rows::runs_schema(), Some(want))? {
        rows.extend(rows::run_rows_from(&batch?).map_err(|e| {
            SweepError::format(path, "(rows)", "rows of a solsim runs table", e.to_string())
        })?);
    }
    check_run_rows(path, &rows, range, strategies)?;
    Ok(rows)
}

/// Checks that the run rows read from `path` are runs `range` under `strategies`, each pair
/// once, in run order (strategies in order within a run): what a chunk, a shard or a sweep of
/// that range writes. Whatever its manifest says, a table that holds other runs is refused.
fn check_run_rows(
    path: &Path,
    rows: &[RunRow],
    range: Range<u64>,
    strategies: &[String],
) -> Result<(), SweepError> {
    let n = strategies.len() as u64;
    let want = (range.end - range.start).saturating_mul(n);
    if rows.len() as u64 != want {
        return Err(SweepError::format(
            path,
            "(rows)",
            format!(
                "{want} rows: runs {}..{} × {n} strategies",
                range.start, range.end
            ),
            format!("{} rows", rows.len()),
        ));
    }
    for (k, row) in rows.iter().enumerate() {
        let k = k as u64;
        let (run, strategy) = (range.start + k / n, &strategies[(k % n) as usize]);
        if row.run_index != run || row.strategy.name() != strategy {
            return Err(SweepError::format(
                path,
                format!("row {k}"),
                format!("run {run} under {strategy}"),
                format!("run {} under {}", row.run_index, row.strategy.name()),
            ));
        }
    }
    Ok(())
}

/// Checks, batch by batch, that the sol rows of a table are of runs in `range` under the
/// sweep's strategies, in (run, strategy, sol) order, each once.
struct SolRowCheck<'a> {
    path: &'a Path,
    range: Range<u64>,
    strategies: &'a [String],
    last: Option<(u64, usize, u32)>,
    rows: u64,
}

impl SolRowCheck<'_> {
    fn batch(&mut self, batch: &arrow_array::RecordBatch) -> Result<(), SweepError> {
        use arrow_array::cast::AsArray as _;
        use arrow_array::types::{UInt32Type, UInt64Type};
        let runs = batch.column(0).as_primitive::<UInt64Type>();
        let names = batch.column(1).as_string::<i32>();
        let sols = batch.column(2).as_primitive::<UInt32Type>();
        for i in 0..batch.num_rows() {
            let (run, name, sol) = (runs.value(i), names.value(i), sols.value(i));
            let key = self
                .strategies
                .iter()
                .position(|s| s == name)
                .map(|s| (run, s, sol));
            let fits = key.is_some_and(|k| {
                self.range.contains(&run) && self.last.is_none_or(|last| k > last)
            });
            if !fits {
                return Err(SweepError::format(
                    self.path,
                    format!("row {}", self.rows),
                    format!(
                        "a sol of runs {}..{} under {}, after the row before it",
                        self.range.start,
                        self.range.end,
                        self.strategies.join(", ")
                    ),
                    maps::input_file::excerpt(&format!("run {run} under {name}, sol {sol}"), 120),
                ));
            }
            self.last = key;
            self.rows += 1;
        }
        Ok(())
    }
}

fn summarise(rows: &[RunRow], manifest: &Manifest) -> Summary {
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
        statistics: summary::statistics(
            rows,
            &strategies,
            baseline,
            manifest.segment.is_some(),
            manifest.seed,
        ),
    }
}

/// `summary.json`'s text for `summary` (pretty JSON and a newline).
fn summary_text(summary: &Summary, dir: &Path) -> Result<String, SweepError> {
    let mut text = serde_json::to_string_pretty(summary).map_err(|e| SweepError::Io {
        path: dir.join("summary.json"),
        what: "cannot serialise".into(),
        message: e.to_string(),
    })?;
    text.push('\n');
    Ok(text)
}

/// A pair of tables that holds runs `range`: a committed chunk, or a shard's output.
struct Source {
    runs: PathBuf,
    sols: PathBuf,
    range: Range<u64>,
}

/// The output files a sweep directory holds once complete.
const OUTPUTS: [&str; 3] = ["runs.parquet", "sols.parquet", "summary.json"];

/// Writes `runs.parquet`, `sols.parquet`, `summary.json` and the complete manifest from
/// `sources`, given in run order, after checking that their rows are the runs they claim. On
/// an error (a source that holds other runs, a full disk) no output file is left behind: the
/// directory still says "running" and lists its chunks, and `--resume` finishes it.
fn assemble(
    dir: &Path,
    sources: &[Source],
    manifest: Manifest,
) -> Result<(Manifest, Summary), SweepError> {
    assemble_outputs(dir, sources, manifest).inspect_err(|_| {
        for name in OUTPUTS {
            let path = dir.join(name);
            let _ = std::fs::remove_file(tmp_path(&path));
            let _ = std::fs::remove_file(&path);
        }
    })
}

fn assemble_outputs(
    dir: &Path,
    sources: &[Source],
    mut manifest: Manifest,
) -> Result<(Manifest, Summary), SweepError> {
    manifest.state = State::Complete;
    manifest.chunk_runs = None;
    manifest.chunks.clear();
    manifest.files.clear();
    let kv = metadata(&manifest);
    let runs_out = dir.join("runs.parquet");
    let sols_out = dir.join("sols.parquet");
    let mut all_runs: Vec<RunRow> = Vec::new();
    let mut w = TableWriter::create(&runs_out, rows::runs_schema(), &kv)?;
    for source in sources {
        let mut rows = Vec::new();
        let want = (source.range.end - source.range.start)
            .saturating_mul(manifest.strategies.len() as u64);
        for batch in table_batches(&source.runs, &rows::runs_schema(), Some(want))? {
            let batch = batch?;
            rows.extend(rows::run_rows_from(&batch).map_err(|e| {
                SweepError::format(
                    &source.runs,
                    "(rows)",
                    "rows of a solsim runs table",
                    e.to_string(),
                )
            })?);
            w.push(&batch)?;
        }
        check_run_rows(
            &source.runs,
            &rows,
            source.range.clone(),
            &manifest.strategies,
        )?;
        all_runs.extend(rows);
    }
    w.finish()?;
    let mut w = TableWriter::create(&sols_out, rows::sols_schema(), &kv)?;
    for source in sources {
        let mut check = SolRowCheck {
            path: &source.sols,
            range: source.range.clone(),
            strategies: &manifest.strategies,
            last: None,
            rows: 0,
        };
        for batch in table_batches(&source.sols, &rows::sols_schema(), None)? {
            let batch = batch?;
            check.batch(&batch)?;
            w.push(&batch)?;
        }
    }
    w.finish()?;
    let summary = summarise(&all_runs, &manifest);
    let text = summary_text(&summary, dir)?;
    write_durably(&dir.join("summary.json"), text.as_bytes())?;
    for name in OUTPUTS {
        manifest
            .files
            .insert(name.into(), sha256_file(&dir.join(name))?);
    }
    manifest.write(dir)?;
    Ok((manifest, summary))
}

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
fn verify_complete(dir: &Path, manifest: &Manifest) -> Result<CompletedSweep, SweepError> {
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
    .map_err(|e| io_gate(&summary_path, e))?;
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

/// Merges complete shard directories (any order) into `out`, writing exactly the files one
/// unsharded sweep writes.
///
/// # Errors
/// A directory that holds no complete sweep; directories of different sweeps; shards that
/// overlap or leave runs out; `out` not new or empty.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<SweepResult, SweepError> {
    if dirs.is_empty() {
        return Err(SweepError::option(
            "DIR",
            "at least one shard directory",
            "none",
        ));
    }
    let mut parts: Vec<(PathBuf, Manifest)> = Vec::new();
    let mut locks = Vec::with_capacity(dirs.len() + 1);
    for d in dirs {
        locks.push(DirLock::take(d, LockKind::Shared, "DIR")?);
        let path = d.join(MANIFEST);
        let m = Manifest::read(d)?.ok_or_else(|| {
            SweepError::format(&path, "(file)", "a sweep manifest", "no such file")
        })?;
        if m.state != State::Complete {
            return Err(SweepError::format(
                &path,
                "state",
                "\"complete\" (finish the shard with --resume first)",
                "\"running\"",
            ));
        }
        if let Some((_, first)) = parts.first()
            && let Some((field, a, b)) = first.differs_from(&m)
        {
            return Err(SweepError::format(
                &path,
                field,
                format!("{a} (as in {})", parts[0].0.join(MANIFEST).display()),
                b,
            ));
        }
        for (name, sha) in &m.files {
            let got = sha256_file(&d.join(name))?;
            if &got != sha {
                return Err(SweepError::format(
                    d.join(name),
                    "(sha256)",
                    format!("{sha} (as listed in {})", path.display()),
                    got,
                ));
            }
        }
        parts.push((d.clone(), m));
    }
    let range = |m: &Manifest| m.shard.map_or(0..m.runs, |s| s.first_run..s.end_run);
    parts.sort_by_key(|(_, m)| range(m).start);
    let runs = parts[0].1.runs;
    let mut next = 0;
    for (d, m) in &parts {
        let r = range(m);
        if r.start != next {
            let what = if r.start < next {
                "overlap"
            } else {
                "leave runs out"
            };
            return Err(SweepError::format(
                d.join(MANIFEST),
                "shard",
                format!("a shard starting at run {next} (the shards {what})"),
                format!("runs {}..{}", r.start, r.end),
            ));
        }
        next = r.end;
    }
    if next != runs {
        return Err(SweepError::option(
            "DIR",
            format!("shards covering runs 0..{runs}"),
            format!("shards covering runs 0..{next}"),
        ));
    }
    if out.exists() {
        let empty = std::fs::read_dir(out)
            .map_err(|e| io(out, "cannot list", e))?
            .next()
            .is_none();
        // An earlier merge of these shards (finished or interrupted) may be written over.
        let same = || -> Result<bool, SweepError> {
            Ok(Manifest::read(out)?
                .is_some_and(|m| m.shard.is_none() && m.differs_from(&parts[0].1).is_none()))
        };
        if !empty && !same()? {
            return Err(SweepError::option(
                "--out",
                "a new or empty directory, or an earlier merge of these shards",
                format!("{} (not empty)", out.display()),
            ));
        }
    }
    std::fs::create_dir_all(out).map_err(|e| io(out, "cannot create the directory", e))?;
    locks.push(DirLock::take(out, LockKind::Exclusive, "--out")?);
    let mut manifest = parts[0].1.clone();
    manifest.shard = None;
    let sources: Vec<Source> = parts
        .iter()
        .map(|(d, m)| Source {
            runs: d.join("runs.parquet"),
            sols: d.join("sols.parquet"),
            range: m.run_range(),
        })
        .collect();
    // A placeholder manifest first, so an interrupted merge leaves a directory that says what
    // it is (running) rather than loose files.
    let mut running = manifest.clone();
    running.state = State::Running;
    running.files.clear();
    running.chunk_runs = Some(DEFAULT_CHUNK_RUNS);
    running.write(out)?;
    let _ = std::fs::remove_file(tmp_path(&out.join(MANIFEST)));
    let (manifest, summary) = assemble(out, &sources, manifest)?;
    Ok(SweepResult {
        dir: out.to_path_buf(),
        manifest,
        summary,
        runs_run: 0,
        runs_resumed: runs,
        already_complete: false,
    })
}
