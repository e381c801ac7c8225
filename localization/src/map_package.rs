//! The onboard map package of a route: the 25 cm orthoimage and the 1 m DEM, masked to a
//! corridor around the strategic route, the DEM as 16-bit centimetres, compressed losslessly
//! (paper 000 §5: "any parts of the map that are not within a 100m radius of the upcoming
//! strategic route are masked out", "the DEM elevations are discretized to 1cm resolution and
//! converted to a 16-bit image", "the appearance map resolution is optionally reduced, for
//! example to 50cm", "the total file size is on the order of a few megabytes").
//!
//! This module renders the package and describes it ([`MapPackage`]): it hands back each
//! file's name and bytes, and the caller writes them (`solsim map package` writes them as one
//! output set, swapped into place whole). The layout — output tiles, render blocks, the
//! corridor mask — is [`maps::package`]'s; the seeds of a scenario's package come from the
//! simulator's seed derivation (`study::map_package`), so the package shows the same orbital
//! world the simulator's onboard localizer matches against.
//!
//! ## What is rendered
//! The scenario maps are coarse (the bundled ones 4 m/px), so the orbital products are rendered
//! with [`crate::synthetic`]: [`truth_patch`](crate::synthetic::truth_patch) (map DEM plus fine
//! detail, ripples and rocks at 25 cm) and [`render_orbital`](crate::synthetic::render_orbital)
//! (the HiRISE stand-in: 25 cm u8 image, 1 m DEM), block by block along the corridor (the
//! layout is [`maps::package::CorridorLayout`]: output tiles of `--tile-m`, render blocks of
//! [`BLOCK_M`], only those the corridor touches).
//!
//! ## Seamless blocks
//! Every value is a pure function of (seed, map position), so blocks join without seams and the
//! package does not depend on the block size, the tile size, the order or the thread count:
//!
//! - one truth seed and one orbital seed for the whole package ([`RenderSettings`]): the truth
//!   terrain, the between-epoch albedo change, the ripple migration and the orthorectification
//!   displacement are fields of map position under those seeds;
//! - [`render_orbital`](crate::synthetic::render_orbital) draws its sensor noise and DEM noise
//!   by *patch* pixel index, so the blocks are rendered with both at 0 and the same noise (the
//!   same Gaussian draws) is added here by *world* pixel index ([`add_world_noise`]; the sensor
//!   noise is applied after the gamma with the response's local slope, which differs from noise
//!   before quantisation by the extra rounding, < 0.3 DN rms);
//! - dust devil tracks are off: the renderer draws them per patch, so they would stop at block
//!   edges (they are smooth, low-contrast bands: leaving them out changes the compressed size
//!   negligibly);
//! - each block is rendered with [`MARGIN_M`] of terrain around it and cropped, so cast shadows,
//!   the PSF and the ortho displacement near a block edge see the same terrain as in the middle
//!   (shadows longer than the margin would be cut; at 35° sun elevation the margin covers
//!   obstacles up to 0.7 × [`MARGIN_M`] high). At the map's own edge the patch is shifted
//!   inwards, so the outermost pixels lack that context.
//!
//! ## Package format
//! - `appearance_rRR_cCCC.png`: 8-bit gray, `--resolution-m` pixels, 0 = outside the corridor
//!   (a rendered 0 inside is stored as 1);
//! - `dem_cm_rRR_cCCC.png`: 16-bit gray, 1 m pixels, centimetres above `datum_m`, 0 = outside
//!   (a height exactly at the datum is stored as 1 cm);
//! - beside each PNG, its georeference for GDAL and QGIS (ground-side aids, not part of the
//!   uplinked bytes in `png_bytes`): `<name>.pgw`, a world file placing its pixels in map
//!   metres ([`maps::raster_io::world_file`]), and `<name>.png.aux.xml`, a GDAL PAM file naming
//!   the map's Mars CRS ([`maps::raster_io::pam_aux_xml`]; a map without one is placed at
//!   [`maps::mars_crs::DEFAULT_ANCHOR`]), so `gdalinfo` reports each tile's CRS and extent;
//! - [`MANIFEST_FILE`]: georeference (map metres, x east, y north; each tile's north-west
//!   corner; the CRS those metres are projected coordinates of, and the bounding box in Mars
//!   longitude/latitude), corridor, route, datum, sizes, pixel counts and the MD5 of every PNG,
//!   and the render seeds and parameters.
//!
//! PNG, because no lossless JPEG-XL encoder is in the dependency set (the paper's JPEG-XL is
//! "typically half the size of PNG").

mod assembly;
mod error;
mod manifest;
mod render;

pub use assembly::{MapPackage, PackageOptions, PackageSource};
pub use error::MapPackageError;
pub use manifest::{MANIFEST_FILE, ManifestTile, PackageFile, PackageSummary, summary_text};
pub use render::{BLOCK_M, MARGIN_M, RenderSettings, add_world_noise, render_block};
