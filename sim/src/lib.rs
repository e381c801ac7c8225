//! # sim — the sol-by-sol traverse simulator
//!
//! One sol flows: the [`calendar`] says what the uplink knows → the [`strategy`] decides whether
//! the rover drives and how it is localized → [`autonav`] drives the route in steps on the
//! [`planning_grid`] (zones grown by the [`uncertainty`] disc, slope hazards), faulting with
//! `NO_PATH` when no path is left → end-of-sol localization ([`localizer`]) → a [`SolRecord`] in
//! the [`outcome`] → next sol. [`campaign::run_campaign`] runs all of it.
//!
//! - [`uncertainty`]: `r = margin + k_vo·d_vo + k_novo·d_novo` and its reset events.
//! - [`pose`]: the true pose and the rover's estimate, kept in different types.
//! - [`planning_grid`]: per-cell clearance to the zones, slope hazards, terrain class.
//! - [`edt`], [`astar`], [`widest_path`]: the grid algorithms (exact EDT, A*, bottleneck path).
//! - [`autonav`]: one sol's drive: plan, step, VO, slip, faults.
//! - [`errors`]: what the estimate does not know (heading, VO scale and failures, slip, ground
//!   localization), calibrated and stress presets.
//! - [`localizer`]: the statistical onboard localizer (0.36 m mean / 0.93 m p99, paper 000 §4).
//! - [`calendar`], [`strategy`]: operations calendar, data availability and the five strategies;
//!   [`policy`]: what each strategy decides (which sols drive, when a drive is cut, when the
//!   rover localizes), in one place.
//! - [`sol_plan`]: each drive sol's activity plan (heating, drive, imaging, passes, science, the
//!   onboard localization chain) from the `planner` crate, executed step by step with repairs
//!   and replans ([`sol_plan::SolExecution`]), every plan validated.
//! - [`science`]: campaign intents that outlive a sol (goal-set targets on the map, periodic,
//!   state-based) and the candidates they offer each sol.
//! - [`campaign`]: the multi-sol runner; [`outcome`]: what it reports; [`campaign_error`]:
//!   [`Campaign::validate`] for campaigns built in code.
//! - [`physics`]: the rover in rapier on terramechanics soils; [`slip_profile`]: the
//!   slip-versus-slope tables it measures, which the traverse reads.
//! - [`seeds`]: the one derivation of every random stream from (scenario seed, purpose, run).
//!
//! ```
//! use sim::uncertainty::{UncertaintyModel, UncertaintyState};
//!
//! // Paper 000 Fig. 2: 655.8 m over sols 717-719, 0.289 m of it without VO.
//! let model = UncertaintyModel::default(); // 5 % with VO, 50 % without
//! let mut disc = UncertaintyState::default();
//! disc.drive(655.8, 0.289 / 655.8);
//! assert!((disc.radius_m(&model) - 32.92).abs() < 1e-3);
//! disc.reset_onboard(0.93, 1.0); // localizer σ + operator margin
//! assert!((disc.radius_m(&model) - 1.93).abs() < 1e-12);
//! ```
#![warn(missing_docs)]

pub mod astar;
pub mod autonav;
pub mod calendar;
pub mod campaign;
pub mod campaign_error;
pub mod earth_time;
pub mod edt;
pub mod errors;
mod filter_localization;
pub mod localizer;
pub mod mars_time;
pub mod ops_calendar;
pub mod outcome;
pub mod physics;
pub mod planning_grid;
pub mod policy;
pub mod pose;
pub mod science;
pub mod seeds;
pub mod slip_profile;
pub mod sol_plan;
mod sol_run;
pub mod strategy;
pub mod time;
pub mod uncertainty;
pub mod widest_path;

pub use autonav::RoverParams;
pub use calendar::{Calendar, SolEntry};
pub use campaign::{Campaign, run_campaign};
pub use campaign_error::CampaignError;
pub use outcome::{CampaignOutcome, DriveEnd, Fault, FaultKind, SolRecord, Totals};
pub use planning_grid::PlanningGrid;
pub use strategy::Strategy;
pub use uncertainty::UncertaintyModel;
