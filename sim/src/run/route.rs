//! Where the rover is along its route: waypoint distances, the estimate projected onto the leg
//! it drives, the route left.

use crate::operations::policy::RoutePosition;
use crate::rover::autonav::RoverState;
use crate::settings::Settings;

/// Distance along the route of each waypoint, metres (waypoint 0 at 0).
#[must_use]
pub fn route_along_m(route: &[[f64; 2]]) -> Vec<f64> {
    let mut along = Vec::with_capacity(route.len());
    let mut s = 0.0;
    for (i, w) in route.iter().enumerate() {
        if i > 0 {
            s += (w[0] - route[i - 1][0]).hypot(w[1] - route[i - 1][1]);
        }
        along.push(s);
    }
    along
}

/// Where the rover's estimate lies along the route: projected onto the leg it drives.
pub(crate) fn route_position(
    route: &[[f64; 2]],
    along: &[f64],
    state: &RoverState,
) -> RoutePosition {
    let next = state.next_waypoint.clamp(1, route.len().max(2) - 1);
    if route.len() < 2 {
        return RoutePosition {
            along_m: 0.0,
            next_waypoint: next,
        };
    }
    let (p, q) = (route[next - 1], route[next]);
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let len2 = dx * dx + dy * dy;
    let e = state.estimate.position_m;
    let t = if len2 > 0.0 {
        (((e.x - p[0]) * dx + (e.y - p[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    RoutePosition {
        along_m: along[next - 1] + t * len2.sqrt(),
        next_waypoint: state.next_waypoint.max(1),
    }
}

/// The route left from the rover's estimate: to its next waypoint, then the legs after it,
/// metres.
pub(crate) fn remaining_m(c: &Settings, state: &RoverState) -> f64 {
    let mut remaining = 0.0;
    if state.next_waypoint < c.route.len() {
        let pos = state.estimate.position_m;
        let wp = c.route[state.next_waypoint];
        remaining += (pos - nalgebra::Vector2::new(wp[0], wp[1])).norm();
        for w in c.route[state.next_waypoint..].windows(2) {
            remaining += ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
        }
    }
    remaining
}
