//! Why a tiled corridor package cannot be laid out or assembled.

use crate::raster_io::RasterError;

/// Why a tiled corridor package cannot be laid out or assembled.
#[derive(Debug, thiserror::Error)]
pub enum PackageError {
    /// A layout parameter is out of range.
    #[error("{field}: expected {expected}, got {got}")]
    Invalid {
        /// The parameter (named as on the command line).
        field: &'static str,
        /// What is allowed.
        expected: &'static str,
        /// The value given.
        got: String,
    },
    /// The corridor does not touch the map.
    #[error("the corridor {corridor_m:?} (x0, y0, x1, y1 in m) does not overlap the map {map_m:?}")]
    OffMap {
        /// Corridor bounding box, metres.
        corridor_m: [f64; 4],
        /// Map extent, metres.
        map_m: [f64; 4],
    },
    /// A rendered block does not have the size that was asked for.
    #[error(
        "block at {origin_m:?} m rendered as {got:?} px (appearance, DEM), expected {expected:?}"
    )]
    BlockSize {
        /// North-west corner of the block, metres.
        origin_m: [f64; 2],
        /// Expected `[appearance width, appearance height, DEM width, DEM height]`, pixels.
        expected: [usize; 4],
        /// What the renderer returned, same order.
        got: [usize; 4],
    },
    /// A raster error (a DEM height the 16-bit centimetre format cannot hold, an encoder error).
    #[error(transparent)]
    Raster(#[from] RasterError),
}
