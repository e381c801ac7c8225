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
