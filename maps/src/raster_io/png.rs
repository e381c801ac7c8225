//! PNG: 8-bit and 16-bit single-channel gray, without georeference.

use std::io::BufReader;
use std::path::Path;

use image::codecs::png::{PngDecoder, PngEncoder};
use image::{ColorType, ExtendedColorType, ImageDecoder, ImageEncoder, ImageError};

use super::sealed::{Samples, SamplesRef};
use super::{
    PngSample, RasterError, Sample, check_geo, check_shape, ext_of, read_io_error, write_atomic,
};
use crate::raster::{GeoTransform, Raster};

/// Largest decoded image accepted, so a corrupt header cannot exhaust memory.
const MAX_DECODED_BYTES: usize = 2 << 30;

const PNG_ONLY_INTEGERS: &str = "a .tif or .tiff file (PNG holds only 8/16-bit integer samples)";

/// Reads a single-channel 8-bit (`T = u8`) or 16-bit (`T = u16`) gray PNG placed by `geo`
/// (PNG carries no georeference).
///
/// # Errors
/// [`RasterError::WrongSampleFormat`] for any other channel layout or bit depth (a 16-bit PNG
/// is not silently narrowed to 8 bits, nor the reverse); [`RasterError::Io`],
/// [`RasterError::Decode`] for unreadable files; [`RasterError::BadGeoreference`] for a `geo`
/// with a non-positive pixel size.
pub fn read_png<T: PngSample>(path: &Path, geo: GeoTransform) -> Result<Raster<T>, RasterError> {
    read_png_any(path, geo)
}

/// Writes a single-channel 8-bit (`u8`) or 16-bit (`u16`) gray PNG atomically. The
/// georeference is lost: keep the [`GeoTransform`] elsewhere, or write a GeoTIFF.
///
/// # Errors
/// [`RasterError::EmptyRaster`] / [`RasterError::DataLength`] for a malformed raster,
/// [`RasterError::Io`] / [`RasterError::Encode`] when writing fails.
pub fn write_png<T: PngSample>(path: &Path, raster: &Raster<T>) -> Result<(), RasterError> {
    write_png_any(path, raster)
}

/// [`read_png`] for any [`Sample`]; `f32` is refused.
pub(super) fn read_png_any<T: Sample>(
    path: &Path,
    geo: GeoTransform,
) -> Result<Raster<T>, RasterError> {
    if matches!(T::as_samples(&[]), SamplesRef::F32(_)) {
        return Err(RasterError::UnsupportedFormat {
            path: path.to_path_buf(),
            expected: PNG_ONLY_INTEGERS,
            found: ext_of(path),
        });
    }
    check_geo(path, &geo)?;
    let file = super::open_raster(path)?;
    let decoder = PngDecoder::with_limits(BufReader::new(file), image::Limits::default())
        .map_err(decode_error(path))?;
    let (w, h) = decoder.dimensions();
    let (width, height) = (w as usize, h as usize);
    let color = decoder.color_type();
    let wrong = || RasterError::WrongSampleFormat {
        path: path.to_path_buf(),
        expected: T::EXPECTED,
        found: describe(color),
    };
    if !matches!(color, ColorType::L8 | ColorType::L16) {
        return Err(wrong());
    }
    let n_bytes = usize::try_from(decoder.total_bytes())
        .ok()
        .filter(|&n| n <= MAX_DECODED_BYTES)
        .ok_or_else(|| RasterError::Decode {
            path: path.to_path_buf(),
            detail: format!("{width}x{height} px exceeds the 2 GiB read limit"),
        })?;
    let mut bytes = vec![0u8; n_bytes];
    let samples = match color {
        ColorType::L8 => {
            decoder.read_image(&mut bytes).map_err(decode_error(path))?;
            Samples::U8(bytes)
        }
        ColorType::L16 => {
            decoder.read_image(&mut bytes).map_err(decode_error(path))?;
            // `read_image` yields native-endian 16-bit samples.
            Samples::U16(
                bytes
                    .chunks_exact(2)
                    .map(|c| u16::from_ne_bytes([c[0], c[1]]))
                    .collect(),
            )
        }
        _ => return Err(wrong()),
    };
    let data = T::from_samples(samples).ok_or_else(wrong)?;
    if data.len() != width * height {
        return Err(RasterError::Decode {
            path: path.to_path_buf(),
            detail: format!("{} samples decoded for {width}x{height} px", data.len()),
        });
    }
    Ok(Raster {
        width,
        height,
        geo,
        data,
    })
}

/// Encodes a single-channel 8-bit (`u8`) or 16-bit (`u16`) gray raster as PNG bytes with the
/// strongest compression `image` offers (deflate level "high", adaptive row filters), for
/// callers that write and checksum the bytes themselves ([`write_png`] writes a file, with
/// the default compression).
///
/// # Errors
/// [`RasterError::EmptyRaster`] / [`RasterError::DataLength`] for a malformed raster,
/// [`RasterError::Encode`] if the encoder refuses; `path` names the future file in messages
/// only.
pub fn encode_png<T: PngSample>(raster: &Raster<T>, path: &Path) -> Result<Vec<u8>, RasterError> {
    use image::codecs::png::{CompressionType, FilterType};
    let (bytes, color) = png_bytes(path, &raster.data)?;
    check_shape(path, raster)?;
    let (w, h) = png_dimensions(path, raster)?;
    let mut out = Vec::new();
    PngEncoder::new_with_quality(&mut out, CompressionType::Best, FilterType::Adaptive)
        .write_image(&bytes, w, h, color)
        .map_err(|e| RasterError::Encode {
            path: path.to_path_buf(),
            detail: e.to_string(),
        })?;
    Ok(out)
}

/// [`write_png`] for any [`Sample`]; `f32` is refused.
pub(super) fn write_png_any<T: Sample>(path: &Path, raster: &Raster<T>) -> Result<(), RasterError> {
    let (bytes, color) = png_bytes(path, &raster.data)?;
    check_shape(path, raster)?;
    let (w, h) = png_dimensions(path, raster)?;
    write_atomic(path, |out| {
        PngEncoder::new(out)
            .write_image(&bytes, w, h, color)
            .map_err(|e| match e {
                ImageError::IoError(source) => RasterError::Io {
                    path: path.to_path_buf(),
                    source,
                },
                other => RasterError::Encode {
                    path: path.to_path_buf(),
                    detail: other.to_string(),
                },
            })
    })
}

/// The samples as the PNG encoder takes them (16-bit native-endian) and their colour type;
/// `f32` is refused.
fn png_bytes<T: Sample>(
    path: &Path,
    data: &[T],
) -> Result<(Vec<u8>, ExtendedColorType), RasterError> {
    match T::as_samples(data) {
        SamplesRef::U8(d) => Ok((d.to_vec(), ExtendedColorType::L8)),
        SamplesRef::U16(d) => Ok((
            d.iter().flat_map(|v| v.to_ne_bytes()).collect(),
            ExtendedColorType::L16,
        )),
        SamplesRef::F32(_) => Err(RasterError::UnsupportedFormat {
            path: path.to_path_buf(),
            expected: PNG_ONLY_INTEGERS,
            found: ext_of(path),
        }),
    }
}

/// The raster's width and height as PNG stores them.
fn png_dimensions<T>(path: &Path, raster: &Raster<T>) -> Result<(u32, u32), RasterError> {
    let too_big = |_| RasterError::Encode {
        path: path.to_path_buf(),
        detail: format!(
            "{}x{} px exceeds the PNG limit of 2^31 - 1 px per side",
            raster.width, raster.height
        ),
    };
    Ok((
        u32::try_from(raster.width).map_err(too_big)?,
        u32::try_from(raster.height).map_err(too_big)?,
    ))
}

fn decode_error(path: &Path) -> impl Fn(ImageError) -> RasterError + '_ {
    move |e| match e {
        ImageError::IoError(source) => read_io_error(path, source),
        other => RasterError::Decode {
            path: path.to_path_buf(),
            detail: other.to_string(),
        },
    }
}

/// Human description of a decoded PNG colour type, e.g. `8-bit RGB`.
fn describe(c: ColorType) -> String {
    match c {
        ColorType::L8 => "8-bit gray",
        ColorType::La8 => "8-bit gray + alpha",
        ColorType::Rgb8 => "8-bit RGB",
        ColorType::Rgba8 => "8-bit RGBA",
        ColorType::L16 => "16-bit gray",
        ColorType::La16 => "16-bit gray + alpha",
        ColorType::Rgb16 => "16-bit RGB",
        ColorType::Rgba16 => "16-bit RGBA",
        ColorType::Rgb32F => "32-bit float RGB",
        ColorType::Rgba32F => "32-bit float RGBA",
        _ => return format!("{c:?}"),
    }
    .to_owned()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn encoded_pngs_decode_to_the_same_samples() {
        let geo = GeoTransform::new(0.0, 10.0, 1.0);
        let mut r = Raster::filled(7, 5, geo, 0u16);
        for (i, v) in r.data.iter_mut().enumerate() {
            *v = (i as u16).wrapping_mul(40_503);
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.png");
        std::fs::write(&path, encode_png(&r, &path).unwrap()).unwrap();
        assert_eq!(read_png::<u16>(&path, geo).unwrap(), r);
        let a = Raster::filled(3, 2, geo, 200u8);
        std::fs::write(&path, encode_png(&a, &path).unwrap()).unwrap();
        assert_eq!(read_png::<u8>(&path, geo).unwrap(), a);
        // A raster whose data does not match its size is an error, not an encoder panic.
        let bad = Raster {
            data: vec![0u8; 5],
            ..a
        };
        assert!(matches!(
            encode_png(&bad, &path),
            Err(RasterError::DataLength { .. })
        ));
    }
}
