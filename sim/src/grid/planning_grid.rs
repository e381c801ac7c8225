//! The grid AutoNav plans on: how much uncertainty each cell tolerates, slope hazards, terrain.
//!
//! Zones are static, only the uncertainty radius `r` changes during a drive, so the grid stores
//! per cell the largest `r` at which the cell is still drivable ("clearance"):
//! `keep_out_clearance = d(cell, nearest keep-out) − footprint` and
//! `keep_in_clearance = d(cell, edge of the keep-in union) − footprint`. A cell is closed at
//! radius `r` when its clearance is `≤ r` — exactly the Minkowski growth of the keep-outs (and
//! shrinkage of the keep-ins) by a disc of radius `r + footprint`, evaluated at cell centres.
//! Distances come from an exact Euclidean distance transform of the rasterised zones
//! ([`crate::grid::edt`]); a cell whose centre is inside a keep-out has distance 0, and a free cell's
//! distance is the distance to the nearest inside cell centre less half a cell, so the zone edge is
//! placed within one cell of where the polygon has it.
//!
//! Slope hazards (from the DEM) are not grown: the rover sees them with its own cameras.

use maps::{GeoTransform, MapLayers, TerrainClass, ZoneSet};

use crate::grid::astar::{AStarPool, PooledAStar};
use crate::grid::edt;
use crate::settings::field_error::FieldError;
use crate::settings::physical_range::PhysicalRange;

/// How the planning grid is built (plain settings struct).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct GridSettings {
    /// Cell size in metres (default: 1.0; range [`GridSettings::RESOLUTION_RANGE_M`]).
    pub resolution_m: f64,
    /// Rover footprint radius added to every keep-out growth, metres (default: 1.5; range
    /// [`GridSettings::FOOTPRINT_RADIUS_RANGE_M`]).
    pub footprint_radius_m: f64,
    /// Cells steeper than this are hazards, degrees (default: 25; range
    /// [`GridSettings::MAX_SLOPE_RANGE_DEG`]).
    pub max_slope_deg: f64,
    /// Keep the DEM's gradient per cell ([`PlanningGrid::gradient`]), for slip that depends on
    /// the slope along the heading (default: false; [`GridSettings::GRADIENT_BYTES_PER_CELL`]).
    pub gradient_layer: bool,
}

impl GridSettings {
    /// Memory per cell of the gradient layer, bytes (two `f32`).
    pub const GRADIENT_BYTES_PER_CELL: u64 = 8;
    /// The cell sizes a grid may have, metres: finer than 1 cm no map has data (and the
    /// grid's memory is budgeted); coarser than 50 m a cell cannot represent a passage.
    pub const RESOLUTION_RANGE_M: PhysicalRange = PhysicalRange::new(0.01, 50.0, "metres");
    /// The rover footprints a grid may grow zones by, metres: Perseverance's radius is about
    /// 1.65 m; 0 plans for the rover's centre alone; beyond 10 m no rover fits a passage.
    pub const FOOTPRINT_RADIUS_RANGE_M: PhysicalRange = PhysicalRange::new(0.0, 10.0, "metres");
    /// The slope limits a grid may have, degrees: below 1° natural ground is all hazard; 90°
    /// is a wall.
    pub const MAX_SLOPE_RANGE_DEG: PhysicalRange = PhysicalRange::new(1.0, 90.0, "degrees");

    /// Checks each setting against its range.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::RESOLUTION_RANGE_M.check("resolution_m", self.resolution_m)?;
        Self::FOOTPRINT_RADIUS_RANGE_M.check("footprint_radius_m", self.footprint_radius_m)?;
        Self::MAX_SLOPE_RANGE_DEG.check("max_slope_deg", self.max_slope_deg)?;
        Ok(())
    }
}

impl Default for GridSettings {
    fn default() -> Self {
        Self {
            resolution_m: 1.0,
            footprint_radius_m: 1.5,
            max_slope_deg: 25.0,
            gradient_layer: false,
        }
    }
}

/// The planning grid of one map (row-major, row 0 = north, like every raster in `maps`).
#[derive(Clone, Debug)]
pub struct PlanningGrid {
    /// Placement of the grid on the map.
    pub geo: GeoTransform,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Largest `r` (metres) at which the cell is outside every grown keep-out.
    pub keep_out_clearance_m: Vec<f32>,
    /// Largest `r` (metres) at which the cell is inside the shrunk keep-in union.
    pub keep_in_clearance_m: Vec<f32>,
    /// `min` of the two clearances: the cell is closed when this is `≤ r`.
    pub clearance_m: Vec<f32>,
    /// Slope over the limit (never grown, never drivable).
    pub hazard: Vec<bool>,
    /// Terrain class code per cell (see [`TerrainClass::code`]; 0 = no data, treated as soil).
    pub terrain: Vec<u8>,
    /// DEM gradient per cell, `[∂z/∂x (east), ∂z/∂y (north)]`, metres per metre; empty unless
    /// built with [`GridSettings::gradient_layer`].
    pub gradient: Vec<[f32; 2]>,
    /// The rover footprint radius the clearances already subtract, metres: a keep-out closes
    /// the cells within `r + footprint_radius_m` of it.
    pub footprint_radius_m: f64,
    /// A* scratch of this grid's size, reused by every run on the grid ([`PlanningGrid::astar`]).
    astar_pool: AStarPool,
}

impl PlanningGrid {
    /// Build the grid over the extent of the map's DEM.
    #[must_use]
    pub fn build(zones: &ZoneSet, layers: &MapLayers, params: &GridSettings) -> Self {
        let (x0, y0, x1, y1) = layers.dem.extent_m();
        let res = params.resolution_m;
        let [width, height] = Self::size_for([x1 - x0, y1 - y0], res);
        let geo = GeoTransform::new(x0, y1, res);
        let gradient_px = layers.dem.gradient();
        let slope = |g: [f32; 2]| f64::from(g[0].hypot(g[1]).atan().to_degrees());
        let mut hazard = vec![false; width * height];
        let mut terrain = vec![0u8; width * height];
        let mut gradient = if params.gradient_layer {
            vec![[0.0f32; 2]; width * height]
        } else {
            Vec::new()
        };
        for row in 0..height {
            for col in 0..width {
                let (x, y) = geo.center_of(col, row);
                let i = row * width + col;
                let g = gradient_px.sample_nearest(x, y);
                hazard[i] = g.is_some_and(|g| slope(g) > params.max_slope_deg);
                terrain[i] = layers.terrain.sample_nearest(x, y).unwrap_or(0);
                if let (Some(g), Some(cell)) = (g, gradient.get_mut(i)) {
                    *cell = g;
                }
            }
        }
        let mut grid = Self::from_parts(
            zones,
            geo,
            width,
            height,
            params.footprint_radius_m,
            hazard,
            terrain,
        );
        grid.gradient = gradient;
        grid
    }

    /// Width and height, cells, of the grid of `resolution_m` cells over a map of `extent_m`
    /// (width, height) metres, as [`PlanningGrid::build`] lays it out (saturating: hostile
    /// sizes do not wrap).
    #[must_use]
    pub fn size_for(extent_m: [f64; 2], resolution_m: f64) -> [usize; 2] {
        extent_m.map(|e| (e / resolution_m).floor().max(1.0) as usize)
    }

    /// Cells of the grid [`PlanningGrid::size_for`] lays out, saturating.
    #[must_use]
    pub fn cells_for(extent_m: [f64; 2], resolution_m: f64) -> u64 {
        let [w, h] = Self::size_for(extent_m, resolution_m);
        (w as u64).saturating_mul(h as u64)
    }

    /// Memory per cell of a built grid, bytes, including what building it holds at its peak.
    /// Measured (peak RSS of `solsim validate` on `scenarios/crater-floor-passage.toml` (then sol383-386) at 0.5 m and
    /// 0.25 m cells: 15.9 B per extra cell) and rounded up.
    pub const BYTES_PER_CELL: u64 = 16;

    /// Memory per cell of one running traverse (the A* search state and the leg searches),
    /// bytes, for each run in progress at once. Measured (peak RSS of `solsim run` minus
    /// `validate` at 0.5 m and 0.25 m cells: 14.5 B per extra cell) and rounded up.
    pub const SEARCH_BYTES_PER_CELL: u64 = 16;

    /// Build a grid from explicit hazard and terrain layers (used by tests and benchmarks).
    ///
    /// # Panics
    /// If `hazard` or `terrain` does not hold `width * height` cells.
    #[must_use]
    pub fn from_parts(
        zones: &ZoneSet,
        geo: GeoTransform,
        width: usize,
        height: usize,
        footprint_radius_m: f64,
        hazard: Vec<bool>,
        terrain: Vec<u8>,
    ) -> Self {
        assert_eq!(hazard.len(), width * height, "hazard layer size");
        assert_eq!(terrain.len(), width * height, "terrain layer size");
        let res = geo.resolution_m_per_px;
        let (keep_out_mask, keep_in_mask) = zones.rasterize(geo, width, height);
        let outside_keep_in: Vec<bool> = keep_in_mask.iter().map(|inside| !inside).collect();
        let to_clearance = |mask: &[bool]| -> Vec<f32> {
            let sq = edt::squared_edt(mask, width, height);
            sq.iter()
                .zip(mask)
                .map(|(&d2, &inside)| {
                    let d = if inside {
                        0.0
                    } else {
                        (f64::from(d2).sqrt() * res - 0.5 * res).max(0.0)
                    };
                    (d - footprint_radius_m) as f32
                })
                .collect()
        };
        let keep_out_clearance_m = to_clearance(&keep_out_mask);
        let keep_in_clearance_m = to_clearance(&outside_keep_in);
        let clearance_m = keep_out_clearance_m
            .iter()
            .zip(&keep_in_clearance_m)
            .map(|(a, b)| a.min(*b))
            .collect();
        Self {
            geo,
            width,
            height,
            keep_out_clearance_m,
            keep_in_clearance_m,
            clearance_m,
            hazard,
            terrain,
            gradient: Vec::new(),
            footprint_radius_m,
            astar_pool: AStarPool::default(),
        }
    }

    /// An A* planner for this grid, reused from an earlier run when one is free (it goes back
    /// when dropped): the grid is shared by every run of a scenario, and a new planner costs
    /// 16 bytes per cell to allocate and zero.
    #[must_use]
    pub fn astar(&self) -> PooledAStar<'_> {
        self.astar_pool.take(self.width, self.height)
    }

    /// Index of the cell containing map point `p` (metres), or `None` off the grid.
    #[must_use]
    pub fn cell_of(&self, p: [f64; 2]) -> Option<usize> {
        let (c, r) = self.geo.pixel_of(p[0], p[1]);
        if !(c >= 0.0 && r >= 0.0) {
            return None;
        }
        let (c, r) = (c.floor() as usize, r.floor() as usize);
        (c < self.width && r < self.height).then_some(r * self.width + c)
    }

    /// Map position (metres) of the centre of cell `index`.
    #[must_use]
    pub fn center_of(&self, index: usize) -> [f64; 2] {
        let (x, y) = self.geo.center_of(index % self.width, index / self.width);
        [x, y]
    }

    /// Whether cell `index` is closed at uncertainty `r_m`: inside a grown keep-out, outside the
    /// shrunk keep-in union, or a slope hazard.
    #[must_use]
    pub fn closed(&self, index: usize, r_m: f64) -> bool {
        self.hazard[index] || f64::from(self.clearance_m[index]) <= r_m
    }

    /// Terrain class of cell `index` (no data counts as soil).
    #[must_use]
    pub fn terrain_class(&self, index: usize) -> TerrainClass {
        TerrainClass::from_code(self.terrain[index]).unwrap_or(TerrainClass::Soil)
    }
}
