//! Exact masked census Hamming counts of every offset by bit-plane FFT correlation
//! (PERFORMANCE.md §2; Fischer–Paterson 1973, Schoenmeyr & Zhang 2005).
//!
//! For each census bit `k`, every image gives two real planes: the sign plane `s` (+1 where the
//! bit is valid and set, −1 where it is valid and clear, 0 where it is invalid) and the mask
//! plane `m` (1 where the bit is valid). At an offset, `Σ m_T·m_M` counts the bits valid in both
//! images and `Σ s_T·s_M` = agreements − disagreements over them, so
//! `valid = Σ_k corr(m_T, m_M)` and `mismatch = (valid − Σ_k corr(s_T, s_M)) / 2`.
//!
//! The correlations are 2-D real FFTs in `f64`: forward transforms of the 32 planes, the
//! products `conj(T̂)·M̂` summed over the bits in the frequency domain, two inverse transforms.
//! Every count is an integer below 2³², far inside the 2⁵³ that `f64` holds exactly, and the
//! rounding error of the transforms is many orders of magnitude below ½, so rounding gives the
//! exact integers: the result is bit-identical to [`super::hamming_scores_naive`].
//!
//! Determinism: the bits are accumulated in order; parallelism (`rayon`) is only over whole
//! transforms and over disjoint chunks of the element-wise products, so the floating-point
//! operations — and hence the rounded counts — are the same on any number of threads.
//!
//! Layout: planes are row-major `ny × nx` (zero-padded, `nx ≥ map width`, `ny ≥ map height`, so
//! the circular correlation never wraps for the offsets we keep). Each row gets a real FFT
//! (`realfft`) whose `nx/2 + 1` outputs are scattered transposed into the spectrum buffer
//! (`[u][y]`, one contiguous column per frequency `u`), then every column gets a complex FFT
//! (`rustfft`). The inverse runs the column FFTs and then the inverse real FFT of only the
//! `dy` rows that are offsets. All-zero template rows are not transformed.

use std::sync::{Arc, Mutex, OnceLock};

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::MatchError;
use super::score::ScoreMap;
use super::transform::{CensusImage, Which};

/// Census bits per pixel.
const BITS: usize = 8;

type C64 = Complex<f64>;

/// The FFT plans for one padded size, shared by every transform of a call (and cached across
/// calls).
struct Plans {
    nx: usize,
    ny: usize,
    row_fwd: Arc<dyn RealToComplex<f64>>,
    row_inv: Arc<dyn ComplexToReal<f64>>,
    col_fwd: Arc<dyn Fft<f64>>,
    col_inv: Arc<dyn Fft<f64>>,
}

impl Plans {
    /// Number of complex outputs of a row's real FFT.
    fn nxh(&self) -> usize {
        self.nx / 2 + 1
    }

    /// Length of a whole spectrum (`nxh` columns of `ny`).
    fn spectrum_len(&self) -> usize {
        self.nxh() * self.ny
    }

    /// Plans for `nx × ny`, from the process-wide cache (planning costs more than a transform).
    fn get(nx: usize, ny: usize) -> Arc<Plans> {
        static CACHE: OnceLock<Mutex<Vec<Arc<Plans>>>> = OnceLock::new();
        let cache = CACHE.get_or_init(|| Mutex::new(Vec::new()));
        // A poisoned lock only means another thread panicked while planning: the list is still
        // a valid list of finished plans.
        let mut list = cache
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(p) = list.iter().find(|p| p.nx == nx && p.ny == ny) {
            return Arc::clone(p);
        }
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        let p = Arc::new(Plans {
            nx,
            ny,
            row_fwd: real.plan_fft_forward(nx),
            row_inv: real.plan_fft_inverse(nx),
            col_fwd: complex.plan_fft_forward(ny),
            col_inv: complex.plan_fft_inverse(ny),
        });
        // Keep the cache small: a matcher uses one or two sizes.
        if list.len() >= 8 {
            list.remove(0);
        }
        list.push(Arc::clone(&p));
        p
    }
}

/// The smallest even `n' ≥ max(n, 2)` of the form 2^a·3^b·5^c (fast sizes for both crates).
fn fft_size(n: usize) -> usize {
    let mut m = n.max(2).next_multiple_of(2);
    loop {
        let mut r = m;
        for f in [2, 3, 5] {
            while r.is_multiple_of(f) {
                r /= f;
            }
        }
        if r == 1 {
            return m;
        }
        m += 2;
    }
}

/// Reusable buffers for forward transforms.
struct Work {
    row: Vec<f64>,
    row_spec: Vec<C64>,
    real_scratch: Vec<C64>,
    col_scratch: Vec<C64>,
}

impl Work {
    fn new(p: &Plans) -> Self {
        Self {
            row: vec![0.0; p.nx],
            row_spec: vec![C64::new(0.0, 0.0); p.nxh()],
            real_scratch: vec![C64::new(0.0, 0.0); p.row_fwd.get_scratch_len()],
            col_scratch: vec![C64::new(0.0, 0.0); p.col_fwd.get_inplace_scratch_len()],
        }
    }
}

/// Row half of a 2-D real FFT: the real FFT of each row `y < rows` that `fill` writes into a
/// zeroed row of `nx` values, scattered transposed into `out` (`[u][y]` layout); rows
/// `rows..ny` are zero. The column FFTs follow in [`forward_plane`].
fn forward_rows(
    p: &Plans,
    w: &mut Work,
    rows: usize,
    fill: impl Fn(usize, &mut [f64]),
    out: &mut [C64],
) {
    let (ny, nxh) = (p.ny, p.nxh());
    for y in 0..rows {
        w.row.fill(0.0);
        fill(y, &mut w.row);
        // Lengths come from the same plans, so this cannot fail.
        p.row_fwd
            .process_with_scratch(&mut w.row, &mut w.row_spec, &mut w.real_scratch)
            .expect("row FFT buffers sized by the plan");
        for (u, &v) in w.row_spec.iter().enumerate() {
            out[u * ny + y] = v;
        }
    }
    for u in 0..nxh {
        out[u * ny + rows..(u + 1) * ny].fill(C64::new(0.0, 0.0));
    }
}

/// Fill a row of a sign (`sign = true`) or mask plane of bit `k` from `width` census pixels.
fn plane_row(codes: &[u8], valid: &[u8], k: usize, sign: bool, row: &mut [f64]) {
    for ((r, &c), &v) in row.iter_mut().zip(codes).zip(valid) {
        let vb = f64::from((v >> k) & 1);
        *r = if sign {
            // +1 valid and set, −1 valid and clear, 0 invalid.
            vb * (2.0 * f64::from((c >> k) & 1) - 1.0)
        } else {
            vb
        };
    }
}

/// `acc[i] += conj(t[i]) · m[i]`.
fn mul_acc(acc: &mut [C64], t: &[C64], m: &[C64]) {
    for ((a, t), m) in acc.iter_mut().zip(t).zip(m) {
        *a += t.conj() * m;
    }
}

/// Forward 2-D FFT of one plane (sign or mask of bit `k`) of `img` into `out` (`[u][y]`).
fn forward_plane(p: &Plans, img: &CensusImage, k: usize, sign: bool, out: &mut [C64]) {
    let mut w = Work::new(p);
    let width = img.width;
    forward_rows(
        p,
        &mut w,
        img.height,
        |y, row| {
            let r = y * width..(y + 1) * width;
            plane_row(
                &img.codes[r.clone()],
                &img.valid[r],
                k,
                sign,
                &mut row[..width],
            );
        },
        out,
    );
    p.col_fwd.process_with_scratch(out, &mut w.col_scratch);
}

/// Elements per parallel chunk of the spectrum multiply-accumulate.
const MAC_CHUNK: usize = 1 << 14;

/// Sum over all bits of the sign and mask cross-spectra, accumulated in bit order.
///
/// Per bit, the four forward transforms (template and map, sign and mask) run as `rayon` tasks
/// (work stealing balances the smaller template against the map), then the element-wise
/// multiply-accumulate runs in parallel chunks. Every spectrum element is computed by the same
/// operations in the same order whatever thread runs it, so the sums do not depend on the
/// thread count. (Fusing the column FFTs with the product, column by column, was measured 8 %
/// slower on 1 thread.)
fn summed_spectra(p: &Plans, template: &CensusImage, map: &CensusImage) -> (Vec<C64>, Vec<C64>) {
    let len = p.spectrum_len();
    let zero = C64::new(0.0, 0.0);
    let (mut acc_s, mut acc_m) = (vec![zero; len], vec![zero; len]);
    let (mut ts, mut ms, mut tm, mut mm) = (
        vec![zero; len],
        vec![zero; len],
        vec![zero; len],
        vec![zero; len],
    );
    for k in 0..BITS {
        rayon::join(
            || {
                rayon::join(
                    || forward_plane(p, map, k, true, &mut ms),
                    || forward_plane(p, template, k, true, &mut ts),
                )
            },
            || {
                rayon::join(
                    || forward_plane(p, map, k, false, &mut mm),
                    || forward_plane(p, template, k, false, &mut tm),
                )
            },
        );
        acc_s
            .par_chunks_mut(MAC_CHUNK)
            .zip(ts.par_chunks(MAC_CHUNK).zip(ms.par_chunks(MAC_CHUNK)))
            .chain(
                acc_m
                    .par_chunks_mut(MAC_CHUNK)
                    .zip(tm.par_chunks(MAC_CHUNK).zip(mm.par_chunks(MAC_CHUNK))),
            )
            .for_each(|(acc, (t, m))| mul_acc(acc, t, m));
    }
    (acc_s, acc_m)
}

/// Inverse 2-D FFT of a `[u][y]` cross-spectrum (consumed), rounded to integers, for offsets
/// `0..ow × 0..oh` (row-major).
fn inverse_rounded(p: &Plans, mut spec: Vec<C64>, ow: usize, oh: usize) -> Vec<i64> {
    let (ny, nxh) = (p.ny, p.nxh());
    let mut scratch = vec![C64::new(0.0, 0.0); p.col_inv.get_inplace_scratch_len()];
    p.col_inv.process_with_scratch(&mut spec, &mut scratch);
    let mut row_spec = vec![C64::new(0.0, 0.0); nxh];
    let mut row = vec![0.0f64; p.nx];
    let mut real_scratch = vec![C64::new(0.0, 0.0); p.row_inv.get_scratch_len()];
    let scale = 1.0 / (p.nx * p.ny) as f64;
    let mut out = Vec::with_capacity(ow * oh);
    for dy in 0..oh {
        for (u, v) in row_spec.iter_mut().enumerate() {
            *v = spec[u * ny + dy];
        }
        // The spectrum of a real plane has real DC and Nyquist terms; drop the rounding noise
        // in their imaginary parts, which the inverse real FFT rejects.
        row_spec[0].im = 0.0;
        row_spec[nxh - 1].im = 0.0;
        p.row_inv
            .process_with_scratch(&mut row_spec, &mut row, &mut real_scratch)
            .expect("inverse row FFT buffers sized by the plan");
        out.extend(row[..ow].iter().map(|&v| (v * scale).round() as i64));
    }
    out
}

/// The masked Hamming counts of every offset by bit-plane FFT correlation: bit-identical to
/// [`hamming_scores_naive`](super::hamming_scores_naive) and
/// [`hamming_scores`](super::hamming_scores), same [`ScoreMap`] layout and offset convention
/// (offset `(dx, dy)` puts template pixel `(x, y)` on map pixel `(x + dx, y + dy)`).
///
/// Its cost depends on the map size only (32 forward and 2 inverse real 2-D FFTs of the map
/// size padded to a 2^a·3^b·5^c size), not on the number of offsets × template pixels, so it
/// wins for large templates with large search windows and loses for small ones. FFT plans are
/// cached per size. The transforms run in parallel on the current `rayon` pool; the result does
/// not depend on the thread count.
///
/// # Performance
/// 240² template over a 480² map (58,081 offsets), 5 % invalid + 30 % wedge, 2-vCPU KVM Xeon,
/// `-C target-cpu=native`: about 37 ms on 1 thread and 21 ms on 2 idle threads, against 165 ms
/// for [`hamming_scores`](super::hamming_scores) on 1 thread and 43 ms for 24 × OpenCV
/// `TM_CCORR` (BENCHMARKS.md, "Localization: exact census scores"). The cost is almost independent of the template size and
/// of the invalid fraction. For small templates or search windows, the brute force is faster.
///
/// # Errors
/// The same as [`hamming_scores_naive`](super::hamming_scores_naive):
/// [`MatchError::SizeMismatch`] if an image's buffers do not hold `width × height` bytes,
/// [`MatchError::EmptyTemplate`], or [`MatchError::TemplateLargerThanMap`]. An all-invalid
/// template is not an error: every `valid` count is then 0.
pub fn hamming_scores_fft(
    template: &CensusImage,
    map: &CensusImage,
) -> Result<ScoreMap, MatchError> {
    template.check(Which::Template)?;
    map.check(Which::Map)?;
    if template.width == 0 || template.height == 0 {
        return Err(MatchError::EmptyTemplate {
            width: template.width,
            height: template.height,
        });
    }
    if template.width > map.width || template.height > map.height {
        return Err(MatchError::TemplateLargerThanMap {
            template_width: template.width,
            template_height: template.height,
            map_width: map.width,
            map_height: map.height,
        });
    }
    let (ow, oh) = (
        map.width - template.width + 1,
        map.height - template.height + 1,
    );
    let p = Plans::get(fft_size(map.width), fft_size(map.height));
    let (sum_s, sum_m) = summed_spectra(&p, template, map);
    let (agree_minus, valid) = rayon::join(
        || inverse_rounded(&p, sum_s, ow, oh),
        || inverse_rounded(&p, sum_m, ow, oh),
    );
    let mismatch = valid
        .iter()
        .zip(&agree_minus)
        .map(|(&v, &s)| {
            debug_assert!((v - s) % 2 == 0 && v >= s.abs());
            ((v - s) / 2) as u32
        })
        .collect();
    let valid = valid.iter().map(|&v| v as u32).collect();
    Ok(ScoreMap {
        width: ow,
        height: oh,
        mismatch,
        valid,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::super::{census_transform, hamming_scores, hamming_scores_naive};
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A seeded random image with `invalid` fraction of missing pixels and, if `wedge`, the left
    /// 30 % of the columns missing (a rear-occlusion wedge), census-transformed.
    fn random_census(w: usize, h: usize, invalid: f64, wedge: bool, seed: u64) -> CensusImage {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let img: Vec<u8> = (0..w * h).map(|_| rng.random_range(0..8u8)).collect();
        let valid: Vec<bool> = (0..w * h)
            .map(|i| {
                let ok = rng.random::<f64>() >= invalid;
                ok && !(wedge && (i % w) * 10 < w * 3)
            })
            .collect();
        census_transform(&img, &valid, w, h)
    }

    #[test]
    fn fft_sizes_are_even_smooth_and_minimal() {
        assert_eq!(fft_size(0), 2);
        assert_eq!(fft_size(1), 2);
        assert_eq!(fft_size(7), 8);
        assert_eq!(fft_size(13), 16);
        assert_eq!(fft_size(480), 480);
        assert_eq!(fft_size(481), 486);
        assert_eq!(fft_size(242), 250);
    }

    #[test]
    fn bit_identical_to_naive_on_random_images() {
        let sizes = [
            ((1, 1), (1, 1)),
            ((1, 1), (5, 3)),
            ((3, 2), (3, 2)),
            ((2, 5), (9, 7)),
            ((7, 7), (20, 13)),
            ((16, 9), (33, 40)),
            ((24, 24), (61, 57)),
            ((40, 31), (64, 64)),
        ];
        let mut seed = 100;
        for &((tw, th), (mw, mh)) in &sizes {
            for invalid in [0.0, 0.05, 0.25, 0.5] {
                for wedge in [false, true] {
                    seed += 1;
                    let t = random_census(tw, th, invalid, wedge, seed);
                    let m = random_census(mw, mh, invalid / 2.0, false, seed + 1000);
                    let want = hamming_scores_naive(&t, &m).unwrap();
                    let got = hamming_scores_fft(&t, &m).unwrap();
                    assert_eq!(got, want, "{tw}×{th} over {mw}×{mh}, {invalid}, {wedge}");
                }
            }
        }
    }

    #[test]
    fn all_invalid_template_and_bad_inputs_match_naive() {
        let t = random_census(6, 5, 1.0, false, 1);
        let m = random_census(12, 9, 0.1, false, 2);
        let got = hamming_scores_fft(&t, &m).unwrap();
        assert_eq!(got, hamming_scores_naive(&t, &m).unwrap());
        assert!(got.valid.iter().all(|&v| v == 0));
        let big = random_census(13, 2, 0.0, false, 3);
        assert_eq!(hamming_scores_fft(&big, &m), hamming_scores_naive(&big, &m));
        let empty = CensusImage {
            width: 0,
            height: 3,
            codes: vec![],
            valid: vec![],
        };
        assert_eq!(
            hamming_scores_fft(&empty, &m),
            hamming_scores_naive(&empty, &m)
        );
        let mut bad = m.clone();
        bad.valid.pop();
        assert_eq!(hamming_scores_fft(&t, &bad), hamming_scores_naive(&t, &bad));
        assert!(hamming_scores_fft(&t, &bad).is_err());
    }

    #[test]
    fn same_result_on_one_and_two_threads() {
        let t = random_census(30, 20, 0.1, true, 7);
        let m = random_census(70, 50, 0.05, false, 8);
        let run = |n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
                .install(|| hamming_scores_fft(&t, &m).unwrap())
        };
        assert_eq!(run(1), run(2));
    }

    #[test]
    fn flight_size_equals_the_packed_kernel() {
        let t = random_census(240, 240, 0.05, true, 42);
        let m = random_census(480, 480, 0.0, false, 43);
        let want = hamming_scores(&t, &m).unwrap();
        let got = hamming_scores_fft(&t, &m).unwrap();
        assert_eq!((got.width, got.height), (241, 241));
        assert_eq!(got, want);
    }
}
