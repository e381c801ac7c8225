//! PNG: 8-bit and 16-bit single-channel gray, without georeference.

use std::fs::File;
use std::io::BufReader;
use std::path::Path;

use image::codecs::png::{PngDecoder, PngEncoder};
use image::{ColorType, ExtendedColorType, ImageDecoder, ImageEncoder, ImageError};

use super::sealed::{Samples, SamplesRef};
use super::{
    PngSample, RasterError, Sample, check_geo, check_shape, ext_of, io_error, read_io_error,
    write_atomic,
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
    let file = File::open(path).map_err(io_error(path))?;
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

/// [`write_png`] for any [`Sample`]; `f32` is refused.
pub(super) fn write_png_any<T: Sample>(path: &Path, raster: &Raster<T>) -> Result<(), RasterError> {
    let (bytes, color) = match T::as_samples(&raster.data) {
        SamplesRef::U8(d) => (d.to_vec(), ExtendedColorType::L8),
        SamplesRef::U16(d) => (
            d.iter().flat_map(|v| v.to_ne_bytes()).collect(),
            ExtendedColorType::L16,
        ),
        SamplesRef::F32(_) => {
            return Err(RasterError::UnsupportedFormat {
                path: path.to_path_buf(),
                expected: PNG_ONLY_INTEGERS,
                found: ext_of(path),
            });
        }
    };
    check_shape(path, raster)?;
    let too_big = |_| RasterError::Encode {
        path: path.to_path_buf(),
        detail: format!(
            "{}x{} px exceeds the PNG limit of 2^31 - 1 px per side",
            raster.width, raster.height
        ),
    };
    let w = u32::try_from(raster.width).map_err(too_big)?;
    let h = u32::try_from(raster.height).map_err(too_big)?;
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
