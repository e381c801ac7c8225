//! `report.html`: one self-contained page an operator opens in a browser — the figures as
//! inline SVG, the tables as HTML, no script, no stylesheet or font from the network.
//!
//! - [`run_report()`]: one seeded run per strategy (what `solsim compare` prints and writes):
//!   the scenario, the compare table and its verdict against `ground`, the statistics over
//!   runs when there are any, the figures of [`crate::figures::run_figures()`], and each strategy's sol log.
//! - [`sweep_report()`]: a sweep directory: the rates with their intervals, the spreads, the
//!   paired differences from the baseline, the CDF of sols and the rates figure.
//!
//! The modules: [`markup`] (escaping, the page, tables), [`mod@run_report`] and its
//! [`run_tables`], [`mod@sweep_report`], and the [`statistics`] tables both show.

pub mod markup;
pub mod run_report;
pub mod run_tables;
pub mod statistics;
pub mod sweep_report;

pub use markup::escape;
pub use run_report::run_report;
pub use sweep_report::{sweep_report, sweep_title};
