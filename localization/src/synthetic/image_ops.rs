//! Image operations the renderers share: bilinear sampling, Lambertian radiance, Gaussian blur.

use rayon::prelude::*;

/// Bilinear sample of a row-major grid at pixel-centre coordinates `(c, r)`, clamped.
#[inline]
pub(super) fn bilinear(data: &[f32], w: usize, h: usize, c: f64, r: f64) -> f32 {
    let c = c.clamp(0.0, (w - 1) as f64);
    let r = r.clamp(0.0, (h - 1) as f64);
    let (c0, r0) = (c as usize, r as usize);
    let (c1, r1) = ((c0 + 1).min(w - 1), (r0 + 1).min(h - 1));
    let (tx, ty) = ((c - c0 as f64) as f32, (r - r0 as f64) as f32);
    let top = data[r0 * w + c0] + tx * (data[r0 * w + c1] - data[r0 * w + c0]);
    let bottom = data[r1 * w + c0] + tx * (data[r1 * w + c1] - data[r1 * w + c0]);
    top + ty * (bottom - top)
}

/// Reflected light of a Lambertian surface: `albedo × (ambient + (1 − ambient) × cos⁺ × lit)`.
#[inline]
pub(super) fn radiance(albedo: f32, cos_incidence: f64, lit: bool, ambient: f64) -> f64 {
    let direct = if lit { cos_incidence.max(0.0) } else { 0.0 };
    f64::from(albedo) * (ambient + (1.0 - ambient) * direct)
}

/// Separable Gaussian blur of a `w × h` image with standard deviation `sigma_px`, edges
/// clamped; the kernel reaches 3σ. `sigma_px <= 0` returns the image unchanged.
pub(super) fn gaussian_blur(img: &[f32], w: usize, h: usize, sigma_px: f64) -> Vec<f32> {
    if sigma_px <= 0.0 || w == 0 || h == 0 {
        return img.to_vec();
    }
    let radius = (3.0 * sigma_px).ceil() as usize;
    let mut kernel: Vec<f32> = (0..=2 * radius)
        .map(|i| {
            let d = i as f64 - radius as f64;
            (-0.5 * d * d / (sigma_px * sigma_px)).exp() as f32
        })
        .collect();
    let total: f32 = kernel.iter().sum();
    kernel.iter_mut().for_each(|k| *k /= total);
    // Each output is `Σ_k kernel[k] · in[clamp(i + k − radius)]` summed in `k` order from the
    // identity of `f32`'s `Sum` (what `Iterator::sum` starts from); the loops run over `k`
    // outside and pixels inside so the compiler vectorizes them, with the same operations in
    // the same order for every pixel.
    let zero: f32 = std::iter::empty::<f32>().sum();
    let clamp = |i: usize, n: usize| (i.saturating_sub(radius)).min(n - 1);
    let mut tmp = vec![0.0f32; w * h];
    tmp.par_chunks_mut(w)
        .enumerate()
        .for_each(|(row, out_row)| {
            let src = &img[row * w..(row + 1) * w];
            out_row.fill(zero);
            // Columns whose taps all lie on the row: contiguous slices.
            let (lo, hi) = if w > 2 * radius {
                (radius, w - radius)
            } else {
                (w, w)
            };
            for (k, &wk) in kernel.iter().enumerate() {
                if lo < hi {
                    for (o, &v) in out_row[lo..hi].iter_mut().zip(&src[lo + k - radius..]) {
                        *o += wk * v;
                    }
                }
                for col in (0..lo).chain(hi..w) {
                    out_row[col] += wk * src[clamp(col + k, w)];
                }
            }
        });
    let mut out = vec![0.0f32; w * h];
    out.par_chunks_mut(w)
        .enumerate()
        .for_each(|(row, out_row)| {
            out_row.fill(zero);
            for (k, &wk) in kernel.iter().enumerate() {
                let r = clamp(row + k, h);
                for (o, &v) in out_row.iter_mut().zip(&tmp[r * w..(r + 1) * w]) {
                    *o += wk * v;
                }
            }
        });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The blur as first written, one output pixel at a time: the reference.
    fn gaussian_blur_reference(img: &[f32], w: usize, h: usize, sigma_px: f64) -> Vec<f32> {
        let radius = (3.0 * sigma_px).ceil() as usize;
        let mut kernel: Vec<f32> = (0..=2 * radius)
            .map(|i| {
                let d = i as f64 - radius as f64;
                (-0.5 * d * d / (sigma_px * sigma_px)).exp() as f32
            })
            .collect();
        let total: f32 = kernel.iter().sum();
        kernel.iter_mut().for_each(|k| *k /= total);
        let clamp = |i: usize, n: usize| (i.saturating_sub(radius)).min(n - 1);
        let tmp: Vec<f32> = (0..w * h)
            .map(|i| {
                let (row, col) = (i / w, i % w);
                kernel
                    .iter()
                    .enumerate()
                    .map(|(k, wk)| wk * img[row * w + clamp(col + k, w)])
                    .sum()
            })
            .collect();
        (0..w * h)
            .map(|i| {
                let (row, col) = (i / w, i % w);
                kernel
                    .iter()
                    .enumerate()
                    .map(|(k, wk)| wk * tmp[clamp(row + k, h) * w + col])
                    .sum()
            })
            .collect()
    }

    #[test]
    fn blur_equals_the_reference_bit_for_bit() {
        use crate::synthetic::noise::gaussian;
        for (w, h, sigma) in [
            (1, 1, 1.0),
            (2, 9, 1.0),
            (5, 4, 0.7),
            (6, 6, 1.0),
            (37, 23, 1.3),
            (64, 3, 2.0),
        ] {
            let img: Vec<f32> = (0..w * h)
                .map(|i| (100.0 + 40.0 * gaussian(3, i as i64, 7)) as f32)
                .collect();
            let got = gaussian_blur(&img, w, h, sigma);
            let want = gaussian_blur_reference(&img, w, h, sigma);
            assert!(
                got.iter()
                    .zip(&want)
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "{w}×{h} σ {sigma}"
            );
        }
    }

    #[test]
    fn blur_preserves_a_constant_and_the_mean() {
        let img = vec![7.0f32; 30];
        assert!(
            gaussian_blur(&img, 6, 5, 0.7)
                .iter()
                .all(|v| (v - 7.0).abs() < 1e-5)
        );
        let mut spike = vec![0.0f32; 121];
        spike[60] = 1.0;
        let b = gaussian_blur(&spike, 11, 11, 0.7);
        assert!((b.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        assert!(b[60] < 0.5 && b[61] > 0.0);
    }
}
