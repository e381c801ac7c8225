//! # sim — the sol-by-sol traverse simulator
//!
//! One sol flows: the [`operations::calendar`] says what the uplink knows → the strategy's
//! [`operations::policy`] decides whether the rover drives and how it is localized → the sol's
//! activity plan ([`operations::sol_plan`]) runs step by step: [`rover::autonav`] drives the
//! route on the [`grid::PlanningGrid`] (zones grown by the [`rover::uncertainty`] disc, slope
//! hazards), faulting with `NO_PATH` when no path is left; the onboard [`localizers`] fix the
//! position after the drive → a [`run::outcome::SolRecord`] → next sol. A [`run::Simulation`]
//! steps it a sol at a time (`finish` runs it to the end).
//!
//! The folders, by domain:
//!
//! - [`grid`]: the planning grid and the grid algorithms (exact EDT, A*, bottleneck path).
//! - [`rover`]: AutoNav, the true pose and the estimate, the uncertainty disc, the errors it
//!   must bound, the rover in rapier and the slip profiles it measures.
//! - [`operations`]: the calendar (typed in or computed from Mars time), the five strategies and
//!   their policy, each drive sol's activity plan, onboard science campaigns.
//! - [`localizers`]: the [`localizers::Localizer`] trait and the built-in localizers
//!   (statistical, image matching, particle filter, EKF), one file each.
//! - [`run`]: the [`run::Simulation`], one drive sol executed, the route's passage
//!   clearances, what a run reports.
//! - [`time`]: sols and LMST ([`time::SolSeconds`]), Mars time from UTC, Earth calendars.
//! - [`settings`]: [`Settings`], everything a run needs but its seeds, and its checks.
//! - [`seeds`]: [`seeds::RunSeeds`], every random stream of a run from (scenario seed, run).
//!
//! ```
//! use sim::rover::uncertainty::{UncertaintyModel, UncertaintyState};
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

pub mod grid;
pub mod localizers;
pub mod operations;
pub mod rover;
pub mod run;
pub mod seeds;
pub mod settings;
pub mod time;

pub use grid::PlanningGrid;
pub use operations::{Calendar, SolEntry, Strategy};
pub use rover::{RoverSettings, UncertaintyModel};
pub use run::Simulation;
pub use run::outcome::{CampaignOutcome, DriveEnd, Fault, FaultKind, SolRecord, Totals};
pub use settings::{FieldError, PhysicalRange, Settings, SettingsError};
