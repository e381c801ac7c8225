//! # study — solsim's library core
//!
//! Everything solsim reads from disk and everything a study does with it, without the
//! command line: the binary (`solsim`) adds only clap, printing and exit codes.
//!
//! - [`scenario`]: scenario files (TOML) → a validated [`Scenario`], loaded once; its maps,
//!   zones and planning grid are shared ([`std::sync::Arc`]) by every run.
//!   [`Scenario::run`] and [`Scenario::compare`] run strategies under any seed. One loader per
//!   section of the file; the simulator's settings structs check their own fields.
//! - [`ranges`]: the physical ranges of what a study file holds beyond the simulator's
//!   settings (the map's placement, coordinates, the study segment, campaign-file drives).
//! - [`calibrate`]: calibrated constants re-derived from a scenario's historic record.
//! - [`expect`]: the `[[expect]]` entries of a scenario ([`Expectation`]) and their validation
//!   (`sweep::expect` checks them).
//! - [`metric`]: the run metrics a sweep or a comparison reports ([`metric::Metric`]).
//! - [`campaign_file`]: the one-sol campaign files of `solsim plan` ([`CampaignFile`]).
//! - [`recipe`]: procedural map recipes of `solsim map generate`; [`generated_map`]: what the
//!   command says of a map made from one.
//! - [`record`], [`record_import`]: the public record of the drives and replay scenarios from
//!   it; [`record_output`]: an import's passages, report and summary; [`baseline`]: `ground`
//!   beside the record.
//! - [`map_package`]: the onboard map package of a scenario's route, under its seeds.
//! - [`localizer_comparison`]: every onboard localizer on the same benchmark cases, side by side
//!   (`solsim localize-bench`).
//! - [`slip_profile`]: the provenance and table of a measured slip profile.
//! - [`starter`]: starter scenarios around a route in Mars longitude/latitude (`solsim init`,
//!   `solsim route import`): the commented scenario, its zones and the map's recipe.
//! - [`starter_output`]: where a starter scenario is written, the checks before, the summary
//!   after.
//! - [`track_file`]: tracks in Mars longitude/latitude (GeoJSON or CSV) for `solsim route
//!   import`.
//! - [`point_files`]: the points CSV of `solsim zones check`, and the CSV dialect and errors of
//!   both kinds of point file.
//! - [`schema`]: JSON Schemas of the scenario and campaign file formats.
//! - [`sanity`]: a scenario that is well formed field by field but nonsense as a whole (a
//!   route in degrees, a waypoint in a keep-out, a leg closed at r = 0), as errors and warnings.
//! - [`validation`]: what `solsim validate` reports of a scenario: findings, what was loaded,
//!   each leg's passage clearance.
//! - [`error`]: [`ScenarioError`], one line naming the file, the field and what was expected.
//! - [`input`]: reading a TOML input (a regular file, a size cap) and the memory budget.
//!
//! ```
//! use sim::Strategy;
//! use study::Scenario;
//!
//! // Sols 383-386 from the public record (paper 000 §2): the historic plan faults NO_PATH on
//! // sol 385; onboard localization after every drive keeps the passage open.
//! let scenario = Scenario::load("../scenarios/sol383-386.toml".as_ref())?;
//! for run in 0..2 {
//!     // Run 0 is the scenario's own seed; each run index is another world and other draws.
//!     let replay = scenario.run_index(Strategy::Replay, run);
//!     assert_eq!(replay.sols.len(), 4);
//!     assert!(replay.totals.no_path_faults >= 1);
//!     assert_eq!(scenario.run_index(Strategy::Onboard, run).totals.no_path_faults, 0);
//! }
//! # Ok::<(), study::ScenarioError>(())
//! ```
//!
//! Hostile input is an error naming the file and the field, before anything large is
//! allocated:
//!
//! ```
//! use std::path::Path;
//! use study::scenario::ScenarioSpec;
//!
//! let text = std::fs::read_to_string("../scenarios/crater-floor-passage.toml")?;
//! let text = text.replace("k_vo = 0.05", "k_vo = 1e300");
//! let e = ScenarioSpec::from_toml_str(Path::new("x.toml"), &text).unwrap_err();
//! assert_eq!(
//!     e.to_string(),
//!     "x.toml: uncertainty.k_vo: expected 0 ..= 1 metres per metre, got 1e300"
//! );
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod baseline;
pub mod calibrate;
pub mod campaign_file;
mod check;
pub mod error;
pub mod expect;
pub mod generated_map;
pub mod input;
pub mod localizer_comparison;
pub mod map_package;
pub mod metric;
mod pair;
pub mod point_files;
pub mod ranges;
pub mod recipe;
pub mod record;
pub mod record_import;
pub mod record_output;
pub mod sanity;
pub mod scenario;
pub mod schema;
pub mod slip_profile;
pub mod starter;
pub mod starter_output;
pub mod track_file;
pub mod validation;

pub use campaign_file::{CampaignFile, PlanFileError};
pub use error::ScenarioError;
pub use expect::{Expectation, StatisticalExpectation};
pub use scenario::Scenario;
