//! [`Settings`]: everything a run of the simulator needs but its seeds, and what makes a
//! hand-built one unusable ([`Settings::validate`], [`SettingsError`]).
//!
//! Each settings struct checks its own fields, next to them, against ranges defined there
//! ([`RoverSettings::validate`], [`Calendar::validate`], …), and says which field is at fault
//! with a [`FieldError`]; [`Settings::validate`] runs them all. The `study` crate's loader runs
//! the same checks on what it read and names the file and the TOML field instead. So a library
//! user who builds `Settings` in code gets the same guarantees as a scenario file: the runner
//! never meets a route off its grid, a calendar with gaps, a drive window that ends before it
//! starts or a NaN rate.
//!
//! A run's seeds are not settings: they come from (scenario seed, run index), once, as
//! [`crate::seeds::RunSeeds`], and go to [`crate::run::Simulation::new`] beside the settings.

use std::sync::Arc;

use crate::grid::PlanningGrid;
use crate::localizers::OnboardLocalizer;
use crate::operations::calendar::Calendar;
use crate::operations::policy::OperationsRules;
use crate::operations::science::Science;
use crate::operations::sol_plan::SolPlanSettings;
use crate::rover::autonav::RoverSettings;
use crate::rover::uncertainty::UncertaintyModel;
pub use field_error::FieldError;
use physical_range::MARGIN_M;
pub use physical_range::PhysicalRange;

pub mod field_error;
pub mod physical_range;

/// Everything a run needs but its seeds (resolved from a scenario file by `study`), shared by
/// every strategy and run of a scenario.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Route waypoints, map metres; waypoint 0 is the start.
    pub route: Vec<[f64; 2]>,
    /// Operations calendar.
    pub calendar: Calendar,
    /// Rover and AutoNav settings.
    pub rover: RoverSettings,
    /// Uncertainty growth.
    pub model: UncertaintyModel,
    /// Onboard localizer: the statistical model, image matching through the co-processor, a
    /// filter, or one of your own ([`OnboardLocalizer::Custom`]).
    pub localizer: OnboardLocalizer,
    /// Operator margin added to the localizer's σ after an onboard localization, metres.
    pub operator_margin_m: f64,
    /// The operations rules every strategy plans under: plan lengths, the optional extension
    /// cap, the planners' passage margin.
    pub rules: OperationsRules,
    /// The planning grid, shared by every run of the scenario (and every thread).
    pub grid: Arc<PlanningGrid>,
    /// Each drive sol's activity plan settings. Its `imaging_s` is the post-drive panorama's
    /// duration, also the time a ground-planned drive whose panorama must make an afternoon
    /// pass stops before it.
    pub sol_plan: SolPlanSettings,
    /// Science campaigns planned onboard each drive sol (none in most scenarios).
    pub science: Science,
}

/// Why [`Settings`] cannot be run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SettingsError {
    /// Fewer than two waypoints (a start and a goal).
    #[error("route: expected at least two waypoints (a start and a goal), got {waypoints}")]
    RouteTooShort {
        /// How many there are.
        waypoints: usize,
    },
    /// A waypoint outside the planning grid (or not finite).
    #[error("route[{index}]: expected a point on the planning grid, got [{}, {}]", position_m[0], position_m[1])]
    WaypointOffGrid {
        /// Index in the route.
        index: usize,
        /// The waypoint, map metres.
        position_m: [f64; 2],
    },
    /// A field of one of the settings outside what its struct allows, named by its path from
    /// [`Settings`]: `rover.step_m`, `calendar.sols[3].sol`, `model.k_vo`.
    #[error(transparent)]
    Field(FieldError),
    /// A planning-grid layer of the wrong length.
    #[error("grid.{layer}: expected {cells} cells (width × height), got {len}")]
    GridLayer {
        /// The layer.
        layer: &'static str,
        /// Its length.
        len: usize,
        /// Width × height.
        cells: usize,
    },
}

impl Settings {
    /// Checks that the settings can be run: grid layers of the grid's size, the route on the
    /// grid, and each settings struct by its own rules — [`Calendar::validate`],
    /// [`RoverSettings::validate`], [`UncertaintyModel::validate`],
    /// [`OnboardLocalizer::validate`], the operator margin ([`MARGIN_M`]),
    /// [`OperationsRules::validate`], [`SolPlanSettings::validate`].
    ///
    /// # Errors
    /// The first [`SettingsError`] found.
    pub fn validate(&self) -> Result<(), SettingsError> {
        let g = &self.grid;
        let cells = g.width * g.height;
        for (layer, len) in [
            ("clearance_m", g.clearance_m.len()),
            ("keep_out_clearance_m", g.keep_out_clearance_m.len()),
            ("keep_in_clearance_m", g.keep_in_clearance_m.len()),
            ("hazard", g.hazard.len()),
            ("terrain", g.terrain.len()),
        ] {
            if len != cells {
                return Err(SettingsError::GridLayer { layer, len, cells });
            }
        }
        if self.route.len() < 2 {
            return Err(SettingsError::RouteTooShort {
                waypoints: self.route.len(),
            });
        }
        for (index, &p) in self.route.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) || g.cell_of(p).is_none() {
                return Err(SettingsError::WaypointOffGrid {
                    index,
                    position_m: p,
                });
            }
        }
        let field =
            |section: &'static str| move |e: FieldError| SettingsError::Field(e.within(section));
        self.calendar.validate().map_err(field("calendar"))?;
        self.rover.validate().map_err(field("rover"))?;
        self.model.validate().map_err(field("model"))?;
        self.localizer.validate().map_err(field("localizer"))?;
        MARGIN_M
            .check("operator_margin_m", self.operator_margin_m)
            .map_err(SettingsError::Field)?;
        self.rules.validate().map_err(field("rules"))?;
        self.sol_plan.validate().map_err(field("sol_plan"))?;
        Ok(())
    }
}
