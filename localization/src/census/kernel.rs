//! The packed kernel behind [`super::hamming_scores`]: byte-packed codes, 8 pixels per `u64`,
//! POPCNT when the CPU has it.
//!
//! One census pixel is one byte, so 8 consecutive pixels are one `u64` and a shift of the
//! template by one pixel is a load one byte further on: no bit shuffling. The template is padded
//! to whole words with invalid (zero) bytes, which therefore never count; the map rows are padded
//! with zero bytes so that every load of the last offsets stays inside the buffer. Template words
//! with no valid bit at all (a rear-occlusion wedge, unseen terrain) add nothing at any offset, so
//! each template row keeps the runs of words that have some valid bit and the kernel skips the
//! rest.

use super::transform::CensusImage;

/// Offsets scored per pass over a template row (register blocking: each template word is loaded
/// once for all of them).
///
/// Scoring 4 was measured 11 % faster for a C AVX2 kernel (docs/design.md, "Exact census scores
/// by bit-plane FFT"), but this scalar POPCNT kernel
/// runs out of registers instead: at flight size (240² over 480², 5 % invalid + 30 % wedge,
/// 1 thread, Zen 1) blocks of 1 / 2 / 3 / 4 / 8 offsets took 215 / 223 / 250 / 245 / 264 ms.
/// Re-measure before changing it; every value gives the same counts.
const BLOCK: usize = 1;

/// Bytes per packed word.
const WORD: usize = 8;

/// The template as rows of `u64` words (8 pixels each), zero-padded to whole words.
pub(super) struct PackedTemplate {
    height: usize,
    words_per_row: usize,
    codes: Vec<u64>,
    valid: Vec<u64>,
    /// Runs of words with some valid bit, as word ranges within the row, row by row.
    runs: Vec<std::ops::Range<usize>>,
    /// `runs[run_start[y]..run_start[y + 1]]` are the runs of row `y`.
    run_start: Vec<usize>,
}

impl PackedTemplate {
    pub(super) fn new(t: &CensusImage) -> Self {
        let words_per_row = t.width.div_ceil(WORD);
        let n = words_per_row * t.height;
        let (mut codes, mut valid) = (vec![0u64; n], vec![0u64; n]);
        for y in 0..t.height {
            let src = y * t.width..(y + 1) * t.width;
            let dst = y * words_per_row..(y + 1) * words_per_row;
            pack_row(&t.codes[src.clone()], &mut codes[dst.clone()]);
            pack_row(&t.valid[src], &mut valid[dst]);
        }
        let (mut runs, mut run_start) = (Vec::new(), vec![0]);
        for row in valid.chunks_exact(words_per_row.max(1)) {
            let mut w = 0;
            while w < row.len() {
                if row[w] == 0 {
                    w += 1;
                    continue;
                }
                let start = w;
                while w < row.len() && row[w] != 0 {
                    w += 1;
                }
                runs.push(start..w);
            }
            run_start.push(runs.len());
        }
        Self {
            height: t.height,
            words_per_row,
            codes,
            valid,
            runs,
            run_start,
        }
    }

    fn row_runs(&self, y: usize) -> &[std::ops::Range<usize>] {
        &self.runs[self.run_start[y]..self.run_start[y + 1]]
    }
}

/// Little-endian packing: byte `j` of word `w` is pixel `8w + j`, the same layout an unaligned
/// `u64` load from the byte rows of the map gives.
fn pack_row(bytes: &[u8], words: &mut [u64]) {
    for (word, chunk) in words.iter_mut().zip(bytes.chunks(WORD)) {
        let mut b = [0u8; WORD];
        b[..chunk.len()].copy_from_slice(chunk);
        *word = u64::from_le_bytes(b);
    }
}

/// The map as byte rows padded with zeros to `stride`, so that loads for offsets up to the next
/// multiple of [`BLOCK`] never leave the row.
pub(super) struct PackedMap {
    stride: usize,
    codes: Vec<u8>,
    valid: Vec<u8>,
}

impl PackedMap {
    /// `offsets_x` = number of x offsets scored, `words_per_row` = the packed template's width.
    pub(super) fn new(m: &CensusImage, offsets_x: usize, words_per_row: usize) -> Self {
        // Last load of a row: starts at most at (round_up(offsets_x) - 1) + WORD·(words - 1) and
        // is WORD bytes long; that is < stride. It also covers the real row: stride ≥ width + 1.
        let stride = offsets_x.next_multiple_of(BLOCK) + WORD * words_per_row;
        debug_assert!(stride > m.width);
        let (mut codes, mut valid) = (vec![0u8; stride * m.height], vec![0u8; stride * m.height]);
        for y in 0..m.height {
            let src = y * m.width..(y + 1) * m.width;
            let dst = y * stride..y * stride + m.width;
            codes[dst.clone()].copy_from_slice(&m.codes[src.clone()]);
            valid[dst].copy_from_slice(&m.valid[src]);
        }
        Self {
            stride,
            codes,
            valid,
        }
    }

    fn row(&self, y: usize) -> (&[u8], &[u8]) {
        let r = y * self.stride..(y + 1) * self.stride;
        (&self.codes[r.clone()], &self.valid[r])
    }
}

/// Which popcount the kernel is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kernel {
    /// `count_ones` compiled with the POPCNT instruction (x86-64 with POPCNT only).
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    Popcnt,
    /// `count_ones` for the default target (a bit-twiddling sequence on baseline x86-64).
    Portable,
}

impl Kernel {
    /// The fastest kernel this CPU runs.
    pub(super) fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("popcnt") {
                return Self::Popcnt;
            }
        }
        Self::Portable
    }
}

/// Score one row of offsets (`dy` fixed, every `dx`): fills `mismatch` and `valid`, whose common
/// length is the number of x offsets.
pub(super) fn score_row(
    kernel: Kernel,
    t: &PackedTemplate,
    m: &PackedMap,
    dy: usize,
    mismatch: &mut [u32],
    valid: &mut [u32],
) {
    match kernel {
        #[cfg(target_arch = "x86_64")]
        Kernel::Popcnt => {
            // SAFETY: `Kernel::Popcnt` is only produced by `Kernel::detect` after
            // `is_x86_feature_detected!("popcnt")` returned true (and by tests that check the
            // same), so the CPU supports every feature the function is compiled for.
            unsafe { score_row_popcnt(t, m, dy, mismatch, valid) }
        }
        _ => score_row_body(t, m, dy, mismatch, valid),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "popcnt")]
fn score_row_popcnt(
    t: &PackedTemplate,
    m: &PackedMap,
    dy: usize,
    mismatch: &mut [u32],
    valid: &mut [u32],
) {
    score_row_body(t, m, dy, mismatch, valid);
}

#[inline(always)]
fn score_row_body(
    t: &PackedTemplate,
    m: &PackedMap,
    dy: usize,
    mismatch: &mut [u32],
    valid: &mut [u32],
) {
    mismatch.fill(0);
    valid.fill(0);
    let nx = mismatch.len();
    let wpr = t.words_per_row;
    for ty in 0..t.height {
        let tc = &t.codes[ty * wpr..(ty + 1) * wpr];
        let tv = &t.valid[ty * wpr..(ty + 1) * wpr];
        let (mc, mv) = m.row(ty + dy);
        for run in t.row_runs(ty) {
            let (tc, tv) = (&tc[run.clone()], &tv[run.clone()]);
            let (mc, mv) = (&mc[WORD * run.start..], &mv[WORD * run.start..]);
            for dx0 in (0..nx).step_by(BLOCK) {
                let (mis, val) = block(tc, tv, &mc[dx0..], &mv[dx0..]);
                let end = (dx0 + BLOCK).min(nx);
                for (k, dx) in (dx0..end).enumerate() {
                    mismatch[dx] += mis[k];
                    valid[dx] += val[k];
                }
            }
        }
    }
}

/// Counts for [`BLOCK`] consecutive offsets of one template row against one map row; `mc` and
/// `mv` start at the first offset's byte.
#[inline(always)]
fn block(tc: &[u64], tv: &[u64], mc: &[u8], mv: &[u8]) -> ([u32; BLOCK], [u32; BLOCK]) {
    let n = tc.len();
    let tv = &tv[..n];
    let need = WORD * n + BLOCK - 1;
    let (mc, mv) = (&mc[..need], &mv[..need]);
    let (mut mis, mut val) = ([0u32; BLOCK], [0u32; BLOCK]);
    for w in 0..n {
        let (a, va) = (tc[w], tv[w]);
        for k in 0..BLOCK {
            let o = WORD * w + k;
            let b = load(mc, o);
            let both = va & load(mv, o);
            mis[k] += ((a ^ b) & both).count_ones();
            val[k] += both.count_ones();
        }
    }
    (mis, val)
}

#[inline(always)]
fn load(bytes: &[u8], at: usize) -> u64 {
    let mut b = [0u8; WORD];
    b.copy_from_slice(&bytes[at..at + WORD]);
    u64::from_le_bytes(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_is_little_endian_and_zero_padded() {
        let mut w = [0u64; 2];
        pack_row(&[1, 2, 3, 4, 5, 6, 7, 8, 9], &mut w);
        assert_eq!(w[0], 0x0807_0605_0403_0201);
        assert_eq!(w[1], 9);
    }

    #[test]
    fn runs_skip_words_without_valid_bits() {
        let mut valid = vec![0u8; 3 * 20];
        valid[0] = 1; // row 0: word 0
        valid[17] = 4; // row 0: word 2
        valid[20 + 8..20 + 16].fill(0xFF); // row 1: word 1; row 2: nothing
        let t = CensusImage {
            width: 20,
            height: 3,
            codes: vec![0; 60],
            valid,
        };
        let p = PackedTemplate::new(&t);
        assert_eq!(p.row_runs(0), [0..1, 2..3]);
        assert_eq!((p.row_runs(1).len(), p.row_runs(1)[0].clone()), (1, 1..2));
        assert!(p.row_runs(2).is_empty());
    }

    #[test]
    fn map_stride_covers_every_load() {
        // 13 px template (2 words), 7 x offsets rounded up to whole blocks: the last load starts
        // at the last offset + 8 and is 8 bytes long.
        let m = CensusImage {
            width: 19,
            height: 2,
            codes: vec![1; 38],
            valid: vec![1; 38],
        };
        let p = PackedMap::new(&m, 7, 2);
        let last_load_end = 7usize.next_multiple_of(BLOCK) - 1 + 8 + 8;
        assert!(p.stride >= last_load_end && p.stride > 19);
        assert_eq!(p.row(1).0[..19], [1; 19]);
        assert!(p.row(1).0[19..].iter().all(|&b| b == 0));
    }

    #[test]
    fn portable_kernel_equals_popcnt_kernel() {
        let t = CensusImage {
            width: 11,
            height: 3,
            codes: (0..33u32).map(|i| (i * 89 % 256) as u8).collect(),
            valid: (0..33u32).map(|i| (i * 151 % 256) as u8).collect(),
        };
        let m = CensusImage {
            width: 20,
            height: 5,
            codes: (0..100u32).map(|i| (i * 97 % 256) as u8).collect(),
            valid: (0..100u32).map(|i| (i * 211 % 256) as u8 | 0x81).collect(),
        };
        let pt = PackedTemplate::new(&t);
        let pm = PackedMap::new(&m, 10, pt.words_per_row);
        let run = |k| {
            let (mut a, mut b) = (vec![0; 10], vec![0; 10]);
            score_row(k, &pt, &pm, 2, &mut a, &mut b);
            (a, b)
        };
        let portable = run(Kernel::Portable);
        assert!(portable.1.iter().all(|&v| v > 0));
        assert_eq!(run(Kernel::detect()), portable);
    }
}
