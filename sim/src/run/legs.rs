//! The route's passages: per leg, the largest uncertainty radius at which a path still exists
//! (independent of strategy), searched once per scenario and shared by every run.

use crate::grid::PlanningGrid;
use crate::grid::widest_path::widest_path_bottleneck;
use crate::run::outcome::LegClearance;
use crate::run::route::route_along_m;
use crate::settings::Settings;

/// Margin of the window around each leg within which [`leg_clearances`] searches, metres.
pub const LEG_WINDOW_MARGIN_M: f64 = 150.0;

/// Most waypoints a route may have. Rover routes have tens to hundreds; every waypoint costs a
/// passage search when a scenario is loaded and a leg in every run (issue 26: 100 000 took 5
/// minutes).
pub const MAX_WAYPOINTS: usize = 10_000;

/// Most grid cells the passage searches of one route may cover together
/// ([`leg_search_cells`]). Measured (issue 26, one core): 2000 legs through the sol 383-386
/// passage, each needing the full search (2.8e8 cells), load in 16 s; legs through open ground
/// take a fraction of that, and a second core halves it.
pub const MAX_LEG_SEARCH_CELLS: u64 = 300_000_000;

/// Per-leg passage clearance of the route (independent of strategy).
///
/// Leg `i` runs from waypoint `i − 1` to waypoint `i`; its clearance is the largest uncertainty
/// radius at which a path between them still exists (a maximin path over cell clearance, slope
/// hazards excluded), searched within [`LEG_WINDOW_MARGIN_M`] of the leg's box. The legs are
/// searched in parallel; the result does not depend on the thread count.
#[must_use]
pub fn leg_clearances(c: &Settings) -> Vec<LegClearance> {
    leg_clearances_observed(c, &|| {})
}

/// [`leg_clearances`], calling `on_leg` as each leg is done (from any thread; for a progress
/// bar).
#[must_use]
pub fn leg_clearances_observed(c: &Settings, on_leg: &(dyn Fn() + Sync)) -> Vec<LegClearance> {
    use rayon::prelude::*;
    let g = &c.grid;
    // Where each leg starts along the route (waypoint i - 1's distance), summed in order
    // before the parallel part.
    let starts_m = route_along_m(&c.route);
    (1..c.route.len())
        .into_par_iter()
        .map(|i| {
            let (p, q) = (c.route[i - 1], c.route[i]);
            let bottleneck = match (g.cell_of(p), g.cell_of(q)) {
                (Some(a), Some(b)) => widest_path_bottleneck(
                    g.width,
                    g.height,
                    &g.clearance_m,
                    |k| !g.hazard[k],
                    a,
                    b,
                    Some(leg_window(g, a, b)),
                ),
                _ => None,
            };
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let (length_m, leg_start_m) = (dx.hypot(dy), starts_m[i - 1]);
            let leg = LegClearance {
                to_waypoint: i,
                clearance_m: bottleneck.map(|b| f64::from(b.clearance)),
                narrowest_along_route_m: bottleneck.map(|b| {
                    // Project the narrowest cell onto the leg.
                    let at = g.center_of(b.narrowest_cell);
                    let t = if length_m > 0.0 {
                        (((at[0] - p[0]) * dx + (at[1] - p[1]) * dy) / (length_m * length_m))
                            .clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    leg_start_m + t * length_m
                }),
                narrowest_m: bottleneck.map(|b| g.center_of(b.narrowest_cell)),
            };
            on_leg();
            leg
        })
        .collect()
}

/// The window `(col0, row0, col1, row1)` [`leg_clearances`] searches for the leg between cells
/// `a` and `b`: their box grown by [`LEG_WINDOW_MARGIN_M`], clipped to the grid.
fn leg_window(g: &PlanningGrid, a: usize, b: usize) -> (usize, usize, usize, usize) {
    let margin = (LEG_WINDOW_MARGIN_M / g.geo.resolution_m_per_px).ceil() as usize;
    let (ca, ra, cb, rb) = (a % g.width, a / g.width, b % g.width, b / g.width);
    (
        ca.min(cb).saturating_sub(margin),
        ra.min(rb).saturating_sub(margin),
        (ca.max(cb) + margin).min(g.width - 1),
        (ra.max(rb) + margin).min(g.height - 1),
    )
}

/// Cells [`leg_clearances`] may search over the whole route, at most: the sum of its legs'
/// windows (legs with an end off the grid count nothing). The time of [`leg_clearances`] is
/// about proportional to it in the worst case, so a scenario can be refused from it before the
/// search runs.
#[must_use]
pub fn leg_search_cells(grid: &PlanningGrid, route: &[[f64; 2]]) -> u64 {
    route
        .windows(2)
        .filter_map(|w| Some((grid.cell_of(w[0])?, grid.cell_of(w[1])?)))
        .map(|(a, b)| {
            let (c0, r0, c1, r1) = leg_window(grid, a, b);
            ((c1 - c0 + 1) as u64).saturating_mul((r1 - r0 + 1) as u64)
        })
        .fold(0u64, u64::saturating_add)
}
