//! The modified census transform and the exact masked Hamming score of every offset (paper 000 §5).
//!
//! The rover orthomosaic (the *template*) is matched against the orbital appearance map by
//! comparing local intensity *orderings* rather than intensities, which makes the score invariant
//! to any monotonic change of brightness (different cameras, exposures, dust): paper 000 Fig. 13.
//!
//! - [`census_transform`] turns an image and its validity mask into a [`CensusImage`]: 8 bits per
//!   pixel, one per 3×3 neighbour in the order of [`NEIGHBOURS`], each with its own validity bit.
//!   A bit whose centre or neighbour has no data is *invalid* and never counts (paper 000 Fig. 12).
//! - [`hamming_scores`] scores every integer offset of the template inside the map:
//!   `mismatch = Σ popcount((a ^ b) & va & vb)` and `valid = Σ popcount(va & vb)` in a
//!   [`ScoreMap`]; [`ScoreMap::normalized`] is their ratio, the fraction of disagreeing bits.
//!   It packs 8 pixels per `u64`, uses the POPCNT instruction when the CPU has it (chosen at run
//!   time), skips template words with no valid bit (an occlusion wedge costs nothing) and spreads
//!   the offset rows over `rayon`. The counts are integers, so the result does not depend on the
//!   thread count.
//!   [`hamming_scores_naive`] is the plain per-pixel reference it is tested against, bit for bit.
//! - [`subpixel_peak`] refines the best integer offset with a least-squares 2-D quadratic over the
//!   3×3 neighbourhood of scores and returns the fitted [`Curvature`] for an uncertainty estimate.
//!
//! Bad input (mismatched lengths, a template larger than the map) is a [`MatchError`]; an
//! all-invalid template is not an error but a score map whose `valid` counts are all zero.
//!
//! ```
//! use localization::census::{census_transform, hamming_scores};
//!
//! // An 8×8 pseudo-random map; the template is its 4×4 patch at column 3, row 1.
//! let (w, h) = (8, 8);
//! let map: Vec<u8> = (0..64u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8).collect();
//! let patch: Vec<u8> = (0..16).map(|i| map[(1 + i / 4) * w + 3 + i % 4]).collect();
//! let map_census = census_transform(&map, &vec![true; w * h], w, h);
//! let template = census_transform(&patch, &[true; 16], 4, 4);
//! let scores = hamming_scores(&template, &map_census)?;
//! assert_eq!((scores.width, scores.height), (5, 5)); // offsets 0..=4 in x and y
//! let best = scores.best_offset(1).expect("some offset has valid bits");
//! assert_eq!(best, (3, 1));
//! assert_eq!(scores.normalized_at(3, 1), Some(0.0));
//! # Ok::<(), localization::census::MatchError>(())
//! ```
//!
//! ## References
//! - Paper 000 §4 (accuracy of the census matcher against ground localization) and §5 (the
//!   modified census transform, Fig. 12 masking of missing data, Hamming scoring, the sub-pixel
//!   quadratic fit over the 3×3 neighbourhood of scores).
//! - R. Zabih and J. Woodfill, "Non-parametric local transforms for computing visual
//!   correspondence", ECCV 1994 (the census transform).
//! - W. Muła, N. Kurz and D. Lemire, "Faster population counts using AVX2 instructions",
//!   Comput. J. 2018 (byte-packed popcount kernels).

mod fft;
mod kernel;
mod score;
mod subpixel;
mod transform;

pub use fft::hamming_scores_fft;
pub use score::{ScoreMap, hamming_scores, hamming_scores_naive};
pub use subpixel::{Curvature, subpixel_peak};
pub use transform::{
    CensusImage, NEIGHBOURS, census_transform, census_transform_raster, try_census_transform,
};

/// Why a census match could not be computed (bad input, not a bad outcome).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MatchError {
    /// A buffer does not hold `width × height` entries.
    #[error("{what} has {actual} entries, expected {expected} (width × height)")]
    SizeMismatch {
        /// Which buffer: `"image"`, `"valid"`, `"template codes"`, `"map valid"`, …
        what: &'static str,
        /// `width × height`.
        expected: usize,
        /// The length found.
        actual: usize,
    },
    /// The template has zero width or height, so no pixel could ever be compared.
    #[error("the template is empty ({width} × {height} px)")]
    EmptyTemplate {
        /// Template width in pixels.
        width: usize,
        /// Template height in pixels.
        height: usize,
    },
    /// The template does not fit inside the map at any offset.
    #[error(
        "the template ({template_width} × {template_height} px) is larger than the map \
         ({map_width} × {map_height} px) in at least one direction; crop the template or use a \
         larger map"
    )]
    TemplateLargerThanMap {
        /// Template width in pixels.
        template_width: usize,
        /// Template height in pixels.
        template_height: usize,
        /// Map width in pixels.
        map_width: usize,
        /// Map height in pixels.
        map_height: usize,
    },
}
