//! [`ZoneError`]: everything that can be wrong with a zones file, each with the file, the feature
//! and the field to fix.

use std::fmt;
use std::path::PathBuf;

/// Why a zones file was rejected.
///
/// Every variant names the file (`path`); those about one feature also carry its index in
/// `features`, its name (`name`, or `zone-<index>` when it has none) and the offending `field` as a
/// path inside the feature, e.g. `geometry.coordinates[0][5]`. The message is a single line:
///
/// ```text
/// zones/x.geojson: features[2] ("dune west").geometry: ring 0 crosses itself at (120.5, 33.0); expected a simple polygon
/// ```
///
/// The message is complete on its own: underlying I/O and JSON errors are quoted in it rather than
/// chained as `source()`, so printing the error (or an `anyhow` chain of it) says everything once.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ZoneError {
    /// The file could not be read.
    #[error("{}: {}", path.display(), crate::input_file::excerpt(&error.to_string(), 200))]
    Io {
        /// The zones file.
        path: PathBuf,
        /// Why it was not read: the operating system's error, not a regular file, too large,
        /// not UTF-8 (part of the message, so not also a `source`).
        error: crate::input_file::InputFileError,
    },

    /// The file is not JSON (the message gives the line and column).
    #[error("{}: invalid JSON: {}", path.display(), crate::input_file::excerpt(&error.to_string(), 200))]
    InvalidJson {
        /// The zones file.
        path: PathBuf,
        /// The parser's complaint, with line and column.
        error: serde_json::Error,
    },

    /// The top level is not a GeoJSON FeatureCollection with a `features` array.
    #[error(
        "{}: {field}: expected a GeoJSON FeatureCollection with a \"features\" array, found {}",
        path.display(), crate::input_file::excerpt(found, 80)
    )]
    NotFeatureCollection {
        /// The zones file.
        path: PathBuf,
        /// `type` or `features`.
        field: String,
        /// What was there instead, e.g. `"Feature"` or `no "type"`.
        found: String,
    },

    /// More features than a [`ZoneHandle`](super::ZoneHandle) can index (2³²).
    #[error("{}: features: {count} features; at most 4294967295 are supported", path.display())]
    TooManyZones {
        /// The zones file.
        path: PathBuf,
        /// How many features the file has.
        count: usize,
    },

    /// A feature is not valid GeoJSON (e.g. not `"type": "Feature"`, or a position with fewer than
    /// two numbers).
    #[error("{}: features[{feature}] ({}): invalid GeoJSON Feature: {}", path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80), crate::input_file::excerpt(&error.to_string(), 200))]
    InvalidFeature {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The GeoJSON reader's complaint.
        error: serde_json::Error,
    },

    /// A feature's `properties.name` is present but not a string.
    #[error("{}: features[{feature}].properties.name: expected a string, found {}", path.display(), crate::input_file::excerpt(found, 80))]
    InvalidName {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The JSON value found.
        found: String,
    },

    /// A feature's `properties.name` holds a control character (ESC, NUL, a newline …) or a
    /// bidirectional override: names are printed in messages and written into reports.
    #[error("{}: features[{feature}].properties.name: expected text without control characters, got {}", path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80))]
    UnsafeName {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The name as written.
        name: String,
    },

    /// A feature has `"geometry": null`.
    #[error("{}: features[{feature}] ({}).geometry: missing; expected a Polygon or MultiPolygon", path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80))]
    MissingGeometry {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
    },

    /// A feature's geometry is neither a Polygon nor a MultiPolygon.
    #[error(
        "{}: features[{feature}] ({}).geometry.type: unsupported geometry {}; expected \"Polygon\" or \"MultiPolygon\"",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80), crate::input_file::excerpt(&format!("{found:?}"), 80)
    )]
    UnsupportedGeometry {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The geometry type found, e.g. `LineString`.
        found: String,
    },

    /// A feature has no `properties.kind`.
    #[error(
        "{}: features[{feature}] ({}).properties.kind: missing{}; expected \"keep_in\" or \"keep_out\"",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80),
        misspelt.as_ref().map_or(String::new(), |k| format!(
            " (the properties have `{}`: did you mean `kind`?)", crate::input_file::excerpt(k, 80)
        ))
    )]
    MissingKind {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// A property key that misspells `kind` (`knd`, `Kind`), if one does.
        misspelt: Option<String>,
    },

    /// A feature's `properties.kind` is not one of the known kinds.
    #[error(
        "{}: features[{feature}] ({}).properties.kind: unknown kind {}; expected \"keep_in\" or \"keep_out\"",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80), crate::input_file::excerpt(found, 80)
    )]
    UnknownKind {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The JSON value found, e.g. `"keep_near"`.
        found: String,
    },

    /// A polygon has no rings (`"coordinates": []`).
    #[error("{}: features[{feature}] ({}).{field}: polygon has no rings", path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80))]
    EmptyPolygon {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The polygon, e.g. `geometry.coordinates` or `geometry.coordinates[1]`.
        field: String,
    },

    /// A MultiPolygon has no polygons (`"coordinates": []`): a zone with no area.
    #[error(
        "{}: features[{feature}] ({}).geometry.coordinates: MultiPolygon has no polygons; expected at least one",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80)
    )]
    EmptyMultiPolygon {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
    },

    /// A coordinate is NaN or infinite (a `NaN` or `Infinity` literal, as some JSON writers emit).
    #[error(
        "{}: features[{feature}] ({}).{field}: {axis} is {value}; expected a finite number of metres",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80)
    )]
    NonFiniteCoordinate {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The position, e.g. `geometry.coordinates[0][5]`.
        field: String,
        /// `x`, `y` or `z`.
        axis: &'static str,
        /// The literal found: `NaN`, `Infinity` or `-Infinity`.
        value: String,
    },

    /// A coordinate is finite but off any Mars map (beyond [`crate::zone::MAX_COORDINATE_M`]):
    /// distances to it would lose every digit of a metre.
    #[error(
        "{}: features[{feature}] ({}).{field}: expected {axis} within ±{} m (map metres on Mars), got {value:e}",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80), crate::zone::MAX_COORDINATE_M
    )]
    CoordinateOutOfRange {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The number's position, e.g. `geometry.coordinates[0][5][0]`.
        field: String,
        /// `x`, `y` or `z`.
        axis: &'static str,
        /// The value found.
        value: f64,
    },

    /// The keep-in polygons have more vertices together than
    /// [`crate::zone::MAX_KEEP_IN_VERTICES`].
    #[error(
        "{}: keep_in zones: expected at most {} vertices in all keep-in polygons together, got {vertices}",
        path.display(), crate::zone::MAX_KEEP_IN_VERTICES
    )]
    TooManyKeepInVertices {
        /// The zones file.
        path: PathBuf,
        /// How many there are.
        vertices: usize,
    },

    /// The polygons have more vertices together than [`crate::zone::MAX_ZONE_VERTICES`].
    #[error(
        "{}: features: expected at most {} vertices in all polygons together, got {vertices}",
        path.display(), crate::zone::MAX_ZONE_VERTICES
    )]
    TooManyVertices {
        /// The zones file.
        path: PathBuf,
        /// How many there are (closing positions included).
        vertices: usize,
    },

    /// The file has more polygons than [`crate::zone::MAX_ZONE_POLYGONS`].
    #[error(
        "{}: features: expected at most {} polygons in all zones together, got {polygons}",
        path.display(), crate::zone::MAX_ZONE_POLYGONS
    )]
    TooManyPolygons {
        /// The zones file.
        path: PathBuf,
        /// How many there are (each part of a MultiPolygon counts).
        polygons: usize,
    },

    /// The zones' geometry ([`crate::ZoneSet::memory_bytes`]) does not fit the memory budget
    /// beside what the command already holds.
    #[error(
        "{}: features: expected zones whose geometry fits the memory budget of {} (--memory-budget-mib) beside the {} the maps and planning grid hold, got {vertices} vertices in {polygons} polygons, which need {}",
        path.display(),
        crate::input_file::human_bytes(budget.limit_bytes),
        crate::input_file::human_bytes(*held_bytes),
        crate::input_file::human_bytes(*need_bytes)
    )]
    OverBudget {
        /// The zones file.
        path: PathBuf,
        /// Polygons in the file.
        polygons: usize,
        /// Vertices in the file.
        vertices: usize,
        /// What the zones need, bytes.
        need_bytes: u64,
        /// What the command already holds, bytes.
        held_bytes: u64,
        /// The budget.
        budget: crate::MemoryBudget,
    },

    /// A position is not two numbers: fewer, or a third (an altitude, which zones do not use).
    #[error(
        "{}: features[{feature}] ({}).{field}: position has {len} number(s); expected [x, y] in metres (no altitude)",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80)
    )]
    PositionNotXy {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The position, e.g. `geometry.coordinates[0][5]`.
        field: String,
        /// How many numbers it has.
        len: usize,
    },

    /// A ring has fewer than the 4 positions GeoJSON requires.
    #[error(
        "{}: features[{feature}] ({}).{field}: ring has {positions} positions; expected at least 4 (first = last)",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80)
    )]
    RingTooShort {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The ring, e.g. `geometry.coordinates[0]`.
        field: String,
        /// How many positions it has.
        positions: usize,
    },

    /// A ring does not end where it starts (GeoJSON rings are explicitly closed).
    #[error(
        "{}: features[{feature}] ({}).{field}: ring is not closed: starts at {} but ends at {}; repeat the first position at the end",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80), Xy(*first), Xy(*last)
    )]
    RingNotClosed {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The ring, e.g. `geometry.coordinates[0]`.
        field: String,
        /// Its first position.
        first: [f64; 2],
        /// Its last position.
        last: [f64; 2],
    },

    /// A ring encloses no area: fewer than 3 distinct vertices, or all on one line.
    #[error(
        "{}: features[{feature}] ({}).{field}: ring encloses zero area; expected at least 3 vertices not on one line",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80)
    )]
    ZeroAreaRing {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The ring, e.g. `geometry.coordinates[1]`.
        field: String,
    },

    /// A ring crosses, touches or doubles back on itself (a bow-tie, a figure eight, a spike).
    #[error(
        "{}: features[{feature}] ({}).{field}: ring {ring} crosses itself at {}; expected a simple polygon",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80), Xy(*at)
    )]
    SelfIntersection {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The polygon, e.g. `geometry` or `geometry.coordinates[2]` in a MultiPolygon.
        field: String,
        /// The ring (0 = outer ring, 1… = holes).
        ring: usize,
        /// Where (map metres).
        at: [f64; 2],
    },

    /// Two rings of a polygon cross or share part of an edge (e.g. a hole crossing its shell).
    #[error(
        "{}: features[{feature}] ({}).{field}: ring {ring_a} crosses ring {ring_b} at {}; rings may only touch at single points",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80), Xy(*at)
    )]
    RingsCross {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The polygon, e.g. `geometry`.
        field: String,
        /// The later ring.
        ring_a: usize,
        /// The earlier ring (0 = outer ring).
        ring_b: usize,
        /// Where (map metres).
        at: [f64; 2],
    },

    /// A hole is not inside its polygon's outer ring.
    #[error(
        "{}: features[{feature}] ({}).{field}: hole (ring {ring}) lies outside the outer ring; expected holes inside ring 0",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80)
    )]
    HoleOutsideShell {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The polygon, e.g. `geometry`.
        field: String,
        /// The hole's ring index.
        ring: usize,
    },

    /// One hole of a polygon lies inside another.
    #[error(
        "{}: features[{feature}] ({}).{field}: holes (rings {ring_a} and {ring_b}) overlap; expected disjoint holes",
        path.display(), crate::input_file::excerpt(&format!("{name:?}"), 80)
    )]
    HolesOverlap {
        /// The zones file.
        path: PathBuf,
        /// Index in `features`.
        feature: usize,
        /// The feature's name, or `zone-<index>`.
        name: String,
        /// The polygon, e.g. `geometry`.
        field: String,
        /// One hole's ring index.
        ring_a: usize,
        /// The other's.
        ring_b: usize,
    },
}

/// Formats a point as `(x, y)` with the shortest round-tripping decimals.
pub(super) struct Xy(pub [f64; 2]);

impl fmt::Display for Xy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({:?}, {:?})", self.0[0], self.0[1])
    }
}
