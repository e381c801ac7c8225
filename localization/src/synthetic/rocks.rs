//! Rocks on the truth terrain: ellipsoidal domes drawn per world cell, so overlapping patches
//! share them, and stamped onto a patch with the tallest winning.

use maps::{GeoTransform, MapLayers, TerrainClass};

use super::bedforms::SandCoverField;
use super::ground_look::ClassLook;
use super::noise::{SplitMix, floor_i64, hash2};

/// Side of the square cells rocks are drawn in, metres. Rocks are a pure function of
/// (seed, cell), so two overlapping patches share their rocks.
pub(super) const ROCK_CELL_M: f64 = 2.0;
/// Rock diameters, metres: a truncated power law N(>D) ∝ D^(−ROCK_SIZE_EXPONENT).
const ROCK_DIAMETER_M: (f64, f64) = (0.1, 1.5);
/// Exponent of the cumulative rock size–frequency law (more small rocks than large).
const ROCK_SIZE_EXPONENT: f64 = 1.8;
/// Rock height as a fraction of its diameter.
const ROCK_HEIGHT_RATIO: (f64, f64) = (0.3, 0.8);
/// Rock albedo (a little darker than bedrock, brighter than sand).
const ROCK_ALBEDO: (f64, f64) = (0.19, 0.27);

/// One rock: an ellipsoidal dome sitting on the ground.
#[derive(Clone, Copy, Debug)]
pub(super) struct Rock {
    center_m: [f64; 2],
    /// Semi-axes, metres.
    semi_axes_m: [f64; 2],
    /// Orientation of the first axis, radians counter-clockwise from east.
    angle_rad: f64,
    height_m: f64,
    albedo: f64,
}

/// The rocks whose centres fall in world cell `(ix, iy)`: a Poisson number at the densest
/// class's rate, thinned by the density of the class under each rock.
pub(super) fn rocks_in_cell(
    seed: u64,
    cover: &mut SandCoverField,
    ix: i64,
    iy: i64,
    layers: &MapLayers,
    out: &mut Vec<Rock>,
) {
    let max_density = ClassLook::of_code(TerrainClass::Bedrock.code()).rocks_per_m2;
    let lambda = max_density * ROCK_CELL_M * ROCK_CELL_M;
    let mut rng = SplitMix(hash2(seed, ix, iy));
    // Poisson by multiplying uniforms (Knuth); λ is under 2.
    let limit = (-lambda).exp();
    let mut n = 0;
    let mut prod = rng.next_f64();
    while prod > limit && n < 32 {
        n += 1;
        prod *= rng.next_f64();
    }
    let (d_min, d_max) = ROCK_DIAMETER_M;
    let (a_min, a_max) = (
        d_min.powf(-ROCK_SIZE_EXPONENT),
        d_max.powf(-ROCK_SIZE_EXPONENT),
    );
    for _ in 0..n {
        let x = (ix as f64 + rng.next_f64()) * ROCK_CELL_M;
        let y = (iy as f64 + rng.next_f64()) * ROCK_CELL_M;
        let keep = rng.next_f64();
        let u = rng.next_f64();
        let diameter = (a_min - u * (a_min - a_max)).powf(-1.0 / ROCK_SIZE_EXPONENT);
        let aspect = rng.range(0.6, 1.0);
        let angle_rad = rng.range(0.0, std::f64::consts::PI);
        let height_m = diameter * rng.range(ROCK_HEIGHT_RATIO.0, ROCK_HEIGHT_RATIO.1);
        let albedo = rng.range(ROCK_ALBEDO.0, ROCK_ALBEDO.1);
        let density = ClassLook::rock_density(layers, cover, x, y);
        if keep * max_density < density {
            out.push(Rock {
                center_m: [x, y],
                semi_axes_m: [0.5 * diameter, 0.5 * diameter * aspect],
                angle_rad,
                height_m,
                albedo,
            });
        }
    }
}

/// Adds, on the pixels `rows × cols` of the `n × n` grid at `geo`, the rocks of every cell that
/// can reach them. Where rocks overlap the tallest wins, so the result does not depend on the
/// order they are stamped in, nor on which other pixels are stamped with them.
#[allow(clippy::too_many_arguments)]
pub(super) fn stamp_rocks(
    seed: u64,
    cover_seed: u64,
    layers: &MapLayers,
    geo: GeoTransform,
    n: usize,
    [rows, cols]: [std::ops::Range<usize>; 2],
    height: &mut [f32],
    albedo: &mut [f32],
) {
    let res = geo.resolution_m_per_px;
    let [ox, oy] = geo.origin_m;
    let reach_m = 0.5 * ROCK_DIAMETER_M.1;
    let cell = |v: f64| floor_i64(v / ROCK_CELL_M);
    // The rectangle's extent, as the whole grid's is `[ox, ox + n·res] × [oy − n·res, oy]`.
    let (x0, x1) = (ox + cols.start as f64 * res, ox + cols.end as f64 * res);
    let (y1, y0) = (oy - rows.start as f64 * res, oy - rows.end as f64 * res);
    let (ix0, ix1) = (cell(x0 - reach_m), cell(x1 + reach_m));
    let (iy0, iy1) = (cell(y0 - reach_m), cell(y1 + reach_m));
    let mut cover = SandCoverField::new(cover_seed);
    let mut rocks = Vec::new();
    for iy in iy0..=iy1 {
        for ix in ix0..=ix1 {
            rocks_in_cell(seed, &mut cover, ix, iy, layers, &mut rocks);
        }
    }
    let (rw, rh) = (cols.len(), rows.len());
    let mut rock_h = vec![0.0f32; rw * rh];
    let mut rock_albedo = vec![0.0f32; rw * rh];
    for rock in &rocks {
        let [rx, ry] = rock.center_m;
        let a = rock.semi_axes_m[0];
        let px = |v: f64| v.floor().clamp(0.0, n as f64) as usize;
        let (c0, c1) = (px((rx - a - ox) / res), px((rx + a - ox) / res + 1.0));
        let (r0, r1) = (px((oy - ry - a) / res), px((oy - ry + a) / res + 1.0));
        let (cos, sin) = (rock.angle_rad.cos(), rock.angle_rad.sin());
        for row in r0.max(rows.start)..r1.min(rows.end) {
            for col in c0.max(cols.start)..c1.min(cols.end) {
                let (x, y) = geo.center_of(col, row);
                let (dx, dy) = (x - rx, y - ry);
                let u = (dx * cos + dy * sin) / rock.semi_axes_m[0];
                let v = (-dx * sin + dy * cos) / rock.semi_axes_m[1];
                let q = 1.0 - u * u - v * v;
                if q <= 0.0 {
                    continue;
                }
                let z = (rock.height_m * q.sqrt()) as f32;
                let i = (row - rows.start) * rw + (col - cols.start);
                if z > rock_h[i] || (z == rock_h[i] && (rock.albedo as f32) > rock_albedo[i]) {
                    rock_h[i] = z;
                    rock_albedo[i] = rock.albedo as f32;
                }
            }
        }
    }
    for (r, row) in rows.enumerate() {
        for (c, col) in cols.clone().enumerate() {
            let (k, i) = (r * rw + c, row * n + col);
            if rock_h[k] > 0.0 {
                height[i] += rock_h[k];
                // Keep a little of the ground's texture on the rock surface.
                albedo[i] = 0.85 * rock_albedo[k] + 0.15 * albedo[i];
            }
        }
    }
}
