//! Monte Carlo studies over run indices: every run's seeds come from [`sim::seeds`], every
//! strategy of one run sees the same world (common random numbers), and the results land in
//! Parquet files with the statistics a study reports.

pub mod engine;
pub mod error;
pub mod lock;
pub mod manifest;
pub mod parquet_io;
pub mod rows;
pub mod stats;
pub mod summary;

pub use engine::{Shard, SweepResult, SweepSpec, merge, run};
pub use error::SweepError;
pub mod expect;
