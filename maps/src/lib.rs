//! # maps — the orbital map side of solsim
//!
//! - [`raster`]: georeferenced rasters ([`GeoTransform`], [`Raster`]); conventions for map metres
//!   (x east, y north) and pixel rows (row 0 = north edge) live there, once.
//! - [`terrain`]: terrain classes ([`TerrainClass`]: sand, soil, bedrock).
//! - [`raster_io`]: PNG and GeoTIFF readers and writers (appearance u8, DEM as 16-bit cm or f32 m,
//!   terrain class u8) and [`MapLayers`], the three layers of one map.
//! - [`input_file`]: reading inputs safely (regular files only, a size cap).
//! - [`mars_crs`]: where a map lies on Mars ([`MapCrs`], [`MarsEquirectangular`]): the IAU 2015
//!   Mars sphere in the Jezero equirectangular projection, whose metres are map metres; WKT for
//!   GDAL and `.prj` files.
//! - [`memory_budget`]: one memory budget per command ([`MemoryBudget`]), checked from sizes
//!   and raster headers before allocating.
//! - [`package`]: onboard map packages: the maps masked to a corridor around the route, PNG.
//! - [`procedural`]: the seeded terrain generator the bundled scenario maps come from.
//! - [`zone`]: keep-in / keep-out zones ([`ZoneSet`]) read from GeoJSON, with exact distance
//!   queries (how far a point is from the nearest keep-out and from the keep-in edge).
//! - [`zone_check`]: named points checked against a [`ZoneSet`] (`solsim zones check`), as a
//!   table or JSON.
//!
//! ```
//! use maps::{GeoTransform, Raster};
//!
//! // A 10 m × 10 m raster of 1 m pixels whose north-west corner is at (100 m E, 500 m N).
//! let geo = GeoTransform::new(100.0, 500.0, 1.0);
//! let mut r = Raster::filled(10, 10, geo, 0u8);
//! r.set(2, 0, 7); // column 2 of the north row
//! assert_eq!(r.sample_nearest(102.5, 499.5), Some(7));
//! assert_eq!(geo.center_of(2, 0), (102.5, 499.5));
//! assert_eq!(r.sample_nearest(99.0, 499.5), None); // west of the map
//! ```
#![warn(missing_docs)]

pub mod input_file;
pub mod mars_crs;
pub mod memory_budget;
pub mod names;
pub mod package;
pub mod procedural;
pub mod raster;
pub mod raster_io;
pub mod terrain;
pub mod zone;
pub mod zone_check;

pub use mars_crs::{MapAnchor, MapCrs, MarsEquirectangular};
pub use memory_budget::MemoryBudget;
pub use raster::{GeoTransform, Raster};
pub use raster_io::{MapLayers, RasterError};
pub use terrain::{PerTerrain, TerrainClass};
pub use zone::{Clearance, Zone, ZoneError, ZoneHandle, ZoneKind, ZoneSet, json_kind};
