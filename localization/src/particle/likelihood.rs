//! From a score surface to the likelihood the filter weighs particles by.

use crate::matcher::ScoreSurface;

/// The likelihood of the rover being at each offset of `surface`, relative to the best:
/// `exp(−(s − s_ref) / T)` with `T = temperature` (score units, > 0), convolved with an
/// isotropic Gaussian of σ = `registration_sigma_m` metres (≥ 0; 0 = no convolution).
/// Offsets without a score contribute nothing; near the edges the convolution is normalised by
/// the kernel mass that fell on the surface, so the edges are not darkened. Row-major, one
/// value per offset, in `[0, 1]` when `s_ref` is the smallest score.
///
/// Why the convolution: the score surface is computed for the rover's own geometry, and the
/// errors it cannot see — the orbital map's orthorectification, the rover's heading and scale
/// (the matcher's `sigma_floor_m`) — shift the whole surface by an unknown offset. The
/// likelihood of a position is then the surface's, averaged over that offset. Without it a
/// single temperature has to do two jobs: be large enough that a peak a pixel or two off the
/// truth still leaves the truth probable, and small enough that unrelated terrain is
/// improbable; the calibration (`examples/particle_temperature.rs`) found no value that does
/// both.
///
/// # Panics
/// If `surface.scores` does not hold `width × height` values.
#[must_use]
pub fn likelihood_grid(
    surface: &ScoreSurface,
    s_ref: f64,
    temperature: f64,
    registration_sigma_m: f64,
) -> Vec<f64> {
    let (w, h) = (surface.width, surface.height);
    assert_eq!(
        surface.scores.len(),
        w * h,
        "likelihood_grid: scores must be width × height"
    );
    let raw: Vec<f64> = surface
        .scores
        .iter()
        .map(|&s| {
            if s.is_finite() {
                (-(s - s_ref) / temperature).exp()
            } else {
                0.0
            }
        })
        .collect();
    let sigma_px = registration_sigma_m / surface.resolution_m_per_px;
    // Also catches a NaN σ.
    if sigma_px.is_nan() || sigma_px <= 0.0 {
        return raw;
    }
    let pad = (3.0 * sigma_px).ceil() as usize;
    let (pw, ph) = (w + 2 * pad, h + 2 * pad);
    let mut value = vec![0.0; pw * ph];
    let mut mask = vec![0.0; pw * ph];
    for row in 0..h {
        for col in 0..w {
            let i = (row + pad) * pw + col + pad;
            if surface.scores[row * w + col].is_finite() {
                value[i] = raw[row * w + col];
                mask[i] = 1.0;
            }
        }
    }
    let blurred = blur_separable(&value, pw, ph, [sigma_px; 2], [pad; 2]);
    let weight = blur_separable(&mask, pw, ph, [sigma_px; 2], [pad; 2]);
    blurred
        .iter()
        .zip(&weight)
        .map(|(v, m)| if *m > 0.0 { v / m } else { 0.0 })
        .collect()
}

/// Separable Gaussian blur of a `src_w × src_h` row-major grid that is padded by `pad` cells
/// on each side (per axis); returns the inner `(src_w − 2 pad_x) × (src_h − 2 pad_y)` cells.
/// `sigma_px` is σ per axis in cells; the kernel reaches `pad` cells (normally ⌈3σ⌉) and is
/// not normalised (a constant factor that cancels in every use here).
pub(super) fn blur_separable(
    src: &[f64],
    src_w: usize,
    src_h: usize,
    sigma_px: [f64; 2],
    pad: [usize; 2],
) -> Vec<f64> {
    let (w, h) = (src_w - 2 * pad[0], src_h - 2 * pad[1]);
    let kernel = |half: usize, sigma: f64| -> Vec<f64> {
        (0..=2 * half)
            .map(|j| {
                let d = j as f64 - half as f64;
                if sigma > 0.0 {
                    (-0.5 * (d / sigma).powi(2)).exp()
                } else if d == 0.0 {
                    1.0
                } else {
                    0.0
                }
            })
            .collect()
    };
    let (kx, ky) = (kernel(pad[0], sigma_px[0]), kernel(pad[1], sigma_px[1]));
    // Along x, only the inner columns are needed; then along y, only the inner rows.
    let mut along_x = vec![0.0; w * src_h];
    for row in 0..src_h {
        let line = &src[row * src_w..(row + 1) * src_w];
        if line.iter().all(|&v| v == 0.0) {
            continue;
        }
        for col in 0..w {
            along_x[row * w + col] = kx
                .iter()
                .zip(&line[col..col + kx.len()])
                .map(|(k, v)| k * v)
                .sum();
        }
    }
    let mut out = vec![0.0; w * h];
    for row in 0..h {
        for (j, k) in ky.iter().enumerate() {
            let line = &along_x[(row + j) * w..(row + j + 1) * w];
            for (o, v) in out[row * w..(row + 1) * w].iter_mut().zip(line) {
                *o += k * v;
            }
        }
    }
    out
}

/// Bilinear interpolation of a `w × h` row-major grid at fractional cell `(fx, fy)`, or `None`
/// outside it.
pub(super) fn bilinear_at(grid: &[f64], w: usize, h: usize, fx: f64, fy: f64) -> Option<f64> {
    if !(fx >= 0.0 && fy >= 0.0) || w == 0 || h == 0 {
        return None;
    }
    if fx > (w - 1) as f64 || fy > (h - 1) as f64 {
        return None;
    }
    let (x0, y0) = (fx.floor() as usize, fy.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
    let (tx, ty) = (fx - x0 as f64, fy - y0 as f64);
    let g = |x: usize, y: usize| grid[y * w + x];
    let top = g(x0, y0) * (1.0 - tx) + g(x1, y0) * tx;
    let bottom = g(x0, y1) * (1.0 - tx) + g(x1, y1) * tx;
    Some(top * (1.0 - ty) + bottom * ty)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn surface(w: usize, h: usize, scores: Vec<f64>) -> ScoreSurface {
        ScoreSurface {
            width: w,
            height: h,
            scores,
            census_valid_bits: None,
            window_origin_m: [0.0, 100.0],
            template_px: [8, 8],
            resolution_m_per_px: 0.25,
            valid_fraction: 1.0,
        }
    }

    #[test]
    fn likelihood_is_exp_of_the_score_and_the_blur_keeps_flat_fields_flat() {
        let s = surface(3, 1, vec![0.3, 0.31, f64::INFINITY]);
        let l = likelihood_grid(&s, 0.3, 0.01, 0.0);
        assert!((l[0] - 1.0).abs() < 1e-15 && (l[1] - (-1.0f64).exp()).abs() < 1e-12);
        assert_eq!(l[2], 0.0);
        // A constant score stays constant after the normalised blur, edges included.
        let flat = surface(20, 15, vec![0.4; 300]);
        for v in likelihood_grid(&flat, 0.3, 0.05, 0.5) {
            assert!((v - (-2.0f64).exp()).abs() < 1e-12, "{v}");
        }
    }

    #[test]
    fn blur_spreads_a_spike_into_its_gaussian() {
        // One spike in the middle of a 21 × 21 surface, σ = 2 px (0.5 m): the blurred values
        // fall off as exp(−d²/8) relative to the centre, away from the edges.
        let mut scores = vec![10.0; 21 * 21];
        scores[10 * 21 + 10] = 0.0;
        let l = likelihood_grid(&surface(21, 21, scores), 0.0, 0.1, 0.5);
        let c = l[10 * 21 + 10];
        for d in 1..=4usize {
            let r = l[10 * 21 + 10 + d] / c;
            let e = (-((d * d) as f64) / 8.0).exp();
            assert!((r - e).abs() < 1e-6, "{d}: {r} vs {e}");
        }
    }

    #[test]
    fn bilinear_inside_and_outside() {
        let g = [0.0, 1.0, 2.0, 3.0];
        assert_eq!(bilinear_at(&g, 2, 2, 0.5, 0.5), Some(1.5));
        assert_eq!(bilinear_at(&g, 2, 2, 1.0, 1.0), Some(3.0));
        assert_eq!(bilinear_at(&g, 2, 2, 1.01, 0.0), None);
        assert_eq!(bilinear_at(&g, 2, 2, -0.01, 0.0), None);
        assert_eq!(bilinear_at(&[], 0, 0, 0.0, 0.0), None);
    }
}
