//! The modified census transform: 8 ordering bits per pixel, each with its own validity bit.

use super::MatchError;
use maps::Raster;

/// The 3×3 neighbours as `(dcol, drow)`; census bit `k` compares the centre with `NEIGHBOURS[k]`.
///
/// Raster order, row 0 = north: bit 0 = north-west, 1 = north, 2 = north-east, 3 = west,
/// 4 = east, 5 = south-west, 6 = south, 7 = south-east.
pub const NEIGHBOURS: [(isize, isize); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// A census-transformed image: one code byte and one validity byte per pixel, row-major.
///
/// Bit `k` of `codes[i]` is set when the centre pixel `i` is strictly brighter than its neighbour
/// [`NEIGHBOURS`]`[k]`. Bit `k` of `valid[i]` is set when both the centre and that neighbour are
/// inside the image and have data; where it is clear, the code bit is clear too.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CensusImage {
    /// Width in pixels (columns).
    pub width: usize,
    /// Height in pixels (rows).
    pub height: usize,
    /// `width × height` code bytes, row-major, row 0 = north.
    pub codes: Vec<u8>,
    /// `width × height` validity bytes, same layout; bit `k` validates bit `k` of the code.
    pub valid: Vec<u8>,
}

impl CensusImage {
    /// Check that `codes` and `valid` both hold `width × height` bytes (the fields are public, so
    /// a caller can build an inconsistent image).
    pub(crate) fn check(&self, what: Which) -> Result<(), MatchError> {
        let expected = self.width * self.height;
        let (codes, valid) = match what {
            Which::Template => ("template codes", "template valid"),
            Which::Map => ("map codes", "map valid"),
        };
        for (what, actual) in [(codes, self.codes.len()), (valid, self.valid.len())] {
            if actual != expected {
                return Err(MatchError::SizeMismatch {
                    what,
                    expected,
                    actual,
                });
            }
        }
        Ok(())
    }

    /// Number of valid census bits in the whole image.
    #[must_use]
    pub fn valid_bits(&self) -> u64 {
        self.valid.iter().map(|v| u64::from(v.count_ones())).sum()
    }
}

/// Which side of a match an image is, for error messages.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Which {
    Template,
    Map,
}

/// The modified census transform of `image` (row-major, `width × height`) with its validity mask.
///
/// Pixels where `valid` is `false` have no data (occlusion, outside the orthomosaic, masked-out
/// map). Every bit that involves such a pixel, or a neighbour outside the image, is invalid
/// (paper 000 Fig. 12), so border pixels carry fewer than 8 valid bits.
///
/// # Panics
/// If `image` or `valid` does not hold `width × height` entries; [`try_census_transform`]
/// returns an error instead.
#[must_use]
pub fn census_transform(image: &[u8], valid: &[bool], width: usize, height: usize) -> CensusImage {
    match try_census_transform(image, valid, width, height) {
        Ok(c) => c,
        Err(e) => panic!("census_transform: {e}"),
    }
}

/// [`census_transform`] that reports mismatched buffer lengths as a [`MatchError::SizeMismatch`].
///
/// # Errors
/// [`MatchError::SizeMismatch`] if `image` or `valid` does not hold `width × height` entries.
pub fn try_census_transform(
    image: &[u8],
    valid: &[bool],
    width: usize,
    height: usize,
) -> Result<CensusImage, MatchError> {
    let n = width * height;
    for (what, actual) in [("image", image.len()), ("valid", valid.len())] {
        if actual != n {
            return Err(MatchError::SizeMismatch {
                what,
                expected: n,
                actual,
            });
        }
    }
    // A one-pixel border of "no data" turns the image edge into ordinary invalid neighbours, so
    // each neighbour direction is one branch-free pass over whole rows (vectorised by LLVM).
    let pw = width + 2;
    let mut pixels = vec![0u8; pw * (height + 2)];
    let mut ok = vec![0u8; pw * (height + 2)];
    for y in 0..height {
        let row = (y + 1) * pw + 1..(y + 1) * pw + 1 + width;
        pixels[row.clone()].copy_from_slice(&image[y * width..(y + 1) * width]);
        for (o, &v) in ok[row].iter_mut().zip(&valid[y * width..(y + 1) * width]) {
            *o = u8::from(v);
        }
    }
    let mut codes = vec![0u8; n];
    let mut vbits = vec![0u8; n];
    for y in 0..height {
        let centre = (y + 1) * pw + 1..(y + 1) * pw + 1 + width;
        let (c, vc) = (&pixels[centre.clone()], &ok[centre.clone()]);
        let codes_row = &mut codes[y * width..(y + 1) * width];
        let valid_row = &mut vbits[y * width..(y + 1) * width];
        for (k, &(dc, dr)) in NEIGHBOURS.iter().enumerate() {
            let start = centre.start.wrapping_add_signed(dr * pw as isize + dc);
            let (nb, vn) = (&pixels[start..start + width], &ok[start..start + width]);
            for ((((code, v), (&c, &vc)), &nb), &vn) in codes_row
                .iter_mut()
                .zip(valid_row.iter_mut())
                .zip(c.iter().zip(vc))
                .zip(nb)
                .zip(vn)
            {
                let both = vc & vn;
                *v |= both << k;
                *code |= (u8::from(c > nb) & both) << k;
            }
        }
    }
    Ok(CensusImage {
        width,
        height,
        codes,
        valid: vbits,
    })
}

/// [`try_census_transform`] of an appearance raster; `valid` is row-major like `appearance.data`.
///
/// # Errors
/// [`MatchError::SizeMismatch`] if `valid` does not hold one entry per raster pixel.
pub fn census_transform_raster(
    appearance: &Raster<u8>,
    valid: &[bool],
) -> Result<CensusImage, MatchError> {
    try_census_transform(&appearance.data, valid, appearance.width, appearance.height)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn neighbours_are_the_eight_distinct_non_centre_offsets() {
        let mut seen = std::collections::BTreeSet::new();
        for &(dc, dr) in &NEIGHBOURS {
            assert!((dc, dr) != (0, 0) && dc.abs() <= 1 && dr.abs() <= 1);
            assert!(seen.insert((dc, dr)));
        }
        assert_eq!(seen.len(), 8);
    }

    #[test]
    fn bits_per_pixel_depend_on_position_only_when_fully_valid() {
        // 4×3 image, all valid: corners have 3 valid bits, edges 5, interior 8.
        let img: Vec<u8> = (0..12).collect();
        let c = census_transform(&img, &[true; 12], 4, 3);
        let counts: Vec<u32> = c.valid.iter().map(|v| v.count_ones()).collect();
        assert_eq!(counts, vec![3, 5, 5, 3, 5, 8, 8, 5, 3, 5, 5, 3]);
        // Increasing ramp (row-major): the centre is brighter than N, NW, NE and W only.
        assert_eq!(c.codes[5], 0b0000_1111);
        assert_eq!(c.valid_bits(), 3 * 4 + 5 * 6 + 8 * 2);
    }

    #[test]
    fn invariant_to_monotonic_brightness_changes() {
        let img: Vec<u8> = (0..64u32).map(|i| ((i * 37 + 11) % 97) as u8).collect();
        let valid: Vec<bool> = (0..64).map(|i| i % 7 != 3).collect();
        let a = census_transform(&img, &valid, 8, 8);
        let darker: Vec<u8> = img.iter().map(|&v| v / 2 + 10).collect(); // not strictly monotone
        let brighter: Vec<u8> = img.iter().map(|&v| v.saturating_mul(2).max(v)).collect();
        let gamma: Vec<u8> = img
            .iter()
            .map(|&v| ((f64::from(v) / 96.0).powf(0.5) * 255.0) as u8)
            .collect();
        assert_eq!(census_transform(&gamma, &valid, 8, 8), a);
        // A mapping that merges levels can only clear bits, never set new ones.
        for other in [&darker, &brighter] {
            let b = census_transform(other, &valid, 8, 8);
            assert_eq!(b.valid, a.valid);
            assert!(b.codes.iter().zip(&a.codes).all(|(&b, &a)| b & !a == 0));
        }
    }

    /// The definition, pixel by pixel: the reference for the row-wise implementation.
    fn census_reference(image: &[u8], valid: &[bool], w: usize, h: usize) -> CensusImage {
        let (mut codes, mut vbits) = (vec![0u8; w * h], vec![0u8; w * h]);
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                for (k, &(dc, dr)) in NEIGHBOURS.iter().enumerate() {
                    let (nx, ny) = (x as isize + dc, y as isize + dr);
                    if nx < 0 || ny < 0 || nx >= w as isize || ny >= h as isize {
                        continue;
                    }
                    let j = ny as usize * w + nx as usize;
                    if valid[i] && valid[j] {
                        vbits[i] |= 1 << k;
                        codes[i] |= u8::from(image[i] > image[j]) << k;
                    }
                }
            }
        }
        CensusImage {
            width: w,
            height: h,
            codes,
            valid: vbits,
        }
    }

    #[test]
    fn row_wise_transform_equals_the_per_pixel_definition() {
        let mut state = 0x1234_5678_u32;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state
        };
        for (w, h) in [(1, 1), (1, 7), (9, 1), (2, 2), (17, 13), (40, 3)] {
            let img: Vec<u8> = (0..w * h).map(|_| (next() % 6) as u8).collect();
            let valid: Vec<bool> = (0..w * h).map(|_| next() % 4 != 0).collect();
            assert_eq!(
                census_transform(&img, &valid, w, h),
                census_reference(&img, &valid, w, h),
                "{w} × {h}"
            );
        }
    }

    #[test]
    fn empty_and_mismatched_inputs() {
        let c = census_transform(&[], &[], 0, 5);
        assert!(c.codes.is_empty() && c.valid.is_empty());
        assert_eq!(
            try_census_transform(&[1, 2, 3], &[true; 4], 2, 2),
            Err(MatchError::SizeMismatch {
                what: "image",
                expected: 4,
                actual: 3
            })
        );
        assert!(matches!(
            try_census_transform(&[1, 2, 3, 4], &[true; 3], 2, 2),
            Err(MatchError::SizeMismatch { what: "valid", .. })
        ));
        let one = census_transform(&[9], &[true], 1, 1);
        assert_eq!((one.codes[0], one.valid[0]), (0, 0));
    }

    #[test]
    fn raster_entry_point_matches_slice_entry_point() {
        let geo = maps::GeoTransform::new(0.0, 0.0, 0.25);
        let mut r = maps::Raster::filled(5, 4, geo, 0u8);
        for (i, v) in r.data.iter_mut().enumerate() {
            *v = (i * 53 % 31) as u8;
        }
        let valid: Vec<bool> = (0..20).map(|i| i != 7).collect();
        assert_eq!(
            census_transform_raster(&r, &valid).unwrap(),
            census_transform(&r.data, &valid, 5, 4)
        );
    }
}
