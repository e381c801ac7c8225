//! Running a strategy over a scenario, sol by sol.
//!
//! - [`simulation`]: [`Simulation`], one run stepped a sol at a time (inspect it between sols);
//!   [`Simulation::finish`] steps it to the end.
//! - `sol` (private): one drive sol executed — its plan step by step, AutoNav, the localization
//!   chain.
//! - [`legs`]: the route's passage clearances, once per scenario ([`leg_clearances`]).
//! - [`route`]: where the rover is along its route (waypoint distances, the leg it drives).
//! - [`outcome`]: what a run reports, one [`outcome::SolRecord`] per sol and the totals.

pub mod legs;
pub mod outcome;
pub mod route;
pub mod simulation;
mod sol;

pub use legs::{
    LEG_WINDOW_MARGIN_M, MAX_LEG_SEARCH_CELLS, MAX_WAYPOINTS, leg_clearances,
    leg_clearances_observed, leg_search_cells,
};
pub use simulation::Simulation;
