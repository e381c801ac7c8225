//! GIS layers of a run, for MMGIS and QGIS: the route and the zones as given, and per strategy
//! the drive paths with the sol ends, the sol-end uncertainty ellipses, the faults and the zones
//! grown at each fault's r. Each layer is written twice:
//!
//! - **`<stem>.geojson`** (each run's paths layer beside the run's JSON, the others in
//!   [`GIS_DIR`]): planetocentric longitude and latitude, degrees east and north, on
//!   the IAU 2015 Mars sphere (RFC 7946 order, what MMGIS reads), with a GeoJSON 2008 `crs`
//!   member naming [`GEOGRAPHIC_URN`] (`IAU_2015:49900`), so GDAL, QGIS and geopandas read Mars
//!   longitude/latitude, not WGS 84;
//! - **`gis/projected/<stem>.geojson`** and **`gis/projected/<stem>.prj`**: map metres, the projected coordinates
//!   of the map's Jezero equirectangular CRS ([`maps::mars_crs`]), the CRS of its GeoTIFFs: the
//!   `crs` member carries its WKT2 (GDAL reads it), the `.prj` its Esri WKT1.
//!
//! Every feature keeps its map-metre coordinates in its properties (`coordinates_m`, and `x_m`,
//! `y_m` for points and ellipse centres). Longitudes and latitudes are rounded to 1e-9° (under
//! 0.06 mm) and map metres to 1 µm, one feature per line, so a rerun writes the same bytes.
//!
//! A map without a Mars CRS (a PNG, an old GeoTIFF, a scenario's `map.origin_m`) is placed with
//! [`maps::mars_crs::DEFAULT_ANCHOR`], and every file's `crs_note` says so.
//!
//! | file | geometry | features |
//! |---|---|---|
//! | `<scenario>.route` | LineString | the route's waypoints |
//! | `<scenario>.zones` | MultiPolygon | keep-in and keep-out zones as given |
//! | `<scenario>.<strategy>` | LineString, Point | each sol's drive (estimated positions); each drive's end with MMGIS ellipse properties |
//! | `<scenario>.<strategy>.ellipses` | Polygon | each drive's end uncertainty disc, [`ELLIPSE_VERTICES`] vertices |
//! | `<scenario>.<strategy>.faults` | Point | where each fault stopped the drive |
//! | `<scenario>.<strategy>.fault-zones` | MultiPolygon | at each fault: every keep-out within r + footprint + 150 m of it (the leg search's margin) grown, and the keep-in union shrunk, by r + footprint |

use std::fmt::Write as _;
use std::path::PathBuf;

use maps::MarsEquirectangular;
use maps::mars_crs::{DEFAULT_ANCHOR, GEOGRAPHIC_URN};
use maps::zone::polygon_rings_m;
use serde_json::{Map, Value, json};
use sim::CampaignOutcome;
use study::Scenario;

use crate::output_set::{OutputSet, OutputSetError};

/// Vertices of a sol-end uncertainty ellipse (one every 5°).
pub const ELLIPSE_VERTICES: usize = 72;

/// A geometry in map metres.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// One position.
    Point([f64; 2]),
    /// A polyline.
    LineString(Vec<[f64; 2]>),
    /// Rings (exterior first, counter-clockwise), each closed.
    Polygon(Vec<Vec<[f64; 2]>>),
    /// Polygons.
    MultiPolygon(Vec<Vec<Vec<[f64; 2]>>>),
}

impl Shape {
    /// The GeoJSON geometry type.
    #[must_use]
    pub fn type_name(&self) -> &'static str {
        match self {
            Shape::Point(_) => "Point",
            Shape::LineString(_) => "LineString",
            Shape::Polygon(_) => "Polygon",
            Shape::MultiPolygon(_) => "MultiPolygon",
        }
    }

    /// The coordinates with every position mapped by `f`, as GeoJSON.
    fn coordinates(&self, f: &impl Fn([f64; 2]) -> [f64; 2]) -> Value {
        let line = |l: &[[f64; 2]]| Value::from(l.iter().map(|&p| pos(f(p))).collect::<Vec<_>>());
        let rings =
            |r: &[Vec<[f64; 2]>]| Value::from(r.iter().map(|l| line(l)).collect::<Vec<_>>());
        match self {
            Shape::Point(p) => pos(f(*p)),
            Shape::LineString(l) => line(l),
            Shape::Polygon(r) => rings(r),
            Shape::MultiPolygon(m) => Value::from(m.iter().map(|r| rings(r)).collect::<Vec<_>>()),
        }
    }
}

fn pos(p: [f64; 2]) -> Value {
    json!([p[0], p[1]])
}

/// Rounds to `per_unit`ths, so reruns and platforms agree on the digits.
fn round(v: f64, per_unit: f64) -> f64 {
    (v * per_unit).round() / per_unit
}

/// One feature: a geometry in map metres and its properties.
#[derive(Clone, Debug, PartialEq)]
pub struct Feature {
    /// Where, map metres.
    pub shape: Shape,
    /// What (`coordinates_m` is added when written).
    pub properties: Map<String, Value>,
}

impl Feature {
    fn new(shape: Shape, properties: Value) -> Self {
        let properties = match properties {
            Value::Object(m) => m,
            _ => Map::new(),
        };
        Self { shape, properties }
    }
}

/// The output folder of the longitude/latitude layers (except each run's paths layer).
pub const GIS_DIR: &str = "gis";
/// The output folder of every layer in the map's projected CRS, each with its `.prj`.
pub const PROJECTED_DIR: &str = "gis/projected";

/// One GIS layer: a file stem and its features.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// File name without `.geojson` / `.prj`, e.g. `sol383-386.onboard.faults`.
    pub stem: String,
    /// Whether its longitude/latitude file goes beside the run's JSON (the paths layer) rather
    /// than into [`GIS_DIR`].
    pub beside_run: bool,
    /// The features, in map metres.
    pub features: Vec<Feature>,
}

/// How a layer's coordinates are written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Frame {
    /// Planetocentric longitude and latitude, degrees (`<stem>.geojson`).
    LonLat,
    /// Map metres: the map's projected CRS (`gis/projected/<stem>.geojson`).
    Projected,
}

impl Layer {
    /// The layer as a GeoJSON FeatureCollection in `frame`, one feature per line. `crs` is the
    /// map's CRS and `note` what the `crs_note` adds to the description of the frame.
    #[must_use]
    pub fn geojson(&self, crs: &MarsEquirectangular, frame: Frame, note: &str) -> String {
        let (crs_name, description) = match frame {
            Frame::LonLat => (
                GEOGRAPHIC_URN.to_owned(),
                format!(
                    "longitude, latitude: planetocentric degrees east and north on the IAU 2015 \
                     Mars sphere (IAU_2015:49900); coordinates_m, x_m, y_m: map metres, the \
                     projected coordinates of {} (the gis/projected twin){note}",
                    crs.name()
                ),
            ),
            Frame::Projected => (
                crs.wkt2(),
                format!(
                    "map metres (x east, y north): the projected coordinates of {} (the .prj beside it), \
                     the CRS of the map's GeoTIFFs{note}",
                    crs.name()
                ),
            ),
        };
        let transform = |p: [f64; 2]| match frame {
            Frame::LonLat => crs.lonlat_from_map(p).map(|v| round(v, 1e9)),
            Frame::Projected => p.map(|v| round(v, 1e6)),
        };
        let in_metres = |p: [f64; 2]| p.map(|v| round(v, 1e6));
        let head = json!({
            "type": "FeatureCollection",
            "name": self.stem,
            "crs": { "type": "name", "properties": { "name": crs_name } },
            "crs_note": description,
        });
        let mut s = serde_json::to_string(&head).unwrap_or_default();
        // Reopen the object to append the features, one per line.
        s.pop();
        s.push_str(",\"features\":[");
        for (i, f) in self.features.iter().enumerate() {
            let mut properties = f.properties.clone();
            properties.insert("coordinates_m".into(), f.shape.coordinates(&in_metres));
            let feature = json!({
                "type": "Feature",
                "geometry": {
                    "type": f.shape.type_name(),
                    "coordinates": f.shape.coordinates(&transform),
                },
                "properties": properties,
            });
            let sep = if i == 0 { "\n" } else { ",\n" };
            let _ = write!(s, "{sep}{feature}");
        }
        s.push_str("\n]}\n");
        s
    }
}

/// What every file's `crs_note` adds for `scenario`'s map: nothing for a map with a Mars CRS,
/// else where it was placed.
fn placement_note(scenario: &Scenario) -> String {
    if scenario.map_crs.is_mars() {
        String::new()
    } else {
        format!(
            "; the map carries no Mars CRS, so map point ({}, {}) m is placed at {}° N {}° E, \
             Perseverance's landing site (assumed)",
            DEFAULT_ANCHOR.anchor_m[0],
            DEFAULT_ANCHOR.anchor_m[1],
            DEFAULT_ANCHOR.lat_deg,
            DEFAULT_ANCHOR.lon_deg
        )
    }
}

/// The layers every strategy shares: the route and the zones as given.
#[must_use]
pub fn scenario_layers(scenario: &Scenario) -> Vec<Layer> {
    let route = &scenario.settings.route;
    let length_m: f64 = route
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum();
    let route_layer = Layer {
        stem: format!("{}.route", scenario.name),
        beside_run: false,
        features: vec![Feature::new(
            Shape::LineString(route.clone()),
            json!({
                "layer": "route",
                "scenario": scenario.name,
                "waypoints": route.len(),
                "length_m": length_m,
            }),
        )],
    };
    let zones = scenario
        .zones
        .iter()
        .map(|(_, z)| {
            Feature::new(
                Shape::MultiPolygon(polygon_rings_m(z.geometry())),
                json!({
                    "layer": "zones",
                    "kind": z.kind().as_str(),
                    "name": z.name(),
                    "feature_index": z.feature_index(),
                    "offset_m": 0.0,
                }),
            )
        })
        .collect();
    vec![
        route_layer,
        Layer {
            stem: format!("{}.zones", scenario.name),
            beside_run: false,
            features: zones,
        },
    ]
}

/// The paths layer of one run (`<scenario>.<strategy>`): each sol's drive as a LineString of
/// estimated positions, and each drive's end as a Point with the uncertainty as MMGIS-style
/// ellipse properties (`uncertainty_semi_major_m`, `uncertainty_semi_minor_m`,
/// `uncertainty_angle_deg`; a disc, so both axes equal r and the angle is 0) and the true
/// position.
#[must_use]
pub fn paths_layer(scenario: &Scenario, outcome: &CampaignOutcome) -> Layer {
    let mut features = Vec::new();
    for r in &outcome.sols {
        let fault = r.fault.as_ref().map(|f| f.kind.name());
        if r.path_m.len() >= 2 {
            features.push(Feature::new(
                Shape::LineString(r.path_m.clone()),
                json!({
                    "layer": "paths",
                    "kind": "drive",
                    "strategy": outcome.strategy,
                    "sol": r.sol,
                    "distance_m": r.distance_m,
                    "fault": fault,
                }),
            ));
        }
        if let Some(l) = &r.onboard_localization
            && let Some(e) = l.ellipse
        {
            features.push(Feature::new(
                Shape::Point(r.end_position_m),
                json!({
                    "layer": "paths",
                    "kind": "localization",
                    "strategy": outcome.strategy,
                    "sol": r.sol,
                    "localizer": l.localizer,
                    "applied": l.applied,
                    "x_m": r.end_position_m[0],
                    "y_m": r.end_position_m[1],
                    "semi_major_m": e.semi_major_m,
                    "semi_minor_m": e.semi_minor_m,
                    "azimuth_deg": e.azimuth_deg,
                    "angle_deg": e.mmgis_angle_deg,
                    "disc_radius_m": e.disc_radius_m,
                }),
            ));
        }
        if r.drove {
            let end = r.path_m.last().copied().unwrap_or(r.end_position_m);
            features.push(Feature::new(
                Shape::Point(end),
                json!({
                    "layer": "paths",
                    "kind": "sol_end",
                    "strategy": outcome.strategy,
                    "sol": r.sol,
                    "x_m": end[0],
                    "y_m": end[1],
                    "uncertainty_m": r.end_uncertainty_m,
                    "uncertainty_semi_major_m": r.end_uncertainty_m,
                    "uncertainty_semi_minor_m": r.end_uncertainty_m,
                    "uncertainty_angle_deg": 0.0,
                    "true_x_m": r.end_true_position_m[0],
                    "true_y_m": r.end_true_position_m[1],
                    "fault": fault,
                }),
            ));
        }
    }
    Layer {
        stem: format!("{}.{}", scenario.name, outcome.strategy),
        beside_run: true,
        features,
    }
}

/// A closed counter-clockwise ring of [`ELLIPSE_VERTICES`] vertices on the circle of radius
/// `r_m` around `centre` (map metres).
fn disc_ring(centre: [f64; 2], r_m: f64) -> Vec<[f64; 2]> {
    let mut ring: Vec<[f64; 2]> = (0..ELLIPSE_VERTICES)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / ELLIPSE_VERTICES as f64;
            [centre[0] + r_m * a.cos(), centre[1] + r_m * a.sin()]
        })
        .collect();
    ring.push(ring[0]);
    ring
}

/// A closed counter-clockwise ring of [`ELLIPSE_VERTICES`] vertices on `sigmas` × the 1σ
/// ellipse `e` around `centre` (map metres; the major axis `e.azimuth_deg` east of north).
fn ellipse_ring(
    centre: [f64; 2],
    e: &sim::run::outcome::PositionEllipse,
    sigmas: f64,
) -> Vec<[f64; 2]> {
    let (a, b) = (sigmas * e.semi_major_m, sigmas * e.semi_minor_m);
    // Unit vectors of the major and minor axes in (east, north).
    let az = e.azimuth_deg.to_radians();
    let major = [az.sin(), az.cos()];
    let minor = [-major[1], major[0]];
    let mut ring: Vec<[f64; 2]> = (0..ELLIPSE_VERTICES)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / ELLIPSE_VERTICES as f64;
            let (u, v) = (a * t.cos(), b * t.sin());
            [
                centre[0] + u * major[0] + v * minor[0],
                centre[1] + u * major[1] + v * minor[1],
            ]
        })
        .collect();
    ring.push(ring[0]);
    ring
}

/// The layers of one run: paths, sol-end ellipses, faults and zones at each fault.
#[must_use]
pub fn run_layers(scenario: &Scenario, outcome: &CampaignOutcome) -> Vec<Layer> {
    let stem = format!("{}.{}", scenario.name, outcome.strategy);
    let footprint_m = scenario.settings.grid.footprint_radius_m;
    let mut ellipses = Vec::new();
    let mut faults = Vec::new();
    let mut fault_zones = Vec::new();
    for r in outcome.sols.iter() {
        let fault = r.fault.as_ref().map(|f| f.kind.name());
        if r.drove && r.end_uncertainty_m > 0.0 && r.end_uncertainty_m.is_finite() {
            let centre = r.path_m.last().copied().unwrap_or(r.end_position_m);
            ellipses.push(Feature::new(
                Shape::Polygon(vec![disc_ring(centre, r.end_uncertainty_m)]),
                json!({
                    "layer": "ellipses",
                    "strategy": outcome.strategy,
                    "sol": r.sol,
                    "x_m": centre[0],
                    "y_m": centre[1],
                    "uncertainty_m": r.end_uncertainty_m,
                    "uncertainty_semi_major_m": r.end_uncertainty_m,
                    "uncertainty_semi_minor_m": r.end_uncertainty_m,
                    "uncertainty_angle_deg": 0.0,
                    "fault": fault,
                }),
            ));
        }
        if let Some(l) = &r.onboard_localization
            && let Some(e) = l.ellipse
            && l.applied
            && e.semi_minor_m > 0.0
        {
            ellipses.push(Feature::new(
                Shape::Polygon(vec![ellipse_ring(r.end_position_m, &e, 3.0)]),
                json!({
                    "layer": "ellipses",
                    "kind": "localization_3sigma",
                    "strategy": outcome.strategy,
                    "sol": r.sol,
                    "localizer": l.localizer,
                    "x_m": r.end_position_m[0],
                    "y_m": r.end_position_m[1],
                    "semi_major_m": 3.0 * e.semi_major_m,
                    "semi_minor_m": 3.0 * e.semi_minor_m,
                    "azimuth_deg": e.azimuth_deg,
                    "angle_deg": e.mmgis_angle_deg,
                }),
            ));
        }
        let Some(f) = &r.fault else { continue };
        faults.push(Feature::new(
            Shape::Point(f.position_m),
            json!({
                "layer": "faults",
                "kind": f.kind.name(),
                "strategy": outcome.strategy,
                "sol": r.sol,
                "after_m": f.after_m,
                "uncertainty_m": f.uncertainty_m,
                "x_m": f.position_m[0],
                "y_m": f.position_m[1],
            }),
        ));
        let offset_m = f.uncertainty_m.max(0.0) + footprint_m;
        let props = |kind: &str, name: &str, signed_offset_m: f64| {
            json!({
                "layer": "fault_zones",
                "kind": kind,
                "name": name,
                "strategy": outcome.strategy,
                "sol": r.sol,
                "fault": f.kind.name(),
                "uncertainty_m": f.uncertainty_m,
                "footprint_radius_m": footprint_m,
                "offset_m": signed_offset_m,
            })
        };
        // The keep-outs within reach of the fault's search (its window around the leg), not
        // every keep-out of the map at every fault: a file of thousands of keep-outs would
        // otherwise write them all again per fault (issue 26: 665 MB).
        let reach_m = offset_m + sim::run::LEG_WINDOW_MARGIN_M;
        for (h, area) in scenario
            .zones
            .keep_outs_grown_near(offset_m, f.position_m, reach_m)
        {
            let z = scenario.zones.get(h).expect("a handle of this set");
            let mut p = props("keep_out", z.name(), offset_m);
            p["feature_index"] = json!(z.feature_index());
            fault_zones.push(Feature::new(Shape::MultiPolygon(polygon_rings_m(&area)), p));
        }
        if let Some(area) = scenario.zones.keep_in_shrunk(offset_m)
            && !area.0.is_empty()
        {
            fault_zones.push(Feature::new(
                Shape::MultiPolygon(polygon_rings_m(&area)),
                props("keep_in", "keep-in union", -offset_m),
            ));
        }
    }
    vec![
        paths_layer(scenario, outcome),
        Layer {
            stem: format!("{stem}.ellipses"),
            beside_run: false,
            features: ellipses,
        },
        Layer {
            stem: format!("{stem}.faults"),
            beside_run: false,
            features: faults,
        },
        Layer {
            stem: format!("{stem}.fault-zones"),
            beside_run: false,
            features: fault_zones,
        },
    ]
}

/// Writes each layer as `<stem>.geojson` (longitude/latitude; in [`GIS_DIR`] unless
/// [`Layer::beside_run`]) and `gis/projected/<stem>.geojson` and `.prj` (map CRS) into `set`;
/// returns the paths written.
///
/// # Errors
/// [`OutputSetError::Io`].
pub fn write_layers(
    set: &OutputSet,
    scenario: &Scenario,
    layers: &[Layer],
) -> Result<Vec<PathBuf>, OutputSetError> {
    let crs = scenario.map_crs.mars_or_default();
    let note = placement_note(scenario);
    let prj = format!("{}\n", crs.wkt1_esri());
    let mut written = Vec::new();
    for l in layers {
        // The paths layer stays beside the run's JSON (where MMGIS users have always found
        // it); the other layers go to gis/.
        let lonlat = if l.beside_run {
            format!("{}.geojson", l.stem)
        } else {
            format!("{GIS_DIR}/{}.geojson", l.stem)
        };
        written.push(set.write(&lonlat, l.geojson(&crs, Frame::LonLat, &note).as_bytes())?);
        written.push(set.write(
            &format!("{PROJECTED_DIR}/{}.geojson", l.stem),
            l.geojson(&crs, Frame::Projected, &note).as_bytes(),
        )?);
        written.push(set.write(&format!("{PROJECTED_DIR}/{}.prj", l.stem), prj.as_bytes())?);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layer() -> Layer {
        Layer {
            stem: "t".into(),
            beside_run: false,
            features: vec![
                Feature::new(Shape::Point([600.0, 600.0]), json!({"a": 1})),
                Feature::new(Shape::Polygon(vec![disc_ring([0.0, 0.0], 2.0)]), json!({})),
            ],
        }
    }

    fn crs() -> MarsEquirectangular {
        MarsEquirectangular::jezero(&maps::MapAnchor {
            anchor_m: [600.0, 600.0],
            lon_deg: 77.4508,
            lat_deg: 18.4447,
        })
    }

    #[test]
    fn both_frames_parse_and_keep_metres_in_properties() {
        for frame in [Frame::LonLat, Frame::Projected] {
            let text = layer().geojson(&crs(), frame, "");
            assert_eq!(text.lines().count(), 4, "{text}");
            let v: Value = serde_json::from_str(&text).expect("GeoJSON");
            let f = &v["features"][0];
            assert_eq!(f["properties"]["coordinates_m"], json!([600.0, 600.0]));
            assert_eq!(f["properties"]["a"], 1);
            let p = &f["geometry"]["coordinates"];
            let want = match frame {
                Frame::LonLat => [77.4508, 18.4447],
                Frame::Projected => [600.0, 600.0],
            };
            for k in 0..2 {
                let got = p[k].as_f64().expect("number");
                assert!((got - want[k]).abs() < 2e-8, "{frame:?} {got}");
            }
        }
    }

    #[test]
    fn ellipse_rings_are_closed_and_counter_clockwise() {
        let ring = disc_ring([10.0, 20.0], 3.0);
        assert_eq!(ring.len(), ELLIPSE_VERTICES + 1);
        assert_eq!(ring.first(), ring.last());
        let twice_area: f64 = ring
            .windows(2)
            .map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1])
            .sum();
        assert!(twice_area > 0.0);
        for p in &ring {
            assert!(((p[0] - 10.0).hypot(p[1] - 20.0) - 3.0).abs() < 1e-12);
        }
    }

    #[test]
    fn filter_ellipse_ring_has_its_axes_and_azimuth() {
        // Major axis 30° east of north: 3σ semi-axes 6 m and 1.5 m.
        let e = sim::run::outcome::PositionEllipse {
            semi_major_m: 2.0,
            semi_minor_m: 0.5,
            azimuth_deg: 30.0,
            mmgis_angle_deg: 120.0,
            disc_radius_m: 6.0,
        };
        let ring = ellipse_ring([10.0, 20.0], &e, 3.0);
        assert_eq!(ring.len(), ELLIPSE_VERTICES + 1);
        assert_eq!(ring.first(), ring.last());
        let twice_area: f64 = ring
            .windows(2)
            .map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1])
            .sum();
        // A 72-gon inscribed in the ellipse: area within 0.2 % of π·a·b, counter-clockwise.
        let exact = std::f64::consts::PI * 6.0 * 1.5;
        assert!(
            (twice_area / 2.0 - exact).abs() < 2e-3 * exact,
            "{twice_area}"
        );
        let far = ring
            .iter()
            .max_by(|p, q| {
                let d = |p: &[f64; 2]| (p[0] - 10.0).hypot(p[1] - 20.0);
                d(p).total_cmp(&d(q))
            })
            .expect("the ring has vertices");
        // The farthest vertex lies 6 m along azimuth 30° (or 210°).
        let bearing = (far[0] - 10.0)
            .atan2(far[1] - 20.0)
            .to_degrees()
            .rem_euclid(180.0);
        assert!((bearing - 30.0).abs() < 1e-9, "{bearing}");
        assert!(((far[0] - 10.0).hypot(far[1] - 20.0) - 6.0).abs() < 1e-9);
    }
}
