//! Binning the 25 cm orthoimage render to a coarser appearance resolution.

use crate::raster::Raster;

/// `f × f` block means of an 8-bit raster (rounded half up); `f = 1` is a copy.
///
/// # Panics
/// If `f` is 0 or does not divide the raster's sides.
#[must_use]
pub fn bin_mean_u8(r: &Raster<u8>, f: usize) -> Raster<u8> {
    assert!(
        f > 0 && r.width.is_multiple_of(f) && r.height.is_multiple_of(f),
        "bin {f} of {}x{}",
        r.width,
        r.height
    );
    if f == 1 {
        return r.clone();
    }
    let (w, h) = (r.width / f, r.height / f);
    let n = (f * f) as u32;
    let mut data = Vec::with_capacity(w * h);
    for row in 0..h {
        for col in 0..w {
            let mut sum = 0u32;
            for rr in row * f..(row + 1) * f {
                for cc in col * f..(col + 1) * f {
                    sum += u32::from(r.data[rr * r.width + cc]);
                }
            }
            data.push(((sum + n / 2) / n) as u8);
        }
    }
    Raster {
        width: w,
        height: h,
        geo: r.geo.scaled(f as f64),
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::GeoTransform;

    #[test]
    fn bins_average_their_pixels() {
        let geo = GeoTransform::new(0.0, 10.0, 1.0);
        let a = bin_mean_u8(&Raster::filled(4, 2, geo, 9u8), 2);
        assert_eq!((a.width, a.height, a.data[0]), (2, 1, 9));
    }
}
