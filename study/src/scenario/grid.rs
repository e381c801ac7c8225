//! `[grid]`: the planning grid's cell size and slope limit, with `[rover]
//! footprint_radius_m` → [`GridSettings`], checked by [`GridSettings::validate`].

use sim::grid::planning_grid::GridSettings;
use sim::rover::autonav::{RoverSettings, SlipModel};

use super::raw::{RawGrid, RawRover};
use crate::check::FieldCheck;
use crate::error::ScenarioError;

/// The file's name of a [`GridSettings`] field: its key in `[grid]`, or in `[rover]` for the
/// footprint.
fn toml_path(field: &str) -> String {
    match field {
        "footprint_radius_m" => format!("rover.{field}"),
        _ => format!("grid.{field}"),
    }
}

/// The planning grid's settings; the slip profile of `rover` needs the DEM's gradient.
///
/// # Errors
/// A [`ScenarioError`] naming the first `grid.…` (or `rover.footprint_radius_m`) field at
/// fault.
pub(crate) fn grid_settings(
    c: &FieldCheck<'_>,
    raw: &RawGrid,
    raw_rover: &RawRover,
    rover: &RoverSettings,
) -> Result<GridSettings, ScenarioError> {
    let d = GridSettings::default();
    let grid = GridSettings {
        resolution_m: raw.resolution_m.unwrap_or(d.resolution_m),
        footprint_radius_m: raw_rover.footprint_radius_m.unwrap_or(d.footprint_radius_m),
        max_slope_deg: raw.max_slope_deg.unwrap_or(d.max_slope_deg),
        gradient_layer: matches!(rover.slip_model, SlipModel::Profile(_)),
    };
    grid.validate().map_err(|e| c.setting(e, toml_path))?;
    Ok(grid)
}
