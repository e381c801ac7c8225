//! The fast path of [`hamming_scores_fft`](super::hamming_scores_fft): one correlation sum over
//! a map whose bits are treated as valid, transformed in column tiles that stay in L2, then
//! the map's few invalid bits taken out exactly ([`super::hole_corrections`]).

use rayon::prelude::*;

use super::{
    BITS, C64, CensusImage, Holes, MAC_CHUNK, Plans, Work, hole_corrections, inverse_rounded,
    mul_acc,
};

/// Spectrum columns per tile of [`fast_partial`]'s column stage (a tile of the template and one
/// of the map, `ny` rows each, stay in L2).
pub(super) const TILE_COLS: usize = 8;

/// Real FFTs of rows `0..rows` of a plane (`fill` writes each into a zeroed row of `nx`
/// values), stored row-major: `out[y * nxh + u]`.
fn rows_forward(
    p: &Plans,
    w: &mut Work,
    rows: usize,
    fill: impl Fn(usize, &mut [f64]),
    out: &mut [C64],
) {
    for (y, spec) in out.chunks_exact_mut(p.nxh()).take(rows).enumerate() {
        w.row.fill(0.0);
        fill(y, &mut w.row);
        // Lengths come from the same plans, so this cannot fail.
        p.row_fwd
            .process_with_scratch(&mut w.row, spec, &mut w.real_scratch)
            .expect("row FFT buffers sized by the plan");
    }
}

/// Columns `u0..u0 + cols` of row-major row spectra (`rows` rows of `nxh`) into a tile of `cols`
/// contiguous columns of `ny` (rows `rows..ny` zero), then their column FFTs.
fn tile_forward(p: &Plans, w: &mut Work, src: &[C64], rows: usize, u0: usize, tile: &mut [C64]) {
    let (ny, nxh) = (p.ny, p.nxh());
    let cols = tile.len() / ny;
    for (y, r) in src.chunks_exact(nxh).take(rows).enumerate() {
        for (c, &v) in r[u0..u0 + cols].iter().enumerate() {
            tile[c * ny + y] = v;
        }
    }
    for col in tile.chunks_exact_mut(ny) {
        col[rows..].fill(C64::new(0.0, 0.0));
    }
    p.col_fwd.process_with_scratch(tile, &mut w.col_scratch);
}

/// `Σ_k conj(Â_k)·B̂_k` over the bits `bits`, with `A_k` the template plane `vT_k − 2·t_k`
/// (0 invalid, +1 valid and clear, −1 valid and set) and `B_k` the map plane of valid set bits.
///
/// Per bit, the row FFTs of both planes are stored row-major (sequential writes); the column
/// stage then works on tiles of [`TILE_COLS`] columns (gathered, transformed, multiplied and
/// accumulated while in cache) instead of scattering every row spectrum across the whole
/// column-major buffer.
fn fast_partial(
    p: &Plans,
    template: &CensusImage,
    map: &CensusImage,
    bits: std::ops::Range<usize>,
) -> Vec<C64> {
    let (ny, nxh) = (p.ny, p.nxh());
    let zero = C64::new(0.0, 0.0);
    let (mut acc, mut t_rows, mut m_rows) = (p.take_buffer(), p.take_buffer(), p.take_buffer());
    acc.fill(zero);
    let mut w = Work::new(p);
    let (mut t_tile, mut m_tile) = (vec![zero; TILE_COLS * ny], vec![zero; TILE_COLS * ny]);
    let (tw, th, mw, mh) = (template.width, template.height, map.width, map.height);
    for k in bits {
        rows_forward(
            p,
            &mut w,
            th,
            |y, row| {
                let r = y * tw..(y + 1) * tw;
                for ((o, &c), &v) in row
                    .iter_mut()
                    .zip(&template.codes[r.clone()])
                    .zip(&template.valid[r])
                {
                    let (v, t) = ((v >> k) & 1, (c & v) >> k & 1);
                    *o = f64::from(v) - 2.0 * f64::from(t);
                }
            },
            &mut t_rows,
        );
        rows_forward(
            p,
            &mut w,
            mh,
            |y, row| {
                let r = y * mw..(y + 1) * mw;
                for ((o, &c), &v) in row.iter_mut().zip(&map.codes[r.clone()]).zip(&map.valid[r]) {
                    *o = f64::from((c & v) >> k & 1);
                }
            },
            &mut m_rows,
        );
        for u0 in (0..nxh).step_by(TILE_COLS) {
            let cols = TILE_COLS.min(nxh - u0);
            let (tt, mt) = (&mut t_tile[..cols * ny], &mut m_tile[..cols * ny]);
            tile_forward(p, &mut w, &t_rows, th, u0, tt);
            tile_forward(p, &mut w, &m_rows, mh, u0, mt);
            mul_acc(&mut acc[u0 * ny..(u0 + cols) * ny], tt, mt);
        }
    }
    p.give_buffer(t_rows);
    p.give_buffer(m_rows);
    acc
}

/// The fast path of [`hamming_scores_fft`] for maps whose census bits are valid almost
/// everywhere (the matcher's search window: all but its one-pixel border).
///
/// Treating every map bit as valid, the disagreements at an offset are
/// `Σ_k Σ_p vT_k·[t_k ≠ b_k] = C + Σ_k corr(A_k, B_k)`, with `C` the template's set valid bits,
/// `A_k = vT_k − 2·t_k` and `B_k` the map's valid set bits: one correlation sum, i.e. 16 forward
/// transforms and 1 inverse instead of 32 and 2. Map bits that are in fact invalid are then
/// taken out exactly, per offset, by [`hole_corrections`] (there, `b_k = 0`, so the template
/// bit counted a disagreement iff it was set).
pub(super) fn fast_scores(
    p: &Plans,
    template: &CensusImage,
    map: &CensusImage,
    holes: &Holes,
    ow: usize,
    oh: usize,
) -> (Vec<u32>, Vec<u32>) {
    // Two fixed halves of the bits (not one per thread), so the sums do not depend on the
    // thread count.
    let ((mut acc, other), (cm, cv)) = rayon::join(
        || {
            rayon::join(
                || fast_partial(p, template, map, 0..BITS / 2),
                || fast_partial(p, template, map, BITS / 2..BITS),
            )
        },
        || hole_corrections(template, map, holes, ow, oh),
    );
    acc.par_chunks_mut(MAC_CHUNK)
        .zip(other.par_chunks(MAC_CHUNK))
        .for_each(|(a, b)| {
            for (a, b) in a.iter_mut().zip(b) {
                *a += b;
            }
        });
    p.give_buffer(other);
    let agree_term = inverse_rounded(p, acc, ow, oh);
    let set_bits: i64 = template
        .codes
        .iter()
        .zip(&template.valid)
        .map(|(&c, &v)| i64::from((c & v).count_ones()))
        .sum();
    let valid_bits: i64 = template
        .valid
        .iter()
        .map(|&v| i64::from(v.count_ones()))
        .sum();
    let mismatch = agree_term
        .iter()
        .zip(&cm)
        .map(|(&s, &c)| {
            let m = set_bits + s - i64::from(c);
            debug_assert!(m >= 0);
            m as u32
        })
        .collect();
    let valid = cv
        .iter()
        .map(|&c| (valid_bits - i64::from(c)) as u32)
        .collect();
    (mismatch, valid)
}
