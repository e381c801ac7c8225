//! Running a sweep into a directory ([`run`]): chunks committed as they finish, a manifest to
//! resume from, and the output files assembled at the end (`crate::assemble`). The sweep's
//! other parts live beside it and are re-exported here: what to sweep (`crate::spec`), the
//! runs simulated in memory (`crate::simulate`), a complete directory read back
//! (`crate::complete`); shards are merged by [`crate::merge()`].
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
use study::Scenario;

use crate::assemble::{Source, assemble, read_run_rows};
use crate::complete::verify_complete;
use crate::error::SweepError;
use crate::lock::{DirLock, LockKind};
use crate::manifest::{ChunkEntry, MANIFEST, Manifest, ShardInfo, State, sha256_file};
use crate::parquet_io::{TableWriter, tmp_path};
use crate::rows::{self, RunRow, SolRow};
use crate::simulate::run_rows;

// The sweep's API, from the modules that hold each part.
pub use crate::complete::{CompletedSweep, read_complete};
pub use crate::simulate::{run_in_memory, summary_in_memory};
pub use crate::spec::{DEFAULT_CHUNK_RUNS, MAX_RUNS, Shard, SweepSpec, check_runs};
pub use crate::summary::Summary;

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

fn chunk_name(kind: &str, first: u64, end: u64) -> String {
    format!("{kind}-{first:010}-{end:010}.parquet")
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
    std::fs::create_dir_all(dir)
        .map_err(|e| SweepError::io(dir, "cannot create the directory", e))?;
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
                .map_err(|e| SweepError::io(&half_written, "cannot remove", e))?;
        }
        let mut entries =
            std::fs::read_dir(dir).map_err(|e| SweepError::io(dir, "cannot list", e))?;
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
        Err(e) => return Err(SweepError::io(&chunks, "cannot look up", e)),
    }
    if found.state == State::Complete {
        // Nothing is rewritten; `run` checks that the files are the ones the manifest lists.
        if chunks.exists() {
            std::fs::remove_dir_all(&chunks)
                .map_err(|e| SweepError::io(&chunks, "cannot remove", e))?;
        }
        return Ok(found);
    }
    // What a kill may have left: temporary files, and chunk files written before the manifest
    // that would have listed them. A listed chunk whose files are missing or changed is run
    // again; one whose checksums agree must also hold exactly the runs its entry names
    // (a file renamed under an edited entry is refused, not merged in).
    std::fs::create_dir_all(&chunks).map_err(|e| SweepError::io(&chunks, "cannot create", e))?;
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
        for e in std::fs::read_dir(d).map_err(|e| SweepError::io(d, "cannot list", e))? {
            let e = e.map_err(|e| SweepError::io(d, "cannot list", e))?;
            let name = e.file_name().to_string_lossy().into_owned();
            let stale = name.ends_with(".tmp")
                || (d == chunks.as_path() && !keep.contains(&name))
                || (d == dir
                    && ["runs.parquet", "sols.parquet", "summary.json"].contains(&name.as_str()));
            if stale {
                std::fs::remove_file(e.path())
                    .map_err(|err| SweepError::io(&e.path(), "cannot remove", err))?;
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
    let (manifest, _lock) = prepare(dir, Manifest::fresh(scenario, spec), resume)?;
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
    std::fs::create_dir_all(&chunks_dir)
        .map_err(|e| SweepError::io(&chunks_dir, "cannot create", e))?;
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
                .flat_map_iter(|run| run_rows(scenario, spec, run))
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
    std::fs::remove_dir_all(&chunks_dir)
        .map_err(|e| SweepError::io(&chunks_dir, "cannot remove", e))?;
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
    let bug = |e: arrow_schema::ArrowError| {
        SweepError::io(chunks_dir, "cannot build the rows of a chunk", e)
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
