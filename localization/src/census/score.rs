//! Masked Hamming scores of a template census at every offset inside a map census.

use super::MatchError;
use super::kernel::{Kernel, PackedMap, PackedTemplate, score_row};
use super::transform::{CensusImage, Which};
use rayon::prelude::*;

/// Masked Hamming counts for every integer offset of the template inside the map.
///
/// Offset `(dx, dy)` puts template pixel `(x, y)` on map pixel `(x + dx, y + dy)`; it is stored at
/// index `dy * width + dx`, with `0 ≤ dx < width = map width − template width + 1` and likewise
/// for `dy`. Over the template's footprint,
/// `mismatch = Σ popcount((a ^ b) & va & vb)` and `valid = Σ popcount(va & vb)`
/// (`a`, `va`: template code and validity bytes; `b`, `vb`: the map's). The `u32` counts hold
/// templates of up to 2²⁹ pixels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScoreMap {
    /// Number of x offsets (`map width − template width + 1`).
    pub width: usize,
    /// Number of y offsets (`map height − template height + 1`).
    pub height: usize,
    /// Disagreeing valid census bits per offset, row-major.
    pub mismatch: Vec<u32>,
    /// Census bits valid in both images per offset, row-major.
    pub valid: Vec<u32>,
}

impl ScoreMap {
    /// Number of offsets.
    #[must_use]
    pub fn len(&self) -> usize {
        self.mismatch.len()
    }

    /// Whether there is no offset at all.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.mismatch.is_empty()
    }

    /// Fraction of the compared bits that disagree at offset index `i` (0 = identical ordering,
    /// about 0.5 = unrelated images), or `None` when no bit was comparable there.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    #[must_use]
    pub fn normalized(&self, i: usize) -> Option<f64> {
        let v = self.valid[i];
        (v > 0).then(|| f64::from(self.mismatch[i]) / f64::from(v))
    }

    /// [`normalized`](Self::normalized) at offset `(dx, dy)`; `None` outside the score map too.
    #[must_use]
    pub fn normalized_at(&self, dx: usize, dy: usize) -> Option<f64> {
        (dx < self.width && dy < self.height)
            .then(|| self.normalized(dy * self.width + dx))
            .flatten()
    }

    /// All normalized scores, row-major, with `+∞` where no bit was comparable: the input
    /// [`subpixel_peak`](super::subpixel_peak) expects.
    #[must_use]
    pub fn normalized_scores(&self) -> Vec<f64> {
        (0..self.len())
            .map(|i| self.normalized(i).unwrap_or(f64::INFINITY))
            .collect()
    }

    /// The offset `(dx, dy)` with the lowest normalized score among those with at least
    /// `min_valid` (and at least one) comparable bits, or `None` if there is none.
    ///
    /// Scores are compared exactly as fractions (`m₁·v₂ < m₂·v₁` in integers), and ties go to
    /// the first offset in row-major order, so the answer never depends on rounding.
    #[must_use]
    pub fn best_offset(&self, min_valid: u32) -> Option<(usize, usize)> {
        let min_valid = min_valid.max(1);
        let mut best: Option<usize> = None;
        for i in 0..self.len() {
            if self.valid[i] < min_valid {
                continue;
            }
            let better = best.is_none_or(|b| {
                u64::from(self.mismatch[i]) * u64::from(self.valid[b])
                    < u64::from(self.mismatch[b]) * u64::from(self.valid[i])
            });
            if better {
                best = Some(i);
            }
        }
        best.map(|i| (i % self.width, i / self.width))
    }
}

/// Validate the pair and return the score-map size.
pub(super) fn offsets(
    template: &CensusImage,
    map: &CensusImage,
) -> Result<(usize, usize), MatchError> {
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
    Ok((
        map.width - template.width + 1,
        map.height - template.height + 1,
    ))
}

/// The plain per-pixel reference: four nested loops over offsets and template pixels.
///
/// Obviously correct and much slower than [`hamming_scores`] (one byte at a time, one thread);
/// kept as the reference the fast path is tested against.
///
/// # Errors
/// [`MatchError::SizeMismatch`] if an image's buffers do not hold `width × height` bytes,
/// [`MatchError::EmptyTemplate`], or [`MatchError::TemplateLargerThanMap`].
pub fn hamming_scores_naive(
    template: &CensusImage,
    map: &CensusImage,
) -> Result<ScoreMap, MatchError> {
    let (width, height) = offsets(template, map)?;
    let mut mismatch = vec![0u32; width * height];
    let mut valid = vec![0u32; width * height];
    for dy in 0..height {
        for dx in 0..width {
            let (mut mis, mut val) = (0u32, 0u32);
            for y in 0..template.height {
                for x in 0..template.width {
                    let t = y * template.width + x;
                    let m = (y + dy) * map.width + x + dx;
                    let both = template.valid[t] & map.valid[m];
                    mis += ((template.codes[t] ^ map.codes[m]) & both).count_ones();
                    val += both.count_ones();
                }
            }
            mismatch[dy * width + dx] = mis;
            valid[dy * width + dx] = val;
        }
    }
    Ok(ScoreMap {
        width,
        height,
        mismatch,
        valid,
    })
}

/// The masked Hamming counts of every offset, fast: bit-identical to [`hamming_scores_naive`].
///
/// Packs 8 census pixels per `u64` (a one-pixel shift is a load one byte further on), uses the
/// POPCNT instruction when [`is_x86_feature_detected!`] finds it (plain `count_ones` otherwise),
/// skips template words without any valid bit, and runs the rows of offsets in parallel on the
/// current `rayon` pool. All sums are integers, so the result is the same on any number of
/// threads.
///
/// # Performance
/// 240² template over a 480² map (58,081 offsets), 5 % invalid pixels, 2-vCPU Zen 1: about
/// 0.28 s on 1 thread and 0.145 s on 2; with a 30 % rear wedge about 0.215 s and 0.11 s, since
/// words without valid bits are skipped.
///
/// # Errors
/// [`MatchError::SizeMismatch`] if an image's buffers do not hold `width × height` bytes,
/// [`MatchError::EmptyTemplate`], or [`MatchError::TemplateLargerThanMap`]. An all-invalid
/// template is not an error: every `valid` count is then 0.
pub fn hamming_scores(template: &CensusImage, map: &CensusImage) -> Result<ScoreMap, MatchError> {
    hamming_scores_with(template, map, Kernel::detect())
}

fn hamming_scores_with(
    template: &CensusImage,
    map: &CensusImage,
    kernel: Kernel,
) -> Result<ScoreMap, MatchError> {
    let (width, height) = offsets(template, map)?;
    let t = PackedTemplate::new(template);
    let m = PackedMap::new(map, width, template.width.div_ceil(8));
    let mut mismatch = vec![0u32; width * height];
    let mut valid = vec![0u32; width * height];
    mismatch
        .par_chunks_mut(width)
        .zip(valid.par_chunks_mut(width))
        .enumerate()
        .for_each(|(dy, (mis, val))| score_row(kernel, &t, &m, dy, mis, val));
    Ok(ScoreMap {
        width,
        height,
        mismatch,
        valid,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::census::census_transform;

    fn image(w: usize, h: usize, seed: u32) -> CensusImage {
        let px: Vec<u8> = (0..(w * h) as u32)
            .map(|i| (i.wrapping_mul(2_654_435_761).wrapping_add(seed) >> 24) as u8)
            .collect();
        let ok: Vec<bool> = (0..w * h)
            .map(|i| !(i as u32 * 7 + seed).is_multiple_of(11))
            .collect();
        census_transform(&px, &ok, w, h)
    }

    #[test]
    fn portable_and_detected_kernels_equal_the_reference() {
        for (tw, th, mw, mh) in [(1, 1, 1, 1), (9, 4, 23, 9), (16, 3, 16, 3), (17, 5, 30, 6)] {
            let (t, m) = (image(tw, th, 1), image(mw, mh, 2));
            let naive = hamming_scores_naive(&t, &m).unwrap();
            assert_eq!(
                hamming_scores_with(&t, &m, Kernel::Portable).unwrap(),
                naive
            );
            assert_eq!(hamming_scores(&t, &m).unwrap(), naive);
        }
    }

    #[test]
    fn degenerate_inputs_are_errors() {
        let (t, m) = (image(5, 5, 1), image(4, 9, 2));
        let e = hamming_scores(&t, &m).unwrap_err();
        assert!(matches!(e, MatchError::TemplateLargerThanMap { .. }));
        assert!(e.to_string().contains("5 × 5"));
        let empty = image(0, 3, 0);
        assert_eq!(
            hamming_scores_naive(&empty, &m),
            Err(MatchError::EmptyTemplate {
                width: 0,
                height: 3
            })
        );
        let mut broken = image(3, 3, 0);
        broken.valid.pop();
        assert_eq!(
            hamming_scores(&broken, &m),
            Err(MatchError::SizeMismatch {
                what: "template valid",
                expected: 9,
                actual: 8
            })
        );
    }

    #[test]
    fn best_offset_compares_fractions_exactly_and_breaks_ties_row_major() {
        let s = ScoreMap {
            width: 3,
            height: 2,
            mismatch: vec![5, 1, 2, 0, 1, 40],
            valid: vec![10, 3, 6, 0, 3, 100],
        };
        // 1/3 at index 1 and 4 (and 2/6 at index 2): the first one wins; index 3 has no bits.
        assert_eq!(s.best_offset(0), Some((1, 0)));
        assert_eq!(s.best_offset(4), Some((2, 0))); // 2/6 beats 5/10 and 40/100
        assert_eq!(s.best_offset(1000), None);
        assert_eq!(s.normalized(3), None);
        assert_eq!(s.normalized_at(0, 1), None);
        assert_eq!(s.normalized_at(3, 0), None);
        assert_eq!(s.normalized_scores()[3], f64::INFINITY);
    }
}
