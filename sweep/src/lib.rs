//! Monte Carlo studies over run indices: every run's seeds come from [`sim::seeds`], every
//! strategy of one run sees the same world (common random numbers), and the results land in
//! Parquet files with the statistics a study reports.
//!
//! - [`engine`]: the sweep itself (seeded, parallel, resumable, sharded) and its [`Summary`](engine::Summary).
//! - [`expect`]: checking a scenario's `[[expect]]` entries, of one run and over runs.
//! - [`manifest`], [`parquet_io`], [`rows`], [`lock`]: the sweep directory's files.
//! - [`stats`], [`summary`]: Wilson intervals, the paired bootstrap, the statistics reported.
//! - [`whatif`]: one strategy's runs on two versions of a scenario that differ in a setting
//!   ([`setting_diff`] names the settings), paired run by run.

mod assemble;
mod complete;
pub mod engine;
pub mod error;
pub mod expect;
pub mod lock;
pub mod manifest;
mod merge;
pub mod parquet_io;
pub mod rows;
pub mod setting_diff;
mod simulate;
mod spec;
pub mod stats;
pub mod summary;
pub mod whatif;

pub use engine::{Shard, SweepResult, SweepSpec, run};
pub use error::SweepError;
pub use merge::merge;
