//! Onboard map packages: the orbital map masked to a corridor around the strategic route, the DEM
//! as 16-bit centimetres, compressed losslessly (PNG) — what would be uplinked for onboard global
//! localization (paper 000 §5: "a few megabytes" for a long traverse).
//!
//! Pixels farther than the corridor half-width from the route polyline are set to 0 (no data), so
//! the lossless encoder spends almost nothing on them; the package keeps full resolution inside.
//! A long route is cut into output tiles and render blocks so that nothing is allocated for its
//! whole bounding box.
//!
//! - [`CorridorLayout`] (in `layout`): the tiles and render blocks of a corridor, and
//!   [`CorridorLayout::assemble_tile`], which renders, bins, masks and converts one tile
//!   ([`TileSpec`], [`BlockRequest`], [`TileRasters`]);
//! - corridor geometry (in `corridor`): [`distance_to_route_m`], [`distance_rect_to_route_m`];
//! - binning (in `binning`): [`bin_mean_u8`], the 25 cm render reduced to 0.5 or 1 m;
//! - [`PackageError`]: why a corridor cannot be laid out or a tile assembled.
//!
//! The PNG encoder the tiles are written with is [`crate::raster_io::encode_png`].

mod binning;
mod corridor;
mod error;
mod layout;

pub use binning::bin_mean_u8;
pub use corridor::{distance_rect_to_route_m, distance_to_route_m};
pub use error::PackageError;
pub use layout::{BlockRequest, CorridorLayout, TileRasters, TileSpec};

/// Pixel size of the package DEM, metres (the HiRISE DTM; paper 000 §5).
pub const PACKAGE_DEM_RESOLUTION_M: f64 = 1.0;

/// Pixel size of the rendered orbital appearance that a layout bins from, metres.
pub const RENDER_RESOLUTION_M: f64 = 0.25;
