//! `manifest.json`: what a sweep directory holds, so a sweep can resume after a kill and
//! shards can be merged.
//!
//! While a sweep runs, the manifest lists the chunks of runs committed so far (each chunk's two
//! Parquet files under `chunks/` with their SHA-256). It is replaced (write aside, `fsync`,
//! rename) after every chunk, so after a kill at any moment it names only whole chunks. When
//! the sweep is done it lists the output files with their SHA-256 instead, and carries nothing
//! that depends on how the work was cut (no chunk list, no chunk size): a sweep that resumed, a
//! sweep on another thread count and a merge of shards write the same manifest.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use study::Scenario;
use study::scenario::StudySegment;

use crate::error::SweepError;
use crate::parquet_io;
use crate::spec::SweepSpec;

/// The value of [`Manifest::format`].
pub const FORMAT: &str = "solsim-sweep/2";
/// The manifest's file name.
pub const MANIFEST: &str = "manifest.json";

/// The scenario a sweep ran.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ScenarioId {
    /// Its `name`.
    pub name: String,
    /// SHA-256 of the scenario file's bytes, hex.
    pub sha256: String,
}

/// A slice of the run indices run on its own (`--shard INDEX/COUNT`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardInfo {
    /// This shard, `0..count`.
    pub index: u64,
    /// Shards in all.
    pub count: u64,
    /// First run index of the slice.
    pub first_run: u64,
    /// One past the last run index of the slice.
    pub end_run: u64,
}

/// One committed chunk of runs.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ChunkEntry {
    /// First run index.
    pub first_run: u64,
    /// One past the last run index.
    pub end_run: u64,
    /// SHA-256 of `chunks/runs-<first>-<end>.parquet`.
    pub runs_sha256: String,
    /// SHA-256 of `chunks/sols-<first>-<end>.parquet`.
    pub sols_sha256: String,
}

/// Whether the sweep is still running.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum State {
    /// Chunks are being committed.
    Running,
    /// The output files are written.
    Complete,
}

/// The contents of `manifest.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// [`FORMAT`].
    pub format: String,
    /// The solsim version that wrote it.
    pub solsim_version: String,
    /// The scenario.
    pub scenario: ScenarioId,
    /// The sweep's seed (run `i` runs under `sim::seeds::RunSeeds::new(seed, i)`).
    pub seed: u64,
    /// Run indices `0..runs` of the whole sweep.
    pub runs: u64,
    /// The strategies, in order.
    pub strategies: Vec<String>,
    /// The strategy paired differences are taken against.
    pub baseline: Option<String>,
    /// The study segment, if the scenario has one.
    pub segment: Option<StudySegment>,
    /// The slice this directory holds (`None`: all runs).
    pub shard: Option<ShardInfo>,
    /// Running or complete.
    pub state: State,
    /// Runs per chunk while running.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chunk_runs: Option<u64>,
    /// Committed chunks while running, by first run index.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub chunks: Vec<ChunkEntry>,
    /// Output files and their SHA-256 once complete.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub files: BTreeMap<String, String>,
}

/// SHA-256 of a file inside a sweep directory, hex, read in blocks through the input gate
/// ([`parquet_io::open_owned`]: a regular file, not a link, at most
/// [`parquet_io::MAX_TABLE_BYTES`]).
///
/// # Errors
/// The file cannot be read or is refused by the gate.
pub fn sha256_file(path: &Path) -> Result<String, SweepError> {
    use sha2::Digest as _;
    use std::io::Read as _;
    let mut file = parquet_io::open_owned(path, parquet_io::MAX_TABLE_BYTES)?;
    let mut hasher = sha2::Sha256::new();
    let mut block = vec![0_u8; 1 << 16];
    loop {
        let n = file
            .read(&mut block)
            .map_err(|e| SweepError::io(path, "cannot read", e))?;
        if n == 0 {
            break;
        }
        hasher.update(&block[..n]);
    }
    Ok(hasher
        .finalize()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect())
}

/// Manifests larger than this are not sweep manifests (a chunk entry is ~200 bytes).
const MAX_MANIFEST_BYTES: u64 = 64 << 20;

impl Manifest {
    /// The manifest of a new sweep of `scenario` under `spec`: running, with no chunk yet.
    #[must_use]
    pub fn fresh(scenario: &Scenario, spec: &SweepSpec) -> Self {
        Manifest {
            format: FORMAT.into(),
            solsim_version: env!("CARGO_PKG_VERSION").into(),
            scenario: ScenarioId {
                name: scenario.name.clone(),
                sha256: scenario.sha256.clone(),
            },
            seed: spec.seed,
            runs: spec.runs,
            strategies: spec.strategies.iter().map(|s| s.name().into()).collect(),
            baseline: spec.baseline.map(|b| b.name().into()),
            segment: scenario.study_segment,
            shard: spec.shard.map(|s| {
                let r = s.range(spec.runs);
                ShardInfo {
                    index: s.index,
                    count: s.count,
                    first_run: r.start,
                    end_run: r.end,
                }
            }),
            state: State::Running,
            chunk_runs: Some(spec.chunk_runs),
            chunks: Vec::new(),
            files: Default::default(),
        }
    }

    /// Reads `dir/manifest.json` (`None` if absent).
    ///
    /// # Errors
    /// It exists but cannot be read or is not a sweep manifest.
    pub fn read(dir: &Path) -> Result<Option<Self>, SweepError> {
        use maps::input_file::{Follow, InputFileError, read_input};
        let path = dir.join(MANIFEST);
        let bytes = match read_input(&path, MAX_MANIFEST_BYTES, Follow::No) {
            Ok(bytes) => bytes,
            Err(InputFileError::Io { error }) if error.kind() == std::io::ErrorKind::NotFound => {
                return Ok(None);
            }
            Err(e) => {
                return Err(SweepError::Io {
                    path,
                    what: "cannot read the sweep manifest".into(),
                    message: e.to_string(),
                });
            }
        };
        let text = String::from_utf8(bytes).map_err(|e| {
            SweepError::format(
                &path,
                "(file)",
                "a solsim sweep manifest (UTF-8 JSON)",
                format!("an invalid byte at offset {}", e.utf8_error().valid_up_to()),
            )
        })?;
        let m: Manifest = serde_json::from_str(&text).map_err(|e| {
            SweepError::format(
                &path,
                "(file)",
                "a solsim sweep manifest",
                // A misspelt key names the closest known one before the list, kept whole.
                maps::names::unknown_name_message(&e.to_string(), 120)
                    .unwrap_or_else(|| maps::input_file::excerpt(&e.to_string(), 200)),
            )
        })?;
        if m.format != FORMAT {
            return Err(SweepError::format(
                &path,
                "format",
                format!("{FORMAT:?}"),
                maps::input_file::excerpt(&format!("{:?}", m.format), 120),
            ));
        }
        m.check_shape(&path)?;
        Ok(Some(m))
    }

    /// Writes `dir/manifest.json` durably (aside, `fsync`, rename).
    ///
    /// # Errors
    /// A write error.
    pub fn write(&self, dir: &Path) -> Result<(), SweepError> {
        let mut text = serde_json::to_string_pretty(self)
            .map_err(|e| SweepError::io(&dir.join(MANIFEST), "cannot serialise", e))?;
        text.push('\n');
        parquet_io::write_durably(&dir.join(MANIFEST), text.as_bytes())
    }

    /// The run indices this manifest's directory holds: its shard's, or `0..runs`.
    #[must_use]
    pub fn run_range(&self) -> std::ops::Range<u64> {
        self.shard.map_or(0..self.runs, |s| s.first_run..s.end_run)
    }

    /// Checks that the manifest is one a sweep could have written, before anything in the
    /// directory is trusted because it lists it: a shard's range is the one its index and count
    /// give; while running, the chunk size is positive and every listed chunk is one cell of the
    /// grid that size lays over the run range, each listed once (so the chunks, with the ones
    /// still to run, tile the range exactly once); once complete, it lists the three output
    /// files and no chunks. `path` is named in the error.
    ///
    /// # Errors
    /// [`SweepError::Format`] naming the first field that breaks a rule.
    pub fn check_shape(&self, path: &Path) -> Result<(), SweepError> {
        let bad = |field: String, expected: String, got: String| {
            Err(SweepError::format(path, field, expected, got))
        };
        if self.runs == 0 || self.runs > crate::spec::MAX_RUNS {
            return bad(
                "runs".into(),
                format!("a number of runs from 1 to {}", crate::spec::MAX_RUNS),
                self.runs.to_string(),
            );
        }
        let mut seen = Vec::new();
        for (i, name) in self.strategies.iter().enumerate() {
            if sim::Strategy::from_name(name).is_none() || seen.contains(&name) {
                return bad(
                    format!("strategies[{i}]"),
                    format!(
                        "one of {}, each once",
                        sim::Strategy::ALL.map(sim::Strategy::name).join(", ")
                    ),
                    maps::input_file::excerpt(&format!("{name:?}"), 120),
                );
            }
            seen.push(name);
        }
        if self.strategies.is_empty() {
            return bad(
                "strategies".into(),
                "at least one strategy".into(),
                "none".into(),
            );
        }
        if let Some(s) = self.shard {
            let want = (s.count > 0 && s.index < s.count && s.count <= self.runs).then(|| {
                crate::spec::Shard {
                    index: s.index,
                    count: s.count,
                }
                .range(self.runs)
            });
            if want != Some(s.first_run..s.end_run) {
                return bad(
                    "shard".into(),
                    want.map_or_else(
                        || format!("index < count <= runs ({})", self.runs),
                        |r| {
                            format!(
                                "runs {}..{} for shard {}/{}",
                                r.start, r.end, s.index, s.count
                            )
                        },
                    ),
                    format!(
                        "runs {}..{} for shard {}/{}",
                        s.first_run, s.end_run, s.index, s.count
                    ),
                );
            }
        }
        let range = self.run_range();
        match self.state {
            State::Running => {
                let Some(size) = self.chunk_runs.filter(|&c| c > 0) else {
                    return bad(
                        "chunk_runs".into(),
                        "a positive number while the sweep runs".into(),
                        format!("{:?}", self.chunk_runs),
                    );
                };
                if !self.files.is_empty() {
                    return bad(
                        "files".into(),
                        "no output files while the sweep runs".into(),
                        format!("{} files", self.files.len()),
                    );
                }
                let mut after = None;
                for (i, c) in self.chunks.iter().enumerate() {
                    let on_grid = c.first_run >= range.start
                        && c.first_run < range.end
                        && (c.first_run - range.start).is_multiple_of(size)
                        && c.end_run == c.first_run.saturating_add(size).min(range.end);
                    if !on_grid {
                        return bad(
                            format!("chunks[{i}]"),
                            format!(
                                "a chunk of {size} runs starting at run {} + a multiple of {size}, within runs {}..{}",
                                range.start, range.start, range.end
                            ),
                            format!("runs {}..{}", c.first_run, c.end_run),
                        );
                    }
                    if after.is_some_and(|a| c.first_run <= a) {
                        return bad(
                            format!("chunks[{i}]"),
                            "chunks listed once each, in run order".into(),
                            format!("runs {}..{} again or out of order", c.first_run, c.end_run),
                        );
                    }
                    after = Some(c.first_run);
                }
            }
            State::Complete => {
                let names: Vec<&str> = self.files.keys().map(String::as_str).collect();
                if names != ["runs.parquet", "sols.parquet", "summary.json"] {
                    return bad(
                        "files".into(),
                        "runs.parquet, sols.parquet and summary.json once complete".into(),
                        maps::input_file::excerpt(&names.join(", "), 120),
                    );
                }
                if self.chunk_runs.is_some() || !self.chunks.is_empty() {
                    return bad(
                        "chunks".into(),
                        "no chunks once complete".into(),
                        format!("{} chunks", self.chunks.len()),
                    );
                }
            }
        }
        Ok(())
    }

    /// The first field in which `other` describes a different sweep than `self` (ignoring the
    /// state and what was committed): `(field, self's value, other's value)`.
    #[must_use]
    pub fn differs_from(&self, other: &Manifest) -> Option<(&'static str, String, String)> {
        let pairs: [(&'static str, String, String); 8] = [
            (
                "scenario.name",
                self.scenario.name.clone(),
                other.scenario.name.clone(),
            ),
            (
                "scenario.sha256",
                self.scenario.sha256.clone(),
                other.scenario.sha256.clone(),
            ),
            ("seed", self.seed.to_string(), other.seed.to_string()),
            ("runs", self.runs.to_string(), other.runs.to_string()),
            (
                "strategies",
                self.strategies.join(","),
                other.strategies.join(","),
            ),
            (
                "baseline",
                format!("{:?}", self.baseline),
                format!("{:?}", other.baseline),
            ),
            (
                "segment",
                format!("{:?}", self.segment),
                format!("{:?}", other.segment),
            ),
            (
                "solsim_version",
                self.solsim_version.clone(),
                other.solsim_version.clone(),
            ),
        ];
        pairs
            .into_iter()
            .find(|(_, a, b)| a != b)
            .map(|(field, a, b)| {
                let quote = |v: String| maps::input_file::excerpt(&v, 120);
                (field, quote(a), quote(b))
            })
    }
}
