//! The landforms summed into the DEM: fBm relief, craters, ridges and dune ripples.
//!
//! Craters and ridges are drawn once, serially, from `ChaCha8Rng::seed_from_u64(seed)` (stream
//! 0 for craters, stream 1 for ridges, so changing the crater density does not move the
//! ridges). After that, the height of a map point is a pure function of its position.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::noise::{Fbm, gradient, sub_seed};
use super::{DuneField, TerrainSettings};

/// Coarsest relief wavelength, metres; octaves halve it down to 25 m.
const RELIEF_WAVELENGTH_M: f64 = 400.0;
const RELIEF_OCTAVES: usize = 5;
/// Decimetre-scale roughness so slopes and shading are never perfectly smooth.
const ROUGHNESS_WAVELENGTH_M: f64 = 6.0;
const ROUGHNESS_M: f64 = 0.15;
/// Ejecta falls off as (r/R)⁻³ and is cut at this many crater radii.
const EJECTA_REACH: f64 = 3.0;
/// Cap on the crater count, so a huge density cannot exhaust memory.
const MAX_CRATERS: usize = 200_000;
/// Crater bins are this many pixels square.
const BIN_PX: usize = 32;
/// Largest sideways wander of a ridge crest, metres.
const RIDGE_MEANDER_M: f64 = 12.0;

/// Salts of the noise fields drawn from the master seed.
pub(super) const SALT_RELIEF: u64 = 1;
const SALT_ROUGHNESS: u64 = 2;
const SALT_RIDGE: u64 = 3;
const SALT_DUNE: u64 = 4;

/// A simple crater: parabolic bowl inside the rim, ejecta blanket outside.
#[derive(Clone, Debug)]
struct Crater {
    x_m: f64,
    y_m: f64,
    radius_m: f64,
    /// Floor depth below the rim crest.
    depth_m: f64,
    /// Rim crest height above the surroundings.
    rim_m: f64,
}

impl Crater {
    fn height_m(&self, x_m: f64, y_m: f64) -> f64 {
        let (dx, dy) = (x_m - self.x_m, y_m - self.y_m);
        let q2 = (dx * dx + dy * dy) / (self.radius_m * self.radius_m);
        if q2 >= EJECTA_REACH * EJECTA_REACH {
            0.0
        } else if q2 < 1.0 {
            self.rim_m - self.depth_m * (1.0 - q2)
        } else {
            let q3 = q2 * q2.sqrt();
            let floor = 1.0 / EJECTA_REACH.powi(3);
            self.rim_m * (1.0 / q3 - floor) / (1.0 - floor)
        }
    }
}

/// The craters of `p` (sanitised): over the map plus a margin, so edge craters are cut, not
/// missing; at most [`MAX_CRATERS`].
fn draw_craters(p: &TerrainSettings) -> Vec<Crater> {
    let res = p.geo.resolution_m_per_px;
    let [ox, oy] = p.geo.origin_m;
    let (width_m, height_m) = (p.width_px as f64 * res, p.height_px as f64 * res);
    let r_min = p.crater_radius_min_m.max(0.01);
    let r_max = p.crater_radius_max_m.max(r_min);
    let margin = EJECTA_REACH * r_max;
    let (area_w, area_h) = (width_m + 2.0 * margin, height_m + 2.0 * margin);
    let mut rng = ChaCha8Rng::seed_from_u64(p.seed);
    let expected = p.crater_density_per_km2.max(0.0) * area_w * area_h * 1e-6;
    let n =
        (expected.floor() + f64::from(u8::from(rng.random::<f64>() < expected.fract()))) as usize;
    (0..n.min(MAX_CRATERS))
        .map(|_| {
            let x_m = ox - margin + rng.random::<f64>() * area_w;
            let y_m = oy + margin - rng.random::<f64>() * area_h;
            // Truncated power law, cumulative N(>r) ∝ r⁻²: many small, few large.
            let u: f64 = rng.random();
            let k = 1.0 - (r_min / r_max).powi(2);
            let radius_m = r_min / (1.0 - u * k).sqrt();
            // Depth/diameter from 0.2 (fresh) down to 0.08 (degraded); rim ≈ 0.2 × depth.
            let depth_m = (0.08 + 0.12 * rng.random::<f64>()) * 2.0 * radius_m;
            Crater {
                x_m,
                y_m,
                radius_m,
                depth_m,
                rim_m: 0.2 * depth_m,
            }
        })
        .collect()
}

/// The bins (columns, rows) crater `c` reaches on the map of `p`, or `None` off the map.
fn crater_bins(
    p: &TerrainSettings,
    c: &Crater,
) -> Option<(
    std::ops::RangeInclusive<usize>,
    std::ops::RangeInclusive<usize>,
)> {
    let (w, h) = (p.width_px, p.height_px);
    let bins_x = w.div_ceil(BIN_PX).max(1);
    let bins_y = h.div_ceil(BIN_PX).max(1);
    let reach = EJECTA_REACH * c.radius_m;
    let (c0, r0) = p.geo.pixel_of(c.x_m - reach, c.y_m + reach);
    let (c1, r1) = p.geo.pixel_of(c.x_m + reach, c.y_m - reach);
    let to_bin = |v: f64, n: usize| ((v.max(0.0) / BIN_PX as f64) as usize).min(n - 1);
    if c1 < 0.0 || r1 < 0.0 || c0 > w as f64 || r0 > h as f64 {
        return None;
    }
    Some((
        to_bin(c0, bins_x)..=to_bin(c1, bins_x),
        to_bin(r0, bins_y)..=to_bin(r1, bins_y),
    ))
}

/// A long linear ridge with a smooth cross-section, tapered ends and a wandering crest.
#[derive(Clone, Debug)]
struct Ridge {
    start_m: [f64; 2],
    /// Unit vector along the ridge.
    dir: [f64; 2],
    length_m: f64,
    half_width_m: f64,
    height_m: f64,
    seed: u64,
    /// Axis-aligned bounds `[min_x, min_y, max_x, max_y]` of everything the ridge touches.
    bounds_m: [f64; 4],
}

impl Ridge {
    fn height_at(&self, x_m: f64, y_m: f64) -> f64 {
        let [x0, y0, x1, y1] = self.bounds_m;
        if x_m < x0 || x_m > x1 || y_m < y0 || y_m > y1 {
            return 0.0;
        }
        let (dx, dy) = (x_m - self.start_m[0], y_m - self.start_m[1]);
        let along = dx * self.dir[0] + dy * self.dir[1];
        if !(0.0..=self.length_m).contains(&along) {
            return 0.0;
        }
        let straight = dx * self.dir[1] - dy * self.dir[0];
        if straight.abs() >= self.half_width_m + RIDGE_MEANDER_M {
            return 0.0;
        }
        let across = straight + RIDGE_MEANDER_M * gradient(self.seed, along / 250.0, 0.5);
        let s = across / self.half_width_m;
        if s.abs() >= 1.0 {
            return 0.0;
        }
        let bump = (1.0 - s * s) * (1.0 - s * s);
        let end = (along.min(self.length_m - along) / (0.15 * self.length_m)).min(1.0);
        let vary = 0.75 + 0.25 * gradient(self.seed, along / 80.0, 3.5);
        self.height_m * bump * smoothstep(end) * vary
    }
}

/// One dune field's derived constants.
#[derive(Clone, Debug)]
struct Dunes {
    field: DuneField,
    /// Unit vector across the crests (the direction the ripple pattern repeats).
    across: [f64; 2],
    seed: u64,
}

impl Dunes {
    /// Ripple height and whether the point is inside the field.
    fn at(&self, x_m: f64, y_m: f64) -> (f64, bool) {
        let f = &self.field;
        let (dx, dy) = (x_m - f.center_m[0], y_m - f.center_m[1]);
        let d2 = dx * dx + dy * dy;
        if d2 >= f.radius_m * f.radius_m {
            return (0.0, false);
        }
        if f.wavelength_m <= 0.0 {
            return (0.0, true);
        }
        let wl = f.wavelength_m;
        // Sinuous crests: warp the phase with smooth noise a few wavelengths across.
        let phase = (dx * self.across[0] + dy * self.across[1]) / wl
            + 0.35 * gradient(self.seed, x_m / (4.0 * wl), y_m / (4.0 * wl));
        let t = phase - phase.floor();
        // Gentle stoss side (65 % of a wavelength), steep lee side near the angle of repose.
        let profile = if t < 0.65 {
            smoothstep(t / 0.65)
        } else {
            smoothstep((1.0 - t) / 0.35)
        };
        let taper = smoothstep(((f.radius_m - d2.sqrt()) / (0.2 * f.radius_m)).min(1.0));
        (f.amplitude_m * (2.0 * profile - 1.0) * taper, true)
    }
}

/// Everything that shapes the DEM, ready to evaluate at any map point.
pub(super) struct Landforms {
    base_m: f64,
    relief_m: f64,
    relief: Fbm,
    roughness: Fbm,
    craters: Vec<Crater>,
    /// Crater indices per bin, CSR layout: bin `b` holds `bin_items[bin_start[b]..bin_start[b + 1]]`.
    bin_start: Vec<u32>,
    bin_items: Vec<u32>,
    bins_x: usize,
    ridges: Vec<Ridge>,
    dunes: Vec<Dunes>,
    /// Sand patches as (centre, radius²).
    patches: Vec<([f64; 2], f64)>,
}

impl Landforms {
    /// Draws craters and ridges for `p` (already sanitised by the caller).
    pub(super) fn new(p: &TerrainSettings) -> Self {
        let (w, h) = (p.width_px, p.height_px);
        let res = p.geo.resolution_m_per_px;
        let [ox, oy] = p.geo.origin_m;
        let (width_m, height_m) = (w as f64 * res, h as f64 * res);

        let craters = draw_craters(p);
        let bins_x = w.div_ceil(BIN_PX).max(1);
        let bins_y = h.div_ceil(BIN_PX).max(1);
        let mut bins: Vec<Vec<u32>> = vec![Vec::new(); bins_x * bins_y];
        for (i, c) in craters.iter().enumerate() {
            if let Some((bx, by)) = crater_bins(p, c) {
                for by in by {
                    for bx in bx.clone() {
                        bins[by * bins_x + bx].push(i as u32);
                    }
                }
            }
        }
        let mut bin_start = Vec::with_capacity(bins.len() + 1);
        let mut bin_items = Vec::new();
        bin_start.push(0);
        for b in &bins {
            bin_items.extend_from_slice(b);
            bin_start.push(bin_items.len() as u32);
        }

        let mut rng = ChaCha8Rng::seed_from_u64(p.seed);
        rng.set_stream(1);
        let diag_m = width_m.hypot(height_m);
        let ridges = (0..p.ridge_count)
            .map(|i| {
                let centre = [
                    ox + rng.random::<f64>() * width_m,
                    oy - rng.random::<f64>() * height_m,
                ];
                let az = rng.random::<f64>() * std::f64::consts::PI;
                let dir = [az.sin(), az.cos()];
                let length_m = (0.3 + 0.5 * rng.random::<f64>()) * diag_m;
                let half_width_m = 10.0 + 15.0 * rng.random::<f64>();
                let height_m = p.ridge_height_m * (0.6 + 0.8 * rng.random::<f64>());
                let start_m = [
                    centre[0] - 0.5 * length_m * dir[0],
                    centre[1] - 0.5 * length_m * dir[1],
                ];
                let end = [
                    start_m[0] + length_m * dir[0],
                    start_m[1] + length_m * dir[1],
                ];
                let pad = half_width_m + RIDGE_MEANDER_M;
                let bounds_m = [
                    start_m[0].min(end[0]) - pad,
                    start_m[1].min(end[1]) - pad,
                    start_m[0].max(end[0]) + pad,
                    start_m[1].max(end[1]) + pad,
                ];
                let seed = sub_seed(p.seed, SALT_RIDGE + 16 * i as u64);
                Ridge {
                    start_m,
                    dir,
                    length_m,
                    half_width_m,
                    height_m,
                    seed,
                    bounds_m,
                }
            })
            .collect();

        let dunes = p
            .dune_fields
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let az = f.crest_azimuth_deg.to_radians();
                Dunes {
                    field: f.clone(),
                    across: [az.cos(), -az.sin()],
                    seed: sub_seed(p.seed, SALT_DUNE + 16 * i as u64),
                }
            })
            .collect();

        Self {
            base_m: p.base_height_m,
            relief_m: p.relief_m,
            relief: Fbm::new(
                sub_seed(p.seed, SALT_RELIEF),
                RELIEF_WAVELENGTH_M,
                RELIEF_OCTAVES,
            ),
            roughness: Fbm::new(sub_seed(p.seed, SALT_ROUGHNESS), ROUGHNESS_WAVELENGTH_M, 2),
            craters,
            bin_start,
            bin_items,
            bins_x,
            ridges,
            dunes,
            patches: p.sand_patches.iter().map(|&(c, r)| (c, r * r)).collect(),
        }
    }

    /// Heights (m, clamped by `clamp`) and forced-sand flags of raster row `row`, whose pixel
    /// centres lie at `(xs[col], y_m)`.
    pub(super) fn fill_row(
        &self,
        row: usize,
        xs: &[f64],
        y_m: f64,
        clamp: impl Fn(f64) -> f64,
        heights: &mut [f32],
        forced: &mut [bool],
    ) {
        let mut relief = vec![0.0; xs.len()];
        let mut roughness = vec![0.0; xs.len()];
        self.relief.row(xs, y_m, &mut relief);
        self.roughness.row(xs, y_m, &mut roughness);
        let bins = self.bins_x * (row / BIN_PX);
        for (col, (&x_m, (z_out, sand_out))) in xs
            .iter()
            .zip(heights.iter_mut().zip(forced.iter_mut()))
            .enumerate()
        {
            let mut z = self.base_m + self.relief_m * relief[col] + ROUGHNESS_M * roughness[col];
            let bin = bins + col / BIN_PX;
            if let (Some(&a), Some(&b)) = (self.bin_start.get(bin), self.bin_start.get(bin + 1)) {
                for &i in &self.bin_items[a as usize..b as usize] {
                    z += self.craters[i as usize].height_m(x_m, y_m);
                }
            }
            for r in &self.ridges {
                z += r.height_at(x_m, y_m);
            }
            let mut sand = false;
            for d in &self.dunes {
                let (dz, inside) = d.at(x_m, y_m);
                z += dz;
                sand |= inside;
            }
            for &(c, r2) in &self.patches {
                let (dx, dy) = (x_m - c[0], y_m - c[1]);
                sand |= dx * dx + dy * dy < r2;
            }
            *z_out = clamp(z) as f32;
            *sand_out = sand;
        }
    }

    /// Evaluations of a landform at a pixel the DEM pass makes for `p` (sanitised): each
    /// crater at every pixel of the bins it reaches, each ridge, dune field and sand patch at
    /// every pixel. The pass's time is about proportional to it.
    pub(super) fn evaluations(p: &TerrainSettings) -> u64 {
        let (w, h) = (p.width_px as u64, p.height_px as u64);
        let bin_px = BIN_PX as u64;
        // Pixels of bins `from..to` along a side of `n` pixels (the last bin may be short).
        let span = |bins: std::ops::RangeInclusive<usize>, n: u64| {
            let (a, b) = (
                *bins.start() as u64 * bin_px,
                (*bins.end() as u64 + 1) * bin_px,
            );
            b.min(n).saturating_sub(a)
        };
        let craters = draw_craters(p)
            .iter()
            .filter_map(|c| crater_bins(p, c))
            .map(|(bx, by)| span(bx, w).saturating_mul(span(by, h)))
            .fold(0u64, u64::saturating_add);
        let others = (p.ridge_count + p.dune_fields.len() + p.sand_patches.len()) as u64;
        craters.saturating_add(w.saturating_mul(h).saturating_mul(others))
    }

    #[cfg(test)]
    /// Number of craters drawn (including those only partly on the map).
    pub(super) fn crater_count(&self) -> usize {
        self.craters.len()
    }
}

/// Cubic ease from 0 at `t ≤ 0` to 1 at `t ≥ 1`.
pub(super) fn smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crater_profile_has_rim_bowl_and_fading_ejecta() {
        let c = Crater {
            x_m: 0.0,
            y_m: 0.0,
            radius_m: 10.0,
            depth_m: 4.0,
            rim_m: 0.8,
        };
        assert!((c.height_m(0.0, 0.0) - (0.8 - 4.0)).abs() < 1e-12, "floor");
        assert!((c.height_m(10.0, 0.0) - 0.8).abs() < 1e-12, "rim inside");
        assert!(
            (c.height_m(0.0, -10.0 - 1e-9) - 0.8).abs() < 1e-6,
            "rim outside"
        );
        assert!(c.height_m(20.0, 0.0) > 0.0 && c.height_m(20.0, 0.0) < 0.8);
        assert!(
            c.height_m(29.999, 0.0).abs() < 1e-3,
            "ejecta reaches zero at 3 radii"
        );
        assert_eq!(c.height_m(31.0, 0.0), 0.0);
        // Inner wall at the rim: 2·depth/radius = 0.8, i.e. 38.7°, a hazard.
        let wall = (c.height_m(10.0, 0.0) - c.height_m(9.99, 0.0)) / 0.01;
        assert!((wall - 0.8).abs() < 1e-2, "{wall}");
    }

    #[test]
    fn craters_are_counted_by_density_and_ridges_ignore_it() {
        let base = TerrainSettings {
            crater_density_per_km2: 0.0,
            ..TerrainSettings::default()
        };
        assert_eq!(Landforms::new(&base).crater_count(), 0);
        let dense = TerrainSettings {
            crater_density_per_km2: 50.0,
            ..TerrainSettings::default()
        };
        // 1 km² map plus a 180 m ejecta margin: 1.36² km² × 50 ≈ 92.
        let n = Landforms::new(&dense).crater_count();
        assert!((91..=93).contains(&n), "{n}");
        let ridge = |p: &TerrainSettings| {
            Landforms::new(p)
                .ridges
                .iter()
                .map(|r| r.start_m)
                .collect::<Vec<_>>()
        };
        assert_eq!(ridge(&base), ridge(&dense));
    }

    #[test]
    fn evaluations_are_the_work_of_the_bins_and_the_other_landforms() {
        // 1000 × 700 px: the last bins are short on both sides.
        let p = TerrainSettings {
            width_px: 1000,
            height_px: 700,
            crater_density_per_km2: 200.0,
            crater_radius_max_m: 90.0,
            ridge_count: 4,
            sand_patches: vec![([10.0, 10.0], 5.0)],
            ..TerrainSettings::default()
        }
        .sanitized();
        let l = Landforms::new(&p);
        let mut want = 0u64;
        for row in 0..p.height_px {
            for col in 0..p.width_px {
                let bin = l.bins_x * (row / BIN_PX) + col / BIN_PX;
                want += u64::from(l.bin_start[bin + 1] - l.bin_start[bin]);
            }
        }
        want += 1000 * 700 * 5;
        assert_eq!(Landforms::evaluations(&p), want);
        assert!(want > 1000 * 700 * 6, "the craters count too: {want}");
    }
}
