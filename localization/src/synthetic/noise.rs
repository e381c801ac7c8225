//! Hash-based noise: every value is a pure function of (seed, position), with no generator state
//! and no call order, so rows can be rendered on any number of threads and give the same bits.

// The lattice hashes are the terrain generator's, so both crates draw from one definition.
pub(super) use maps::procedural::noise::{hash2, mix64, sub_seed};

/// The top 53 bits of `h` as a uniform value in `[0, 1)`.
#[inline]
fn unit(h: u64) -> f64 {
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// An approximately standard normal value for lattice point `(ix, iy)`: the Irwin–Hall sum of
/// four 16-bit uniforms from one hash, centred and scaled to unit variance (range ±3.46). Only
/// integer hashing and `+`, `*`: no libm, so the bits do not depend on the platform.
#[inline]
#[must_use]
pub(crate) fn gaussian(seed: u64, ix: i64, iy: i64) -> f64 {
    let h = hash2(seed, ix, iy);
    let sum = (h & 0xFFFF) + ((h >> 16) & 0xFFFF) + ((h >> 32) & 0xFFFF) + (h >> 48);
    // Each 16-bit part is uniform on {0, …, 65535}: mean 32767.5, variance (65536² − 1) / 12.
    const SCALE: f64 = 1.0 / 37_837.226_5; // 1 / √(4 × (65536² − 1) / 12)
    (sum as f64 - 4.0 * 32_767.5) * SCALE
}

/// `floor(x)` as an integer (NaN gives 0, huge values saturate).
#[inline]
pub(super) fn floor_i64(x: f64) -> i64 {
    let i = x as i64;
    if i as f64 > x { i - 1 } else { i }
}

#[inline]
fn smoothstep(t: f64) -> f64 {
    t * t * (3.0 - 2.0 * t)
}

/// A lattice value with zero mean and unit variance: uniform on `[-√3, √3)` (hashing only, no
/// transcendental functions: value noise is the hot loop of the truth patch).
#[inline]
fn lattice(seed: u64, ix: i64, iy: i64) -> f64 {
    (2.0 * unit(hash2(seed, ix, iy)) - 1.0) * 3f64.sqrt()
}

/// Value noise at `(x, y)` in lattice units: zero-mean, unit-variance lattice values blended
/// with a smoothstep, so the field is continuous with a standard deviation of about 0.75.
/// The renderers evaluate it through [`CachedValue`]; this is its reference.
#[cfg(test)]
#[must_use]
pub(super) fn value(seed: u64, x: f64, y: f64) -> f64 {
    let (ix, iy) = (floor_i64(x), floor_i64(y));
    let (u, v) = (smoothstep(x - ix as f64), smoothstep(y - iy as f64));
    let a = lattice(seed, ix, iy);
    let b = lattice(seed, ix + 1, iy);
    let c = lattice(seed, ix, iy + 1);
    let d = lattice(seed, ix + 1, iy + 1);
    let top = a + u * (b - a);
    let bottom = c + u * (d - c);
    top + v * (bottom - top)
}

/// [`value`] noise of one seed that remembers the corners of the last lattice cell it
/// evaluated: neighbouring pixels of a 25 cm grid mostly fall in the cell of a noise of metres
/// wavelength, so most calls hash nothing. Bit-identical to [`value`].
#[derive(Clone, Debug)]
pub(super) struct CachedValue {
    seed: u64,
    /// The cell `(ix, iy)` whose corners are held (`None` before the first call).
    cell: Option<(i64, i64)>,
    corners: [f64; 4],
}

impl CachedValue {
    /// Value noise of `seed`.
    #[must_use]
    pub(super) fn new(seed: u64) -> Self {
        Self {
            seed,
            cell: None,
            corners: [0.0; 4],
        }
    }

    /// `value(seed, x, y)`.
    #[inline]
    pub(super) fn at(&mut self, x: f64, y: f64) -> f64 {
        let (ix, iy) = (floor_i64(x), floor_i64(y));
        if self.cell != Some((ix, iy)) {
            let s = self.seed;
            self.corners = [
                lattice(s, ix, iy),
                lattice(s, ix + 1, iy),
                lattice(s, ix, iy + 1),
                lattice(s, ix + 1, iy + 1),
            ];
            self.cell = Some((ix, iy));
        }
        let [a, b, c, d] = self.corners;
        let (u, v) = (smoothstep(x - ix as f64), smoothstep(y - iy as f64));
        let top = a + u * (b - a);
        let bottom = c + u * (d - c);
        top + v * (bottom - top)
    }
}

/// [`value`]`(seed, xs[i], y)` into `out[i]` for a row of points: bit-identical, with each
/// lattice cell's run of points blended in a loop the compiler vectorizes (as
/// [`ValueFbm::row`]).
pub(super) fn value_row(seed: u64, xs: &[f64], y: f64, out: &mut [f64]) {
    let iy = floor_i64(y);
    let v = smoothstep(y - iy as f64);
    let n = out.len().min(xs.len());
    let mut i = 0;
    while i < n {
        let ix = floor_i64(xs[i]);
        let [a, b, c, d] = [
            lattice(seed, ix, iy),
            lattice(seed, ix + 1, iy),
            lattice(seed, ix, iy + 1),
            lattice(seed, ix + 1, iy + 1),
        ];
        let lo = ix as f64;
        let mut end = i + 1;
        if lo.abs() < 1e15 {
            while end < n && xs[end] >= lo && xs[end] < lo + 1.0 {
                end += 1;
            }
        }
        for (o, &x) in out[i..end].iter_mut().zip(&xs[i..end]) {
            let u = smoothstep(x - lo);
            let top = a + u * (b - a);
            let bottom = c + u * (d - c);
            *o = top + v * (bottom - top);
        }
        i = end;
    }
}

/// Most octaves a [`ValueFbm`] sums.
const MAX_OCTAVES: usize = 6;

/// Fractal value noise: octaves of [`value`] noise, each half the wavelength and half the
/// amplitude of the previous, normalised so the result has a standard deviation of about 0.6.
#[derive(Clone, Debug)]
pub(super) struct ValueFbm {
    seeds: [u64; MAX_OCTAVES],
    octaves: usize,
    base_frequency: f64,
    norm: f64,
}

impl ValueFbm {
    /// Noise whose coarsest octave has wavelength `wavelength_m`; `octaves` is clamped to 1..=6.
    #[must_use]
    pub(super) fn new(seed: u64, wavelength_m: f64, octaves: usize) -> Self {
        let octaves = octaves.clamp(1, MAX_OCTAVES);
        let mut seeds = [0; MAX_OCTAVES];
        let (mut amp, mut total_sq) = (1.0, 0.0);
        for (o, s) in seeds.iter_mut().enumerate().take(octaves) {
            *s = sub_seed(seed, o as u64);
            total_sq += amp * amp;
            amp *= 0.5;
        }
        Self {
            seeds,
            octaves,
            base_frequency: 1.0 / wavelength_m,
            norm: 0.8 / f64::sqrt(total_sq),
        }
    }

    /// The noise at map point `(x_m, y_m)`: the reference for [`ValueFbm::row`].
    #[cfg(test)]
    #[must_use]
    pub(super) fn at(&self, x_m: f64, y_m: f64) -> f64 {
        let (mut sum, mut amp, mut f) = (0.0, 1.0, self.base_frequency);
        for &s in &self.seeds[..self.octaves] {
            // Octaves are offset by their seed so their lattices never line up.
            let off = (s >> 40) as f64 * (1.0 / (1u64 << 14) as f64);
            sum += amp * value(s, x_m * f + off, y_m * f - off);
            amp *= 0.5;
            f *= 2.0;
        }
        sum * self.norm
    }

    /// The noise at `(xs[i], y)` into `out[i]`, bit-identical to [`ValueFbm::at`] but faster:
    /// along a row each octave's lattice cell, and so its four corner values, is reused.
    pub(super) fn row(&self, xs: &[f64], y_m: f64, out: &mut [f64]) {
        out.fill(0.0);
        let (mut amp, mut f) = (1.0, self.base_frequency);
        for &s in &self.seeds[..self.octaves] {
            let off = (s >> 40) as f64 * (1.0 / (1u64 << 14) as f64);
            let y = y_m * f - off;
            let iy = floor_i64(y);
            let v = smoothstep(y - iy as f64);
            let mut cell: Option<(i64, [f64; 4])> = None;
            let n = out.len().min(xs.len());
            let mut i = 0;
            while i < n {
                let ix = floor_i64(xs[i] * f + off);
                let [a, b, c, d] = match cell {
                    Some((cx, corners)) if cx == ix => corners,
                    // The next cell east shares its west corners with this one's east ones.
                    Some((cx, [_, b, _, d])) if cx.checked_add(1) == Some(ix) => {
                        let corners = [b, lattice(s, ix + 1, iy), d, lattice(s, ix + 1, iy + 1)];
                        cell = Some((ix, corners));
                        corners
                    }
                    _ => {
                        let corners = [
                            lattice(s, ix, iy),
                            lattice(s, ix + 1, iy),
                            lattice(s, ix, iy + 1),
                            lattice(s, ix + 1, iy + 1),
                        ];
                        cell = Some((ix, corners));
                        corners
                    }
                };
                // The run of pixels in this cell (`floor(x) == ix` is `lo ≤ x < lo + 1` where
                // both ends are exact), then its blends in a loop the compiler vectorizes.
                let lo = ix as f64;
                let mut end = i + 1;
                if lo.abs() < 1e15 {
                    while end < n {
                        let x = xs[end] * f + off;
                        if !(x >= lo && x < lo + 1.0) {
                            break;
                        }
                        end += 1;
                    }
                }
                for (acc, &x_m) in out[i..end].iter_mut().zip(&xs[i..end]) {
                    let u = smoothstep(x_m * f + off - lo);
                    let top = a + u * (b - a);
                    let bottom = c + u * (d - c);
                    *acc += amp * (top + v * (bottom - top));
                }
                i = end;
            }
            amp *= 0.5;
            f *= 2.0;
        }
        for acc in out.iter_mut() {
            *acc *= self.norm;
        }
    }
}

/// A tiny splitmix64 stream for a handful of draws seeded from a hash (one rock cell).
#[derive(Clone, Debug)]
pub(super) struct SplitMix(pub(super) u64);

impl SplitMix {
    /// The next uniform value in `[0, 1)`.
    pub(super) fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        unit(mix64(self.0))
    }

    /// A uniform value in `[lo, hi)`.
    pub(super) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_has_unit_moments() {
        let n = 200_000;
        let xs: Vec<f64> = (0..n).map(|i| gaussian(5, i % 401, i / 401)).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
        assert!(
            mean.abs() < 0.01 && (var - 1.0).abs() < 0.02,
            "{mean} {var}"
        );
    }

    #[test]
    fn value_noise_is_continuous_and_pure() {
        for i in 0..2000 {
            let (x, y) = (i as f64 * 0.173 - 40.0, i as f64 * 0.071 + 9.0);
            let v = value(3, x, y);
            assert_eq!(v.to_bits(), value(3, x, y).to_bits());
            assert!((value(3, x + 1e-7, y) - v).abs() < 1e-5);
        }
        let f = ValueFbm::new(1, 3.0, 4);
        let n = 20_000;
        let sd = ((0..n)
            .map(|i| f.at(i as f64 * 0.37, i as f64 * 0.11).powi(2))
            .sum::<f64>()
            / n as f64)
            .sqrt();
        assert!(sd > 0.3 && sd < 1.0, "{sd}");
    }

    #[test]
    fn value_noise_has_the_documented_spread() {
        let n = 100_000;
        let sd = ((0..n)
            .map(|i| value(4, i as f64 * 0.377, i as f64 * 0.0131).powi(2))
            .sum::<f64>()
            / n as f64)
            .sqrt();
        assert!((sd - 0.75).abs() < 0.08, "{sd}");
    }

    #[test]
    fn row_evaluation_matches_pointwise_bit_for_bit() {
        let f = ValueFbm::new(99, 3.0, 4);
        let row: Vec<f64> = (0..300).map(|i| -20.0 + (i as f64 + 0.5) * 0.25).collect();
        // A row of pixels, the same backwards, scattered, and far from the origin.
        let backwards: Vec<f64> = row.iter().rev().copied().collect();
        let scattered: Vec<f64> = (0..300)
            .map(|i| f64::from(i * 37 % 101) * 0.31 - 9.0)
            .collect();
        let far: Vec<f64> = row.iter().map(|x| x + 3.0e6).collect();
        for xs in [row, backwards, scattered, far] {
            let mut out = vec![0.0; xs.len()];
            for y in [-5.125, 0.0, 3.5, 1e4 + 0.375] {
                f.row(&xs, y, &mut out);
                for (x, v) in xs.iter().zip(&out) {
                    assert_eq!(v.to_bits(), f.at(*x, y).to_bits(), "({x}, {y})");
                }
            }
        }
    }

    #[test]
    fn cached_value_matches_value_bit_for_bit() {
        let mut cached = CachedValue::new(17);
        // Along rows, down columns, jumping about, across negative cells and back.
        let mut points: Vec<(f64, f64)> = (0..600)
            .map(|i| (-30.0 + f64::from(i) * 0.0625, 4.3 - f64::from(i / 97) * 0.9))
            .collect();
        points.extend((0..200).map(|i| (f64::from(i * 37 % 23) - 11.5, f64::from(i % 7) * -1.3)));
        for (x, y) in points {
            assert_eq!(
                cached.at(x, y).to_bits(),
                value(17, x, y).to_bits(),
                "({x}, {y})"
            );
        }
    }

    #[test]
    fn value_row_matches_value_bit_for_bit() {
        let row: Vec<f64> = (0..700).map(|i| -3.1 + f64::from(i) * 0.00625).collect();
        let backwards: Vec<f64> = row.iter().rev().copied().collect();
        let scattered: Vec<f64> = (0..300)
            .map(|i| f64::from(i * 37 % 101) * 0.031 - 1.0)
            .collect();
        for xs in [row, backwards, scattered] {
            let mut out = vec![0.0; xs.len()];
            for y in [-2.4375, 0.0, 0.99, 250.5] {
                value_row(23, &xs, y, &mut out);
                for (x, v) in xs.iter().zip(&out) {
                    assert_eq!(v.to_bits(), value(23, *x, y).to_bits(), "({x}, {y})");
                }
            }
        }
    }

    #[test]
    fn floor_matches_std() {
        for x in [-2.5, -2.0, -0.1, 0.0, 0.1, 3.0, 3.9] {
            assert_eq!(floor_i64(x), x.floor() as i64);
        }
    }
}
