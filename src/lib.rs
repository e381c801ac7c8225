//! # solsim — the command-line simulator's library half
//!
//! The binary (`src/main.rs`) is a thin clap front end over these modules, so integration tests
//! and benchmarks drive exactly what users run.
//!
//! The file formats, their validation and the study API live in the [`study`] crate; these
//! modules are the commands: argument structs, orchestration and printing.
//!
//! - [`cmd_sweep`]: Monte Carlo sweeps, their printed statistics, shard merges and Slurm
//!   submit scripts (the engine is the [`sweep`] crate).
//! - [`regress`]: runs every scenario's `[[expect]]` entries; text and JUnit reports.
//! - [`report`]: JSON, per-sol CSV, GeoJSON outputs and terminal tables.
//! - [`report_gis`]: the GIS layers of a run (route, zones, paths, sol-end ellipses, faults,
//!   zones at each fault) in Mars longitude/latitude and in the map's projected CRS.
//! - [`report_runs`]: `compare --runs N`, each strategy against ground over N seeded runs with
//!   intervals (the statistics of the [`sweep`] crate).
//! - [`cmd_init`], [`cmd_route`], [`track_file`]: starter scenarios, from a bundled example
//!   or from your own track in Mars longitude/latitude (GeoJSON or CSV).
//! - [`output_set`]: output directories replaced whole ([`output_set::OutputSet`]), never a
//!   mix of two runs.
#![warn(missing_docs)]

pub mod cmd_calibrate;
pub mod cmd_init;
pub mod cmd_localize;
pub mod cmd_localize_rasters;
pub mod cmd_map;
pub mod cmd_package;
pub mod cmd_plan;
pub mod cmd_record;
pub mod cmd_report;
pub mod cmd_route;
pub mod cmd_slip_profile;
pub mod cmd_sweep;
pub mod cmd_validate;
pub mod cmd_whatif;
pub mod cmd_zones;
pub mod figures;
pub mod localizer_comparison;
pub mod output_set;
pub mod progress;
pub mod regress;
pub mod report;
pub mod report_gis;
pub mod report_html;
pub mod report_runs;
pub mod track_file;
