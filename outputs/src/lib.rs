//! # outputs — everything solsim writes and prints about a run
//!
//! The `solsim` binary parses arguments, shows progress and picks exit codes; what it writes
//! and prints comes from here, so a program can produce the same files without it (see
//! `examples/compare_out.rs`: the directory `solsim compare SCENARIO --out DIR --report`
//! writes, from the libraries alone). Nothing here prints or exits; every failure is an error
//! type of its module.
//!
//! The compare pipeline:
//! - [`compare`]: run a loaded scenario's strategies (and the statistics over runs), then
//!   write the output directory ([`compare::Comparison::write`]) or print it.
//!
//! Files:
//! - [`output_set`]: output directories replaced whole ([`output_set::OutputSet`]), never a
//!   mix of two runs.
//! - [`run_files`]: a run's JSON with provenance, its per-sol CSV, atomic single files.
//! - [`gis`]: the GIS layers of a run (route, zones, paths, sol-end ellipses, faults, zones at
//!   each fault) in Mars longitude/latitude and in the map's projected CRS.
//! - [`figures`]: the SVG figures (uncertainty and metres per sol, route maps and passages,
//!   sol-plan Gantt charts, a sweep's CDF and rates, the slip profile).
//! - [`html`]: `report.html`, one self-contained page for a compare run or a sweep;
//!   [`report_dir`] writes it afterwards for a directory, after checking the directory is
//!   what the scenario gives ([`report_dir_error`]).
//!
//! What is printed:
//! - [`tables`]: the sol-by-sol table of a run and the compare table.
//! - [`verdict`]: the one-line verdict against ground; [`against_ground`]: each strategy
//!   against ground on the same seed.
//! - [`over_runs`]: `compare --runs N`, each strategy against ground over N seeded runs with
//!   intervals, and its JSON.
//! - [`sweep_text`]: `solsim sweep`'s table, the merge line and their `--json`;
//!   [`slurm_script`]: the Slurm submit script of `sweep slurm`.
//! - [`plan_report`]: one sol planned from a campaign file (`solsim plan`); [`plan_table`]:
//!   its table and JSON.
//! - [`regress`]: every scenario's `[[expect]]` entries checked (by [`sweep::expect`]), as
//!   text, JSON and JUnit XML.
//!
//! ```
//! use outputs::compare::compare;
//!
//! // Sols 383-386 (paper 000 §2): the replay faults NO_PATH on sol 385.
//! let scenario = study::Scenario::load("../scenarios/sol383-386.toml".as_ref())?;
//! let comparison = compare(&scenario, None, &|_, _| {});
//! let text = comparison.text();
//! assert!(text.starts_with("sol383-386 — "));
//! assert!(text.contains("Verdict against ground"));
//! # Ok::<(), study::ScenarioError>(())
//! ```
#![warn(missing_docs)]

pub mod against_ground;
pub mod compare;
pub mod figures;
pub mod gis;
pub mod html;
pub mod output_set;
pub mod over_runs;
pub mod plan_report;
pub mod plan_table;
pub mod regress;
pub mod report_dir;
pub mod report_dir_error;
pub mod run_files;
pub mod slurm_script;
pub mod sweep_text;
pub mod tables;
pub mod verdict;

pub use output_set::{OutputSet, OutputSetError};
