//! Merging the complete directories of a sweep's shards into the directory one unsharded sweep
//! writes ([`merge`]).

use std::path::{Path, PathBuf};

use crate::assemble::{Source, assemble};
use crate::engine::SweepResult;
use crate::error::SweepError;
use crate::lock::{DirLock, LockKind};
use crate::manifest::{MANIFEST, Manifest, State, sha256_file};
use crate::parquet_io::tmp_path;
use crate::spec::DEFAULT_CHUNK_RUNS;

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
            .map_err(|e| SweepError::io(out, "cannot list", e))?
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
    std::fs::create_dir_all(out)
        .map_err(|e| SweepError::io(out, "cannot create the directory", e))?;
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
