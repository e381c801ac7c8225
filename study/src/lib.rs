//! # study — solsim's library core
//!
//! Everything solsim reads from disk and everything a study does with it, without the
//! command line: the binary (`solsim`) adds only clap, printing and exit codes.
//!
//! - [`scenario`]: scenario files (TOML) → a validated [`Scenario`], loaded once; its maps,
//!   zones and planning grid are shared ([`std::sync::Arc`]) by every run.
//!   [`Scenario::run`] and [`Scenario::compare`] run strategies under any seed.
//! - [`expect`]: the `[[expect]]` entries of a scenario ([`Expectation`]) and their checks.
//! - [`science`]: a scenario's `[science]` section (targets and campaign intents).
//! - [`campaign_file`]: the one-sol campaign files of `solsim plan` ([`CampaignFile`]).
//! - [`recipe`]: procedural map recipes of `solsim map generate`.
//! - [`error`]: [`ScenarioError`], one line naming the file, the field and what was expected.
//! - [`input`]: reading a TOML input (a regular file, a size cap) and the memory budget.
//!
//! ```no_run
//! use study::Scenario;
//! use sim::Strategy;
//!
//! let scenario = Scenario::load("scenarios/sol383-386.toml".as_ref())?;
//! for seed in 0..10 {
//!     let outcome = scenario.run(Strategy::Onboard, seed);
//!     println!("seed {seed}: {} NO_PATH faults", outcome.totals.no_path_faults);
//! }
//! # Ok::<(), study::ScenarioError>(())
//! ```
#![warn(missing_docs)]

pub mod campaign_file;
mod check;
pub mod error;
pub mod expect;
pub mod input;
pub mod recipe;
pub mod scenario;
pub mod science;

pub use campaign_file::{CampaignFile, PlanFileError};
pub use error::ScenarioError;
pub use expect::Expectation;
pub use scenario::Scenario;
