//! Exact masked census Hamming counts of every offset by bit-plane FFT correlation
//! (docs/design.md, "Exact census scores by bit-plane FFT"; Fischer–Paterson 1973, Schoenmeyr &
//! Zhang 2005).
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
//! **Fast path** (the matcher's case: a map whose census bits are valid everywhere but on a few
//! pixels, such as its one-pixel border). Counting every map bit as valid, the disagreements are
//! `C + Σ_k corr(A_k, B_k)` with `A_k = vT_k − 2·t_k` (0, ±1), `B_k` the map's valid set bits and
//! `C` the template's valid set bits, and the valid count is the template's. That is one
//! correlation sum: 16 forward transforms and 1 inverse instead of 32 and 2. The bits of the
//! template that land on the map's invalid bits are then subtracted exactly, per offset, from
//! both counts (integer popcounts; see [`hole_corrections`]). Bound on the error before
//! rounding: about `ε·log₂N·Σ_k‖A_k‖‖B_k‖ ≈ 1.1e-16 · 18 · 8 · 240 · 480 ≈ 2e-9` at flight size,
//! far below ½. The path is taken when those corrections are cheap ([`FAST_PAIRS_PER_OFFSET`]).
//!
//! Determinism: every count is an exactly rounded integer, and the floating-point sums are
//! grouped by fixed ranges of bits and fixed chunks, never by thread; parallelism (`rayon`) is
//! only over whole transforms, bit groups, column tiles and disjoint chunks of the element-wise
//! products, so the counts are the same on any number of threads.
//!
//! Layout: planes are row-major `ny × nx` (zero-padded, `nx ≥ map width`, `ny ≥ map height`, so
//! the circular correlation never wraps for the offsets we keep). Each row gets a real FFT
//! (`realfft`) whose `nx/2 + 1` outputs are transposed into the spectrum buffer (`[u][y]`, one
//! contiguous column per frequency `u`), then every column gets a complex FFT (`rustfft`). The
//! fast path transposes in tiles of [`TILE_COLS`](fast_path::TILE_COLS) columns and multiplies each tile while it is in
//! cache. The inverse runs the column FFTs and then the inverse real FFT of only the `dy` rows
//! that are offsets. All-zero template rows are not transformed.

use std::sync::{Arc, Mutex, OnceLock};

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::MatchError;
use super::score::ScoreMap;
use super::transform::CensusImage;

mod fast_path;

use fast_path::fast_scores;

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
    /// Spectrum buffers (`spectrum_len` each) kept for reuse across calls: fresh multi-MB
    /// buffers cost page faults and zeroing on every call.
    spare: Mutex<Vec<Vec<C64>>>,
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

    /// A spectrum buffer of `spectrum_len` elements with arbitrary contents.
    fn take_buffer(&self) -> Vec<C64> {
        let spare = self
            .spare
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .pop();
        spare.unwrap_or_else(|| vec![C64::new(0.0, 0.0); self.spectrum_len()])
    }

    /// Return a buffer from [`Plans::take_buffer`] for reuse (at most [`SPARE_BUFFERS`] are kept).
    fn give_buffer(&self, buf: Vec<C64>) {
        let mut spare = self
            .spare
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if buf.len() == self.spectrum_len() && spare.len() < SPARE_BUFFERS {
            spare.push(buf);
        }
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
            spare: Mutex::new(Vec::new()),
        });
        // Keep the cache small: a matcher uses one or two sizes.
        if list.len() >= 8 {
            list.remove(0);
        }
        list.push(Arc::clone(&p));
        p
    }
}

/// Spectrum buffers kept per size for reuse: the fast path uses 6 at once (3 per half).
const SPARE_BUFFERS: usize = 6;

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
    /// The spectra of [`ROW_BLOCK`] consecutive rows, `nxh` each.
    block: Vec<C64>,
    real_scratch: Vec<C64>,
    col_scratch: Vec<C64>,
}

impl Work {
    fn new(p: &Plans) -> Self {
        Self {
            row: vec![0.0; p.nx],
            block: vec![C64::new(0.0, 0.0); ROW_BLOCK * p.nxh()],
            real_scratch: vec![C64::new(0.0, 0.0); p.row_fwd.get_scratch_len()],
            col_scratch: vec![C64::new(0.0, 0.0); p.col_fwd.get_inplace_scratch_len()],
        }
    }
}

/// Rows transformed before their spectra are scattered into the column-major spectrum, so each
/// column receives `ROW_BLOCK` contiguous values (whole cache lines) instead of one.
const ROW_BLOCK: usize = 8;

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
    for y0 in (0..rows).step_by(ROW_BLOCK) {
        let nb = ROW_BLOCK.min(rows - y0);
        for (j, spec) in w.block.chunks_exact_mut(nxh).take(nb).enumerate() {
            w.row.fill(0.0);
            fill(y0 + j, &mut w.row);
            // Lengths come from the same plans, so this cannot fail.
            p.row_fwd
                .process_with_scratch(&mut w.row, spec, &mut w.real_scratch)
                .expect("row FFT buffers sized by the plan");
        }
        for (u, col) in out.chunks_exact_mut(ny).enumerate() {
            for (j, v) in col[y0..y0 + nb].iter_mut().enumerate() {
                *v = w.block[j * nxh + u];
            }
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

/// The fast path of [`hamming_scores_fft`] is taken while its hole corrections visit at most
/// this many (hole, offset) pairs per offset on average (the matcher's window: about 4, its
/// one-pixel border).
const FAST_PAIRS_PER_OFFSET: u64 = 64;

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

/// Columns per parallel task of the inverse column FFTs.
const INV_COLS: usize = 16;
/// Offset rows per parallel task of the inverse row FFTs.
const INV_ROWS: usize = 8;

/// Inverse 2-D FFT of a `[u][y]` cross-spectrum (consumed), rounded to integers, for offsets
/// `0..ow × 0..oh` (row-major). Column FFTs and then row FFTs run in parallel chunks; each
/// element is computed by the same operations whatever thread runs it.
fn inverse_rounded(p: &Plans, mut spec: Vec<C64>, ow: usize, oh: usize) -> Vec<i64> {
    let (ny, nxh) = (p.ny, p.nxh());
    let zero = C64::new(0.0, 0.0);
    spec.par_chunks_mut(ny * INV_COLS).for_each_init(
        || vec![zero; p.col_inv.get_inplace_scratch_len()],
        |scratch, cols| p.col_inv.process_with_scratch(cols, scratch),
    );
    let scale = 1.0 / (p.nx * p.ny) as f64;
    let mut out = vec![0i64; ow * oh];
    out.par_chunks_mut(ow * INV_ROWS).enumerate().for_each_init(
        || {
            (
                vec![zero; nxh],
                vec![0.0f64; p.nx],
                vec![zero; p.row_inv.get_scratch_len()],
            )
        },
        |(row_spec, row, real_scratch), (chunk, rows_out)| {
            for (j, out_row) in rows_out.chunks_exact_mut(ow).enumerate() {
                let dy = chunk * INV_ROWS + j;
                for (u, v) in row_spec.iter_mut().enumerate() {
                    *v = spec[u * ny + dy];
                }
                // The spectrum of a real plane has real DC and Nyquist terms; drop the rounding
                // noise in their imaginary parts, which the inverse real FFT rejects.
                row_spec[0].im = 0.0;
                row_spec[nxh - 1].im = 0.0;
                p.row_inv
                    .process_with_scratch(row_spec, row, real_scratch)
                    .expect("inverse row FFT buffers sized by the plan");
                for (o, &v) in out_row.iter_mut().zip(&row[..ow]) {
                    *o = (v * scale).round() as i64;
                }
            }
        },
    );
    p.give_buffer(spec);
    out
}

/// Map pixels with at least one invalid census bit, by row: the columns of row `y` are
/// `cols[starts[y]..starts[y + 1]]`.
struct Holes {
    starts: Vec<usize>,
    cols: Vec<usize>,
}

impl Holes {
    fn of(map: &CensusImage) -> Self {
        let mut starts = Vec::with_capacity(map.height + 1);
        let mut cols = Vec::new();
        starts.push(0);
        for row in map.valid.chunks_exact(map.width) {
            cols.extend((0..map.width).filter(|&x| row[x] != u8::MAX));
            starts.push(cols.len());
        }
        Self { starts, cols }
    }

    /// Number of (hole, offset) pairs where the template covers the hole: the work of
    /// [`hole_corrections`].
    fn pairs(&self, tw: usize, th: usize, ow: usize, oh: usize) -> u64 {
        // Offsets d in 0..n whose template span d..d + t covers coordinate q.
        let covering = |q: usize, t: usize, n: usize| {
            (q.min(n - 1) + 1).saturating_sub((q + 1).saturating_sub(t)) as u64
        };
        (0..self.starts.len() - 1)
            .map(|y| {
                let ny = covering(y, th, oh);
                self.cols[self.starts[y]..self.starts[y + 1]]
                    .iter()
                    .map(|&x| ny * covering(x, tw, ow))
                    .sum::<u64>()
            })
            .sum()
    }
}

/// Per offset, the template bits that land on invalid map bits: `(Σ popcount(t & !vM),
/// Σ popcount(vT & !vM))` with `t` the template's valid code bits, summed over the template
/// pixels that fall on map holes. Offset rows in parallel (integer sums).
fn hole_corrections(
    template: &CensusImage,
    map: &CensusImage,
    holes: &Holes,
    ow: usize,
    oh: usize,
) -> (Vec<u32>, Vec<u32>) {
    let (tw, th) = (template.width, template.height);
    let (mut cm, mut cv) = (vec![0u32; ow * oh], vec![0u32; ow * oh]);
    cm.par_chunks_mut(ow)
        .zip(cv.par_chunks_mut(ow))
        .enumerate()
        .for_each(|(dy, (cm, cv))| {
            for qy in dy..(dy + th).min(map.height) {
                let py = qy - dy;
                let (t_codes, t_valid) = (
                    &template.codes[py * tw..(py + 1) * tw],
                    &template.valid[py * tw..(py + 1) * tw],
                );
                for &qx in &holes.cols[holes.starts[qy]..holes.starts[qy + 1]] {
                    let inv = !map.valid[qy * map.width + qx];
                    // dx with qx - dx in 0..tw and dx in 0..ow.
                    for dx in (qx + 1).saturating_sub(tw)..=qx.min(ow - 1) {
                        let px = qx - dx;
                        let tv = t_valid[px] & inv;
                        cm[dx] += (t_codes[px] & tv).count_ones();
                        cv[dx] += tv.count_ones();
                    }
                }
            }
        });
    (cm, cv)
}

/// The masked Hamming counts of every offset by bit-plane FFT correlation: bit-identical to
/// [`hamming_scores_naive`](super::hamming_scores_naive) and
/// [`hamming_scores`](super::hamming_scores), same [`ScoreMap`] layout and offset convention
/// (offset `(dx, dy)` puts template pixel `(x, y)` on map pixel `(x + dx, y + dy)`).
///
/// Its cost depends on the map size only (16 forward and 1 inverse real 2-D FFTs of the map
/// size padded to a 2^a·3^b·5^c size on the fast path — a map valid everywhere but on a few
/// pixels, as in the matcher — and 32 + 2 otherwise), not on the number of offsets × template
/// pixels, so it wins for large templates with large search windows and loses for small ones.
/// FFT plans and spectrum buffers are cached per size. The transforms run in parallel on the
/// current `rayon` pool; the result does not depend on the thread count.
///
/// # Performance
/// 240² template over a 480² map (58,081 offsets), 5 % invalid + 30 % wedge, fully valid map,
/// 2-vCPU KVM Xeon, `-C target-cpu=native`: about 14 ms on 1 thread (37 ms before the fast
/// path), against 165 ms for [`hamming_scores`](super::hamming_scores) on 1 thread and about
/// 43 ms for 24 × OpenCV `TM_CCORR` (BENCHMARKS.md, "Localization: exact census scores"). The
/// cost is almost independent of the template size and of the invalid fraction of the
/// template. For small templates or search windows, the brute force is faster.
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
    let (ow, oh) = super::score::offsets(template, map)?;
    let p = Plans::get(fft_size(map.width), fft_size(map.height));
    let holes = Holes::of(map);
    // The fast path when its exact corrections cost little next to the transforms it saves.
    if holes.pairs(template.width, template.height, ow, oh)
        <= FAST_PAIRS_PER_OFFSET * (ow * oh) as u64
    {
        let (mismatch, valid) = fast_scores(&p, template, map, &holes, ow, oh);
        return Ok(ScoreMap {
            width: ow,
            height: oh,
            mismatch,
            valid,
        });
    }
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

    /// Whether `hamming_scores_fft` takes the fast path for this pair.
    fn fast_path(t: &CensusImage, m: &CensusImage) -> bool {
        let (ow, oh) = (m.width - t.width + 1, m.height - t.height + 1);
        Holes::of(m).pairs(t.width, t.height, ow, oh) <= FAST_PAIRS_PER_OFFSET * (ow * oh) as u64
    }

    #[test]
    fn fast_path_with_holes_inside_the_map_and_general_path_equal_naive() {
        // A map valid everywhere but its border and a few scattered pixels: the fast path, with
        // corrections inside the map too (the pixels' neighbours lose bits as well).
        let t = random_census(40, 31, 0.05, true, 11);
        let img = random_census(96, 80, 0.0, false, 12);
        let mut valid = vec![true; 96 * 80];
        for i in [97 * 13, 96 * 40 + 50, 96 * 79 - 2, 96 * 21 + 3] {
            valid[i] = false;
        }
        let m = census_transform(&img.codes, &valid, 96, 80);
        assert!(fast_path(&t, &m));
        assert_eq!(
            hamming_scores_fft(&t, &m).unwrap(),
            hamming_scores_naive(&t, &m).unwrap()
        );
        // A map with many holes: the general path (32 + 2 transforms).
        let m = random_census(96, 80, 0.1, false, 13);
        assert!(!fast_path(&t, &m));
        assert_eq!(
            hamming_scores_fft(&t, &m).unwrap(),
            hamming_scores_naive(&t, &m).unwrap()
        );
        // Codes with bits set where they are invalid (the fields are public) count as clear.
        let mut t2 = t.clone();
        for (c, v) in t2.codes.iter_mut().zip(&t2.valid) {
            *c |= !v & 0b1010_0101;
        }
        let m = random_census(96, 80, 0.0, false, 14);
        assert!(fast_path(&t2, &m));
        assert_eq!(
            hamming_scores_fft(&t2, &m).unwrap(),
            hamming_scores_naive(&t2, &m).unwrap()
        );
    }
}
