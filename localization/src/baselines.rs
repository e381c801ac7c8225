//! Baseline appearance scores the census matcher is compared against (paper 000 §3-§4): masked
//! normalized cross-correlation and mutual information.
//!
//! Both score **every integer offset** of a template (the rover orthomosaic, with a validity
//! mask) inside a fully valid map (the orbital window), with the same offset convention as the
//! census [`ScoreMap`](crate::census::ScoreMap): offset `(dx, dy)` puts template pixel `(x, y)`
//! on map pixel `(x + dx, y + dy)` and is stored at index `dy * width + dx`, with
//! `width = map width − template width + 1` (likewise `height`). **Lower is better**, so the
//! matcher's minimum search, sub-pixel fit and peak ratio work unchanged.
//!
//! - [`ncc_scores`]: `1 − ncc`, where `ncc` is the zero-mean normalized cross-correlation of the
//!   template with the map patch over the pixels valid in the template. Exact per offset (up to
//!   floating-point rounding): the masked sums `Σ m·I`, `Σ m·I²` and `Σ m·T·I` are three
//!   cross-correlations computed with 2-D FFTs of the map size (the map is packed as `I + i·I²`
//!   so one forward transform serves both). A degenerate offset — template or map patch with
//!   (numerically) zero variance — scores `1` (no correlation); an all-invalid template scores
//!   `+∞` everywhere. [`ncc_scores_naive`] is the direct per-offset reference.
//! - [`mi_scores`]: `−MI` (nats) between the quantized template and map patch over the valid
//!   pixels, from a [`MI_BINS`] × [`MI_BINS`] joint histogram. Intensities are quantized by
//!   *rank* (equal-population bins of each image's own histogram), so the binning itself does not
//!   depend on a monotonic brightness change; MI then tolerates any one-to-one intensity mapping,
//!   monotonic or not. Because the map is fully valid, every valid template pixel is counted at
//!   every offset and the template entropy [`template_entropy`] is the same for all offsets.
//!
//!   **Search strategy (not every offset is evaluated exactly).** A joint histogram costs one
//!   increment per valid template pixel per offset, so MI is evaluated exactly on a 2×
//!   subsampled offset grid (even `dx`, `dy`, plus the last row and column); then the
//!   [`MI_REFINE_CANDIDATES`] best local minima of that coarse grid are refined at full
//!   resolution: every offset within ±2 of the candidate is evaluated exactly, and the box is
//!   re-centred on its best offset until that best lies inside the box (so it is an exact local
//!   minimum with an exact 3×3 neighbourhood for the sub-pixel fit). All other offsets are
//!   bilinearly interpolated from the coarse grid and flagged `exact = false`. An interpolated
//!   value is a convex combination of coarse values, so it can never undercut the refined
//!   minimum; but a secondary peak that falls between coarse samples and is not among the refined
//!   candidates is under-represented, which makes a peak ratio computed from these scores
//!   slightly optimistic.
//!
//! Both use `rayon` (FFT rows/columns and offset rows for NCC; coarse offset rows for MI).
//!
//! ## References
//! - Paper 000 §3 (related work: MI for appearance (its ref. 26), NCC-based approaches (ref. 28)) and §4
//!   (masked NCC and mutual information produce more outliers and ambiguous peaks than census).
//! - J. P. Lewis, "Fast normalized cross-correlation", Vision Interface 1995.
//! - D. Padfield, "Masked object registration in the Fourier domain", IEEE TIP 2012.
//! - P. Viola and W. M. Wells, "Alignment by maximization of mutual information", IJCV 1997.

use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use crate::census::MatchError;

/// Number of intensity bins per image in the MI joint histogram.
pub const MI_BINS: usize = 16;

/// Number of coarse-grid local minima refined at full resolution by [`mi_scores`].
pub const MI_REFINE_CANDIDATES: usize = 8;

/// Half-width of the full-resolution box evaluated around each MI candidate, offsets.
const MI_REFINE_RADIUS: usize = 2;

/// Per-pixel variance (intensity²) below which an NCC patch counts as flat.
const NCC_MIN_VARIANCE: f64 = 1e-6;

/// A baseline score for every integer offset (lower is better).
#[derive(Clone, Debug, PartialEq)]
pub struct BaselineScores {
    /// Number of x offsets (`map width − template width + 1`).
    pub width: usize,
    /// Number of y offsets (`map height − template height + 1`).
    pub height: usize,
    /// Score per offset, row-major (`+∞` where nothing was comparable).
    pub scores: Vec<f64>,
    /// Whether each score was evaluated exactly (always for NCC; for MI, the coarse grid and the
    /// refined neighbourhoods) rather than interpolated.
    pub exact: Vec<bool>,
}

impl BaselineScores {
    /// Score at offset `(dx, dy)`, `None` outside the score map.
    #[must_use]
    pub fn at(&self, dx: usize, dy: usize) -> Option<f64> {
        (dx < self.width && dy < self.height).then(|| self.scores[dy * self.width + dx])
    }

    /// The finite-scored offset with the lowest score (ties to the first in row-major order).
    #[must_use]
    pub fn best_offset(&self) -> Option<(usize, usize)> {
        (0..self.scores.len())
            .filter(|&i| self.scores[i].is_finite())
            .min_by(|&a, &b| self.scores[a].total_cmp(&self.scores[b]).then(a.cmp(&b)))
            .map(|i| (i % self.width, i / self.width))
    }
}

/// Check the buffers and return the offset grid size.
fn check(
    template: &[u8],
    valid: &[bool],
    (tw, th): (usize, usize),
    map: &[u8],
    (mw, mh): (usize, usize),
) -> Result<(usize, usize), MatchError> {
    let size = |what, expected: usize, actual: usize| {
        if expected == actual {
            Ok(())
        } else {
            Err(MatchError::SizeMismatch {
                what,
                expected,
                actual,
            })
        }
    };
    size("template", tw * th, template.len())?;
    size("template valid", tw * th, valid.len())?;
    size("map", mw * mh, map.len())?;
    if tw == 0 || th == 0 {
        return Err(MatchError::EmptyTemplate {
            width: tw,
            height: th,
        });
    }
    if tw > mw || th > mh {
        return Err(MatchError::TemplateLargerThanMap {
            template_width: tw,
            template_height: th,
            map_width: mw,
            map_height: mh,
        });
    }
    Ok((mw - tw + 1, mh - th + 1))
}

/// `1 − ncc` from the masked sums at one offset (`st`, `stt` of the template; `si`, `sii`,
/// `sti` under the mask; `n` valid pixels).
fn ncc_score(n: f64, st: f64, stt: f64, si: f64, sii: f64, sti: f64) -> f64 {
    let var_t = stt - st * st / n;
    let var_i = sii - si * si / n;
    if var_t <= NCC_MIN_VARIANCE * n || var_i <= NCC_MIN_VARIANCE * n {
        return 1.0;
    }
    let ncc = (sti - st * si / n) / (var_t * var_i).sqrt();
    1.0 - ncc.clamp(-1.0, 1.0)
}

/// In-place 2-D FFT of a row-major `w × h` complex grid (rows, then columns via a transpose).
fn fft2(
    data: &mut [Complex<f64>],
    tmp: &mut [Complex<f64>],
    (w, h): (usize, usize),
    (fw, fh): (&Arc<dyn Fft<f64>>, &Arc<dyn Fft<f64>>),
) {
    let run = |grid: &mut [Complex<f64>], len: usize, fft: &Arc<dyn Fft<f64>>| {
        grid.par_chunks_mut(len).for_each_init(
            || vec![Complex::default(); fft.get_inplace_scratch_len()],
            |scratch, line| fft.process_with_scratch(line, scratch),
        );
    };
    run(data, w, fw);
    tmp.par_chunks_mut(h).enumerate().for_each(|(x, col)| {
        for (y, v) in col.iter_mut().enumerate() {
            *v = data[y * w + x];
        }
    });
    run(tmp, h, fh);
    data.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, v) in row.iter_mut().enumerate() {
            *v = tmp[x * h + y];
        }
    });
}

/// Masked NCC score `1 − ncc` of the `tw × th` template (pixels with `valid` false ignored) at
/// every offset inside the fully valid `mw × mh` map; see the [module docs](self).
///
/// # Errors
/// [`MatchError`] when a buffer length is not `width × height`, the template is empty, or it is
/// larger than the map.
pub fn ncc_scores(
    template: &[u8],
    valid: &[bool],
    tw: usize,
    th: usize,
    map: &[u8],
    mw: usize,
    mh: usize,
) -> Result<BaselineScores, MatchError> {
    let (ow, oh) = check(template, valid, (tw, th), map, (mw, mh))?;
    let n = valid.iter().filter(|&&v| v).count();
    if n == 0 {
        return Ok(BaselineScores {
            width: ow,
            height: oh,
            scores: vec![f64::INFINITY; ow * oh],
            exact: vec![true; ow * oh],
        });
    }
    // Remove the means (NCC is invariant to it) to keep the FFT sums small and accurate.
    let mean_t = template
        .iter()
        .zip(valid)
        .filter(|(_, v)| **v)
        .map(|(&t, _)| f64::from(t))
        .sum::<f64>()
        / n as f64;
    let mean_i = map.iter().map(|&v| f64::from(v)).sum::<f64>() / map.len() as f64;
    let (mut st, mut stt) = (0.0, 0.0);
    let len = mw * mh;
    let mut fb: Vec<Complex<f64>> = map
        .iter()
        .map(|&v| {
            let i = f64::from(v) - mean_i;
            Complex::new(i, i * i)
        })
        .collect();
    let mut fm = vec![Complex::default(); len];
    let mut ft = vec![Complex::default(); len];
    for y in 0..th {
        for x in 0..tw {
            if valid[y * tw + x] {
                let t = f64::from(template[y * tw + x]) - mean_t;
                st += t;
                stt += t * t;
                fm[y * mw + x] = Complex::new(1.0, 0.0);
                ft[y * mw + x] = Complex::new(t, 0.0);
            }
        }
    }
    let mut planner = FftPlanner::<f64>::new();
    let (fwd_w, fwd_h) = (planner.plan_fft_forward(mw), planner.plan_fft_forward(mh));
    let (inv_w, inv_h) = (planner.plan_fft_inverse(mw), planner.plan_fft_inverse(mh));
    let mut tmp = vec![Complex::default(); len];
    for grid in [&mut fb, &mut fm, &mut ft] {
        fft2(grid, &mut tmp, (mw, mh), (&fwd_w, &fwd_h));
    }
    // Cross-correlation c[d] = Σ a[x]·b[x + d] ↔ conj(A)·B (a real, no wrap for valid offsets).
    fm.par_iter_mut()
        .zip(ft.par_iter_mut())
        .zip(fb.par_iter())
        .for_each(|((m, t), b)| {
            *m = m.conj() * b;
            *t = t.conj() * b;
        });
    fft2(&mut fm, &mut tmp, (mw, mh), (&inv_w, &inv_h));
    fft2(&mut ft, &mut tmp, (mw, mh), (&inv_w, &inv_h));
    let norm = 1.0 / len as f64;
    let nf = n as f64;
    let mut scores = vec![0.0; ow * oh];
    scores.par_chunks_mut(ow).enumerate().for_each(|(dy, row)| {
        for (dx, s) in row.iter_mut().enumerate() {
            let k = dy * mw + dx;
            let (si, sii) = (fm[k].re * norm, fm[k].im * norm);
            *s = ncc_score(nf, st, stt, si, sii, ft[k].re * norm);
        }
    });
    Ok(BaselineScores {
        width: ow,
        height: oh,
        scores,
        exact: vec![true; ow * oh],
    })
}

/// Direct per-offset reference for [`ncc_scores`] (O(offsets × pixels); for tests and small
/// inputs).
///
/// # Errors
/// As [`ncc_scores`].
pub fn ncc_scores_naive(
    template: &[u8],
    valid: &[bool],
    tw: usize,
    th: usize,
    map: &[u8],
    mw: usize,
    mh: usize,
) -> Result<BaselineScores, MatchError> {
    let (ow, oh) = check(template, valid, (tw, th), map, (mw, mh))?;
    let mut scores = vec![f64::INFINITY; ow * oh];
    for dy in 0..oh {
        for dx in 0..ow {
            let (mut n, mut st, mut stt, mut si, mut sii, mut sti) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
            for y in 0..th {
                for x in 0..tw {
                    if valid[y * tw + x] {
                        let t = f64::from(template[y * tw + x]);
                        let i = f64::from(map[(y + dy) * mw + x + dx]);
                        n += 1.0;
                        st += t;
                        stt += t * t;
                        si += i;
                        sii += i * i;
                        sti += t * i;
                    }
                }
            }
            if n > 0.0 {
                scores[dy * ow + dx] = ncc_score(n, st, stt, si, sii, sti);
            }
        }
    }
    Ok(BaselineScores {
        width: ow,
        height: oh,
        scores,
        exact: vec![true; ow * oh],
    })
}

/// Rank (equal-population) quantization of the pixels with `valid` (all if `None`) to
/// [`MI_BINS`] bins: an intensity's bin is `⌊bins · (count below + half its count) / n⌋`.
fn quantize(data: &[u8], valid: Option<&[bool]>) -> Vec<u8> {
    let is_valid = |i: usize| valid.is_none_or(|v| v[i]);
    let mut hist = [0usize; 256];
    for (i, &v) in data.iter().enumerate() {
        if is_valid(i) {
            hist[usize::from(v)] += 1;
        }
    }
    let n: usize = hist.iter().sum();
    let mut bin = [0u8; 256];
    let mut below = 0usize;
    for v in 0..256 {
        if n > 0 {
            let rank2 = 2 * below + hist[v]; // twice the mid-rank
            bin[v] = ((MI_BINS * rank2) / (2 * n)).min(MI_BINS - 1) as u8;
        }
        below += hist[v];
    }
    data.iter().map(|&v| bin[usize::from(v)]).collect()
}

/// Entropy (nats) of the rank-quantized valid template pixels: the `H(T)` of
/// `MI = H(T) + H(M) − H(T, M)`, the same at every offset. `0` for an all-invalid or flat
/// template. `1 + (−MI) / H(T)` is the fraction of the template's information the map does *not*
/// explain (the matcher's MI score).
#[must_use]
pub fn template_entropy(template: &[u8], valid: &[bool]) -> f64 {
    let q = quantize(template, Some(valid));
    let mut hist = [0usize; MI_BINS];
    for (i, &b) in q.iter().enumerate() {
        if valid.get(i).copied().unwrap_or(false) {
            hist[usize::from(b)] += 1;
        }
    }
    let n: usize = hist.iter().sum();
    if n == 0 {
        return 0.0;
    }
    let nf = n as f64;
    hist.iter()
        .filter(|&&c| c > 0)
        .map(|&c| {
            let p = c as f64 / nf;
            -p * p.ln()
        })
        .sum()
}

/// Everything the per-offset MI evaluation needs, precomputed once.
struct MiContext {
    /// Template bin × `MI_BINS`, per template pixel.
    tb: Vec<u16>,
    /// Valid runs `(y, x0, len)` of the template.
    runs: Vec<(usize, usize, usize)>,
    /// Quantized map.
    mq: Vec<u8>,
    tw: usize,
    mw: usize,
    /// `c·ln c` for `c = 0..=n`.
    clnc: Vec<f64>,
    /// `Σ c·ln c` over the template's marginal histogram.
    t_term: f64,
    /// Valid template pixels.
    n: usize,
}

impl MiContext {
    /// `−MI` (nats) at offset `(dx, dy)`.
    fn neg_mi(&self, dx: usize, dy: usize) -> f64 {
        const NB: usize = MI_BINS * MI_BINS;
        // Four interleaved histograms break the store-to-load dependency of repeated bins.
        let mut h = [[0u32; NB]; 4];
        for &(y, x0, len) in &self.runs {
            let t = &self.tb[y * self.tw + x0..y * self.tw + x0 + len];
            let m = &self.mq[(y + dy) * self.mw + x0 + dx..(y + dy) * self.mw + x0 + dx + len];
            let mut tc = t.chunks_exact(4);
            let mut mc = m.chunks_exact(4);
            for (t4, m4) in (&mut tc).zip(&mut mc) {
                for k in 0..4 {
                    h[k][usize::from(t4[k]) + usize::from(m4[k])] += 1;
                }
            }
            for (&a, &b) in tc.remainder().iter().zip(mc.remainder()) {
                h[0][usize::from(a) + usize::from(b)] += 1;
            }
        }
        let mut joint_term = 0.0;
        let mut m_marg = [0usize; MI_BINS];
        for i in 0..NB {
            let c = (h[0][i] + h[1][i] + h[2][i] + h[3][i]) as usize;
            joint_term += self.clnc[c];
            m_marg[i % MI_BINS] += c;
        }
        let m_term: f64 = m_marg.iter().map(|&c| self.clnc[c]).sum();
        // MI = ln n + (Σ c_tm ln c_tm − Σ c_t ln c_t − Σ c_m ln c_m) / n.
        let nf = self.n as f64;
        -(nf.ln() + (joint_term - self.t_term - m_term) / nf)
    }
}

/// Mutual-information score `−MI` (nats) of the `tw × th` template (pixels with `valid` false
/// ignored) at every offset inside the fully valid `mw × mh` map, with the coarse-then-refine
/// search described in the [module docs](self) (`exact` marks the offsets evaluated exactly).
///
/// # Errors
/// [`MatchError`] when a buffer length is not `width × height`, the template is empty, or it is
/// larger than the map.
pub fn mi_scores(
    template: &[u8],
    valid: &[bool],
    tw: usize,
    th: usize,
    map: &[u8],
    mw: usize,
    mh: usize,
) -> Result<BaselineScores, MatchError> {
    let (ow, oh) = check(template, valid, (tw, th), map, (mw, mh))?;
    let n = valid.iter().filter(|&&v| v).count();
    if n == 0 {
        return Ok(BaselineScores {
            width: ow,
            height: oh,
            scores: vec![f64::INFINITY; ow * oh],
            exact: vec![true; ow * oh],
        });
    }
    let tq = quantize(template, Some(valid));
    let mut runs = Vec::new();
    for y in 0..th {
        let mut x = 0;
        while x < tw {
            if valid[y * tw + x] {
                let x0 = x;
                while x < tw && valid[y * tw + x] {
                    x += 1;
                }
                runs.push((y, x0, x - x0));
            } else {
                x += 1;
            }
        }
    }
    let clnc: Vec<f64> = (0..=n)
        .map(|c| {
            if c == 0 {
                0.0
            } else {
                c as f64 * (c as f64).ln()
            }
        })
        .collect();
    let mut t_marg = [0usize; MI_BINS];
    for (i, &b) in tq.iter().enumerate() {
        if valid[i] {
            t_marg[usize::from(b)] += 1;
        }
    }
    let ctx = MiContext {
        tb: tq.iter().map(|&b| u16::from(b) * MI_BINS as u16).collect(),
        runs,
        mq: quantize(map, None),
        tw,
        mw,
        t_term: t_marg.iter().map(|&c| clnc[c]).sum(),
        clnc,
        n,
    };

    // 1. The coarse grid: even offsets plus the last one in each direction.
    let grid = |len: usize| -> Vec<usize> {
        let mut g: Vec<usize> = (0..len).step_by(2).collect();
        if g.last() != Some(&(len - 1)) {
            g.push(len - 1);
        }
        g
    };
    let (gx, gy) = (grid(ow), grid(oh));
    let coarse: Vec<Vec<f64>> = gy
        .par_iter()
        .map(|&dy| gx.iter().map(|&dx| ctx.neg_mi(dx, dy)).collect())
        .collect();

    // 2. Fill every offset by bilinear interpolation of the coarse grid.
    let bracket = |g: &[usize], v: usize| -> (usize, usize, f64) {
        let i = g.partition_point(|&x| x <= v).saturating_sub(1);
        if i + 1 >= g.len() {
            return (i, i, 0.0);
        }
        (i, i + 1, (v - g[i]) as f64 / (g[i + 1] - g[i]) as f64)
    };
    let mut scores = vec![0.0; ow * oh];
    let mut exact = vec![false; ow * oh];
    for dy in 0..oh {
        let (j0, j1, ty) = bracket(&gy, dy);
        for dx in 0..ow {
            let (i0, i1, tx) = bracket(&gx, dx);
            let top = coarse[j0][i0] * (1.0 - tx) + coarse[j0][i1] * tx;
            let bottom = coarse[j1][i0] * (1.0 - tx) + coarse[j1][i1] * tx;
            scores[dy * ow + dx] = top * (1.0 - ty) + bottom * ty;
        }
    }
    for (j, &dy) in gy.iter().enumerate() {
        for (i, &dx) in gx.iter().enumerate() {
            scores[dy * ow + dx] = coarse[j][i];
            exact[dy * ow + dx] = true;
        }
    }

    // 3. Refine the best coarse local minima at full resolution.
    let mut minima: Vec<(f64, usize, usize)> = Vec::new();
    for (j, row) in coarse.iter().enumerate() {
        for (i, &v) in row.iter().enumerate() {
            let lower_neighbour = (j.saturating_sub(1)..(j + 2).min(gy.len())).any(|jj| {
                (i.saturating_sub(1)..(i + 2).min(gx.len()))
                    .any(|ii| (ii, jj) != (i, j) && coarse[jj][ii] < v)
            });
            if !lower_neighbour {
                minima.push((v, gx[i], gy[j]));
            }
        }
    }
    minima.sort_by(|a, b| a.0.total_cmp(&b.0).then((a.2, a.1).cmp(&(b.2, b.1))));
    minima.truncate(MI_REFINE_CANDIDATES);
    let r = MI_REFINE_RADIUS;
    for &(_, cx, cy) in &minima {
        let (mut cx, mut cy) = (cx, cy);
        // Hill-descend: re-centre until the box's best offset is strictly inside the box (or on
        // the edge of the offset grid); each step moves to a strictly lower score, so it ends.
        for _ in 0..ow.max(oh) {
            let (x0, x1) = (cx.saturating_sub(r), (cx + r).min(ow - 1));
            let (y0, y1) = (cy.saturating_sub(r), (cy + r).min(oh - 1));
            let todo: Vec<(usize, usize)> = (y0..=y1)
                .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
                .filter(|&(x, y)| !exact[y * ow + x])
                .collect();
            let done: Vec<f64> = todo.par_iter().map(|&(x, y)| ctx.neg_mi(x, y)).collect();
            for (&(x, y), v) in todo.iter().zip(done) {
                scores[y * ow + x] = v;
                exact[y * ow + x] = true;
            }
            let (mut bx, mut by) = (cx, cy);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    if scores[y * ow + x] < scores[by * ow + bx] {
                        (bx, by) = (x, y);
                    }
                }
            }
            let inside = |b: usize, lo: usize, hi: usize, last: usize| {
                (b > lo || lo == 0) && (b < hi || hi == last)
            };
            if (bx, by) == (cx, cy) || (inside(bx, x0, x1, ow - 1) && inside(by, y0, y1, oh - 1)) {
                break;
            }
            (cx, cy) = (bx, by);
        }
    }
    Ok(BaselineScores {
        width: ow,
        height: oh,
        scores,
        exact,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random generator for test images.
    fn lcg(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A smooth random texture (sum of seeded sinusoids), 0..255, row-major.
    fn texture(w: usize, h: usize, seed: u64) -> Vec<u8> {
        crate::synthetic::sinusoid_texture(w, h, maps::GeoTransform::new(0.0, h as f64, 1.0), seed)
            .data
    }

    fn crop(map: &[u8], mw: usize, x0: usize, y0: usize, w: usize, h: usize) -> Vec<u8> {
        (0..h)
            .flat_map(|y| map[(y0 + y) * mw + x0..(y0 + y) * mw + x0 + w].to_vec())
            .collect()
    }

    #[test]
    fn ncc_matches_the_naive_reference() {
        let mut next = lcg(3);
        for &(tw, th, mw, mh) in &[(5, 4, 13, 11), (7, 7, 7, 9), (1, 3, 6, 3), (8, 6, 20, 17)] {
            let t: Vec<u8> = (0..tw * th).map(|_| (next() * 256.0) as u8).collect();
            let v: Vec<bool> = (0..tw * th).map(|_| next() > 0.3).collect();
            let m: Vec<u8> = (0..mw * mh).map(|_| (next() * 256.0) as u8).collect();
            let fast = ncc_scores(&t, &v, tw, th, &m, mw, mh).unwrap();
            let slow = ncc_scores_naive(&t, &v, tw, th, &m, mw, mh).unwrap();
            assert_eq!((fast.width, fast.height), (mw - tw + 1, mh - th + 1));
            for (a, b) in fast.scores.iter().zip(&slow.scores) {
                assert!((a - b).abs() < 1e-9, "{a} vs {b} ({tw}×{th} in {mw}×{mh})");
            }
        }
        // Flat template: no correlation anywhere; all-invalid: nothing comparable.
        let m: Vec<u8> = (0..100).map(|_| (next() * 256.0) as u8).collect();
        let flat = ncc_scores(&[7; 9], &[true; 9], 3, 3, &m, 10, 10).unwrap();
        assert!(flat.scores.iter().all(|&s| s == 1.0));
        let none = ncc_scores(&[7; 9], &[false; 9], 3, 3, &m, 10, 10).unwrap();
        assert!(none.scores.iter().all(|s| s.is_infinite()));
        assert!(matches!(
            ncc_scores(&[7; 9], &[true; 8], 3, 3, &m, 10, 10),
            Err(MatchError::SizeMismatch { .. })
        ));
        assert!(matches!(
            mi_scores(&[7; 9], &[true; 9], 3, 3, &m, 2, 50),
            Err(MatchError::TemplateLargerThanMap { .. })
        ));
    }

    /// Plant a 60×60 crop at (`x0`, `y0`) of a 120×100 texture, remap its intensities, mask a
    /// wedge, and return the best offsets of NCC and MI.
    fn planted(x0: usize, y0: usize, remap: impl Fn(u8) -> u8) -> ((usize, usize), (usize, usize)) {
        let (mw, mh, tw, th) = (120, 100, 60, 60);
        let map = texture(mw, mh, 5);
        let t: Vec<u8> = crop(&map, mw, x0, y0, tw, th)
            .into_iter()
            .map(remap)
            .collect();
        let v: Vec<bool> = (0..tw * th).map(|i| i % tw >= 15).collect();
        let ncc = ncc_scores(&t, &v, tw, th, &map, mw, mh).unwrap();
        let mi = mi_scores(&t, &v, tw, th, &map, mw, mh).unwrap();
        let (bx, by) = mi.best_offset().unwrap();
        assert!(mi.exact[by * mi.width + bx]);
        (ncc.best_offset().unwrap(), (bx, by))
    }

    #[test]
    fn ncc_and_mi_recover_a_planted_offset_under_a_linear_brightness_change() {
        for (x0, y0) in [(37, 21), (12, 30), (55, 9)] {
            let (ncc, mi) = planted(x0, y0, |v| (0.6 * f64::from(v) + 70.0) as u8);
            assert_eq!(ncc, (x0, y0));
            assert_eq!(mi, (x0, y0));
        }
    }

    #[test]
    fn mi_survives_a_non_monotonic_change_where_ncc_fails() {
        // Two full cosine periods over 0..=255: dark, mid-grey and bright all map to bright, so
        // the template's brightness is a many-to-one function of the map's and is (nearly)
        // uncorrelated with it.
        let wave = |v: u8| {
            (128.0 + 120.0 * (std::f64::consts::TAU * f64::from(v) / 128.0).cos()).round() as u8
        };
        let mut ncc_hits = 0;
        for (x0, y0) in [(37, 21), (12, 30), (55, 9)] {
            let (ncc, mi) = planted(x0, y0, wave);
            eprintln!("cosine remap: truth {:?} ncc {ncc:?} mi {mi:?}", (x0, y0));
            assert_eq!(mi, (x0, y0));
            ncc_hits += usize::from(ncc == (x0, y0));
        }
        assert_eq!(
            ncc_hits, 0,
            "NCC should not see a non-monotonic brightness change"
        );
    }

    #[test]
    fn mi_exact_offsets_match_a_direct_evaluation() {
        let (mw, mh, tw, th) = (40, 36, 17, 15);
        let map = texture(mw, mh, 9);
        let t = crop(&map, mw, 11, 8, tw, th);
        let v = vec![true; tw * th];
        let s = mi_scores(&t, &v, tw, th, &map, mw, mh).unwrap();
        // Direct −MI from probabilities at a few exact offsets.
        let tq = quantize(&t, Some(&v));
        let mq = quantize(&map, None);
        for dy in 0..s.height {
            for dx in 0..s.width {
                if !s.exact[dy * s.width + dx] {
                    continue;
                }
                let mut joint = [[0.0f64; MI_BINS]; MI_BINS];
                for y in 0..th {
                    for x in 0..tw {
                        let a = usize::from(tq[y * tw + x]);
                        let b = usize::from(mq[(y + dy) * mw + x + dx]);
                        joint[a][b] += 1.0 / (tw * th) as f64;
                    }
                }
                let mut mi = 0.0;
                for a in 0..MI_BINS {
                    for b in 0..MI_BINS {
                        let pa: f64 = joint[a].iter().sum();
                        let pb: f64 = (0..MI_BINS).map(|k| joint[k][b]).sum();
                        if joint[a][b] > 0.0 {
                            mi += joint[a][b] * (joint[a][b] / (pa * pb)).ln();
                        }
                    }
                }
                assert!((s.scores[dy * s.width + dx] + mi).abs() < 1e-9);
            }
        }
        assert_eq!(s.best_offset(), Some((11, 8)));
        // At the true offset the map explains most of the template's information (not all: the
        // two images are rank-quantized separately, so their bin edges differ).
        let h = template_entropy(&t, &v);
        let mi = -s.at(11, 8).unwrap();
        assert!(mi <= h + 1e-9 && mi > 0.75 * h, "MI {mi} vs H(T) {h}");
    }
}
