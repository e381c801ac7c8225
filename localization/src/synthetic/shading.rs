//! Shared rendering pieces: bilinear heights and cast shadows (the image operations are in
//! [`super::image_ops`]).
//!
//! Coordinates here are *pixel-centre* coordinates of a truth grid: `(c, r) = (0, 0)` is the
//! centre of pixel (0, 0), `c` grows east and `r` grows south (the `maps` raster convention).

use maps::Raster;

use super::image_ops::bilinear;

/// Heights below the shadow or sight ray by less than this do not block it (metres): the
/// bilinear surface between pixel centres is not the surface the pixels were shaded with.
const RAY_CLEARANCE_M: f32 = 0.02;

/// Tile sizes of the skip levels as powers of two (64, 16 and 4 pixels), coarsest first. A ray
/// whose points stay above the highest sample of the 3 × 3 tiles around its current point skips
/// a tile size of steps at once.
const SKIP_TILE_SHIFTS: [u32; 3] = [6, 4, 2];

/// A straight ray over the grid: point `k` is at `start + step × k` (pixel-centre coordinates)
/// with height `z0 + dz × k` (metres).
#[derive(Clone, Copy, Debug)]
pub(super) struct Ray {
    pub(super) start: [f64; 2],
    pub(super) step: [f64; 2],
    pub(super) z0: f64,
    pub(super) dz: f64,
}

impl Ray {
    #[inline]
    fn at(&self, k: usize) -> (f64, f64) {
        let t = k as f64;
        (
            self.start[0] + self.step[0] * t,
            self.start[1] + self.step[1] * t,
        )
    }

    #[inline]
    fn z(&self, k: usize) -> f32 {
        (self.z0 + self.dz * k as f64) as f32
    }
}

/// Maxima of one skip level: per tile, the highest sample that a bilinear lookup at any point
/// within `tile_px − 1` pixels of a point in that tile can read.
#[derive(Clone, Debug)]
struct SkipLevel {
    tile_px: usize,
    /// `tile_px = 1 << shift`: a shift, not a division, in the hot loop.
    shift: u32,
    tiles_x: usize,
    max_near: Vec<f32>,
}

impl SkipLevel {
    /// The level of `1 << shift` pixel tiles over the `w × h` grid `data` (the reference the
    /// levels built by [`HeightField::new`] are tested against).
    #[cfg(test)]
    fn new(data: &[f32], w: usize, h: usize, shift: u32) -> Self {
        let tile_px = 1usize << shift;
        let (tiles_x, tiles_y) = (w.div_ceil(tile_px), h.div_ceil(tile_px));
        // A tile's own maximum includes one pixel east and south: bilinear reads them.
        let mut own = vec![f32::NEG_INFINITY; tiles_x * tiles_y];
        for (t, m) in own.iter_mut().enumerate() {
            let (tx, ty) = (t % tiles_x, t / tiles_x);
            for row in ty * tile_px..=((ty + 1) * tile_px).min(h - 1) {
                for col in tx * tile_px..=((tx + 1) * tile_px).min(w - 1) {
                    *m = m.max(data[row * w + col]);
                }
            }
        }
        Self::from_own(&own, tiles_x, tiles_y, shift)
    }

    /// Per tile of `1 << shift` pixels, the highest sample of the tile and of one pixel east and
    /// south of it (bilinear reads them): `(maxima, tiles_x, tiles_y)`. One pass over each
    /// band of rows, a column maximum at a time.
    fn own_maxima(data: &[f32], w: usize, h: usize, shift: u32) -> (Vec<f32>, usize, usize) {
        let tile_px = 1usize << shift;
        let (tiles_x, tiles_y) = (w.div_ceil(tile_px), h.div_ceil(tile_px));
        let mut own = vec![f32::NEG_INFINITY; tiles_x * tiles_y];
        let mut column = vec![f32::NEG_INFINITY; w];
        for ty in 0..tiles_y {
            column.fill(f32::NEG_INFINITY);
            for row in ty * tile_px..=((ty + 1) * tile_px).min(h - 1) {
                for (m, &v) in column.iter_mut().zip(&data[row * w..(row + 1) * w]) {
                    *m = m.max(v);
                }
            }
            for (tx, m) in own[ty * tiles_x..(ty + 1) * tiles_x].iter_mut().enumerate() {
                for &v in &column[tx * tile_px..=((tx + 1) * tile_px).min(w - 1)] {
                    *m = m.max(v);
                }
            }
        }
        (own, tiles_x, tiles_y)
    }

    /// The own maxima of tiles `1 << step` times larger than those of `own` (`tiles_x ×
    /// tiles_y`): the maximum of each block of `(1 << step)²` of them, which covers exactly the
    /// larger tile and its extra pixel east and south (maxima are exact in any grouping).
    fn coarser(own: &[f32], tiles_x: usize, tiles_y: usize, step: u32) -> (Vec<f32>, usize, usize) {
        let k = 1usize << step;
        let (cx, cy) = (tiles_x.div_ceil(k), tiles_y.div_ceil(k));
        let mut out = vec![f32::NEG_INFINITY; cx * cy];
        for (t, m) in out.iter_mut().enumerate() {
            let (tx, ty) = (t % cx, t / cx);
            for fy in ty * k..((ty + 1) * k).min(tiles_y) {
                for &v in &own[fy * tiles_x + tx * k..fy * tiles_x + ((tx + 1) * k).min(tiles_x)] {
                    *m = m.max(v);
                }
            }
        }
        (out, cx, cy)
    }

    /// The level whose tiles' own maxima are `own` (`tiles_x × tiles_y` tiles of `1 << shift`
    /// pixels).
    fn from_own(own: &[f32], tiles_x: usize, tiles_y: usize, shift: u32) -> Self {
        // Points up to tile_px − 1 away read at most one tile further in each direction.
        let max_near = (0..tiles_x * tiles_y)
            .map(|t| {
                let (tx, ty) = (t % tiles_x, t / tiles_x);
                let mut m = f32::NEG_INFINITY;
                for ny in ty.saturating_sub(1)..=(ty + 1).min(tiles_y - 1) {
                    for nx in tx.saturating_sub(1)..=(tx + 1).min(tiles_x - 1) {
                        m = m.max(own[ny * tiles_x + nx]);
                    }
                }
                m
            })
            .collect();
        Self {
            tile_px: 1usize << shift,
            shift,
            tiles_x,
            max_near,
        }
    }
}

/// A read-only view of a height grid with its pixel size, highest sample and skip levels.
#[derive(Clone, Debug)]
pub(super) struct HeightField<'a> {
    pub(super) data: &'a [f32],
    pub(super) width: usize,
    pub(super) height: usize,
    pub(super) resolution_m: f64,
    pub(super) max_m: f32,
    levels: Vec<SkipLevel>,
    /// Division by the central and one-sided difference spacings, `2 × res` and `res`.
    per_spacing: [ExactDiv; 2],
}

impl<'a> HeightField<'a> {
    /// A view of `raster` (heights in metres).
    pub(super) fn new(raster: &'a Raster<f32>) -> Self {
        let (w, h) = (raster.width, raster.height);
        let mut levels = Vec::with_capacity(SKIP_TILE_SHIFTS.len());
        let mut max_m = f32::NEG_INFINITY;
        if w > 0 && h > 0 {
            // Finest level from the samples, each coarser one from the level below it.
            let mut shifts = SKIP_TILE_SHIFTS.iter().rev();
            let mut shift = shifts.next().copied().unwrap_or(0);
            let (mut own, mut tx, mut ty) = SkipLevel::own_maxima(&raster.data, w, h, shift);
            levels.push(SkipLevel::from_own(&own, tx, ty, shift));
            for &coarser in shifts {
                (own, tx, ty) = SkipLevel::coarser(&own, tx, ty, coarser - shift);
                shift = coarser;
                levels.push(SkipLevel::from_own(&own, tx, ty, shift));
            }
            levels.reverse();
            // The tiles cover every sample.
            max_m = own.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        }
        Self {
            data: &raster.data,
            width: w,
            height: h,
            resolution_m: raster.geo.resolution_m_per_px,
            per_spacing: [1.0, 2.0].map(|k: f64| ExactDiv::new(k * raster.geo.resolution_m_per_px)),
            max_m,
            levels,
        }
    }

    /// Whether pixel-centre coordinates `(c, r)` lie on the grid (within half a pixel).
    #[inline]
    pub(super) fn contains(&self, c: f64, r: f64) -> bool {
        c >= -0.5 && r >= -0.5 && c < self.width as f64 - 0.5 && r < self.height as f64 - 0.5
    }

    /// Height at pixel `(col, row)`.
    #[inline]
    pub(super) fn at(&self, col: usize, row: usize) -> f32 {
        self.data[row * self.width + col]
    }

    /// Bilinear height at pixel-centre coordinates `(c, r)`, clamped at the edges.
    #[inline]
    pub(super) fn bilinear(&self, c: f64, r: f64) -> f32 {
        bilinear(self.data, self.width, self.height, c, r)
    }

    /// Cosine of the angle between the surface normal at pixel `(col, row)` (central
    /// differences, one-sided at the edges) and the unit vector `sun` (x east, y north, z up).
    pub(super) fn cos_incidence(&self, col: usize, row: usize, sun: [f64; 3]) -> f64 {
        let (w, h) = (self.width, self.height);
        let (west, east) = (col.saturating_sub(1), (col + 1).min(w - 1));
        let (north, south) = (row.saturating_sub(1), (row + 1).min(h - 1));
        // Spacing `(east − west).max(1) × res`: 1 or 2 pixels.
        let per = |span: usize| self.per_spacing[usize::from(span >= 2)];
        let dz_dx = per(east - west).of(f64::from(self.at(east, row) - self.at(west, row)));
        let dz_dy = per(south - north).of(f64::from(self.at(col, north) - self.at(col, south)));
        (-dz_dx * sun[0] - dz_dy * sun[1] + sun[2]) / (1.0 + dz_dx * dz_dx + dz_dy * dz_dy).sqrt()
    }

    /// [`HeightField::cos_incidence`] of every pixel of row `row` into `out` (`width` long):
    /// the same operations, the interior in a loop the compiler vectorizes.
    pub(super) fn cos_incidence_row(&self, row: usize, sun: [f64; 3], out: &mut [f64]) {
        let (w, h) = (self.width, self.height);
        if w < 3 || h < 3 || row == 0 || row + 1 == h {
            for (col, o) in out.iter_mut().enumerate().take(w) {
                *o = self.cos_incidence(col, row, sun);
            }
            return;
        }
        let (up, here, down) = (
            &self.data[(row - 1) * w..row * w],
            &self.data[row * w..(row + 1) * w],
            &self.data[(row + 1) * w..(row + 2) * w],
        );
        // Interior pixels: central differences over 2 pixels both ways.
        let cos = |dz_dx: f64, dz_dy: f64| {
            (-dz_dx * sun[0] - dz_dy * sun[1] + sun[2])
                / (1.0 + dz_dx * dz_dx + dz_dy * dz_dy).sqrt()
        };
        let per = self.per_spacing[1];
        let interior = out[1..w - 1]
            .iter_mut()
            .zip(here.windows(3))
            .zip(up[1..w - 1].iter().zip(&down[1..w - 1]));
        match per.inv {
            Some(inv) => {
                for ((o, e), (&n, &s)) in interior {
                    *o = cos(f64::from(e[2] - e[0]) * inv, f64::from(n - s) * inv);
                }
            }
            None => {
                for ((o, e), (&n, &s)) in interior {
                    *o = cos(f64::from(e[2] - e[0]) / per.d, f64::from(n - s) / per.d);
                }
            }
        }
        out[0] = self.cos_incidence(0, row, sun);
        out[w - 1] = self.cos_incidence(w - 1, row, sun);
    }

    /// Whether the terrain rises more than [`RAY_CLEARANCE_M`] above `ray` at one of its points
    /// `1..=k_last`; the ray's steps must be at most one pixel long. The march ends without a
    /// hit where the ray leaves the grid or, rising, clears the highest sample. Runs of points
    /// that stay above the tile maxima around them are skipped whole; the answer is exactly
    /// that of [`HeightField::ray_hits_reference`] (the grid is convex and a rising ray stays
    /// risen, so nothing skipped could have ended the march differently).
    pub(super) fn ray_hits(&self, ray: &Ray, k_last: usize) -> bool {
        self.march(ray, k_last, None)
    }

    /// [`HeightField::ray_hits`], ending also where a rising ray clears `ahead` at its point:
    /// per pixel, a bound on every sample the ray can still read (see [`SunShadows`]).
    fn march(&self, ray: &Ray, k_last: usize, ahead: Option<&[f32]>) -> bool {
        let Some(finest) = self.levels.last() else {
            return false;
        };
        let (w_max, h_max) = ((self.width - 1) as f64, (self.height - 1) as f64);
        let mut k = 1;
        'march: while k <= k_last {
            let (c, r) = ray.at(k);
            let z = ray.z(k);
            if !self.contains(c, r) || (ray.dz >= 0.0 && z > self.max_m) {
                return false;
            }
            // The highest sample bilinear lookups within `tile_px − 1` pixels of the point can
            // read: its clamped pixel's tile (clamping is 1-Lipschitz, so clamped points stay as
            // close as the points themselves), found once for every level.
            let (pc, pr) = (c.clamp(0.0, w_max) as usize, r.clamp(0.0, h_max) as usize);
            if let Some(ahead) = ahead
                && ray.dz >= 0.0
                && z + RAY_CLEARANCE_M > ahead[pr * self.width + pc] + 1e-3
            {
                return false;
            }
            for level in &self.levels {
                let k_end = k.saturating_add(level.tile_px - 1).min(k_last);
                let z_low = z.min(ray.z(k_end));
                let near =
                    level.max_near[(pr >> level.shift) * level.tiles_x + (pc >> level.shift)];
                // 1 mm absorbs the rounding of a bilinear blend above its largest corner.
                if z_low + RAY_CLEARANCE_M > near + 1e-3 {
                    if k_end == k_last {
                        return false;
                    }
                    k = k_end + 1;
                    continue 'march;
                }
            }
            let k_end = k.saturating_add(finest.tile_px - 1).min(k_last);
            for kk in k..=k_end {
                let (c, r) = ray.at(kk);
                let z = ray.z(kk);
                if !self.contains(c, r) || (ray.dz >= 0.0 && z > self.max_m) {
                    return false;
                }
                if self.bilinear(c, r) > z + RAY_CLEARANCE_M {
                    return true;
                }
            }
            if k_end == k_last {
                return false;
            }
            k = k_end + 1;
        }
        false
    }

    /// [`HeightField::ray_hits`] one point at a time: the reference it is tested against.
    #[cfg(test)]
    pub(super) fn ray_hits_reference(&self, ray: &Ray, k_last: usize) -> bool {
        for k in 1..=k_last {
            let (c, r) = ray.at(k);
            let z = ray.z(k);
            if !self.contains(c, r) || (ray.dz >= 0.0 && z > self.max_m) {
                return false;
            }
            if self.bilinear(c, r) > z + RAY_CLEARANCE_M {
                return true;
            }
        }
        false
    }

    /// The ray from pixel `(col, row)` towards the sun, one pixel per step.
    pub(super) fn sun_ray(&self, col: usize, row: usize, sun: &Sun) -> Ray {
        Ray {
            start: [col as f64, row as f64],
            step: [sun.step_col, sun.step_row],
            z0: f64::from(self.at(col, row)),
            dz: sun.rise_per_step_m,
        }
    }

    /// Whether pixel `(col, row)` sees the sun: march towards it and report a shadow if the
    /// terrain rises above the ray. Terrain beyond the grid casts no shadow.
    #[cfg(test)]
    pub(super) fn sunlit(&self, col: usize, row: usize, sun: &Sun) -> bool {
        !self.ray_hits(&self.sun_ray(col, row, sun), usize::MAX)
    }

    /// [`HeightField::sunlit`] for many pixels under one `sun` (see [`SunShadows`]).
    pub(super) fn shadows(&self, sun: Sun) -> SunShadows<'_, 'a> {
        SunShadows::new(self, sun)
    }

    /// The sight line from a camera at `camera` (pixel-centre coordinates, height `camera_z`)
    /// to the surface at `target` (height `target_z`), one pixel per step, and the number of
    /// steps to test: all but the last pixel before the target, so a surface does not hide
    /// itself.
    pub(super) fn sight_ray(
        camera: [f64; 2],
        camera_z: f32,
        target: [f64; 2],
        target_z: f32,
    ) -> (Ray, usize) {
        let (dc, dr) = (target[0] - camera[0], target[1] - camera[1]);
        let dist_px = dc.hypot(dr);
        if dist_px <= 1.0 {
            let still = Ray {
                start: camera,
                step: [0.0, 0.0],
                z0: f64::from(camera_z),
                dz: 0.0,
            };
            return (still, 0);
        }
        let ray = Ray {
            start: camera,
            step: [dc / dist_px, dr / dist_px],
            z0: f64::from(camera_z),
            dz: f64::from(target_z - camera_z) / dist_px,
        };
        (ray, (dist_px - 1.0) as usize)
    }

    /// Whether the surface at `target` (height `target_z`) can be seen from the camera at
    /// `camera` (height `camera_z`): no terrain between them rises above the sight line.
    pub(super) fn line_of_sight(
        &self,
        camera: [f64; 2],
        camera_z: f32,
        target: [f64; 2],
        target_z: f32,
    ) -> bool {
        let (ray, steps) = Self::sight_ray(camera, camera_z, target, target_z);
        !self.ray_hits(&ray, steps)
    }
}

/// Cast shadows under one sun: [`HeightField::sunlit`], with a bound that ends most marches
/// early.
///
/// A sun ray moves the same way across the grid from every pixel, so every sample it can still
/// read from a point lies in the quadrant ahead of that point (columns and rows no further back
/// than the bilinear lookup at the point reads). `ahead` holds per pixel the highest sample of
/// that quadrant (a two-pass running maximum); a rising ray above it can hit nothing more, the
/// same argument as the march's end above the grid's highest sample, so the answers are
/// exactly [`HeightField::sunlit`]'s (tested).
#[derive(Debug)]
pub(super) struct SunShadows<'h, 'a> {
    hf: &'h HeightField<'a>,
    sun: Sun,
    ahead: Vec<f32>,
}

impl<'h, 'a> SunShadows<'h, 'a> {
    fn new(hf: &'h HeightField<'a>, sun: Sun) -> Self {
        let (w, h) = (hf.width, hf.height);
        let mut ahead = vec![f32::NEG_INFINITY; w * h];
        if w > 0 && h > 0 {
            // Along each row: the columns a ray from column c can read (c and everything on its
            // way, one more for the bilinear lookup's east neighbour).
            for (out, row) in ahead.chunks_exact_mut(w).zip(hf.data.chunks_exact(w)) {
                if sun.step_col < 0.0 {
                    let mut m = f32::NEG_INFINITY;
                    for c in 0..w {
                        m = m.max(row[c]);
                        out[c] = m;
                    }
                    // Column c reads c + 1 too.
                    for c in 0..w - 1 {
                        out[c] = out[c + 1];
                    }
                } else if sun.step_col > 0.0 {
                    let mut m = f32::NEG_INFINITY;
                    for c in (0..w).rev() {
                        m = m.max(row[c]);
                        out[c] = m;
                    }
                } else {
                    let m = row.iter().copied().fold(f32::NEG_INFINITY, f32::max);
                    out.fill(m);
                }
            }
            // Down (or up) the columns, likewise.
            let rows: Vec<usize> = if sun.step_row > 0.0 {
                (0..h).rev().collect()
            } else {
                (0..h).collect()
            };
            if sun.step_row == 0.0 {
                for c in 0..w {
                    let m = (0..h)
                        .map(|r| ahead[r * w + c])
                        .fold(f32::NEG_INFINITY, f32::max);
                    (0..h).for_each(|r| ahead[r * w + c] = m);
                }
            } else {
                let mut m = vec![f32::NEG_INFINITY; w];
                for &r in &rows {
                    for (mc, a) in m.iter_mut().zip(&mut ahead[r * w..(r + 1) * w]) {
                        *mc = mc.max(*a);
                        *a = *mc;
                    }
                }
                if sun.step_row < 0.0 {
                    // Row r reads r + 1 too.
                    for r in 0..h - 1 {
                        let (top, below) = ahead.split_at_mut((r + 1) * w);
                        top[r * w..].copy_from_slice(&below[..w]);
                    }
                }
            }
        }
        Self { hf, sun, ahead }
    }

    /// [`HeightField::sunlit`]`(col, row, sun)`.
    pub(super) fn sunlit(&self, col: usize, row: usize) -> bool {
        let ray = self.hf.sun_ray(col, row, &self.sun);
        !self.hf.march(&ray, usize::MAX, Some(&self.ahead))
    }
}

/// `x / d` for one divisor `d`, as a multiplication when `d` is a power of two: dividing by
/// `2^k` and multiplying by `2^-k` give the same correctly rounded result, and the
/// multiplication is several times faster.
#[derive(Clone, Copy, Debug)]
pub(super) struct ExactDiv {
    d: f64,
    /// `1 / d` if that is exact (a power of two), else `None`.
    inv: Option<f64>,
}

impl ExactDiv {
    pub(super) fn new(d: f64) -> Self {
        let inv = 1.0 / d;
        let power_of_two = |v: f64| v.is_normal() && v.to_bits() & ((1u64 << 52) - 1) == 0;
        Self {
            d,
            inv: (power_of_two(d) && power_of_two(inv)).then_some(inv),
        }
    }

    /// `x / d`.
    #[inline]
    pub(super) fn of(self, x: f64) -> f64 {
        match self.inv {
            Some(inv) => x * inv,
            None => x / self.d,
        }
    }
}

/// The sun as a unit vector and as a per-pixel march step.
#[derive(Clone, Copy, Debug)]
pub(super) struct Sun {
    /// Unit vector towards the sun: x east, y north, z up.
    pub(super) dir: [f64; 3],
    /// Column change per march step (one pixel horizontally towards the sun).
    step_col: f64,
    /// Row change per march step (rows grow south).
    step_row: f64,
    /// Rise of the sun ray per march step, metres.
    rise_per_step_m: f64,
}

impl Sun {
    /// The sun at `azimuth_deg` (direction the light comes from, clockwise from north) and
    /// `elevation_deg` above the horizon, over a grid of `resolution_m` pixels.
    pub(super) fn new(azimuth_deg: f64, elevation_deg: f64, resolution_m: f64) -> Self {
        let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        Self {
            dir: [az.sin() * el.cos(), az.cos() * el.cos(), el.sin()],
            step_col: az.sin(),
            step_row: -az.cos(),
            rise_per_step_m: el.tan() * resolution_m,
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use maps::GeoTransform;

    fn flat_with_wall() -> Raster<f32> {
        let mut r = Raster::filled(40, 40, GeoTransform::new(0.0, 10.0, 0.25), 0.0f32);
        for row in 0..40 {
            r.set(20, row, 3.0); // a 3 m wall along column 20
        }
        r
    }

    #[test]
    fn wall_casts_a_shadow_on_its_lee_side_only() {
        let ras = flat_with_wall();
        let hf = HeightField::new(&ras);
        // Sun from the east (azimuth 90°), 45° up: the shadow falls west of the wall.
        let sun = Sun::new(90.0, 45.0, 0.25);
        assert!(!hf.sunlit(15, 20, &sun));
        assert!(hf.sunlit(25, 20, &sun));
        // 3 m at 45° reaches 12 pixels west of the wall.
        assert!(hf.sunlit(5, 20, &sun));
    }

    #[test]
    fn wall_blocks_the_line_of_sight() {
        let ras = flat_with_wall();
        let hf = HeightField::new(&ras);
        assert!(!hf.line_of_sight([10.0, 20.0], 2.0, [30.0, 20.0], 0.0));
        assert!(hf.line_of_sight([10.0, 20.0], 2.0, [18.0, 20.0], 0.0));
        assert!(hf.line_of_sight([10.0, 20.0], 2.0, [10.0, 39.0], 0.0));
    }

    #[test]
    fn tile_skipping_march_equals_the_reference() {
        use crate::synthetic::noise::{ValueFbm, gaussian};
        let (w, h) = (150, 120);
        let f = ValueFbm::new(3, 6.0, 4);
        let mut ras = Raster::filled(w, h, GeoTransform::new(0.0, 30.0, 0.25), 0.0f32);
        for row in 0..h {
            for col in 0..w {
                let bump = if gaussian(9, col as i64, row as i64) > 2.5 {
                    0.6
                } else {
                    0.0
                };
                let v = 1.5 * f.at(col as f64 * 0.25, row as f64 * 0.25) + bump;
                ras.set(col, row, v as f32);
            }
        }
        let hf = HeightField::new(&ras);
        let (mut hits, mut total) = (0, 0);
        for el in [5.0, 15.0, 35.0, 70.0] {
            for az in [0.0, 45.0, 90.0, 133.0, 250.0, 301.0] {
                let sun = Sun::new(az, el, 0.25);
                for row in (0..h).step_by(7) {
                    for col in (0..w).step_by(5) {
                        let ray = hf.sun_ray(col, row, &sun);
                        let fast = hf.ray_hits(&ray, usize::MAX);
                        assert_eq!(fast, hf.ray_hits_reference(&ray, usize::MAX));
                        hits += usize::from(fast);
                        total += 1;
                    }
                }
            }
        }
        let camera = [75.3, 60.1];
        let cz = hf.bilinear(camera[0], camera[1]) + 2.0;
        for row in 0..h {
            for col in (row % 3..w).step_by(3) {
                let t = [col as f64 + 0.3, row as f64 - 0.2];
                let tz = hf.bilinear(t[0], t[1]);
                let (ray, steps) = HeightField::sight_ray(camera, cz, t, tz);
                let fast = hf.ray_hits(&ray, steps);
                assert_eq!(fast, hf.ray_hits_reference(&ray, steps), "{t:?}");
                hits += usize::from(fast);
                total += 1;
            }
        }
        // Both outcomes occur often enough for the comparison to mean something.
        assert!(
            hits > total / 20 && hits < total * 19 / 20,
            "{hits}/{total}"
        );
    }

    #[test]
    fn skip_levels_equal_the_direct_maxima() {
        use crate::synthetic::noise::gaussian;
        for (w, h) in [(1, 1), (3, 2), (64, 64), (65, 64), (130, 97), (257, 300)] {
            let mut ras = Raster::filled(w, h, GeoTransform::new(0.0, 30.0, 0.25), 0.0f32);
            for row in 0..h {
                for col in 0..w {
                    ras.set(col, row, gaussian(5, col as i64, row as i64) as f32);
                }
            }
            let hf = HeightField::new(&ras);
            let max = ras.data.iter().copied().fold(f32::NEG_INFINITY, f32::max);
            assert_eq!(hf.max_m.to_bits(), max.to_bits());
            assert_eq!(hf.levels.len(), SKIP_TILE_SHIFTS.len());
            for (level, &shift) in hf.levels.iter().zip(&SKIP_TILE_SHIFTS) {
                let want = SkipLevel::new(&ras.data, w, h, shift);
                assert_eq!((level.tile_px, level.shift), (want.tile_px, want.shift));
                assert_eq!(level.tiles_x, want.tiles_x);
                assert_eq!(level.max_near, want.max_near, "{w}×{h}, shift {shift}");
            }
        }
    }

    #[test]
    fn shadows_with_the_bound_ahead_equal_the_plain_march() {
        use crate::synthetic::noise::{ValueFbm, gaussian};
        let (w, h) = (90, 70);
        let f = ValueFbm::new(8, 5.0, 4);
        let mut ras = Raster::filled(w, h, GeoTransform::new(0.0, 30.0, 0.25), 0.0f32);
        for row in 0..h {
            for col in 0..w {
                let bump = if gaussian(4, col as i64, row as i64) > 2.3 {
                    0.7
                } else {
                    0.0
                };
                let slope = 0.03 * col as f64 - 0.02 * row as f64;
                ras.set(
                    col,
                    row,
                    (1.2 * f.at(col as f64 * 0.25, row as f64 * 0.25) + bump + slope) as f32,
                );
            }
        }
        let hf = HeightField::new(&ras);
        let (mut lit, mut total) = (0, 0);
        for el in [8.0, 20.0, 35.0, 60.0] {
            for az in [0.0, 45.0, 90.0, 133.0, 180.0, 250.0, 270.0, 301.0, 359.0] {
                let sun = Sun::new(az, el, 0.25);
                let shadows = hf.shadows(sun);
                for row in 0..h {
                    for col in 0..w {
                        let want = hf.sunlit(col, row, &sun);
                        assert_eq!(
                            shadows.sunlit(col, row),
                            want,
                            "az {az} el {el} ({col}, {row})"
                        );
                        lit += usize::from(want);
                        total += 1;
                    }
                }
            }
        }
        assert!(lit > total / 10 && lit < total * 19 / 20, "{lit}/{total}");
    }

    #[test]
    fn cos_incidence_rows_equal_pixels() {
        use crate::synthetic::noise::gaussian;
        for (w, h, res) in [
            (1, 1, 0.25),
            (2, 5, 0.25),
            (3, 3, 0.25),
            (37, 19, 0.25),
            (20, 9, 0.3),
        ] {
            let mut ras = Raster::filled(w, h, GeoTransform::new(0.0, 30.0, res), 0.0f32);
            for row in 0..h {
                for col in 0..w {
                    ras.set(col, row, gaussian(2, col as i64, row as i64) as f32);
                }
            }
            let hf = HeightField::new(&ras);
            let sun = Sun::new(250.0, 35.0, res).dir;
            let mut out = vec![0.0; w];
            for row in 0..h {
                hf.cos_incidence_row(row, sun, &mut out);
                for (col, v) in out.iter().enumerate() {
                    assert_eq!(v.to_bits(), hf.cos_incidence(col, row, sun).to_bits());
                }
            }
        }
    }

    #[test]
    fn flat_ground_faces_the_sun_by_its_elevation() {
        let ras = Raster::filled(4, 4, GeoTransform::new(0.0, 1.0, 0.25), 1.0f32);
        let sun = Sun::new(250.0, 30.0, 0.25);
        let cos = HeightField::new(&ras).cos_incidence(1, 1, sun.dir);
        assert!((cos - 0.5).abs() < 1e-12);
    }

    #[test]
    fn exact_div_equals_division() {
        use crate::synthetic::noise::gaussian;
        for d in [0.25, 0.5, 1.0, 4.0, 0.3, 3.0, 1e-300, 2f64.powi(-1030)] {
            let div = ExactDiv::new(d);
            for i in 0..2000 {
                let x = gaussian(1, i, 2) * 10f64.powi((i % 40) as i32 - 20);
                assert_eq!(div.of(x).to_bits(), (x / d).to_bits(), "{x} / {d}");
            }
            for x in [0.0, -0.0, 1e308, -1e-310, f64::INFINITY] {
                assert_eq!(div.of(x).to_bits(), (x / d).to_bits(), "{x} / {d}");
            }
        }
    }
}
