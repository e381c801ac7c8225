//! Checking a scenario's `[[expect]]` entries: the one place both kinds are checked.
//!
//! - [`one_run`]: entries of one seeded run per strategy ([`check_one_run`], [`check_run`]).
//! - [`over_runs`]: statistical entries (`runs = N`) over an in-memory sweep
//!   ([`check_statistical`]), with the rates' and paired differences' 95 % intervals.
//!
//! `solsim regress` (`outputs::regress`) runs both over a directory of scenarios; anyone with a
//! loaded [`study::Scenario`] can call them.
//!
//! **Why here.** The entries' types and their parsing stay in [`study::expect`], beside the
//! scenario loader that reads them, so the types live in one place. Checking the statistical
//! entries needs this crate's engine and statistics (the sweep, Wilson intervals, the paired
//! bootstrap), and `sweep` depends on `study`, not the other way: `study` cannot check them,
//! and the `outputs` crate above `sweep` would leave the sweep unable to use its own checks.
//! `sweep` is the lowest crate that can check both kinds, so it checks both.

pub mod one_run;
pub mod over_runs;

pub use one_run::{check_one_run, check_run};
pub use over_runs::{SolBounds, StatResult, check, check_statistical};
