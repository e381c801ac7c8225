//! How a long corridor is cut into output tiles and render blocks, and how a tile is assembled
//! from its rendered blocks: binned, masked to the corridor and converted to centimetres.

use std::path::Path;

use super::binning::bin_mean_u8;
use super::corridor::{distance_rect_to_route_m, mask_in_place, row_mask};
use super::{PACKAGE_DEM_RESOLUTION_M, PackageError, RENDER_RESOLUTION_M};
use crate::raster::{GeoTransform, Raster};
use crate::raster_io::RasterError;

/// One output tile of a [`CorridorLayout`]: a rectangle of whole metres on the DEM lattice.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TileSpec {
    /// Tile row (0 = northmost) in the layout's grid.
    pub row: usize,
    /// Tile column (0 = westmost).
    pub col: usize,
    /// North-west corner, map metres.
    pub origin_m: [f64; 2],
    /// Width and height, whole metres (edge tiles are clipped to the corridor's bounding box).
    pub size_m: [usize; 2],
}

impl TileSpec {
    /// Extent `[x0, y0, x1, y1]`, metres.
    #[must_use]
    pub fn extent_m(&self) -> [f64; 4] {
        let [ox, oy] = self.origin_m;
        [
            ox,
            oy - self.size_m[1] as f64,
            ox + self.size_m[0] as f64,
            oy,
        ]
    }
}

/// A render request: a rectangle of whole metres whose 25 cm appearance and 1 m DEM the caller
/// renders (see [`CorridorLayout::assemble_tile`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockRequest {
    /// North-west corner, map metres (on the DEM lattice).
    pub origin_m: [f64; 2],
    /// Width and height, whole metres.
    pub size_m: [usize; 2],
}

/// One assembled, masked tile, ready to encode.
#[derive(Clone, Debug, PartialEq)]
pub struct TileRasters {
    /// Appearance at the layout's resolution: 0 = outside the corridor, 1..=255 inside (a
    /// rendered 0 is stored as 1, so no data is unambiguous).
    pub appearance: Raster<u8>,
    /// DEM at 1 m: centimetres above the datum, 0 = outside the corridor (a kept height exactly
    /// at the datum is stored as 1 cm).
    pub dem_cm: Raster<u16>,
    /// Pixels inside the corridor (appearance, DEM).
    pub kept_px: [usize; 2],
}

/// How a long corridor is cut into output tiles and render blocks.
///
/// ## Design (memory)
/// A 9 km route on a diagonal has a bounding box of ~6.4 km × 6.4 km: 25600² px ≈ 650 MB of u8
/// at 25 cm, almost all of it masked. The corridor itself (100 m either side) is only ~30 M px.
/// So nothing is ever allocated for the whole bounding box:
///
/// - the box (route ± half-width, clipped to the map, snapped outward to whole metres of the
///   DEM's lattice) is cut into square **output tiles** of `tile_m` metres (edge tiles clipped);
///   only tiles that the corridor touches are kept, each becomes one appearance PNG and one DEM
///   PNG (onboard, the matcher loads only the tiles around the rover);
/// - each tile is assembled from **render blocks** of `block_m` metres on a lattice anchored at
///   the box's north-west corner (so blocks never depend on the tile size); only blocks that
///   the corridor touches are rendered, the rest of the tile stays "no data";
/// - tiles are assembled one at a time, so peak memory is one tile (`tile_m = 1024` at 25 cm:
///   16 MB of u8 plus 4 MB of f32 DEM) plus the blocks in flight.
///
/// PNG has no streaming encoder in the dependency set (`image` encodes whole buffers), which
/// is the other reason the output is tiled rather than one huge mostly-masked image.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CorridorLayout {
    /// The strategic route, map metres.
    pub route: Vec<[f64; 2]>,
    /// Corridor half-width (the paper's "100 m radius of the strategic route"), metres.
    pub half_width_m: f64,
    /// Appearance pixel size, metres: a multiple of the 25 cm render (0.25, 0.5 or 1).
    pub appearance_resolution_m: f64,
    /// North-west corner of the corridor's bounding box, map metres.
    pub origin_m: [f64; 2],
    /// Bounding box width and height, whole metres.
    pub size_m: [usize; 2],
    /// Output tile side, whole metres.
    pub tile_m: usize,
    /// Render block side, whole metres.
    pub block_m: usize,
    /// Output tiles the corridor touches, row-major from the north-west.
    pub tiles: Vec<TileSpec>,
}

impl CorridorLayout {
    /// Lays out the corridor of half-width `half_width_m` around `route` on a map of extent
    /// `map_extent_m` (`(x0, y0, x1, y1)`), with whole metres counted from `lattice_origin_m`
    /// (the map DEM's north-west corner).
    ///
    /// # Errors
    /// [`PackageError::Invalid`] for an empty route, a non-positive or non-finite half-width,
    /// an appearance resolution other than 0.25, 0.5 or 1 m, or zero tile / block sizes;
    /// [`PackageError::OffMap`] if the corridor misses the map.
    pub fn new(
        route: &[[f64; 2]],
        half_width_m: f64,
        appearance_resolution_m: f64,
        map_extent_m: (f64, f64, f64, f64),
        lattice_origin_m: [f64; 2],
        tile_m: usize,
        block_m: usize,
    ) -> Result<Self, PackageError> {
        let invalid = |field, expected, got: String| {
            Err(PackageError::Invalid {
                field,
                expected,
                got,
            })
        };
        if route.is_empty() || route.iter().flatten().any(|v| !v.is_finite()) {
            return invalid(
                "route",
                "at least one finite waypoint",
                format!("{route:?}"),
            );
        }
        if !(half_width_m.is_finite() && half_width_m > 0.0) {
            return invalid(
                "--corridor-m",
                "a positive number of metres",
                half_width_m.to_string(),
            );
        }
        if bin_factor(appearance_resolution_m).is_none() {
            return invalid(
                "--resolution-m",
                "0.25, 0.5 or 1 (the 25 cm orthoimage binned 1×1, 2×2 or 4×4)",
                appearance_resolution_m.to_string(),
            );
        }
        if tile_m == 0 || tile_m > 4096 {
            return invalid("--tile-m", "1 ..= 4096 metres", tile_m.to_string());
        }
        if block_m == 0 {
            return invalid("--block-m", "at least 1 metre", block_m.to_string());
        }
        let (mx0, my0, mx1, my1) = map_extent_m;
        let xs = route.iter().map(|p| p[0]);
        let ys = route.iter().map(|p| p[1]);
        let corridor = [
            xs.clone().fold(f64::INFINITY, f64::min) - half_width_m,
            ys.clone().fold(f64::INFINITY, f64::min) - half_width_m,
            xs.fold(f64::NEG_INFINITY, f64::max) + half_width_m,
            ys.fold(f64::NEG_INFINITY, f64::max) + half_width_m,
        ];
        let [lx, ly] = lattice_origin_m;
        // Whole metres from the lattice origin: outward for the corridor, inward for the map.
        let x0 = (corridor[0] - lx).floor().max((mx0 - lx - 1e-9).ceil());
        let x1 = (corridor[2] - lx).ceil().min((mx1 - lx + 1e-9).floor());
        let y0 = (ly - corridor[3]).floor().max((ly - my1 - 1e-9).ceil()); // metres south of ly
        let y1 = (ly - corridor[1]).ceil().min((ly - my0 + 1e-9).floor());
        if !(x1 > x0 && y1 > y0) {
            return Err(PackageError::OffMap {
                corridor_m: corridor,
                map_m: [mx0, my0, mx1, my1],
            });
        }
        let origin_m = [lx + x0, ly - y0];
        let size_m = [(x1 - x0) as usize, (y1 - y0) as usize];
        let mut layout = Self {
            route: route.to_vec(),
            half_width_m,
            appearance_resolution_m,
            origin_m,
            size_m,
            tile_m,
            block_m,
            tiles: Vec::new(),
        };
        for row in 0..size_m[1].div_ceil(tile_m) {
            for col in 0..size_m[0].div_ceil(tile_m) {
                let tile = TileSpec {
                    row,
                    col,
                    origin_m: [
                        origin_m[0] + (col * tile_m) as f64,
                        origin_m[1] - (row * tile_m) as f64,
                    ],
                    size_m: [
                        tile_m.min(size_m[0] - col * tile_m),
                        tile_m.min(size_m[1] - row * tile_m),
                    ],
                };
                if layout.touches(tile.extent_m()) {
                    layout.tiles.push(tile);
                }
            }
        }
        Ok(layout)
    }

    /// Whether the corridor reaches into the rectangle `[x0, y0, x1, y1]` (closed).
    #[must_use]
    pub fn touches(&self, rect: [f64; 4]) -> bool {
        distance_rect_to_route_m(rect, &self.route) <= self.half_width_m
    }

    /// The render blocks of `tile` that the corridor touches: the block lattice (side
    /// `block_m`, anchored at the layout's north-west corner) clipped to the tile.
    #[must_use]
    pub fn blocks(&self, tile: &TileSpec) -> Vec<BlockRequest> {
        let b = self.block_m;
        // Tile offsets from the layout origin, whole metres.
        let tx = (tile.origin_m[0] - self.origin_m[0]).round() as usize;
        let ty = (self.origin_m[1] - tile.origin_m[1]).round() as usize;
        let mut out = Vec::new();
        for by in (ty / b)..(ty + tile.size_m[1]).div_ceil(b) {
            for bx in (tx / b)..(tx + tile.size_m[0]).div_ceil(b) {
                let (x0, x1) = ((bx * b).max(tx), ((bx + 1) * b).min(tx + tile.size_m[0]));
                let (y0, y1) = ((by * b).max(ty), ((by + 1) * b).min(ty + tile.size_m[1]));
                let req = BlockRequest {
                    origin_m: [self.origin_m[0] + x0 as f64, self.origin_m[1] - y0 as f64],
                    size_m: [x1 - x0, y1 - y0],
                };
                let [ox, oy] = req.origin_m;
                if self.touches([ox, oy - req.size_m[1] as f64, ox + req.size_m[0] as f64, oy]) {
                    out.push(req);
                }
            }
        }
        out
    }

    /// Appearance pixels per metre.
    fn app_px_per_m(&self) -> usize {
        (1.0 / self.appearance_resolution_m).round() as usize
    }

    /// Renders the blocks of `tile` (in parallel) with `render`, which returns the 25 cm
    /// appearance ([`RENDER_RESOLUTION_M`]) and the 1 m DEM of a [`BlockRequest`] with its
    /// north-west corner at the request's; bins the appearance to the layout's resolution,
    /// masks both to the corridor and converts the DEM to centimetres above `datum_m`.
    /// `dem_path` names the DEM file in errors.
    ///
    /// The result depends on the blocks only through `render`: if `render` is a pure function
    /// of map position (as the synthetic orbital renderer with a margin is), the tile is
    /// independent of the block and tile sizes and of the thread count.
    ///
    /// # Errors
    /// The first error of `render`; converted into `E`: [`PackageError::BlockSize`] for a block rendered at
    /// the wrong size; [`PackageError::Raster`] with [`RasterError::HeightOutOfRange`] /
    /// [`RasterError::NonFinite`] for a kept height the 16-bit cm format cannot hold.
    pub fn assemble_tile<E, F>(
        &self,
        tile: &TileSpec,
        datum_m: f64,
        dem_path: &Path,
        render: F,
    ) -> Result<TileRasters, E>
    where
        E: Send + From<PackageError>,
        F: Fn(&BlockRequest) -> Result<(Raster<u8>, Raster<f32>), E> + Sync,
    {
        use rayon::prelude::*;
        let blocks = self.blocks(tile);
        let rendered: Vec<(BlockRequest, Raster<u8>, Raster<f32>)> = blocks
            .par_iter()
            .map(|b| render(b).map(|(a, d)| (*b, a, d)))
            .collect::<Result<_, E>>()?;
        Ok(self.paste(tile, datum_m, dem_path, &rendered)?)
    }

    /// Pastes rendered blocks into a tile, then masks and converts it.
    fn paste(
        &self,
        tile: &TileSpec,
        datum_m: f64,
        dem_path: &Path,
        rendered: &[(BlockRequest, Raster<u8>, Raster<f32>)],
    ) -> Result<TileRasters, PackageError> {
        let k = self.app_px_per_m();
        let render_k = (1.0 / RENDER_RESOLUTION_M).round() as usize;
        let bin = render_k / k;
        let [tw, th] = tile.size_m;
        let app_geo = GeoTransform::new(
            tile.origin_m[0],
            tile.origin_m[1],
            self.appearance_resolution_m,
        );
        let dem_geo =
            GeoTransform::new(tile.origin_m[0], tile.origin_m[1], PACKAGE_DEM_RESOLUTION_M);
        let mut app = Raster::filled(tw * k, th * k, app_geo, 0u8);
        let mut dem = Raster::filled(tw, th, dem_geo, f32::NAN);
        for (b, a, d) in rendered {
            let expected = [
                b.size_m[0] * render_k,
                b.size_m[1] * render_k,
                b.size_m[0],
                b.size_m[1],
            ];
            let got = [a.width, a.height, d.width, d.height];
            if got != expected || a.data.len() != a.width * a.height {
                return Err(PackageError::BlockSize {
                    origin_m: b.origin_m,
                    expected,
                    got,
                });
            }
            let c0 = (b.origin_m[0] - tile.origin_m[0]).round() as usize;
            let r0 = (tile.origin_m[1] - b.origin_m[1]).round() as usize;
            let binned = bin_mean_u8(a, bin);
            for row in 0..binned.height {
                let dst = (r0 * k + row) * app.width + c0 * k;
                app.data[dst..dst + binned.width]
                    .copy_from_slice(&binned.data[row * binned.width..(row + 1) * binned.width]);
            }
            for row in 0..d.height {
                let dst = (r0 + row) * dem.width + c0;
                dem.data[dst..dst + d.width]
                    .copy_from_slice(&d.data[row * d.width..(row + 1) * d.width]);
            }
        }
        let route = &self.route;
        let hw = self.half_width_m;
        let app_kept = mask_in_place(&mut app, route, hw, |v| v.max(1), 0);
        let mut dem_cm = Raster::filled(tw, th, dem_geo, 0u16);
        let mut dem_kept = 0;
        for row in 0..th {
            let keep = row_mask(&dem_geo, row, tw, route, hw);
            for (col, &inside) in keep.iter().enumerate() {
                if !inside {
                    continue;
                }
                let h = dem.data[row * tw + col];
                if !h.is_finite() {
                    return Err(RasterError::NonFinite {
                        path: dem_path.to_path_buf(),
                        pixel: (col, row),
                        value_m: h,
                    }
                    .into());
                }
                let cm = ((f64::from(h) - datum_m) * 100.0).round();
                if !(0.0..=f64::from(u16::MAX)).contains(&cm) {
                    return Err(RasterError::HeightOutOfRange {
                        path: dem_path.to_path_buf(),
                        pixel: (col, row),
                        value_m: h,
                        datum_m,
                    }
                    .into());
                }
                dem_cm.data[row * tw + col] = (cm as u16).max(1);
                dem_kept += 1;
            }
        }
        Ok(TileRasters {
            appearance: app,
            dem_cm,
            kept_px: [app_kept, dem_kept],
        })
    }
}

/// The bin factor from the 25 cm render to `resolution_m` (1, 2 or 4), if allowed.
fn bin_factor(resolution_m: f64) -> Option<usize> {
    [1usize, 2, 4]
        .into_iter()
        .find(|&f| (resolution_m - RENDER_RESOLUTION_M * f as f64).abs() < 1e-9)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::package::distance_to_route_m;

    /// A renderer that is a pure function of map position: appearance from the pixel centre,
    /// DEM heights 100 m + x / 100.
    fn fake_render(req: &BlockRequest) -> Result<(Raster<u8>, Raster<f32>), PackageError> {
        let [w, h] = req.size_m;
        let ageo = GeoTransform::new(req.origin_m[0], req.origin_m[1], 0.25);
        let dgeo = GeoTransform::new(req.origin_m[0], req.origin_m[1], 1.0);
        let mut a = Raster::filled(w * 4, h * 4, ageo, 0u8);
        for row in 0..h * 4 {
            for col in 0..w * 4 {
                let (x, y) = ageo.center_of(col, row);
                a.set(
                    col,
                    row,
                    ((x * 4.0 + y * 12.0) as i64).rem_euclid(256) as u8,
                );
            }
        }
        let mut d = Raster::filled(w, h, dgeo, 0.0f32);
        for row in 0..h {
            for col in 0..w {
                d.set(
                    col,
                    row,
                    100.0 + (dgeo.center_of(col, row).0 / 100.0) as f32,
                );
            }
        }
        Ok((a, d))
    }

    #[test]
    fn layout_keeps_only_tiles_the_corridor_touches_and_blocks_cover_it() {
        let route = [[10.0, 90.0], [290.0, 20.0]];
        let map = (0.0, 0.0, 300.0, 100.0);
        let l = CorridorLayout::new(&route, 8.0, 0.25, map, [0.0, 100.0], 64, 16).unwrap();
        // Route box ± 8 m, clipped to the map: x 2..298, y 12..98.
        assert_eq!(l.origin_m, [2.0, 98.0]);
        assert_eq!(l.size_m, [296, 86]);
        let all = 296usize.div_ceil(64) * 86usize.div_ceil(64);
        assert!(l.tiles.len() < all, "{} of {all}", l.tiles.len());
        for t in &l.tiles {
            let blocks = l.blocks(t);
            assert!(!blocks.is_empty());
            // Every metre cell of the tile whose centre is in the corridor is in a block.
            let [ox, oy] = t.origin_m;
            for r in 0..t.size_m[1] {
                for c in 0..t.size_m[0] {
                    let (x, y) = (ox + c as f64 + 0.5, oy - r as f64 - 0.5);
                    if distance_to_route_m([x, y], &route) <= 8.0 {
                        assert!(blocks.iter().any(|b| {
                            x > b.origin_m[0]
                                && x < b.origin_m[0] + b.size_m[0] as f64
                                && y < b.origin_m[1]
                                && y > b.origin_m[1] - b.size_m[1] as f64
                        }));
                    }
                }
            }
        }
        for (hw, res, tile, block, field) in [
            (0.0, 0.25, 64, 16, "--corridor-m"),
            (f64::NAN, 0.25, 64, 16, "--corridor-m"),
            (8.0, 0.3, 64, 16, "--resolution-m"),
            (8.0, 0.25, 0, 16, "--tile-m"),
            (8.0, 0.25, 64, 0, "--block-m"),
        ] {
            match CorridorLayout::new(&route, hw, res, map, [0.0, 100.0], tile, block) {
                Err(PackageError::Invalid { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{field}: {other:?}"),
            }
        }
        assert!(matches!(
            CorridorLayout::new(&[[500.0, 500.0]], 8.0, 0.25, map, [0.0, 100.0], 64, 16),
            Err(PackageError::OffMap { .. })
        ));
    }

    #[test]
    fn tiles_are_masked_converted_and_independent_of_the_blocks() {
        let route = [[20.0, 50.0], [100.0, 60.0]];
        let map = (0.0, 0.0, 200.0, 100.0);
        let dem_path = Path::new("dem.png");
        let tiles_for = |block_m, res| {
            let l = CorridorLayout::new(&route, 6.0, res, map, [0.0, 100.0], 40, block_m).unwrap();
            l.tiles
                .iter()
                .map(|t| {
                    l.assemble_tile::<PackageError, _>(t, 90.0, dem_path, fake_render)
                        .unwrap()
                })
                .collect::<Vec<_>>()
        };
        let a = tiles_for(16, 0.25);
        assert_eq!(a, tiles_for(7, 0.25));
        let mut kept = 0;
        for t in &a {
            for row in 0..t.dem_cm.height {
                for col in 0..t.dem_cm.width {
                    let (x, y) = t.dem_cm.geo.center_of(col, row);
                    let cm = t.dem_cm.get(col, row);
                    if distance_to_route_m([x, y], &route) <= 6.0 {
                        // 100 m + x / 100 above a 90 m datum, to the centimetre.
                        let h = 100.0 + (x / 100.0) as f32;
                        assert_eq!(cm, ((f64::from(h) - 90.0) * 100.0).round() as u16);
                        kept += 1;
                    } else {
                        assert_eq!(cm, 0);
                    }
                }
            }
            let inside = t.appearance.data.iter().filter(|&&v| v != 0).count();
            assert_eq!(inside, t.kept_px[0]);
        }
        assert_eq!(kept, a.iter().map(|t| t.kept_px[1]).sum::<usize>());
        // 2 × 2 binning: a quarter of the pixels, the DEM unchanged.
        let b = tiles_for(16, 0.5);
        assert_eq!(b[0].appearance.width * 2, a[0].appearance.width);
        assert_eq!(b[0].dem_cm, a[0].dem_cm);
        // A height below the datum is an error naming the DEM file.
        let l = CorridorLayout::new(&route, 6.0, 0.25, map, [0.0, 100.0], 40, 16).unwrap();
        let err = l
            .assemble_tile::<PackageError, _>(&l.tiles[0], 150.0, dem_path, fake_render)
            .unwrap_err();
        assert!(err.to_string().contains("dem.png"), "{err}");
    }
}
