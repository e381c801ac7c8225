//! `[rover]`: AutoNav's rate, step and tolerances, the terrain costs and the slip model →
//! [`RoverSettings`] (with the `[errors]` model), checked by [`RoverSettings::validate`]. Its
//! `footprint_radius_m` is the planning grid's (`super::grid`).

use sim::rover::autonav::{ProfileSlip, RoverSettings, SlipModel};
use sim::rover::errors::ErrorModel;

use super::errors;
use super::raw::{RawPerTerrain, RawRover};
use crate::check::FieldCheck;
use crate::error::ScenarioError;

/// The file's name of a [`RoverSettings`] field: its key in `[rover]` (the slip model's too), or
/// in `[errors]` for the error model's.
fn toml_path(field: &str) -> String {
    match field.strip_prefix("errors.") {
        Some(error) => errors::toml_path(error),
        None => format!(
            "rover.{}",
            field.strip_prefix("slip_model.").unwrap_or(field)
        ),
    }
}

/// The rover `[rover]` describes, with the error model of `[errors]`.
///
/// # Errors
/// A [`ScenarioError`] naming the first `rover.…` field at fault.
pub(crate) fn rover_settings(
    c: &FieldCheck<'_>,
    r: &RawRover,
    errors: ErrorModel,
) -> Result<RoverSettings, ScenarioError> {
    let d = RoverSettings::default();
    let rover = RoverSettings {
        drive_rate_m_per_h: r.drive_rate_m_per_h.unwrap_or(d.drive_rate_m_per_h),
        step_m: r.step_m.unwrap_or(d.step_m),
        waypoint_tolerance_m: r.waypoint_tolerance_m.unwrap_or(d.waypoint_tolerance_m),
        terrain_cost: RawPerTerrain::over(r.terrain_cost.as_ref(), d.terrain_cost),
        edge_buffer_m: r.edge_buffer_m.unwrap_or(d.edge_buffer_m),
        slip_model: slip_model(c, r, errors.slip_sigma_relative)?,
        errors,
    };
    rover.validate().map_err(|e| c.setting(e, toml_path))?;
    Ok(rover)
}

/// `[rover] slip_model` and its settings: `"terrain"` (the default) refuses the profile's
/// settings rather than ignoring them.
fn slip_model(
    c: &FieldCheck<'_>,
    r: &RawRover,
    slip_sigma_relative: f64,
) -> Result<SlipModel, ScenarioError> {
    let profile = match r.slip_model.as_deref() {
        None | Some("terrain") => false,
        Some("profile") => true,
        Some(other) => {
            return Err(c.err(
                "rover.slip_model",
                "\"terrain\" (slip per terrain class) or \"profile\" (slip by class, slope and heading from the rapier rover's profile)",
                format!("{other:?}"),
            ));
        }
    };
    if !profile {
        let stray = [
            ("rover.slip_aware_routing", r.slip_aware_routing.is_some()),
            ("rover.slip_limit", r.slip_limit.is_some()),
            ("rover.avoid_slip_above", r.avoid_slip_above.is_some()),
            ("rover.max_tilt_deg", r.max_tilt_deg.is_some()),
        ];
        if let Some(&(field, _)) = stray.iter().find(|(_, set)| *set) {
            return Err(c.err(
                field,
                "no value unless rover.slip_model = \"profile\"",
                "a value",
            ));
        }
        return Ok(SlipModel::Terrain);
    }
    let d = ProfileSlip::default();
    let slip_limit = r.slip_limit.unwrap_or(d.slip_limit);
    Ok(SlipModel::Profile(ProfileSlip {
        aware_routing: r.slip_aware_routing.unwrap_or(d.aware_routing),
        slip_limit,
        avoid_slip_above: r.avoid_slip_above.unwrap_or_else(|| {
            ProfileSlip::derived_avoid_slip_above(slip_limit, slip_sigma_relative)
        }),
        max_tilt_deg: r.max_tilt_deg.unwrap_or(d.max_tilt_deg),
    }))
}
