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

use crate::error::SweepError;
use crate::parquet_io;

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

/// The study segment a sweep reports (`[study_segment]` of the scenario).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SegmentInfo {
    /// First sol counted.
    pub from_sol: u32,
    /// Metres to cover.
    pub distance_m: f64,
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
    /// The sweep's seed (run `i` runs under `sim::seeds::run_seed(seed, i)`).
    pub seed: u64,
    /// Run indices `0..runs` of the whole sweep.
    pub runs: u64,
    /// The strategies, in order.
    pub strategies: Vec<String>,
    /// The strategy paired differences are taken against.
    pub baseline: Option<String>,
    /// The study segment, if the scenario has one.
    pub segment: Option<SegmentInfo>,
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

/// SHA-256 of a file, hex.
///
/// # Errors
/// The file cannot be read.
pub fn sha256_file(path: &Path) -> Result<String, SweepError> {
    let bytes = std::fs::read(path).map_err(|e| SweepError::Io {
        path: path.to_path_buf(),
        what: "cannot read".into(),
        message: e.to_string(),
    })?;
    Ok(study::input::sha256_hex(&bytes))
}

/// Manifests larger than this are not sweep manifests (a chunk entry is ~200 bytes).
const MAX_MANIFEST_BYTES: u64 = 64 << 20;

impl Manifest {
    /// Reads `dir/manifest.json` (`None` if absent).
    ///
    /// # Errors
    /// It exists but cannot be read or is not a sweep manifest.
    pub fn read(dir: &Path) -> Result<Option<Self>, SweepError> {
        let path = dir.join(MANIFEST);
        if !path.exists() {
            return Ok(None);
        }
        let text =
            maps::input_file::read_text_file_capped(&path, MAX_MANIFEST_BYTES).map_err(|e| {
                SweepError::Io {
                    path: path.clone(),
                    what: "cannot read the sweep manifest".into(),
                    message: e.to_string(),
                }
            })?;
        let m: Manifest = serde_json::from_str(&text).map_err(|e| {
            SweepError::format(&path, "(file)", "a solsim sweep manifest", e.to_string())
        })?;
        if m.format != FORMAT {
            return Err(SweepError::format(
                &path,
                "format",
                format!("{FORMAT:?}"),
                format!("{:?}", m.format),
            ));
        }
        Ok(Some(m))
    }

    /// Writes `dir/manifest.json` durably (aside, `fsync`, rename).
    ///
    /// # Errors
    /// A write error.
    pub fn write(&self, dir: &Path) -> Result<(), SweepError> {
        let mut text = serde_json::to_string_pretty(self).map_err(|e| SweepError::Io {
            path: dir.join(MANIFEST),
            what: "cannot serialise".into(),
            message: e.to_string(),
        })?;
        text.push('\n');
        parquet_io::write_durably(&dir.join(MANIFEST), text.as_bytes())
    }

    /// The first field in which `other` describes a different sweep than `self` (ignoring the
    /// state and what was committed): `(field, self's value, other's value)`.
    #[must_use]
    pub fn differs_from(&self, other: &Manifest) -> Option<(&'static str, String, String)> {
        let pairs: [(&'static str, String, String); 7] = [
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
        pairs.into_iter().find(|(_, a, b)| a != b)
    }
}
