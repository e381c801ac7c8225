//! # solsim — the command-line simulator's library half
//!
//! The binary (`src/main.rs`) is a thin clap front end over these modules, so integration tests
//! and benchmarks drive exactly what users run.
//!
//! The file formats, their validation and the study API live in the [`study`] crate; every
//! output (files, figures, the HTML report, tables, regression reports, the compare pipeline)
//! in the [`outputs`] crate; these modules are the commands: argument structs, orchestration,
//! progress and printing.
//!
//! - [`cmd_compare`]: `compare`, `run` and `replay` (the pipeline is [`outputs::compare`]).
//! - [`cmd_sweep`]: Monte Carlo sweeps, shard merges and Slurm submit scripts (the engine is
//!   the [`sweep`] crate, the printed statistics and the script [`outputs`]).
//! - [`cmd_report`]: `solsim report`'s arguments ([`outputs::report_dir`] writes the page).
//! - [`cmd_plan`]: `solsim plan`'s arguments ([`outputs::plan_report`] plans).
//! - [`cmd_init`], [`cmd_route`]: starter scenarios, from a bundled example or from your own
//!   track in Mars longitude/latitude (GeoJSON or CSV; read by [`study::track_file`]).
//! - [`progress`]: progress bars on a terminal's standard error.
#![warn(missing_docs)]

pub mod cmd_calibrate;
pub mod cmd_compare;
pub mod cmd_init;
pub mod cmd_localize;
pub mod cmd_localize_rasters;
pub mod cmd_map;
pub mod cmd_package;
pub mod cmd_plan;
pub mod cmd_record;
pub mod cmd_regress;
pub mod cmd_report;
pub mod cmd_route;
pub mod cmd_slip_profile;
pub mod cmd_sweep;
pub mod cmd_validate;
pub mod cmd_whatif;
pub mod cmd_zones;
pub mod progress;
