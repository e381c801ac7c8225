//! The output files of a sweep directory from tables that hold its runs — the committed chunks
//! of a sweep, or the outputs of its shards — each table's rows checked to be the runs it
//! claims before they are copied: `runs.parquet`, `sols.parquet`, `summary.json` and the
//! complete manifest.

use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::error::SweepError;
use crate::manifest::{Manifest, State, sha256_file};
use crate::parquet_io::{TableWriter, table_batches, tmp_path, write_durably};
use crate::rows::{self, RunRow};
use crate::summary::{Summary, summarise, summary_text};

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

/// A pair of tables that holds runs `range`: a committed chunk, or a shard's output.
pub(crate) struct Source {
    /// Its `runs` table.
    pub(crate) runs: PathBuf,
    /// Its `sols` table.
    pub(crate) sols: PathBuf,
    /// The runs it holds.
    pub(crate) range: Range<u64>,
}

/// The output files a sweep directory holds once complete.
pub(crate) const OUTPUTS: [&str; 3] = ["runs.parquet", "sols.parquet", "summary.json"];

/// Writes `runs.parquet`, `sols.parquet`, `summary.json` and the complete manifest from
/// `sources`, given in run order, after checking that their rows are the runs they claim. On
/// an error (a source that holds other runs, a full disk) no output file is left behind: the
/// directory still says "running" and lists its chunks, and `--resume` finishes it.
pub(crate) fn assemble(
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

/// The run rows of runs `range` under `strategies` read from `path`, checked as
/// [`check_run_rows`] does (the row count before anything is decoded).
pub(crate) fn read_run_rows(
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
