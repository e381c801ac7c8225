//! A raster's size from its header alone, so a budget can be checked before decoding.

use std::io::BufReader;
use std::path::Path;

use image::ImageDecoder as _;
use image::codecs::png::PngDecoder;
use tiff::decoder::Decoder;

use super::{Format, RasterError};
use crate::memory_budget::{MemoryBudget, bytes_of};

/// What a raster file's header says about its size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterHeader {
    /// Width, pixels.
    pub width: u64,
    /// Height, pixels.
    pub height: u64,
    /// Bits per sample in the file (8, 16 or 32; other layouts are refused by the readers).
    pub bits_per_sample: u64,
    /// Pixel size from a GeoTIFF's `ModelPixelScaleTag`, metres (`None` for a PNG, or a TIFF
    /// without a usable one).
    pub pixel_size_m: Option<f64>,
}

impl RasterHeader {
    /// Bytes the raster takes in memory as `bytes_per_sample`-byte samples (an `f32` DEM read
    /// from 16-bit centimetres takes 4).
    #[must_use]
    pub fn bytes_as(&self, bytes_per_sample: u64) -> u64 {
        bytes_of(&[self.width, self.height, bytes_per_sample])
    }

    /// Bytes the decoder's buffer takes.
    #[must_use]
    pub fn decoded_bytes(&self) -> u64 {
        bytes_of(&[
            self.width,
            self.height,
            self.bits_per_sample.div_ceil(8).max(1),
        ])
    }

    /// The error for a raster at `path` whose `need_bytes` do not fit `budget`.
    #[must_use]
    pub fn over_budget(&self, path: &Path, need_bytes: u64, budget: MemoryBudget) -> RasterError {
        RasterError::OverBudget {
            path: path.to_path_buf(),
            width: self.width,
            height: self.height,
            need_bytes,
            budget,
        }
    }

    /// An [`RasterError::OverBudget`] for `path` if `need_bytes` do not fit `budget`.
    ///
    /// # Errors
    /// [`RasterError::OverBudget`].
    pub fn check(
        &self,
        path: &Path,
        need_bytes: u64,
        budget: MemoryBudget,
    ) -> Result<(), RasterError> {
        if budget.allows(need_bytes) {
            Ok(())
        } else {
            Err(self.over_budget(path, need_bytes, budget))
        }
    }
}

/// Reads the width, height and sample size of a PNG or TIFF without decoding its pixels
/// (refusing a FIFO or device before opening it).
///
/// # Errors
/// [`RasterError::NotAFile`], [`RasterError::UnsupportedFormat`], [`RasterError::Io`] or
/// [`RasterError::Decode`] for a header that cannot be read.
pub fn read_header(path: &Path) -> Result<RasterHeader, RasterError> {
    let format = Format::of(path)?;
    let file = super::open_raster(path)?;
    let decode = |detail: String| RasterError::Decode {
        path: path.to_path_buf(),
        detail,
    };
    match format {
        Format::Png => {
            let d = PngDecoder::new(BufReader::new(file)).map_err(|e| decode(e.to_string()))?;
            let (w, h) = d.dimensions();
            Ok(RasterHeader {
                width: u64::from(w),
                height: u64::from(h),
                bits_per_sample: u64::from(d.color_type().bits_per_pixel())
                    / u64::from(d.color_type().channel_count()).max(1),
                pixel_size_m: None,
            })
        }
        Format::GeoTiff => {
            let mut d = Decoder::new(BufReader::new(file)).map_err(|e| decode(e.to_string()))?;
            let (w, h) = d.dimensions().map_err(|e| decode(e.to_string()))?;
            let bits = match d.colortype().map_err(|e| decode(e.to_string()))? {
                tiff::ColorType::Gray(b) => u64::from(b),
                _ => 32,
            };
            let pixel_size_m = d
                .find_tag(tiff::tags::Tag::ModelPixelScaleTag)
                .ok()
                .flatten()
                .and_then(|v| v.into_f64_vec().ok())
                .and_then(|v| v.first().copied())
                .filter(|s| s.is_finite() && *s > 0.0);
            Ok(RasterHeader {
                width: u64::from(w),
                height: u64::from(h),
                bits_per_sample: bits,
                pixel_size_m,
            })
        }
    }
}
