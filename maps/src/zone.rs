//! Keep-in and keep-out zones: where the rover may drive.
//!
//! A [`ZoneSet`] is read from a GeoJSON `FeatureCollection` ([`ZoneSet::load`]). Each feature is a
//! `Polygon` or `MultiPolygon` (holes allowed) in map metres (x east, y north; see
//! [`raster`](crate::raster)) with two properties:
//! - `kind`: `"keep_in"` or `"keep_out"` (case, `-` and `_` do not matter: `"KEEP-IN"` works);
//! - `name`: optional string; a feature without one is called `zone-<index>`.
//!
//! Rings must follow the GeoJSON and OGC rules (closed, at least 4 positions, non-zero area, no
//! self-intersections, holes inside their shell); every violation is a [`ZoneError`] naming the
//! file, the feature and the field. Ring orientation is free. Parts of a `MultiPolygon`, and
//! different zones, may overlap: zones of one kind act as their union.
//!
//! Zones live in the set and are named by a `Copy` [`ZoneHandle`] ([`ZoneSet::iter`],
//! [`ZoneSet::get`]). Queries ([`ZoneSet::clearances`] for many points, in parallel) use exact
//! predicates for inside/outside and closed-form point-to-segment distances, so answers are exact
//! up to a few ulps: there is no polygonal approximation of the rover's disc. Keep-out edges and
//! the edge of the keep-in union are held in bounding-volume hierarchies, so a query costs about
//! `log(edges)` plus the polygons whose box holds the point. [`ZoneSet::rasterize`] marks grid cells
//! for the simulator. [`ZoneSet::keep_outs_grown`] and [`ZoneSet::keep_in_shrunk`] give the
//! grown and shrunk zones as polygons (chords of the exact offsets), for maps and GIS layers.
//!
//! ```
//! use maps::ZoneSet;
//! use std::path::Path;
//!
//! let text = r#"{"type": "FeatureCollection", "features": [{
//!     "type": "Feature",
//!     "properties": {"kind": "keep_out", "name": "crater"},
//!     "geometry": {"type": "Polygon",
//!                  "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]]]}}]}"#;
//! let zones = ZoneSet::from_geojson_str(text, Path::new("zones.geojson"))?;
//! assert_eq!(zones.distance_to_keep_out_m([13.0, 14.0]), 5.0);
//! assert_eq!(zones.distance_to_keep_in_edge_m([13.0, 14.0]), f64::INFINITY); // no keep-ins
//! assert_eq!(zones.max_uncertainty_m([13.0, 14.0], 1.5), 3.5);
//! # Ok::<(), maps::ZoneError>(())
//! ```
//!
//! ## What the queries mean
//! For a point `p` (map metres):
//! - [`ZoneSet::distance_to_keep_out_m`]: Euclidean distance from `p` to the nearest keep-out
//!   zone; 0 inside or on the edge of one (a point in a hole is outside the zone); `∞` when there
//!   are no keep-outs.
//! - [`ZoneSet::distance_to_keep_in_edge_m`]: if `p` is in the union `U` of the keep-in zones,
//!   the distance from `p` to the edge of `U` (where keep-ins overlap or abut, their inner edges do
//!   not count); 0 outside `U`; `∞` when there are no keep-ins (then everywhere is allowed).
//! - [`ZoneSet::max_uncertainty_m`] = min(the two) − footprint radius: the largest position error
//!   `r` for which `p` stays drivable when keep-outs are grown, and keep-ins shrunk, by
//!   `r + footprint`. Negative means the rover there is already touching a forbidden area.
//!
//! ## References
//! - H. Butler et al., *The GeoJSON Format*, RFC 7946 (2016), §3.1.6 (polygons, closed rings).
//! - OGC 06-103r4, *Simple Feature Access – Part 1* (2011), §6.1.11 (valid polygons).
//! - J. R. Shewchuk, *Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
//!   Predicates* (1997), for the exact orientation test.

mod error;
mod geojson_reader;
mod geometry;
mod offset;
mod polygons;
mod rasterization;
mod segment_tree;
mod union_boundary;
mod validation;

pub use error::ZoneError;
pub use geojson_reader::json_kind;
pub use offset::{ARC_STEP_RAD, polygon_rings_m};

use crate::raster::GeoTransform;
use geo::{LineString, MultiPolygon, Polygon};
use polygons::Polygons;
use rayon::prelude::*;
use segment_tree::SegmentTree;
use std::fmt;
use std::path::{Path, PathBuf};

/// What a zone means for driving.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ZoneKind {
    /// Drive only inside (the union of all keep-in zones).
    KeepIn,
    /// Never enter.
    KeepOut,
}

impl ZoneKind {
    /// `"keep_in"` or `"keep_out"`, as written in zone files.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            ZoneKind::KeepIn => "keep_in",
            ZoneKind::KeepOut => "keep_out",
        }
    }
}

impl fmt::Display for ZoneKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Names one zone of a [`ZoneSet`]: its position in the file's `features`.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub struct ZoneHandle(u32);

impl ZoneHandle {
    /// The index of the zone in its set (and of its feature in the file).
    #[must_use]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// One keep-in or keep-out zone, as read and validated.
#[derive(Clone, Debug, PartialEq)]
pub struct Zone {
    name: String,
    kind: ZoneKind,
    feature_index: usize,
    geometry: MultiPolygon<f64>,
}

impl Zone {
    /// The `name` property, or `zone-<index>` when the feature has none.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Keep-in or keep-out.
    #[must_use]
    pub fn kind(&self) -> ZoneKind {
        self.kind
    }

    /// Index of the feature in the file's `features` array.
    #[must_use]
    pub fn feature_index(&self) -> usize {
        self.feature_index
    }

    /// The zone's area in map metres: closed rings without repeated vertices, outer rings
    /// counter-clockwise and holes clockwise. A `Polygon` feature gives one polygon.
    #[must_use]
    pub fn geometry(&self) -> &MultiPolygon<f64> {
        &self.geometry
    }

    /// Whether `p` (map metres) lies in the zone, edges included (a point in a hole does not).
    #[must_use]
    pub fn covers(&self, p: [f64; 2]) -> bool {
        use geo::Intersects;
        self.geometry.intersects(&geo::Point::new(p[0], p[1]))
    }
}

/// How far one point is from trouble (all in metres; see the [module docs](self)).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Clearance {
    /// Distance to the nearest keep-out zone (0 inside one; `∞` without keep-outs).
    pub keep_out_distance_m: f64,
    /// Distance to the edge of the keep-in union from inside it (0 outside; `∞` without keep-ins).
    pub keep_in_edge_distance_m: f64,
    /// `min(keep_out_distance_m, keep_in_edge_distance_m) − footprint radius`: the largest position
    /// error that keeps the rover's footprint clear of both. Negative when it already is not.
    pub max_uncertainty_m: f64,
}

/// The keep-in and keep-out zones of one map, ready for distance queries.
///
/// Build it with [`ZoneSet::load`] or [`ZoneSet::from_geojson_str`]; [`ZoneSet::default`] is the
/// empty set (everything drivable). Queries take `&self` and may run from many threads.
#[derive(Clone, Debug, Default)]
pub struct ZoneSet {
    source: PathBuf,
    zones: Vec<Zone>,
    keep_out: Polygons,
    keep_in: Polygons,
    /// Every edge of every keep-out polygon.
    keep_out_edges: SegmentTree,
    /// The edge of the union of the keep-in polygons.
    keep_in_edges: SegmentTree,
}

/// Largest map-metre coordinate accepted anywhere (zone vertices, waypoints, origins), metres:
/// half the equatorial circumference of Mars is 10 660 km, so a larger coordinate is off the
/// planet, and at 1e20 the distance queries would lose every digit of a metre.
pub const MAX_COORDINATE_M: f64 = 11_000_000.0;

/// Most vertices all keep-in polygons of one zones file may have together (their union is
/// computed on load, in time quadratic in overlapping edges). Rover planners' keep-in zones
/// have tens to hundreds.
pub const MAX_KEEP_IN_VERTICES: usize = 10_000;

/// Most vertices (positions, closing ones included) all polygons of one zones file may have
/// together. Measured (issue 26, 2 cores): the worst shapes at this cap — one ring of 199 000
/// vertices, as a fine circle or as saw teeth, or 10 000 spiky polygons of 19 — run
/// `solsim compare --report` in 1 to 12 s at a peak of 270 to 430 MB, within the default
/// memory budget. Rover planners' zone files have hundreds to thousands.
pub const MAX_ZONE_VERTICES: usize = 200_000;

/// Most polygons (a `Polygon` feature is one, a `MultiPolygon` one per part) one zones file may
/// have. Each keep-out is grown again for the maps of a run, and near each fault for its GIS
/// layer, so outputs grow with it: at this cap `compare --report` writes 130 to 170 MB.
pub const MAX_ZONE_POLYGONS: usize = 10_000;

/// Memory a command holds per zone vertex at its peak (`solsim compare --report`: parsing,
/// the zone set, its grown copies, the maps and GIS layers written), bytes. Measured from
/// peak RSS over rings of 100 000 and 199 000 vertices (630 B per vertex) and rounded up.
pub const BYTES_PER_ZONE_VERTEX: u64 = 1_000;

/// Memory a command holds per zone polygon beyond its vertices (each grown keep-out's round
/// corners in the maps and GIS layers), bytes. Measured like [`BYTES_PER_ZONE_VERTEX`] over
/// 10 000 squares (22 kB per polygon) and rounded up.
pub const BYTES_PER_ZONE_POLYGON: u64 = 30_000;

impl ZoneSet {
    /// Read and validate a zones GeoJSON file (see the [module docs](self) for the format)
    /// within the default [`MemoryBudget`](crate::MemoryBudget).
    ///
    /// # Errors
    /// [`ZoneError::Io`] when the file cannot be read (also for a FIFO, a device or a file over
    /// [`crate::input_file::MAX_TEXT_FILE_BYTES`]), otherwise as
    /// [`ZoneSet::from_geojson_str`].
    pub fn load(path: &Path) -> Result<ZoneSet, ZoneError> {
        Self::load_within(path, crate::MemoryBudget::default(), 0)
    }

    /// [`ZoneSet::load`] for a command that already holds `held_bytes` (maps, planning grid)
    /// of `budget`: the zones' geometry ([`ZoneSet::memory_bytes`]) must fit beside them.
    ///
    /// # Errors
    /// As [`ZoneSet::load`], and [`ZoneError::OverBudget`].
    pub fn load_within(
        path: &Path,
        budget: crate::MemoryBudget,
        held_bytes: u64,
    ) -> Result<ZoneSet, ZoneError> {
        let text = crate::input_file::read_text_file(path).map_err(|error| ZoneError::Io {
            path: path.to_owned(),
            error,
        })?;
        Self::from_geojson_str_within(&text, path, budget, held_bytes)
    }

    /// Memory a command holds for zones of `polygons` polygons with `vertices` vertices in all,
    /// at its peak, bytes (saturating): what [`ZoneSet::load_within`] counts against the
    /// budget.
    #[must_use]
    pub fn memory_bytes(polygons: usize, vertices: usize) -> u64 {
        crate::memory_budget::bytes_of(&[vertices as u64, BYTES_PER_ZONE_VERTEX]).saturating_add(
            crate::memory_budget::bytes_of(&[polygons as u64, BYTES_PER_ZONE_POLYGON]),
        )
    }

    /// Parse and validate zones from GeoJSON text; `source` is the file name used in errors.
    ///
    /// # Errors
    /// A [`ZoneError`] for the first problem found: invalid JSON, not a FeatureCollection, more
    /// than [`MAX_ZONE_POLYGONS`] polygons or [`MAX_ZONE_VERTICES`] vertices, a feature without
    /// a valid `kind`, an unsupported geometry, a non-finite coordinate or an invalid ring.
    pub fn from_geojson_str(text: &str, source: &Path) -> Result<ZoneSet, ZoneError> {
        Self::from_geojson_str_within(text, source, crate::MemoryBudget::default(), 0)
    }

    /// [`ZoneSet::from_geojson_str`] within `budget`, of which `held_bytes` are taken (see
    /// [`ZoneSet::load_within`]). The polygons and vertices are counted, and refused over the
    /// caps or the budget, before any geometry is converted or validated.
    ///
    /// # Errors
    /// As [`ZoneSet::from_geojson_str`], and [`ZoneError::OverBudget`].
    pub fn from_geojson_str_within(
        text: &str,
        source: &Path,
        budget: crate::MemoryBudget,
        held_bytes: u64,
    ) -> Result<ZoneSet, ZoneError> {
        let check = |polygons: usize, vertices: usize| {
            let path = source.to_owned();
            if polygons > MAX_ZONE_POLYGONS {
                return Err(ZoneError::TooManyPolygons { path, polygons });
            }
            if vertices > MAX_ZONE_VERTICES {
                return Err(ZoneError::TooManyVertices { path, vertices });
            }
            let need_bytes = Self::memory_bytes(polygons, vertices);
            if !budget.allows(held_bytes.saturating_add(need_bytes)) {
                return Err(ZoneError::OverBudget {
                    path,
                    polygons,
                    vertices,
                    need_bytes,
                    held_bytes,
                    budget,
                });
            }
            Ok(())
        };
        let records = geojson_reader::read_zones(text, source, &check)?;
        // The keep-in union's boundary costs time quadratic in overlapping keep-in edges
        // (10 000 vertices of 100 overlapping keep-ins: 0.9 s; 64 000: 29 s): bound it.
        let keep_in_vertices: usize = records
            .iter()
            .filter(|r| r.kind == ZoneKind::KeepIn)
            .flat_map(|r| r.polygons.iter().flatten())
            .map(Vec::len)
            .sum();
        if keep_in_vertices > MAX_KEEP_IN_VERTICES {
            return Err(ZoneError::TooManyKeepInVertices {
                path: source.to_owned(),
                vertices: keep_in_vertices,
            });
        }
        let mut set = ZoneSet {
            source: source.to_owned(),
            ..ZoneSet::default()
        };
        for record in records {
            let target = match record.kind {
                ZoneKind::KeepIn => &mut set.keep_in,
                ZoneKind::KeepOut => &mut set.keep_out,
            };
            let mut parts = Vec::with_capacity(record.polygons.len());
            for rings in &record.polygons {
                target.push(rings);
                let mut rings = rings.iter().map(|r| LineString::from(r.clone()));
                let shell = rings.next().unwrap_or_else(|| LineString::new(Vec::new()));
                parts.push(Polygon::new(shell, rings.collect()));
            }
            set.zones.push(Zone {
                name: record.name,
                kind: record.kind,
                feature_index: record.feature,
                geometry: MultiPolygon::new(parts),
            });
        }
        set.keep_out_edges = SegmentTree::new(set.keep_out.all_edges());
        set.keep_in_edges = SegmentTree::new(union_boundary::union_boundary(&set.keep_in));
        Ok(set)
    }

    /// The file the zones came from (as given to [`ZoneSet::load`]).
    #[must_use]
    pub fn source(&self) -> &Path {
        &self.source
    }

    /// Number of zones (features).
    #[must_use]
    pub fn len(&self) -> usize {
        self.zones.len()
    }

    /// Whether there are no zones at all.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.zones.is_empty()
    }

    /// The zone named by `handle`, if it belongs to this set.
    #[must_use]
    pub fn get(&self, handle: ZoneHandle) -> Option<&Zone> {
        self.zones.get(handle.index())
    }

    /// Every zone with its handle, in file order.
    pub fn iter(&self) -> impl Iterator<Item = (ZoneHandle, &Zone)> + '_ {
        // `from_geojson_str` rejects more than u32::MAX features.
        self.zones
            .iter()
            .enumerate()
            .map(|(i, z)| (ZoneHandle(i as u32), z))
    }

    /// The keep-out zones with their handles.
    pub fn keep_outs(&self) -> impl Iterator<Item = (ZoneHandle, &Zone)> + '_ {
        self.iter().filter(|(_, z)| z.kind == ZoneKind::KeepOut)
    }

    /// The keep-in zones with their handles.
    pub fn keep_ins(&self) -> impl Iterator<Item = (ZoneHandle, &Zone)> + '_ {
        self.iter().filter(|(_, z)| z.kind == ZoneKind::KeepIn)
    }

    /// Whether `p` lies in a keep-out zone, edges included (a point in a hole does not).
    /// `false` for a non-finite point.
    #[must_use]
    pub fn in_keep_out(&self, p: [f64; 2]) -> bool {
        self.keep_out.covers(p)
    }

    /// Whether `p` lies in the union of the keep-in zones, edges included; `true` everywhere when
    /// there are no keep-in zones. `false` for a non-finite point when there are keep-ins.
    #[must_use]
    pub fn in_keep_in(&self, p: [f64; 2]) -> bool {
        self.keep_in.is_empty() || self.keep_in.covers(p)
    }

    /// Euclidean distance from `p` to the nearest keep-out zone: 0 inside or on the edge of one,
    /// `f64::INFINITY` when there are no keep-outs, NaN when `p` is not finite.
    ///
    /// # Units
    /// Metres, like `p`.
    #[must_use]
    pub fn distance_to_keep_out_m(&self, p: [f64; 2]) -> f64 {
        if !is_finite(p) {
            return f64::NAN;
        }
        if self.keep_out.is_empty() {
            return f64::INFINITY;
        }
        if self.keep_out.covers(p) {
            return 0.0;
        }
        self.keep_out_edges.nearest_distance(p)
    }

    /// Distance from `p` to the edge of the union of keep-in zones when `p` is inside it, 0 when
    /// outside (or on the edge), `f64::INFINITY` when there are no keep-in zones, NaN when `p` is
    /// not finite. Where keep-ins overlap or abut, their inner edges are not part of the edge.
    ///
    /// # Units
    /// Metres, like `p`.
    #[must_use]
    pub fn distance_to_keep_in_edge_m(&self, p: [f64; 2]) -> f64 {
        if !is_finite(p) {
            return f64::NAN;
        }
        if self.keep_in.is_empty() {
            return f64::INFINITY;
        }
        if !self.keep_in.covers(p) {
            return 0.0;
        }
        self.keep_in_edges.nearest_distance(p)
    }

    /// The largest position uncertainty `r` at which `p` stays drivable for a rover of footprint
    /// radius `footprint_radius_m`, with keep-outs grown and keep-ins shrunk by
    /// `r + footprint_radius_m`: `min(distance_to_keep_out_m, distance_to_keep_in_edge_m) −
    /// footprint_radius_m`. Negative when the footprint already touches a forbidden area;
    /// `f64::INFINITY` when there are no zones.
    ///
    /// # Units
    /// Metres.
    #[must_use]
    pub fn max_uncertainty_m(&self, p: [f64; 2], footprint_radius_m: f64) -> f64 {
        self.clearance(p, footprint_radius_m).max_uncertainty_m
    }

    /// All three distances for one point.
    #[must_use]
    pub fn clearance(&self, p: [f64; 2], footprint_radius_m: f64) -> Clearance {
        let keep_out_distance_m = self.distance_to_keep_out_m(p);
        let keep_in_edge_distance_m = self.distance_to_keep_in_edge_m(p);
        Clearance {
            keep_out_distance_m,
            keep_in_edge_distance_m,
            max_uncertainty_m: keep_out_distance_m.min(keep_in_edge_distance_m)
                - footprint_radius_m,
        }
    }

    /// [`ZoneSet::clearance`] for many points, in parallel; the result (in input order) does not
    /// depend on the number of threads.
    #[must_use]
    pub fn clearances(&self, points: &[[f64; 2]], footprint_radius_m: f64) -> Vec<Clearance> {
        points
            .par_iter()
            .map(|&p| self.clearance(p, footprint_radius_m))
            .collect()
    }

    /// Rasterise the zones onto a `width × height` grid placed by `geo` (row 0 north; see
    /// [`raster`](crate::raster)). Returns `(keep_out, keep_in)`, each `width * height` cells
    /// row-major: a keep-out cell has its centre inside some keep-out zone; a keep-in cell has its
    /// centre inside the keep-in union, and all cells are keep-in when there are no keep-ins.
    /// Centres exactly on an edge may fall either way. A non-positive or non-finite resolution
    /// marks no cell.
    ///
    /// # Panics
    /// If `width * height` overflows `usize`.
    #[must_use]
    pub fn rasterize(
        &self,
        geo: GeoTransform,
        width: usize,
        height: usize,
    ) -> (Vec<bool>, Vec<bool>) {
        let cells = width
            .checked_mul(height)
            .unwrap_or_else(|| panic!("raster of {width} x {height} cells is too large"));
        let mut keep_out = vec![false; cells];
        rasterization::fill_polygons(&self.keep_out, geo, width, &mut keep_out);
        let keep_in = if self.keep_in.is_empty() {
            vec![true; cells]
        } else {
            let mut keep_in = vec![false; cells];
            rasterization::fill_polygons(&self.keep_in, geo, width, &mut keep_in);
            keep_in
        };
        (keep_out, keep_in)
    }
}

fn is_finite(p: [f64; 2]) -> bool {
    p[0].is_finite() && p[1].is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(features: &str) -> ZoneSet {
        let text = format!(r#"{{"type": "FeatureCollection", "features": [{features}]}}"#);
        ZoneSet::from_geojson_str(&text, Path::new("t.geojson")).expect("valid zones")
    }

    fn square_feature(kind: &str, x0: f64, y0: f64, side: f64) -> String {
        let (x1, y1) = (x0 + side, y0 + side);
        format!(
            r#"{{"type": "Feature", "properties": {{"kind": "{kind}"}}, "geometry": {{"type": "Polygon",
               "coordinates": [[[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}], [{x0}, {y0}]]]}}}}"#
        )
    }

    #[test]
    fn empty_set_allows_everything() {
        let zones = ZoneSet::default();
        assert!(zones.is_empty());
        assert_eq!(zones.distance_to_keep_out_m([1.0, 2.0]), f64::INFINITY);
        assert_eq!(zones.distance_to_keep_in_edge_m([1.0, 2.0]), f64::INFINITY);
        assert_eq!(zones.max_uncertainty_m([1.0, 2.0], 3.0), f64::INFINITY);
        assert!(zones.in_keep_in([1.0, 2.0]));
        assert!(!zones.in_keep_out([1.0, 2.0]));
        let (out, inside) = zones.rasterize(GeoTransform::new(0.0, 3.0, 1.0), 3, 3);
        assert_eq!((out, inside), (vec![false; 9], vec![true; 9]));
        assert_eq!(set("").len(), 0);
    }

    #[test]
    fn non_finite_points_give_nan() {
        let zones = set(&square_feature("keep_in", 0.0, 0.0, 10.0));
        assert!(zones.distance_to_keep_out_m([f64::NAN, 0.0]).is_nan());
        assert!(
            zones
                .distance_to_keep_in_edge_m([0.0, f64::INFINITY])
                .is_nan()
        );
        assert!(!zones.in_keep_in([f64::NAN, 1.0]));
    }

    #[test]
    fn handles_and_kinds() {
        let zones = set(&format!(
            "{}, {}",
            square_feature("keep_out", 0.0, 0.0, 1.0),
            square_feature("KEEP-IN", -5.0, -5.0, 20.0)
        ));
        assert_eq!(zones.len(), 2);
        let (h, z) = zones.keep_ins().next().expect("one keep-in");
        assert_eq!(
            (h.index(), z.name(), z.kind(), z.feature_index()),
            (1, "zone-1", ZoneKind::KeepIn, 1)
        );
        assert_eq!(zones.get(h), Some(z));
        assert_eq!(zones.get(ZoneHandle(7)), None);
        assert_eq!(zones.keep_outs().count(), 1);
        assert_eq!(zones.source(), Path::new("t.geojson"));
        assert_eq!(ZoneKind::KeepOut.to_string(), "keep_out");
    }

    #[test]
    fn rasterize_matches_point_queries() {
        let zones = set(&format!(
            "{}, {}, {}",
            square_feature("keep_out", 2.3, 2.2, 3.1),
            square_feature("keep_in", 0.4, 0.3, 6.05),
            square_feature("keep_in", 4.1, 4.2, 5.5)
        ));
        let geo = GeoTransform::new(-1.0, 11.0, 0.25);
        let (w, h) = (48, 50);
        let (out, inside) = zones.rasterize(geo, w, h);
        for row in 0..h {
            for col in 0..w {
                let (x, y) = geo.center_of(col, row);
                assert_eq!(
                    out[row * w + col],
                    zones.in_keep_out([x, y]),
                    "keep-out at {col},{row}"
                );
                assert_eq!(
                    inside[row * w + col],
                    zones.in_keep_in([x, y]),
                    "keep-in at {col},{row}"
                );
            }
        }
        assert!(out.iter().any(|&c| c) && inside.iter().any(|&c| !c));
        let (out, _) = zones.rasterize(GeoTransform::new(0.0, 0.0, f64::NAN), 4, 4);
        assert_eq!(out, vec![false; 16]);
    }
}
