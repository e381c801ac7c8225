//! The planning grid's clearance (exact EDT of the rasterised zones) agrees with the exact
//! polygon distances of `maps::ZoneSet` (parry2d point-to-segment) to within one grid cell, at
//! every cell of the bundled crater-floor passage, conjunction (the hand-built rapid traverse) and
//! record-imported rapid-traverse zones (sampled), including the
//! 24-gon "craters" and the concave keep-in corridors.

use std::path::Path;

use maps::{GeoTransform, ZoneSet};
use sim::grid::planning_grid::PlanningGrid;

fn check(zones_file: &str, geo: GeoTransform, width: usize, height: usize) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenarios")
        .join(zones_file);
    let zones = ZoneSet::load(&path).expect("bundled zones load");
    let footprint = 1.5;
    let grid = PlanningGrid::from_parts(
        &zones,
        geo,
        width,
        height,
        footprint,
        vec![false; width * height],
        vec![2; width * height],
    );
    let res = geo.resolution_m_per_px;
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for i in (0..width * height).step_by(97) {
        let p = grid.center_of(i);
        let exact = zones.max_uncertainty_m(p, footprint);
        let ours = f64::from(grid.clearance_m[i]);
        if exact <= -footprint + 1e-9 {
            // Inside a keep-out or outside the keep-in union: closed at every r ≥ 0 — unless the
            // centre is within a cell of the edge.
            assert!(
                ours <= -footprint + res,
                "{zones_file}: cell {i} at {p:?} is in a zone but grid says {ours}"
            );
            continue;
        }
        let err = (ours - exact).abs();
        worst = worst.max(err);
        checked += 1;
        assert!(
            err <= res + 1e-3,
            "{zones_file}: cell {i} at {p:?}: grid {ours:.3} m, exact {exact:.3} m"
        );
    }
    assert!(checked > 1000, "{zones_file}: only {checked} cells checked");
    eprintln!("{zones_file}: {checked} cells, worst |grid − exact| = {worst:.3} m (cell {res} m)");
}

#[test]
fn sol383_zones_grid_within_one_cell_of_exact() {
    check(
        "crater-floor-passage.zones.geojson",
        GeoTransform::new(0.0, 1200.0, 1.0),
        1200,
        1200,
    );
}

#[test]
fn rapid_traverse_zones_grid_within_one_cell_of_exact() {
    check(
        "conjunction.zones.geojson",
        GeoTransform::new(0.0, 2000.0, 2.0),
        4800,
        1000,
    );
}

/// The zones `solsim record import` writes: passages across the recorded route and the keep-in
/// corridor, the route buffered by 150 m (a MultiPolygon from geo's buffer, round joins).
#[test]
fn record_import_zones_grid_within_one_cell_of_exact() {
    check(
        "rapid-traverse-379-409.zones.geojson",
        GeoTransform::new(0.0, 2056.0, 2.0),
        2038,
        1028,
    );
}
