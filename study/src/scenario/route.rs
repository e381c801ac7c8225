//! `[route]`: the waypoints, start first, in map metres (on the map: checked by
//! `Scenario::build` once the map is read).

use sim::run;

use super::raw::RawRoute;
use crate::check::FieldCheck;
use crate::error::ScenarioError;
use crate::ranges;

/// The route's waypoints: a start and a goal at least, at most [`run::MAX_WAYPOINTS`],
/// each coordinate on the planet.
///
/// # Errors
/// A [`ScenarioError`] naming `route.waypoints` or the first coordinate at fault.
pub(crate) fn waypoints(
    c: &FieldCheck<'_>,
    raw: &RawRoute,
) -> Result<Vec<[f64; 2]>, ScenarioError> {
    if !(2..=run::MAX_WAYPOINTS).contains(&raw.waypoints.len()) {
        return Err(c.err(
            "route.waypoints",
            format!(
                "2 ..= {} waypoints (the start and a goal at least)",
                run::MAX_WAYPOINTS
            ),
            raw.waypoints.len(),
        ));
    }
    let waypoints: Vec<[f64; 2]> = raw.waypoints.iter().map(|w| w.0).collect();
    for (i, w) in waypoints.iter().enumerate() {
        for (k, v) in w.iter().enumerate() {
            c.range(
                ranges::COORDINATE_M,
                &format!("route.waypoints[{i}][{k}]"),
                *v,
            )?;
        }
    }
    Ok(waypoints)
}
