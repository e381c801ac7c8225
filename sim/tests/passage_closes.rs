//! A passage of width `w` between two keep-outs closes exactly when the grown keep-outs meet:
//! `r + footprint > w / 2`, to within one grid cell — both for path existence (A* on the grid at
//! uncertainty `r`), for the passage clearance (maximin path) and for a whole AutoNav drive, which
//! faults `NO_PATH` before the passage when it is closed and drives through when it is open.

use std::path::Path;

use maps::{GeoTransform, ZoneSet};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use sim::grid::astar::AStar;
use sim::grid::planning_grid::PlanningGrid;
use sim::grid::widest_path::widest_path;
use sim::rover::autonav::{
    DriveContext, DriveLimits, RoverSettings, RoverState, VoSource, drive_sol,
};
use sim::rover::uncertainty::UncertaintyModel;
use sim::run::outcome::FaultKind;

const FOOTPRINT_M: f64 = 1.5;
const RES_M: f64 = 1.0;

/// A 100 m × 200 m map (x 0..100, y 0..200) with a wall of keep-out across y 90..110, cut by a
/// passage of width `w` centred on `cx`.
fn passage(w: f64, cx: f64) -> PlanningGrid {
    let (l, r) = (cx - w / 2.0, cx + w / 2.0);
    let text = format!(
        r#"{{"type": "FeatureCollection", "features": [
        {{"type": "Feature", "properties": {{"kind": "keep_out", "name": "west sand"}},
          "geometry": {{"type": "Polygon", "coordinates": [[[-50, 90], [{l}, 90], [{l}, 110], [-50, 110], [-50, 90]]]}}}},
        {{"type": "Feature", "properties": {{"kind": "keep_out", "name": "east sand"}},
          "geometry": {{"type": "Polygon", "coordinates": [[[{r}, 90], [150, 90], [150, 110], [{r}, 110], [{r}, 90]]]}}}}
    ]}}"#
    );
    let zones =
        ZoneSet::from_geojson_str(&text, Path::new("passage.geojson")).expect("valid zones");
    let (width, height) = (100, 200);
    let geo = GeoTransform::new(0.0, 200.0, RES_M);
    PlanningGrid::from_parts(
        &zones,
        geo,
        width,
        height,
        FOOTPRINT_M,
        vec![false; width * height],
        vec![2; width * height],
    )
}

fn path_exists(grid: &PlanningGrid, r_m: f64) -> bool {
    let start = grid.cell_of([50.0, 20.0]).expect("on grid");
    let goal = grid.cell_of([50.0, 180.0]).expect("on grid");
    let mut astar = AStar::new(grid.width, grid.height);
    astar
        .plan(start, goal, 1.0, |i| {
            if grid.closed(i, r_m) {
                f32::INFINITY
            } else {
                1.0
            }
        })
        .is_some()
}

#[test]
fn passage_closes_when_the_grown_keep_outs_meet() {
    for (w, cx) in [
        (10.0, 50.0),
        (15.3, 50.37),
        (20.0, 49.5),
        (27.7, 51.2),
        (40.0, 50.0),
    ] {
        let grid = passage(w, cx);
        let half = w / 2.0;
        // Scan r in 1 cm steps around the analytic closing radius and find where paths stop.
        let mut last_open = None;
        let mut first_closed = None;
        let mut r = (half - FOOTPRINT_M - 3.0).max(0.0);
        while r < half - FOOTPRINT_M + 3.0 {
            if path_exists(&grid, r) {
                assert!(
                    first_closed.is_none(),
                    "w={w}: path re-opened at r={r} after closing"
                );
                last_open = Some(r);
            } else if first_closed.is_none() {
                first_closed = Some(r);
            }
            r += 0.01;
        }
        let closes_at = first_closed.expect("passage must close in the scanned range");
        let analytic = half - FOOTPRINT_M; // r + footprint > w/2
        assert!(
            (closes_at - analytic).abs() <= RES_M,
            "w={w} cx={cx}: closes at r={closes_at:.2}, analytic {analytic:.2}, last open {last_open:?}"
        );
        // Clearly open below, clearly closed above.
        assert!(
            path_exists(&grid, analytic - RES_M - 0.01),
            "w={w}: must be open one cell below"
        );
        assert!(
            !path_exists(&grid, analytic + RES_M + 0.01),
            "w={w}: must be closed one cell above"
        );
        // The maximin path value is the same threshold: open iff r < value.
        let start = grid.cell_of([50.0, 20.0]).expect("on grid");
        let goal = grid.cell_of([50.0, 180.0]).expect("on grid");
        let clearance = widest_path(
            grid.width,
            grid.height,
            &grid.clearance_m,
            |k| !grid.hazard[k],
            start,
            goal,
            None,
        )
        .expect("a path exists at r = 0");
        let c = f64::from(clearance);
        assert!(
            path_exists(&grid, c - 1e-3) && !path_exists(&grid, c + 1e-3),
            "w={w}: clearance {c} is the threshold"
        );
        assert!(
            (c - analytic).abs() <= RES_M,
            "w={w}: clearance {c:.2} vs analytic {analytic:.2}"
        );
    }
}

/// Drive 160 m north through the passage with a fixed uncertainty `r0` (growth switched off).
fn drive_with(grid: &PlanningGrid, r0: f64) -> Option<FaultKind> {
    let route = [[50.0, 20.0], [50.0, 180.0]];
    let rover = RoverSettings::default();
    let model = UncertaintyModel {
        k_vo: 0.0,
        k_novo: 0.0,
        initial_margin_m: r0,
    };
    let ctx = DriveContext {
        grid,
        route: &route,
        rover: &rover,
        model: &model,
    };
    let mut state = RoverState::new(route[0], r0);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut astar = AStar::new(grid.width, grid.height);
    let limits = DriveLimits {
        max_distance_m: Some(400.0),
        max_time_s: None,
    };
    let result = drive_sol(
        &ctx,
        &mut state,
        limits,
        VoSource::Terrain,
        rover.errors.draw_sol(&mut rng),
        &mut rng,
        &mut astar,
    );
    if result.fault.is_none() {
        assert!(
            result.reached_goal,
            "no fault, so the rover must get through"
        );
    }
    result.fault.map(|f| f.kind)
}

#[test]
fn autonav_faults_no_path_exactly_when_the_passage_is_closed() {
    let w = 20.0;
    let grid = passage(w, 50.0);
    let analytic = w / 2.0 - FOOTPRINT_M;
    for r0 in [0.0, 4.0, analytic - RES_M - 0.05] {
        assert_eq!(
            drive_with(&grid, r0),
            None,
            "r0={r0}: passage open, the drive must get through"
        );
    }
    for r0 in [analytic + RES_M + 0.05, analytic + 5.0] {
        assert_eq!(
            drive_with(&grid, r0),
            Some(FaultKind::NoPath),
            "r0={r0}: passage closed"
        );
    }
}
