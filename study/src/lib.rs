//! # study — solsim's library core
//!
//! Everything solsim reads from disk and everything a study does with it, without the
//! command line: the binary (`solsim`) adds only clap, printing and exit codes.
//!
//! - [`scenario`]: scenario files (TOML) → a validated [`Scenario`], loaded once; its maps,
//!   zones and planning grid are shared ([`std::sync::Arc`]) by every run.
//!   [`Scenario::run`] and [`Scenario::compare`] run strategies under any seed.
//! - [`calibrate`]: calibrated constants re-derived from a scenario's historic record.
//! - [`expect`]: the `[[expect]]` entries of a scenario ([`Expectation`]) and their checks.
//! - [`science`]: a scenario's `[science]` section (targets and campaign intents).
//! - [`campaign_file`]: the one-sol campaign files of `solsim plan` ([`CampaignFile`]).
//! - [`recipe`]: procedural map recipes of `solsim map generate`.
//! - [`starter`]: starter scenarios around a route in Mars longitude/latitude (`solsim init`,
//!   `solsim route import`): the commented scenario, its zones and the map's recipe.
//! - [`schema`]: JSON Schemas of the scenario and campaign file formats.
//! - [`sanity`]: a scenario that is well formed field by field but nonsense as a whole (a
//!   route in degrees, a waypoint in a keep-out, a leg closed at r = 0), as errors and warnings.
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
pub mod figure;
pub mod input;
pub mod recipe;
pub mod record;
pub mod record_import;
pub mod sanity;
pub mod scenario;
pub mod schema;
pub mod science;
pub mod starter;

pub use campaign_file::{CampaignFile, PlanFileError};
pub use error::ScenarioError;
pub use expect::{Expectation, StatisticalExpectation};
pub use scenario::Scenario;
