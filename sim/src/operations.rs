//! Mission operations: the calendar, the strategies and what they decide, each drive sol's
//! activity plan, and the science campaigns planned onboard.
//!
//! - [`calendar`]: which sols get a plan, which are restricted, when data reaches Earth;
//!   [`ops_calendar`]: that calendar computed from Mars time and the team's working rules.
//! - [`strategy`]: the five strategies; [`policy`]: what each decides (which sols drive, when a
//!   drive is cut, when the rover localizes), in one place.
//! - [`sol_plan`]: each drive sol's activity plan from the `planner` crate, executed step by step
//!   with repairs and replans.
//! - [`science`]: campaign intents that outlive a sol and the candidates they offer each sol.

pub mod calendar;
pub mod ops_calendar;
pub mod policy;
pub mod science;
pub mod sol_plan;
pub mod strategy;

pub use calendar::{Calendar, SolEntry};
pub use strategy::Strategy;
