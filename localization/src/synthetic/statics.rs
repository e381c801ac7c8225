//! The seed-independent fields of a map's truth terrain, computed once per tile and shared by
//! every patch rendered from that map.
//!
//! A truth patch ([`super::truth_patch`]) and the orbital epoch of its sand
//! ([`super::render_orbital`]) spend much of their time on values that depend on the map
//! position only, not on the world's seed: the bilinear map-DEM height, the depth of the
//! interdune ring around a sand pixel, and the ripple field at the rover's epoch and at the
//! orbital one. A Monte Carlo study renders thousands of patches of one map with different
//! seeds, so [`TerrainStatics`] keeps those values per 16 m tile of the 25 cm world lattice,
//! built on first use (tiles are filled in parallel, and a tile is the same whichever thread
//! builds it), up to a memory budget. Every value is computed by the same code, from the same
//! map coordinates, as the uncached path, so patches are bit-identical with and without it.
//!
//! The coordinates are the same bits only because they are exact: the patch grid's corner
//! lies on the map DEM's 1 m lattice ([`super::truth_patch`]), and pixel centres are that corner
//! plus multiples of 12.5 cm. [`TerrainStatics`] serves only maps whose DEM corner is a
//! multiple of 1/8 m below 2⁴⁰ m, where those sums have no rounding.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

use maps::{GeoTransform, MapLayers, TerrainClass};
use rayon::prelude::*;

use super::TRUTH_RESOLUTION_M_PER_PX;
use super::bedforms::{RippleField, SandCoverField};
use super::ground_look::terrain_corners;

/// Tile side, world pixels (16 m at 25 cm).
const TILE_PX: usize = 64;
/// Pixels per metre of the world lattice.
const PX_PER_M: f64 = 1.0 / TRUTH_RESOLUTION_M_PER_PX;
/// Largest map coordinate, metres, whose lattice sums are exact (see the module docs).
const EXACT_LIMIT_M: f64 = (1u64 << 40) as f64;

/// Memory [`TerrainStatics::new`] may fill, bytes (default 256 MiB: a 1 km sand corridor 200 m
/// wide takes about 90 MiB). Over it, patches are rendered without the tiles.
pub const DEFAULT_BUDGET_BYTES: usize = 256 << 20;

/// One tile of the lattice: the DEM height of every pixel, and the sand fields where a
/// terrain-class corner of the pixel is sand (the only pixels whose truth can carry ripples).
#[derive(Debug)]
struct Tile {
    ground: Box<[f32]>,
    sand: Option<SandTile>,
}

/// The sand fields of a tile (NaN where no terrain corner is sand).
#[derive(Debug)]
struct SandTile {
    /// Mean map-DEM height on the interdune ring minus the pixel's ground, metres.
    depth_m: Box<[f64]>,
    /// Ripple height at the rover's epoch, metres.
    ripple_m: Box<[f64]>,
    /// Ripple height at the orbital epoch minus `ripple_m`, metres.
    moved_m: Box<[f64]>,
}

impl Tile {
    fn bytes(&self) -> usize {
        4 * TILE_PX * TILE_PX + self.sand.as_ref().map_or(0, |_| 24 * TILE_PX * TILE_PX)
    }
}

/// The seed-independent terrain fields of one map (see the module docs), shared by every
/// localization run on it.
pub struct TerrainStatics {
    layers: Arc<MapLayers>,
    migration_m: f64,
    /// North-west corner of the lattice (the map DEM's), metres.
    origin_m: [f64; 2],
    tiles_x: usize,
    tiles_y: usize,
    tiles: Vec<OnceLock<Tile>>,
    budget_bytes: usize,
    used_bytes: AtomicUsize,
    /// Whether lattice coordinates are exact on this map (see the module docs).
    exact: bool,
}

impl std::fmt::Debug for TerrainStatics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TerrainStatics")
            .field("migration_m", &self.migration_m)
            .field("tiles", &[self.tiles_x, self.tiles_y])
            .field("used_bytes", &self.used_bytes.load(Ordering::Relaxed))
            .field("budget_bytes", &self.budget_bytes)
            .field("exact", &self.exact)
            .finish_non_exhaustive()
    }
}

impl TerrainStatics {
    /// The fields of `layers` for an orbital epoch `migration_m` before the rover's
    /// ([`super::OrbitalSettings::ripple_migration_m`]), within `DEFAULT_BUDGET_BYTES`.
    #[must_use]
    pub fn new(layers: Arc<MapLayers>, migration_m: f64) -> Self {
        Self::with_budget(layers, migration_m, DEFAULT_BUDGET_BYTES)
    }

    /// As [`TerrainStatics::new`], filling at most `budget_bytes`.
    #[must_use]
    pub fn with_budget(layers: Arc<MapLayers>, migration_m: f64, budget_bytes: usize) -> Self {
        let (x0, y0, x1, y1) = layers.dem.extent_m();
        let origin_m = layers.dem.geo.origin_m;
        let on_lattice = |v: f64| v.is_finite() && (v * 8.0).fract() == 0.0;
        let exact = migration_m.is_finite()
            && origin_m.iter().all(|&v| on_lattice(v))
            && [x0, y0, x1, y1].iter().all(|v| v.abs() < EXACT_LIMIT_M);
        let tiles_along = |extent_m: f64| {
            if exact {
                ((extent_m * PX_PER_M).ceil() as usize).div_ceil(TILE_PX)
            } else {
                0
            }
        };
        let (tiles_x, tiles_y) = (tiles_along(x1 - x0), tiles_along(y1 - y0));
        Self {
            layers,
            migration_m,
            origin_m,
            tiles_x,
            tiles_y,
            tiles: (0..tiles_x * tiles_y).map(|_| OnceLock::new()).collect(),
            budget_bytes,
            used_bytes: AtomicUsize::new(0),
            exact,
        }
    }

    /// Whether these are the fields of `layers` (the same allocation) at `migration_m`.
    #[must_use]
    pub fn serves(&self, layers: &MapLayers, migration_m: f64) -> bool {
        self.exact && self.is_of(layers) && self.migration_m.to_bits() == migration_m.to_bits()
    }

    /// Whether these are fields of `layers` (the same allocation), at whatever migration.
    #[must_use]
    pub fn is_of(&self, layers: &MapLayers) -> bool {
        std::ptr::eq(Arc::as_ptr(&self.layers), layers)
    }

    /// Bytes of tiles built so far.
    #[must_use]
    pub fn used_bytes(&self) -> usize {
        self.used_bytes.load(Ordering::Relaxed)
    }

    /// The fields of the `n × n` patch grid `geo` (a [`super::truth_patch`] grid of this map),
    /// with every tile it covers built; `None` if the grid is not on the lattice or the tiles
    /// would exceed the budget.
    pub(crate) fn patch(&self, geo: GeoTransform, n: usize) -> Option<PatchStatics<'_>> {
        if !self.exact || geo.resolution_m_per_px != TRUTH_RESOLUTION_M_PER_PX {
            return None;
        }
        let ci = (geo.origin_m[0] - self.origin_m[0]) * PX_PER_M;
        let cj = (self.origin_m[1] - geo.origin_m[1]) * PX_PER_M;
        if !(ci >= 0.0 && cj >= 0.0 && ci.fract() == 0.0 && cj.fract() == 0.0) {
            return None;
        }
        let (i0, j0) = (ci as usize, cj as usize);
        let (t0x, t0y) = (i0 / TILE_PX, j0 / TILE_PX);
        let (t1x, t1y) = ((i0 + n).div_ceil(TILE_PX), (j0 + n).div_ceil(TILE_PX));
        if n == 0 || t1x > self.tiles_x || t1y > self.tiles_y {
            return None;
        }
        let missing: Vec<usize> = (t0y..t1y)
            .flat_map(|ty| (t0x..t1x).map(move |tx| ty * self.tiles_x + tx))
            .filter(|&t| self.tiles[t].get().is_none())
            .collect();
        // Each missing tile costs at most a sand tile.
        let worst = missing.len() * (28 * TILE_PX * TILE_PX);
        if self.used_bytes() + worst > self.budget_bytes {
            return None;
        }
        missing.par_iter().for_each(|&t| {
            self.tiles[t].get_or_init(|| {
                let tile = self.build(t % self.tiles_x, t / self.tiles_x);
                self.used_bytes.fetch_add(tile.bytes(), Ordering::Relaxed);
                tile
            });
        });
        Some(PatchStatics {
            statics: self,
            i0,
            j0,
            n,
        })
    }

    /// Tile `(tx, ty)`: the same computations, on the same coordinates, as the uncached truth
    /// patch and orbital epoch.
    fn build(&self, tx: usize, ty: usize) -> Tile {
        let layers = &*self.layers;
        let res = TRUTH_RESOLUTION_M_PER_PX;
        // The tile's corner is on the 1 m lattice, as a patch's is.
        let geo = GeoTransform::new(
            self.origin_m[0] + (tx * TILE_PX) as f64 * res,
            self.origin_m[1] - (ty * TILE_PX) as f64 * res,
            res,
        );
        let n = TILE_PX * TILE_PX;
        let mut ground = vec![0.0f32; n];
        let mut sand = SandTile {
            depth_m: vec![f64::NAN; n].into(),
            ripple_m: vec![f64::NAN; n].into(),
            moved_m: vec![f64::NAN; n].into(),
        };
        let mut any_sand = false;
        let (mut now, mut then) = (RippleField::new(), RippleField::new());
        let cover = SandCoverField::new(0);
        for row in 0..TILE_PX {
            for col in 0..TILE_PX {
                let (x, y) = geo.center_of(col, row);
                let i = row * TILE_PX + col;
                let g = layers.dem.sample_bilinear(x, y).unwrap_or(0.0);
                ground[i] = g;
                let sandy = terrain_corners(&layers.terrain, x, y)
                    .iter()
                    .any(|&(code, _)| code == TerrainClass::Sand.code());
                if !sandy {
                    continue;
                }
                any_sand = true;
                sand.depth_m[i] = cover.depth_m(&layers.dem, x, y, f64::from(g));
                let weights = now.weights(x, y);
                let ripple = now.height_m(x, y, 0.0, &weights);
                sand.ripple_m[i] = ripple;
                sand.moved_m[i] = then.height_m(x, y, -self.migration_m, &weights) - ripple;
            }
        }
        Tile {
            ground: ground.into(),
            sand: any_sand.then_some(sand),
        }
    }
}

/// The fields of one patch grid, every tile built ([`TerrainStatics::patch`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PatchStatics<'a> {
    statics: &'a TerrainStatics,
    /// World pixel of the patch's pixel (0, 0).
    i0: usize,
    j0: usize,
    /// Patch side, pixels.
    n: usize,
}

impl PatchStatics<'_> {
    /// Patch side, pixels.
    pub(crate) fn n(&self) -> usize {
        self.n
    }

    /// Row `row` of the patch, tile by tile: `f(first column, tile, tile offset of that column,
    /// count)`.
    fn for_row(&self, row: usize, mut f: impl FnMut(usize, &Tile, usize, usize)) {
        let s = self.statics;
        let j = self.j0 + row;
        let (ty, tr) = (j / TILE_PX, j % TILE_PX);
        let mut col = 0;
        while col < self.n {
            let i = self.i0 + col;
            let (tx, tc) = (i / TILE_PX, i % TILE_PX);
            let count = (TILE_PX - tc).min(self.n - col);
            // Built by `TerrainStatics::patch` before this view was made.
            if let Some(tile) = s.tiles[ty * s.tiles_x + tx].get() {
                f(col, tile, tr * TILE_PX + tc, count);
            }
            col += count;
        }
    }

    /// Row `row`'s ground heights (the map DEM, bilinear), ring depths and rover-epoch ripple
    /// heights (NaN where no terrain corner is sand).
    pub(crate) fn truth_row(
        &self,
        row: usize,
        ground: &mut [f32],
        depth_m: &mut [f64],
        ripple_m: &mut [f64],
    ) {
        self.for_row(row, |col, tile, at, count| {
            ground[col..col + count].copy_from_slice(&tile.ground[at..at + count]);
            match &tile.sand {
                Some(s) => {
                    depth_m[col..col + count].copy_from_slice(&s.depth_m[at..at + count]);
                    ripple_m[col..col + count].copy_from_slice(&s.ripple_m[at..at + count]);
                }
                None => {
                    depth_m[col..col + count].fill(f64::NAN);
                    ripple_m[col..col + count].fill(f64::NAN);
                }
            }
        });
    }

    /// Row `row`'s ripple height change from the rover's epoch to the orbital one (NaN where
    /// no terrain corner is sand).
    pub(crate) fn moved_row(&self, row: usize, moved_m: &mut [f64]) {
        self.for_row(row, |col, tile, at, count| match &tile.sand {
            Some(s) => moved_m[col..col + count].copy_from_slice(&s.moved_m[at..at + count]),
            None => moved_m[col..col + count].fill(f64::NAN),
        });
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::synthetic::{
        OrbitalSettings, patch_grid, render_orbital, render_orbital_with, truth_patch,
        truth_patch_on,
    };
    use maps::Raster;

    /// A 120 m map of sand bedforms (20 m spacing) with soil and bedrock bands across it.
    fn layers(origin_x_m: f64) -> MapLayers {
        let geo = GeoTransform::new(origin_x_m, 120.0, 1.0);
        let mut dem = Raster::filled(120, 120, geo, 0.0f32);
        let mut terrain = Raster::filled(120, 120, geo, TerrainClass::Sand.code());
        for row in 0..120 {
            for col in 0..120 {
                let h =
                    10.0 + (std::f64::consts::TAU * col as f64 / 20.0).cos() + 0.02 * row as f64;
                dem.set(col, row, h as f32);
                let band = match (col / 15 + row / 40) % 4 {
                    0 => TerrainClass::Soil,
                    2 => TerrainClass::Bedrock,
                    _ => TerrainClass::Sand,
                };
                terrain.set(col, row, band.code());
            }
        }
        MapLayers {
            appearance: Raster::filled(120, 120, geo, 0),
            dem,
            terrain,
        }
    }

    #[test]
    fn patches_with_the_tiles_equal_patches_without() {
        let layers = Arc::new(layers(0.0));
        let params = OrbitalSettings::default();
        let statics = TerrainStatics::new(Arc::clone(&layers), params.ripple_migration_m);
        assert!(statics.serves(&layers, params.ripple_migration_m));
        for (k, (center, half)) in [
            ([60.0, 60.0], 20.0),
            ([47.3, 71.9], 13.4),
            ([61.0, 58.5], 30.0),
        ]
        .into_iter()
        .enumerate()
        {
            let seed = 40 + k as u64;
            let (geo, n) = patch_grid(&layers, center, half).unwrap();
            let fields = statics.patch(geo, n).unwrap();
            let with = truth_patch_on(&layers, geo, n, seed, Some(&fields), None);
            let without = truth_patch(&layers, center, half, seed).unwrap();
            assert!(without.sand.data.iter().any(|&s| s > 0.0));
            for (a, b) in [
                (&with.height_m, &without.height_m),
                (&with.albedo, &without.albedo),
                (&with.sand, &without.sand),
            ] {
                assert_eq!(a.geo, b.geo);
                assert!(
                    a.data
                        .iter()
                        .zip(&b.data)
                        .all(|(x, y)| x.to_bits() == y.to_bits())
                );
            }
            let orbital = render_orbital_with(&with, &params, seed + 1, Some(&fields)).unwrap();
            assert_eq!(
                orbital,
                render_orbital(&without, &params, seed + 1).unwrap()
            );
        }
        assert!(statics.used_bytes() > 0);
    }

    #[test]
    fn donor_patches_lend_their_pixels_exactly() {
        let layers = Arc::new(layers(0.0));
        let statics = TerrainStatics::new(Arc::clone(&layers), 0.75);
        let seed = 9;
        let (donor_center, half) = ([60.0, 60.0], 18.0);
        let donor = truth_patch(&layers, donor_center, half, seed).unwrap();
        // Shifted by whole metres and fractions of one, in every direction, partly or not
        // at all overlapping, other sizes; with and without the terrain fields.
        for (dx, dy, h) in [
            (0.0, 0.0, half),
            (0.6, -0.3, half),
            (3.2, 1.0, half),
            (-7.0, 4.4, half),
            (-2.0, -11.0, 10.0),
            (12.0, 5.0, 25.0),
            (40.0, 0.0, half),
        ] {
            let center = [donor_center[0] + dx, donor_center[1] + dy];
            let (geo, n) = patch_grid(&layers, center, h).unwrap();
            let want = truth_patch(&layers, center, h, seed).unwrap();
            let fields = statics.patch(geo, n).unwrap();
            for fields in [None, Some(&fields)] {
                let got = truth_patch_on(&layers, geo, n, seed, fields, Some(&donor));
                for (a, b) in [
                    (&got.height_m, &want.height_m),
                    (&got.albedo, &want.albedo),
                    (&got.sand, &want.sand),
                ] {
                    assert_eq!(a.geo, b.geo);
                    assert!(
                        a.data
                            .iter()
                            .zip(&b.data)
                            .all(|(x, y)| x.to_bits() == y.to_bits()),
                        "shift ({dx}, {dy}), half {h}"
                    );
                }
            }
        }
    }

    #[test]
    fn other_maps_grids_and_budgets_are_not_served() {
        let layers = Arc::new(layers(0.0));
        let statics = TerrainStatics::new(Arc::clone(&layers), 0.75);
        // Another migration, another map with the same contents.
        assert!(!statics.serves(&layers, 0.5));
        assert!(!statics.serves(&self::layers(0.0), 0.75));
        // A grid off the lattice or off the map.
        let (geo, n) = patch_grid(&layers, [60.0, 60.0], 10.0).unwrap();
        let shifted = GeoTransform::new(geo.origin_m[0] + 0.1, geo.origin_m[1], 0.25);
        assert!(statics.patch(shifted, n).is_none());
        assert!(statics.patch(geo, 10_000).is_none());
        // No room for a tile.
        let empty = TerrainStatics::with_budget(Arc::clone(&layers), 0.75, 0);
        assert!(empty.patch(geo, n).is_none());
        // A DEM corner off the 1/8 m lattice: sums of coordinates may round.
        let odd = Arc::new(self::layers(0.3));
        assert!(!TerrainStatics::new(Arc::clone(&odd), 0.75).serves(&odd, 0.75));
    }
}
