//! Hash-based lattice noise for the terrain generator.
//!
//! Every value is a pure function of (seed, position): there is no generator state and no call
//! order, so rows can be computed in any order on any number of threads and give the same bits.
//! No libm function is used per sample (only integer hashing, `+`, `*`), so results do not
//! depend on the platform's libm either.
//!
//! ## References
//! K. Perlin, "Improving noise", SIGGRAPH 2002 (gradient lattice, quintic fade);
//! S. Vigna, splitmix64 (the 64-bit finaliser used as the lattice hash).

/// Most octaves an [`Fbm`] sums.
const MAX_OCTAVES: usize = 8;

/// The splitmix64 finaliser: a bijective 64-bit mix with full avalanche.
#[inline]
pub(super) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// An independent seed for one use (`salt`) of the master `seed`.
#[must_use]
pub(super) fn sub_seed(seed: u64, salt: u64) -> u64 {
    mix64(seed ^ mix64(salt.wrapping_add(0x9E37_79B9_7F4A_7C15)))
}

/// Hash of lattice cell `(ix, iy)` under `seed`.
#[inline]
fn hash2(seed: u64, ix: i64, iy: i64) -> u64 {
    // Casting wraps negative cells to distinct u64 values, which is all a hash needs.
    mix64(
        seed ^ (ix as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
            ^ (iy as u64)
                .wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
                .rotate_left(29),
    )
}

/// A uniform value in `[-1, 1)` for lattice cell `(ix, iy)`: white noise, one value per pixel.
#[inline]
#[must_use]
pub(super) fn white(seed: u64, ix: i64, iy: i64) -> f64 {
    (hash2(seed, ix, iy) >> 11) as f64 * (2.0 / (1u64 << 53) as f64) - 1.0
}

/// Sixteen unit gradients, 22.5° apart (literal values: no trigonometry at run time).
const GRADIENTS: [(f64, f64); 16] = [
    (1.0, 0.0),
    (0.923_879_532_511_286_7, 0.382_683_432_365_089_8),
    (0.707_106_781_186_547_6, 0.707_106_781_186_547_6),
    (0.382_683_432_365_089_8, 0.923_879_532_511_286_7),
    (0.0, 1.0),
    (-0.382_683_432_365_089_8, 0.923_879_532_511_286_7),
    (-0.707_106_781_186_547_6, 0.707_106_781_186_547_6),
    (-0.923_879_532_511_286_7, 0.382_683_432_365_089_8),
    (-1.0, 0.0),
    (-0.923_879_532_511_286_7, -0.382_683_432_365_089_8),
    (-0.707_106_781_186_547_6, -0.707_106_781_186_547_6),
    (-0.382_683_432_365_089_8, -0.923_879_532_511_286_7),
    (0.0, -1.0),
    (0.382_683_432_365_089_8, -0.923_879_532_511_286_7),
    (0.707_106_781_186_547_6, -0.707_106_781_186_547_6),
    (0.923_879_532_511_286_7, -0.382_683_432_365_089_8),
];

#[inline]
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// `floor(x)` as an integer, inlined: the libm call is a measurable share of the generator on
/// x86-64 without SSE4.1. NaN gives 0; values beyond ±2⁶³ saturate.
#[inline]
fn floor_i64(x: f64) -> i64 {
    let i = x as i64;
    if i as f64 > x { i - 1 } else { i }
}

/// The gradient of a lattice corner from its column and row hashes: one multiply per corner
/// (the column and row products are shared by the four corners of a cell).
#[inline]
fn corner_gradient(seed: u64, hx: u64, hy: u64) -> (f64, f64) {
    let mut h = seed ^ hx ^ hy;
    h = (h ^ (h >> 32)).wrapping_mul(0xD6E8_FEB8_6659_FD93);
    GRADIENTS[(h >> 60) as usize]
}

/// Gradient noise at `(x, y)` in lattice units: smooth, zero on lattice points, roughly in
/// `[-1, 1]` (scaled by √2 from the unit-gradient range).
#[inline]
#[must_use]
pub(super) fn gradient(seed: u64, x: f64, y: f64) -> f64 {
    let (ix, iy) = (floor_i64(x), floor_i64(y));
    let (fx, fy) = (x - ix as f64, y - iy as f64);
    const KX: u64 = 0x9E37_79B9_7F4A_7C15;
    const KY: u64 = 0xC2B2_AE3D_27D4_EB4F;
    // Casting wraps negative cells to distinct u64 values, which is all a hash needs.
    let (hx0, hx1) = ((ix as u64).wrapping_mul(KX), (ix.wrapping_add(1) as u64).wrapping_mul(KX));
    let (hy0, hy1) = (
        (iy as u64).wrapping_mul(KY).rotate_left(29),
        (iy.wrapping_add(1) as u64).wrapping_mul(KY).rotate_left(29),
    );
    let dot = |hx: u64, hy: u64, dx: f64, dy: f64| {
        let (gx, gy) = corner_gradient(seed, hx, hy);
        gx * dx + gy * dy
    };
    let n00 = dot(hx0, hy0, fx, fy);
    let n10 = dot(hx1, hy0, fx - 1.0, fy);
    let n01 = dot(hx0, hy1, fx, fy - 1.0);
    let n11 = dot(hx1, hy1, fx - 1.0, fy - 1.0);
    let (u, v) = (fade(fx), fade(fy));
    let a = n00 + u * (n10 - n00);
    let b = n01 + u * (n11 - n01);
    (a + v * (b - a)) * std::f64::consts::SQRT_2
}

/// Fractal Brownian motion: `octaves` of [`gradient`] noise, each half the wavelength and half
/// the amplitude of the previous, normalised so the result stays roughly in `[-1, 1]`.
/// Each octave is rotated and offset so the lattices never line up.
#[derive(Clone, Debug)]
pub(super) struct Fbm {
    seeds: [u64; MAX_OCTAVES],
    /// Per octave: the rotation (cos, sin) times the octave frequency, and an offset.
    frames: [(f64, f64, f64, f64); MAX_OCTAVES],
    octaves: usize,
    norm: f64,
}

impl Fbm {
    /// Noise whose coarsest octave has wavelength `wavelength_m` (in the units of the
    /// coordinates passed to [`Fbm::at`]); `octaves` is clamped to 1..=8.
    #[must_use]
    pub(super) fn new(seed: u64, wavelength_m: f64, octaves: usize) -> Self {
        let octaves = octaves.clamp(1, MAX_OCTAVES);
        let mut seeds = [0; MAX_OCTAVES];
        let mut frames = [(0.0, 0.0, 0.0, 0.0); MAX_OCTAVES];
        // Rotate each octave by atan2(3, 4) ≈ 36.87° more than the last: no trigonometry needed.
        let (mut c, mut s) = (1.0f64, 0.0f64);
        let mut freq = 1.0 / wavelength_m;
        let (mut amp, mut total) = (1.0, 0.0);
        for o in 0..octaves {
            seeds[o] = sub_seed(seed, o as u64);
            let off = 1000.0 * white(seeds[o], -1, -1);
            frames[o] = (c * freq, s * freq, off, -off);
            (c, s) = (0.8 * c - 0.6 * s, 0.6 * c + 0.8 * s);
            freq *= 2.0;
            total += amp;
            amp *= 0.5;
        }
        Self {
            seeds,
            frames,
            octaves,
            norm: 1.0 / total,
        }
    }

    /// The noise at `(x, y)`.
    #[inline]
    #[must_use]
    pub(super) fn at(&self, x: f64, y: f64) -> f64 {
        let mut sum = 0.0;
        let mut amp = 1.0;
        for o in 0..self.octaves {
            let (c, s, ox, oy) = self.frames[o];
            sum += amp * gradient(self.seeds[o], c * x - s * y + ox, s * x + c * y + oy);
            amp *= 0.5;
        }
        sum * self.norm
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradient_noise_is_smooth_bounded_and_zero_on_the_lattice() {
        let seed = 42;
        assert_eq!(gradient(seed, 3.0, -7.0), 0.0);
        let mut max_abs = 0.0f64;
        for i in 0..20_000 {
            let (x, y) = (i as f64 * 0.0137 - 50.0, i as f64 * 0.0291 + 3.0);
            let v = gradient(seed, x, y);
            max_abs = max_abs.max(v.abs());
            // Continuity: a tiny step moves the value a little.
            assert!((gradient(seed, x + 1e-6, y) - v).abs() < 1e-4);
        }
        assert!(max_abs <= 1.0 + 1e-9 && max_abs > 0.5, "{max_abs}");
    }

    #[test]
    fn values_depend_only_on_seed_and_position() {
        let f = Fbm::new(7, 100.0, 5);
        let g = Fbm::new(7, 100.0, 5);
        let h = Fbm::new(8, 100.0, 5);
        let a = f.at(123.4, -56.7);
        assert_eq!(a.to_bits(), g.at(123.4, -56.7).to_bits());
        assert_ne!(a.to_bits(), h.at(123.4, -56.7).to_bits());
        assert_eq!(white(1, 2, 3), white(1, 2, 3));
        assert_ne!(white(1, 2, 3), white(1, 3, 2));
        assert_ne!(sub_seed(1, 0), sub_seed(1, 1));
    }

    #[test]
    fn white_noise_is_roughly_uniform() {
        let n = 100_000;
        let mean: f64 = (0..n).map(|i| white(9, i % 317, i / 317)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.01, "{mean}");
        assert!((0..n).all(|i| (-1.0..1.0).contains(&white(9, i, -i))));
    }
}
