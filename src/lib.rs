//! # solsim — the command-line simulator's library half
//!
//! The binary (`src/main.rs`) is a thin clap front end over these modules, so integration tests
//! and benchmarks drive exactly what users run.
//!
//! - [`scenario`]: scenario files (TOML) → a validated [`scenario::Scenario`].
//! - [`expect`]: expected outcomes in scenario files; [`regress`] runs them.
//! - [`report`]: JSON, per-sol CSV, GeoJSON outputs and terminal tables.
//! - [`error`]: [`error::ScenarioError`], one line naming file, field and what was expected.
#![warn(missing_docs)]

pub mod cmd_localize;
pub mod cmd_localize_rasters;
pub mod cmd_map;
pub mod cmd_package;
pub mod cmd_plan;
pub mod cmd_zones;
pub mod error;
pub mod expect;
pub mod regress;
pub mod report;
pub mod scenario;
