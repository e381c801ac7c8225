//! `Scenario::build`: a [`ScenarioSpec`] with its maps read — the files checked and held to
//! the memory budget before anything is decoded, the route and the science targets checked
//! against the map, the planning grid and the route's leg clearances built once, and the
//! simulator's [`Settings`] checked whole.

use std::path::Path;
use std::sync::Arc;

use maps::{MapLayers, MemoryBudget, ZoneSet};
use sim::Settings;
use sim::grid::planning_grid::{GridSettings, PlanningGrid};
use sim::run;

use super::Scenario;
use super::spec::ScenarioSpec;
use crate::error::ScenarioError;

/// One item of a scenario's memory budget: the field it comes from, its bytes, and for a
/// raster the file and header (to name it in the error).
type BudgetItem<'a> = (
    &'a str,
    u64,
    Option<(&'a Path, maps::raster_io::RasterHeader)>,
);

impl Scenario {
    /// Reads the maps and zones a validated [`ScenarioSpec`] names, checks the route and the
    /// science targets against the map, and builds the planning grid and leg clearances.
    ///
    /// # Errors
    /// A [`ScenarioError`] naming the file and the field at fault.
    pub fn build(spec: ScenarioSpec, budget: MemoryBudget) -> Result<Self, ScenarioError> {
        Self::build_observed(spec, budget, &|_, _| {})
    }

    /// [`Scenario::build`] with progress over the legs, as [`Scenario::inspect_observed`].
    ///
    /// # Errors
    /// As [`Scenario::build`].
    pub fn build_observed(
        spec: ScenarioSpec,
        budget: MemoryBudget,
        on_leg: &(dyn Fn(u64, u64) + Sync),
    ) -> Result<Self, ScenarioError> {
        let path = spec.path.as_path();
        let m = &spec.map;
        let map_error = |field: &str, source: maps::RasterError| ScenarioError::Map {
            path: path.to_path_buf(),
            field: field.to_string(),
            source: Box::new(source),
        };
        for (field, p) in [
            ("map.appearance", &m.appearance),
            ("map.dem", &m.dem),
            ("map.terrain", &m.terrain),
            ("map.zones", &m.zones),
        ] {
            if let Err(e) = maps::input_file::regular_file_len(p) {
                return Err(ScenarioError::field(
                    path,
                    field,
                    "an existing regular file (paths are relative to the scenario file)",
                    format!("{} ({e})", p.display()),
                ));
            }
        }
        // The memory the command will hold, before anything is decoded: each layer as read
        // (from its header: appearance and terrain u8; the DEM f32 plus its 16-bit decode
        // buffer and its slope layer), one planning grid, and one search per thread of the pool
        // that runs the strategies (grid size from the DEM's extent). Over the budget, the
        // largest item is named.
        let mut items: Vec<BudgetItem<'_>> = Vec::new();
        let mut dem_extent_m = None;
        for (field, p, bytes_per_px) in [
            ("map.appearance", &m.appearance, 1),
            ("map.dem", &m.dem, 10),
            ("map.terrain", &m.terrain, 1),
        ] {
            let h = maps::raster_io::read_header(p).map_err(|e| map_error(field, e))?;
            if field == "map.dem" {
                let res = m.georef.map(|g| g.resolution_m_per_px).or(h.pixel_size_m);
                dem_extent_m = res.map(|r| [h.width as f64 * r, h.height as f64 * r]);
            }
            items.push((field, h.bytes_as(bytes_per_px), Some((p.as_path(), h))));
        }
        let gradient = if spec.grid.gradient_layer {
            GridSettings::GRADIENT_BYTES_PER_CELL
        } else {
            0
        };
        let per_cell = (PlanningGrid::BYTES_PER_CELL + gradient).saturating_add(
            PlanningGrid::SEARCH_BYTES_PER_CELL.saturating_mul(rayon::current_num_threads() as u64),
        );
        let grid_bytes = |extent_m: [f64; 2]| {
            let cells = PlanningGrid::cells_for(extent_m, spec.grid.resolution_m);
            (cells, maps::memory_budget::bytes_of(&[cells, per_cell]))
        };
        let grid_error = |extent_m: [f64; 2], total: u64| {
            let (cells, _) = grid_bytes(extent_m);
            ScenarioError::field(
                path,
                "grid.resolution_m",
                format!(
                    "a cell size whose planning grid fits the memory budget with the maps \
                     ({}; --memory-budget-mib)",
                    maps::input_file::human_bytes(budget.limit_bytes)
                ),
                format!(
                    "{} m: {cells} cells over {:.0} × {:.0} m need {}",
                    spec.grid.resolution_m,
                    extent_m[0],
                    extent_m[1],
                    maps::input_file::human_bytes(total)
                ),
            )
        };
        if let Some(extent_m) = dem_extent_m {
            items.push(("grid.resolution_m", grid_bytes(extent_m).1, None));
        }
        let total = items.iter().fold(0u64, |t, i| t.saturating_add(i.1));
        if !budget.allows(total) {
            let largest = items
                .iter()
                .max_by_key(|i| i.1)
                .expect("three layers at least");
            return Err(match (largest.2, dem_extent_m) {
                (Some((p, h)), _) => map_error(largest.0, h.over_budget(p, largest.1, budget)),
                (None, Some(extent_m)) => grid_error(extent_m, total),
                (None, None) => unreachable!("the grid item needs the DEM extent"),
            });
        }
        let layers = MapLayers::load(&m.appearance, &m.dem, &m.terrain, m.dem_datum_m, m.georef)
            .map_err(|source| {
                // Name the layer the error is about; a mismatch between layers names `map`.
                let field = [
                    ("map.appearance", &m.appearance),
                    ("map.dem", &m.dem),
                    ("map.terrain", &m.terrain),
                ]
                .into_iter()
                .find(|(_, p)| p.as_path() == source.path())
                .map_or("map", |(f, _)| f);
                map_error(field, source)
            })?;
        let map_crs = match m.georef {
            Some(_) => maps::MapCrs::Local,
            None => maps::raster_io::read_map_crs(&m.appearance)
                .map_err(|e| map_error("map.appearance", e))?,
        };
        let (x0, y0, x1, y1) = layers.dem.extent_m();
        let mut total = total;
        if dem_extent_m.is_none() {
            // A DEM placed by neither the scenario nor its own tags: its grid is known only now.
            let extent_m = [x1 - x0, y1 - y0];
            total = total.saturating_add(grid_bytes(extent_m).1);
            if !budget.allows(total) {
                return Err(grid_error(extent_m, total));
            }
        }
        // The zones' geometry counts too: refused from its vertex and polygon counts, before
        // it is converted, if it does not fit beside the maps and grid.
        let zones = ZoneSet::load_within(&m.zones, budget, total).map_err(|source| {
            ScenarioError::Zones {
                path: path.to_path_buf(),
                source: Box::new(source),
            }
        })?;

        let extent = format!("x {x0:.1}..{x1:.1} m, y {y0:.1}..{y1:.1} m");
        for (i, t) in spec.science.targets.iter().enumerate() {
            let [x, y] = t.position_m;
            if !layers.dem.contains_point(x, y) {
                return Err(ScenarioError::field(
                    path,
                    format!("science.targets[{i}].position_m"),
                    format!("a point on the map ({extent})"),
                    format!("[{x}, {y}]"),
                ));
            }
        }
        let grid = Arc::new(PlanningGrid::build(&zones, &layers, &spec.grid));
        // Waypoints are on the map when they are in a grid cell: the simulator places them in
        // cells, and a point within rounding of the map's south or east edge (y = 1e-60 over
        // y0 = 0) passes `contains_point` yet lies in no cell.
        if let Some(i) = spec.route.iter().position(|w| grid.cell_of(*w).is_none()) {
            let w = spec.route[i];
            return Err(ScenarioError::field(
                path,
                format!("route.waypoints[{i}]"),
                format!("a point on the map ({extent})"),
                format!("[{}, {}]", w[0], w[1]),
            ));
        }
        let layers = Arc::new(layers);
        let mut inputs_sha256 = Vec::new();
        for (field, p) in [
            ("map.appearance", &m.appearance),
            ("map.dem", &m.dem),
            ("map.terrain", &m.terrain),
            ("map.zones", &m.zones),
        ] {
            // Read already (and within the budget) to build the layers and zones.
            let bytes = maps::input_file::read_input(p, u64::MAX, maps::input_file::Follow::Yes)
                .map_err(|e| {
                    ScenarioError::field(
                        path,
                        field,
                        "a readable file",
                        format!("{} ({e})", p.display()),
                    )
                })?;
            inputs_sha256.push((field, p.clone(), crate::input::sha256_hex(&bytes)));
        }
        let localizer = spec.localizer.localizer(&layers, spec.hbs_link_bytes_per_s);
        let settings = Settings {
            route: spec.route,
            calendar: spec.calendar,
            rover: spec.rover,
            model: spec.model,
            localizer,
            operator_margin_m: spec.operator_margin_m,
            rules: spec.rules,
            grid,
            sol_plan: spec.sol_plan,
            science: spec.science,
        };
        settings
            .validate()
            .map_err(|source| ScenarioError::Settings {
                path: path.to_path_buf(),
                source,
            })?;
        // The leg searches' time grows with the cells of their windows: refused over the cap
        // before they run.
        let search_cells = run::leg_search_cells(&settings.grid, &settings.route);
        if search_cells > run::MAX_LEG_SEARCH_CELLS {
            return Err(ScenarioError::field(
                path,
                "route.waypoints",
                format!(
                    "a route whose legs' passage searches (each leg's box and {} m around it) \
                     cover at most {} grid cells together",
                    run::LEG_WINDOW_MARGIN_M,
                    run::MAX_LEG_SEARCH_CELLS
                ),
                format!(
                    "{} legs covering {search_cells} cells of {} m",
                    settings.route.len() - 1,
                    settings.grid.geo.resolution_m_per_px
                ),
            ));
        }
        let legs_total = (settings.route.len() - 1) as u64;
        let legs_done = std::sync::atomic::AtomicU64::new(0);
        let legs = run::leg_clearances_observed(&settings, &|| {
            let done = legs_done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            on_leg(done, legs_total);
        });
        Ok(Scenario {
            path: spec.path,
            name: spec.name,
            description: spec.description,
            sha256: spec.sha256,
            seed: spec.seed,
            settings,
            expectations: spec.expectations,
            statistical_expectations: spec.statistical_expectations,
            study_segment: spec.study_segment,
            notes: spec.notes,
            computed_calendar: spec.computed_calendar,
            historic_sources: spec.historic_sources,
            has_history: spec.has_history,
            layers,
            zones: Arc::new(zones),
            legs,
            map_crs,
            inputs_sha256,
        })
    }
}
