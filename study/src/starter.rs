//! Starter scenarios: a commented scenario file, its zones and a procedural map placed around a
//! route given in Mars longitude and latitude — what `solsim init` and `solsim route import`
//! write.
//!
//! [`Starter::new`] takes the route as planetocentric `[longitude east, latitude north]`
//! degrees on the IAU 2015 Mars sphere (the frame of solsim's own GIS outputs and of MMGIS) and
//! projects it into map metres with the one conversion solsim has,
//! [`MarsEquirectangular::jezero`] ([`maps::mars_crs`]): the map's recipe carries a
//! `[georeference]` that puts the route's first point at its longitude and latitude, so the
//! generated GeoTIFFs carry the same CRS, and `solsim compare`'s `<scenario>.route.geojson`
//! gives the route's longitudes and latitudes back within [`ROUND_TRIP_TOLERANCE_DEG`].
//!
//! The map is procedural (`maps::procedural`), [`StarterOptions::map_margin_m`] wider than the
//! route on every side; its size is held to the command's [`MemoryBudget`] — generating it, and
//! later holding its layers and planning grid in `compare` — before anything is written.
//!
//! Every field of the scenario is written with a comment giving its meaning, unit and default;
//! optional settings appear as commented-out lines at their default values (a test uncomments
//! them all and checks the loader reads the same scenario).

use std::fmt::Write as _;
use std::path::Path;

use maps::mars_crs::JEZERO_TRUE_SCALE_LATITUDE_DEG;
use maps::{MapAnchor, MarsEquirectangular, MemoryBudget};
use sim::grid::planning_grid::PlanningGrid;

use crate::error::ScenarioError;

mod scenario_file;

/// Default map margin around the route, metres: room for AutoNav's detours and for a
/// route's keep-outs, as `solsim record import` leaves.
pub const DEFAULT_MAP_MARGIN_M: f64 = 300.0;
/// Map margins accepted, metres: AutoNav keeps `edge_buffer_m` (5 m) from the map's edge and
/// needs room to detour around hazards at the route's ends.
pub const MAP_MARGIN_RANGE_M: std::ops::RangeInclusive<f64> = 50.0..=100_000.0;
/// What [`MAP_MARGIN_RANGE_M`] asks for, in words.
pub const MAP_MARGIN_EXPECTED: &str =
    "50 ..= 100000 metres (AutoNav keeps 5 m from the map's edge and detours around hazards)";
/// Default first sol of the calendar: Mars 2020 sol 1100 (March 2024), a sol of no historic
/// drive the bundled scenarios replay, so nothing is mistaken for history.
pub const DEFAULT_FIRST_SOL: u32 = 1100;
/// Planning-grid cell, metres: as the scenarios `solsim record import` writes (the loader's
/// default, 1 m, searches 4 × the cells).
pub const GRID_RESOLUTION_M: f64 = 2.0;
/// Largest map side drawn with 2 m pixels, metres; larger maps get 4 m pixels.
pub const FINE_MAP_MAX_SIDE_M: f64 = 4000.0;
/// Waypoints are written to the millimetre.
const WAYPOINT_STEP_M: f64 = 1e-3;
/// How closely a route written by this module comes back from solsim's longitude/latitude
/// GIS output, degrees: waypoints rounded to 1 mm (≤ 9e-9° of longitude at the Jezero
/// projection's 0.5 mm), plus the GIS output's rounding to 1e-9°. 1e-8° is 0.6 mm on Mars.
pub const ROUND_TRIP_TOLERANCE_DEG: f64 = 1e-8;
/// AutoNav rate, metres per hour: the mean speed of the record's sols 379-409 (4834.0 m over
/// 65.27 h, `solsim record import --sols 379-409`).
const DRIVE_RATE_M_PER_H: f64 = 74.1;
/// The median drive window of the record's sols 379-409, LMST (`solsim record import`).
const DRIVE_WINDOW_LMST: (&str, &str) = ("11:45", "14:31");
/// Sols of calendar per metre of route: one sol per 100 m, about half of a drive sol at the
/// record's 74.1 m/h over its median window (205 m), so `ground`, which the calendar keeps
/// from driving some sols, can reach the end.
const SOLS_PER_M: f64 = 1.0 / 100.0;
/// Calendar sols added to the route's, and the fewest written: a week.
const MIN_SOLS: u32 = 7;

/// One point of a route, with where it came from (for error messages).
#[derive(Clone, Debug, PartialEq)]
pub struct TrackPoint {
    /// Planetocentric `[longitude east, latitude north]`, degrees.
    pub lonlat_deg: [f64; 2],
    /// Where the point is in its file: `features[3].geometry.coordinates`, `line 7`, ….
    pub at: String,
}

/// How a starter scenario is made.
#[derive(Clone, Debug, PartialEq)]
pub struct StarterOptions {
    /// Scenario name (output directory names).
    pub name: String,
    /// Scenario seed, and the map's (default: the first sol).
    pub seed: u64,
    /// Map margin around the route's bounding box, metres (default [`DEFAULT_MAP_MARGIN_M`]).
    pub map_margin_m: f64,
    /// First sol of the calendar (default [`DEFAULT_FIRST_SOL`]).
    pub first_sol: u32,
    /// What the route came from, for the file's header (`"the track tracks/a.geojson"`).
    pub source: String,
    /// Add one example keep-out beside the route (for `solsim init`: it shows the format).
    pub example_keep_out: bool,
}

impl StarterOptions {
    /// The defaults for scenario `name`, route from `source`.
    #[must_use]
    pub fn new(name: &str, source: &str) -> Self {
        Self {
            name: name.to_owned(),
            seed: u64::from(DEFAULT_FIRST_SOL),
            map_margin_m: DEFAULT_MAP_MARGIN_M,
            first_sol: DEFAULT_FIRST_SOL,
            source: source.to_owned(),
            example_keep_out: false,
        }
    }
}

/// A starter scenario: its texts and what was decided.
#[derive(Clone, Debug, PartialEq)]
pub struct Starter {
    /// The options it was made with.
    pub options: StarterOptions,
    /// The route as given, degrees.
    pub route_lonlat_deg: Vec<[f64; 2]>,
    /// The route, map metres (x east, y north), rounded to the millimetre.
    pub route_m: Vec<[f64; 2]>,
    /// Length of the route, metres.
    pub route_length_m: f64,
    /// The map's CRS (through [`Starter::anchor`]).
    pub crs: MarsEquirectangular,
    /// The recipe's `[georeference]`: the route's first point at its map position.
    pub anchor: MapAnchor,
    /// Map size, pixels (columns, rows).
    pub map_px: [usize; 2],
    /// Map pixel size, metres.
    pub resolution_m_per_px: f64,
    /// The calendar's sols.
    pub sols: std::ops::RangeInclusive<u32>,
    /// Map metres per ground metre along a parallel at the route's mean latitude (the
    /// equirectangular projection is true to scale at 18.4663° N only).
    pub easting_scale: f64,
    /// The zones file (GeoJSON, map metres).
    pub zones_geojson: String,
}

/// Rounds to `step`.
fn round_to(v: f64, step: f64) -> f64 {
    (v / step).round() * step
}

/// A number as TOML writes it, without float noise (`1621.8`, not `1621.8000000000002`).
fn num(v: f64) -> String {
    let s = format!("{:.3}", v);
    let s = s.trim_end_matches('0');
    let s = s
        .strip_suffix('.')
        .map_or_else(|| s.to_owned(), |s| format!("{s}.0"));
    if s == "-0.0" { "0.0".to_owned() } else { s }
}

/// Cumulative length along `points`, metres.
fn length_m(points: &[[f64; 2]]) -> f64 {
    points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum()
}

impl Starter {
    /// Place `track` (degrees) on a procedural map and write the scenario's pieces. `path` is
    /// the file the track came from, named in errors.
    ///
    /// Longitudes are taken within 180° of the first point's (a track across the 180°
    /// meridian stays one track: 179.9 then −179.9 is 180.1).
    ///
    /// # Errors
    /// A [`ScenarioError::Field`] naming `path` and the point or the track: fewer than two
    /// points; a latitude beyond ±89° (no equirectangular map there); two consecutive points
    /// at the same millimetre; a track within one grid cell; a map (with the margin) over
    /// 20 000 px a side, beyond ±11 000 km, or whose generation, layers and planning grid do
    /// not fit `budget`.
    pub fn new(
        path: &Path,
        track: &[TrackPoint],
        options: &StarterOptions,
        budget: MemoryBudget,
    ) -> Result<Self, ScenarioError> {
        let err = |field: &str, expected: String, got: String| {
            ScenarioError::field(path, field, expected, got)
        };
        let Some(first) = track.first() else {
            return Err(err(
                "track",
                "at least 2 points (a route)".into(),
                "none".into(),
            ));
        };
        if track.len() < 2 {
            return Err(err(
                "track",
                "at least 2 points (a route)".into(),
                "1 point".into(),
            ));
        }
        if !MAP_MARGIN_RANGE_M.contains(&options.map_margin_m) {
            return Err(err(
                "map margin",
                MAP_MARGIN_EXPECTED.into(),
                options.map_margin_m.to_string(),
            ));
        }
        let duplicate = |p: &TrackPoint, i: usize| {
            err(
                &p.at,
                format!(
                    "a point apart from the one before it ({}): consecutive points at the same \
                     millimetre are a duplicate",
                    track[i - 1].at
                ),
                format!(
                    "{}° E {}° N, the same position",
                    p.lonlat_deg[0], p.lonlat_deg[1]
                ),
            )
        };
        let lon0 = first.lonlat_deg[0];
        let mut lonlat = Vec::with_capacity(track.len());
        for p in track {
            let [lon, lat] = p.lonlat_deg;
            if !(lat.is_finite() && lat.abs() <= 89.0) {
                return Err(err(
                    &p.at,
                    "a latitude within ±89° (an equirectangular map near a pole is no map)".into(),
                    format!("{lat}° N"),
                ));
            }
            let lon = lon - 360.0 * ((lon - lon0) / 360.0).round();
            if let Some(prev) = lonlat.last()
                && *prev == [lon, lat]
            {
                return Err(duplicate(p, lonlat.len()));
            }
            lonlat.push([lon, lat]);
        }
        // The route's first point at a provisional map origin, then the whole route shifted
        // so the map starts `map_margin_m` west and south of it.
        let provisional = MarsEquirectangular::jezero(&MapAnchor {
            anchor_m: [0.0, 0.0],
            lon_deg: lonlat[0][0],
            lat_deg: lonlat[0][1],
        });
        let raw: Vec<[f64; 2]> = lonlat
            .iter()
            .map(|p| provisional.map_from_lonlat(*p))
            .collect();
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in &raw {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let span = [hi[0] - lo[0], hi[1] - lo[1]];
        if span[0].max(span[1]) < GRID_RESOLUTION_M {
            return Err(err(
                "track",
                format!(
                    "a route spanning more than one {GRID_RESOLUTION_M} m grid cell (points in \
                     degrees: planetocentric east longitude, north latitude)"
                ),
                format!(
                    "{} points within {:.3} × {:.3} m",
                    track.len(),
                    span[0],
                    span[1]
                ),
            ));
        }
        let m = options.map_margin_m;
        let width_m = span[0] + 2.0 * m;
        let height_m = span[1] + 2.0 * m;
        let resolution = if width_m.max(height_m) <= FINE_MAP_MAX_SIDE_M {
            2.0
        } else {
            4.0
        };
        let map_px = [
            (width_m / resolution).ceil() as usize,
            (height_m / resolution).ceil() as usize,
        ];
        let track_km = format!(
            "a track spanning {:.1} × {:.1} km",
            span[0] / 1000.0,
            span[1] / 1000.0
        );
        let max_side = crate::recipe::MAX_SIDE_PX;
        if map_px[0].max(map_px[1]) > max_side
            || width_m.max(height_m) > maps::zone::MAX_COORDINATE_M
        {
            return Err(err(
                "track",
                format!(
                    "a track whose map (margin {m} m, {resolution} m pixels) is at most {max_side} \
                     px, {} km, a side",
                    max_side as f64 * resolution / 1000.0
                ),
                format!("{track_km}: {} × {} px", map_px[0], map_px[1]),
            ));
        }
        // Memory: generating the map (`map generate`'s measured bytes per pixel), and later
        // holding its layers and planning grid (what `Scenario::load_within` counts).
        let px = [map_px[0] as u64, map_px[1] as u64];
        let generate_bytes =
            maps::memory_budget::bytes_of(&[px[0], px[1], crate::recipe::BYTES_PER_PX]);
        let cells = PlanningGrid::cells_for(
            [px[0] as f64 * resolution, px[1] as f64 * resolution],
            GRID_RESOLUTION_M,
        );
        let per_cell = PlanningGrid::BYTES_PER_CELL.saturating_add(
            PlanningGrid::SEARCH_BYTES_PER_CELL.saturating_mul(rayon::current_num_threads() as u64),
        );
        // Layers as `Scenario::load_within` counts them: appearance and terrain 1 byte per
        // pixel, the DEM 10.
        let run_bytes = maps::memory_budget::bytes_of(&[px[0], px[1], 12])
            .saturating_add(maps::memory_budget::bytes_of(&[cells, per_cell]));
        let need = generate_bytes.max(run_bytes);
        if !budget.allows(need) {
            return Err(err(
                "track",
                format!(
                    "a track whose map (margin {m} m) and planning grid fit the memory budget \
                     ({}; --memory-budget-mib)",
                    maps::input_file::human_bytes(budget.limit_bytes)
                ),
                format!(
                    "{track_km}: a {} × {} px map at {resolution} m/px and {cells} grid cells \
                     need {}",
                    map_px[0],
                    map_px[1],
                    maps::input_file::human_bytes(need)
                ),
            ));
        }
        let anchor = MapAnchor {
            anchor_m: [round_to(m - lo[0], 0.1), round_to(m - lo[1], 0.1)],
            lon_deg: lonlat[0][0],
            lat_deg: lonlat[0][1],
        };
        let crs = MarsEquirectangular::jezero(&anchor);
        let mut route_m: Vec<[f64; 2]> = Vec::with_capacity(lonlat.len());
        for (i, p) in lonlat.iter().enumerate() {
            let q = crs
                .map_from_lonlat(*p)
                .map(|v| round_to(v, WAYPOINT_STEP_M));
            if route_m.last() == Some(&q) {
                return Err(duplicate(&track[i], i));
            }
            route_m.push(q);
        }
        let route_length_m = length_m(&route_m);
        let n_sols = ((route_length_m * SOLS_PER_M).ceil() as u32)
            .saturating_add(3)
            .max(MIN_SOLS);
        let last_sol = options.first_sol.saturating_add(n_sols - 1);
        let mean_lat = lonlat.iter().map(|p| p[1]).sum::<f64>() / lonlat.len() as f64;
        let easting_scale =
            JEZERO_TRUE_SCALE_LATITUDE_DEG.to_radians().cos() / mean_lat.to_radians().cos();
        let mut starter = Self {
            options: options.clone(),
            route_lonlat_deg: lonlat,
            route_m,
            route_length_m,
            crs,
            anchor,
            map_px,
            resolution_m_per_px: resolution,
            sols: options.first_sol..=last_sol,
            easting_scale,
            zones_geojson: String::new(),
        };
        starter.zones_geojson = starter.zones();
        Ok(starter)
    }

    /// The zones file: empty, or with [`StarterOptions::example_keep_out`] a 20 m square 40 m
    /// to the left of the middle of the route's longest leg.
    fn zones(&self) -> String {
        let empty = "{\"type\": \"FeatureCollection\", \"features\": []}\n".to_owned();
        if !self.options.example_keep_out {
            return empty;
        }
        let Some(leg) = self.route_m.windows(2).max_by(|a, b| {
            length_m(a)
                .partial_cmp(&length_m(b))
                .unwrap_or(std::cmp::Ordering::Equal)
        }) else {
            return empty;
        };
        let (a, b) = (leg[0], leg[1]);
        let len = length_m(leg);
        let left = [-(b[1] - a[1]) / len, (b[0] - a[0]) / len];
        let c = [
            (a[0] + b[0]) / 2.0 + 40.0 * left[0],
            (a[1] + b[1]) / 2.0 + 40.0 * left[1],
        ];
        let ring: Vec<String> = [
            [-10.0, -10.0],
            [10.0, -10.0],
            [10.0, 10.0],
            [-10.0, 10.0],
            [-10.0, -10.0],
        ]
        .iter()
        .map(|d| format!("[{}, {}]", num(c[0] + d[0]), num(c[1] + d[1])))
        .collect();
        format!(
            "{{\"type\": \"FeatureCollection\", \"features\": [\n{{\"type\": \"Feature\", \"properties\": {{\"kind\": \"keep_out\", \"name\": \"example boulder field\"}}, \"geometry\": {{\"type\": \"Polygon\", \"coordinates\": [[{}]]}}}}\n]}}\n",
            ring.join(", ")
        )
    }

    /// The map's recipe (TOML) with terrain seed `map_seed`: `solsim map generate` rebuilds the
    /// map from it.
    #[must_use]
    pub fn recipe_toml(&self, map_seed: u64) -> String {
        let r = self.resolution_m_per_px;
        let mut t = String::new();
        let _ = writeln!(
            t,
            "# Procedural stand-in for the ground around the route of scenario {:?} (not a\n\
             # registration to orbital images). Written by solsim; rebuild with\n\
             # `solsim map generate recipe.toml --out .`. Fields: README.md, \"Map recipes\".",
            self.options.name
        );
        let _ = writeln!(t, "dem_datum_m = 0.0\n\n[terrain]\nseed = {map_seed}");
        let _ = writeln!(
            t,
            "width_px = {}\nheight_px = {}",
            self.map_px[0], self.map_px[1]
        );
        let _ = writeln!(
            t,
            "geo = {{ origin_m = [0.0, {}], resolution_m_per_px = {} }}",
            num(self.map_px[1] as f64 * r),
            num(r)
        );
        // The ground of the record's maps (`solsim record import`): the crater floor's relief,
        // a few small fresh craters and low ridges.
        let _ = writeln!(
            t,
            "base_height_m = 120.0\nrelief_m = 12.0\ncrater_density_per_km2 = 1.5\n\
             crater_radius_min_m = 8.0\ncrater_radius_max_m = 30.0\nridge_count = 2\n\
             ridge_height_m = 2.0\nsand_fraction = 0.12\nbedrock_fraction = 0.30\n\
             sun_azimuth_deg = 250.0\nsun_elevation_deg = 35.0"
        );
        let _ = writeln!(
            t,
            "\n# The route's first point, {:.9}° E {:.9}° N (planetocentric, IAU 2015 Mars sphere),\n\
             # at its map position: the GeoTIFFs carry the Jezero equirectangular CRS through it.",
            self.anchor.lon_deg, self.anchor.lat_deg
        );
        let _ = writeln!(
            t,
            "[georeference]\nanchor_m = [{}, {}]\nlon_deg = {}\nlat_deg = {}",
            num(self.anchor.anchor_m[0]),
            num(self.anchor.anchor_m[1]),
            self.anchor.lon_deg,
            self.anchor.lat_deg
        );
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::ScenarioSpec;

    fn track(points: &[[f64; 2]]) -> Vec<TrackPoint> {
        points
            .iter()
            .enumerate()
            .map(|(i, p)| TrackPoint {
                lonlat_deg: *p,
                at: format!("point {i}"),
            })
            .collect()
    }

    const JEZERO: [[f64; 2]; 3] = [[77.4508, 18.4447], [77.4550, 18.4480], [77.4600, 18.4470]];

    fn make(points: &[[f64; 2]]) -> Result<Starter, ScenarioError> {
        Starter::new(
            Path::new("t.geojson"),
            &track(points),
            &StarterOptions::new("t", "a test"),
            MemoryBudget::default(),
        )
    }

    #[test]
    fn the_route_lands_where_the_track_is() {
        let s = make(&JEZERO).expect("a starter");
        for (m, ll) in s.route_m.iter().zip(JEZERO) {
            let back = s.crs.lonlat_from_map(*m);
            assert!(
                (back[0] - ll[0]).abs() < ROUND_TRIP_TOLERANCE_DEG,
                "{back:?}"
            );
            assert!(
                (back[1] - ll[1]).abs() < ROUND_TRIP_TOLERANCE_DEG,
                "{back:?}"
            );
        }
        // The first point sits the margin in from the map's west and south edges (its
        // longitude is the westmost, its latitude the southmost of the three).
        assert!((s.route_m[0][0] - DEFAULT_MAP_MARGIN_M).abs() < 0.1);
        assert!((s.route_m[0][1] - DEFAULT_MAP_MARGIN_M).abs() < 0.1);
        assert_eq!(s.resolution_m_per_px, 2.0);
        // 594 m of route: 6 + 3 sols.
        assert!(
            (s.route_length_m - 593.9).abs() < 0.1,
            "{}",
            s.route_length_m
        );
        assert_eq!(s.sols.clone().count(), 9);
    }

    #[test]
    fn bad_tracks_are_refused_naming_the_point() {
        let e = make(&JEZERO[..1]).expect_err("one point");
        assert!(e.to_string().contains("at least 2 points"), "{e}");
        let e = make(&[JEZERO[0], JEZERO[0], JEZERO[1]]).expect_err("duplicate");
        assert!(
            e.to_string().contains(
                "t.geojson: point 1: expected a point apart from the one before it (point 0)"
            ),
            "{e}"
        );
        let e = make(&[[77.0, 89.5], [77.1, 89.5]]).expect_err("polar");
        assert!(
            e.to_string()
                .contains("point 0: expected a latitude within ±89°"),
            "{e}"
        );
        let e = make(&[[77.0, 18.0], [77.000001, 18.0]]).expect_err("tiny");
        assert!(e.to_string().contains("one 2 m grid cell"), "{e}");
        let e = make(&[[77.0, 18.0], [97.0, 30.0]]).expect_err("huge");
        assert!(
            e.to_string()
                .contains("t.geojson: track: expected a track whose map"),
            "{e}"
        );
        let e = Starter::new(
            Path::new("t.geojson"),
            &track(&[[77.0, 18.0], [77.3, 18.2]]),
            &StarterOptions::new("t", "a test"),
            MemoryBudget::new(100 << 20),
        )
        .expect_err("over budget");
        assert!(
            e.to_string().contains("fit the memory budget (100 MiB"),
            "{e}"
        );
    }

    #[test]
    fn a_track_across_the_antimeridian_stays_one_track() {
        let s = make(&[[179.999, 10.0], [-179.999, 10.0]]).expect("a starter");
        assert!(s.route_length_m < 200.0, "{}", s.route_length_m);
    }

    /// The commented-out settings are the loader's defaults: uncommenting every one of them
    /// reads the same scenario.
    #[test]
    fn commented_defaults_are_the_loaders() {
        let s = make(&JEZERO).expect("a starter");
        let text = s.scenario_toml("m", "z.geojson", 1);
        let uncommented: String = text
            .lines()
            .map(|l| {
                let rest = l.strip_prefix("# ").unwrap_or(l);
                let key = rest.split(" = ").next().unwrap_or("");
                if rest != l
                    && rest.contains(" = ")
                    && !key.is_empty()
                    && key.chars().all(|c| c.is_ascii_lowercase() || c == '_')
                {
                    rest.to_owned()
                } else {
                    l.to_owned()
                }
            })
            .collect::<Vec<_>>()
            .join("\n");
        let changed = uncommented
            .lines()
            .zip(text.lines())
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(changed, 19, "{uncommented}");
        let path = Path::new("s.toml");
        let a = ScenarioSpec::from_toml_str(path, &text).expect("as written");
        let b = ScenarioSpec::from_toml_str(path, &uncommented).expect("uncommented");
        let debug = |s: &ScenarioSpec| format!("{s:?}").replace(&s.sha256, "");
        assert_eq!(debug(&a), debug(&b));
    }
}
