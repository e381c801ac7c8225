//! [`RasterError`]: everything that can go wrong reading or writing a raster.

use std::path::PathBuf;

/// Largest height a 16-bit centimetre DEM holds above its datum, in metres.
pub const DEM_CM_MAX_M: f64 = u16::MAX as f64 / 100.0;

/// Errors reading or writing rasters. Every variant names the file; its message is one line
/// saying what was expected and what was found.
#[derive(Debug, thiserror::Error)]
pub enum RasterError {
    /// The file could not be opened, read, written or renamed.
    #[error("{}: {source}", path.display())]
    Io {
        /// File concerned.
        path: PathBuf,
        /// Underlying operating-system error.
        source: std::io::Error,
    },
    /// Not a regular file (a FIFO, a device, a directory): refused before it is
    /// opened, so a named pipe cannot block the reader.
    #[error("{}: {error}", path.display())]
    NotAFile {
        /// File concerned.
        path: PathBuf,
        /// Why (part of the message, so not also a `source`).
        error: crate::input_file::InputFileError,
    },
    /// Decoding the raster would take more memory than the command's budget allows (checked
    /// from the header, before anything is decoded).
    #[error("{}: {width} × {height} px would need {}: {budget}", path.display(), crate::input_file::human_bytes(*need_bytes))]
    OverBudget {
        /// File concerned.
        path: PathBuf,
        /// Width in the header, pixels.
        width: u64,
        /// Height in the header, pixels.
        height: u64,
        /// Bytes the decoded raster would take.
        need_bytes: u64,
        /// The budget it exceeds.
        budget: crate::memory_budget::MemoryBudget,
    },
    /// The extension does not name a format this operation supports.
    #[error("{}: expected {expected}, found {found:?}", path.display())]
    UnsupportedFormat {
        /// File concerned.
        path: PathBuf,
        /// Formats accepted here, e.g. `"a .png, .tif or .tiff file"`.
        expected: &'static str,
        /// The extension found (empty when there is none).
        found: String,
    },
    /// The file is not a valid PNG / TIFF (corrupt, truncated, unsupported compression, ...).
    #[error("{}: cannot decode: {detail}", path.display())]
    Decode {
        /// File concerned.
        path: PathBuf,
        /// What the decoder reported.
        detail: String,
    },
    /// The encoder refused the raster (e.g. wider than 2³² − 1 px).
    #[error("{}: cannot encode: {detail}", path.display())]
    Encode {
        /// File concerned.
        path: PathBuf,
        /// What the encoder reported.
        detail: String,
    },
    /// The samples are not of the expected band count, bit depth or number type.
    #[error("{}: expected {expected}, found {found}", path.display())]
    WrongSampleFormat {
        /// File concerned.
        path: PathBuf,
        /// Sample format wanted, e.g. `"a single-band 16-bit unsigned raster"`.
        expected: &'static str,
        /// Sample format in the file, e.g. `"8-bit RGB"`.
        found: String,
    },
    /// No georeference: a PNG always, or a GeoTIFF without `ModelPixelScaleTag` +
    /// `ModelTiepointTag` (or `ModelTransformationTag`), and none supplied by the caller.
    #[error(
        "{}: expected a georeference (GeoTIFF ModelPixelScale + ModelTiepoint tags, or a \
         GeoTransform supplied by the caller), found none",
        path.display()
    )]
    MissingGeoreference {
        /// File concerned.
        path: PathBuf,
    },
    /// A georeference that is not a north-up grid of square metre pixels (rotated, sheared,
    /// non-square, geographic degrees, ground control points, non-finite values ...).
    #[error("{}: expected a north-up georeference with square pixels in metres, found {detail}", path.display())]
    BadGeoreference {
        /// File concerned.
        path: PathBuf,
        /// What is wrong, with the values found.
        detail: String,
    },
    /// The `GDAL_NODATA` tag is not a number.
    #[error("{}: expected a number in the GDAL_NODATA tag, found {found:?}", path.display())]
    BadNodata {
        /// File concerned.
        path: PathBuf,
        /// The tag's text.
        found: String,
    },
    /// A layer does not have the pixel size that a single shared GeoTransform requires.
    #[error(
        "{}: expected {}x{} px like the other layers (one GeoTransform was given for all), found {}x{} px",
        path.display(), expected.0, expected.1, found.0, found.1
    )]
    SizeMismatch {
        /// File concerned.
        path: PathBuf,
        /// Expected (width, height) in pixels.
        expected: (usize, usize),
        /// Found (width, height) in pixels.
        found: (usize, usize),
    },
    /// A map layer covers different ground than the reference layer.
    #[error(
        "{}: expected the extent of {} (x {:.3}..{:.3} m, y {:.3}..{:.3} m) within {tolerance_m} m, \
         found x {:.3}..{:.3} m, y {:.3}..{:.3} m",
        path.display(), reference.display(),
        expected[0], expected[2], expected[1], expected[3],
        found[0], found[2], found[1], found[3]
    )]
    ExtentMismatch {
        /// File concerned.
        path: PathBuf,
        /// The layer it was compared with.
        reference: PathBuf,
        /// Reference extent `[min_x, min_y, max_x, max_y]` in metres.
        expected: [f64; 4],
        /// This file's extent `[min_x, min_y, max_x, max_y]` in metres.
        found: [f64; 4],
        /// Allowed difference per edge: half a pixel of the coarsest layer, in metres.
        tolerance_m: f64,
    },
    /// A raster in memory has no pixels; image formats cannot hold it.
    #[error("{}: expected a raster of at least 1x1 px, found {width}x{height}", path.display())]
    EmptyRaster {
        /// File concerned.
        path: PathBuf,
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
    },
    /// A raster in memory whose `data` length disagrees with `width * height`.
    #[error(
        "{}: expected {width}x{height} = {} samples, found {len}",
        path.display(), width * height
    )]
    DataLength {
        /// File concerned.
        path: PathBuf,
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
        /// Length of `data`.
        len: usize,
    },
    /// A DEM holds NaN or infinity.
    #[error("{}: expected finite heights, found {value_m} at pixel ({}, {})", path.display(), pixel.0, pixel.1)]
    NonFinite {
        /// File concerned (`<DEM in memory>` when converting a raster not yet written).
        path: PathBuf,
        /// First offending pixel (column, row).
        pixel: (usize, usize),
        /// The value found.
        value_m: f32,
    },
    /// A DEM holds the file's declared no-data value: a hole the simulator cannot drive on.
    #[error("{}: expected a DEM without holes, found the no-data value {nodata} at pixel ({}, {})", path.display(), pixel.0, pixel.1)]
    NoData {
        /// File concerned.
        path: PathBuf,
        /// First offending pixel (column, row).
        pixel: (usize, usize),
        /// The `GDAL_NODATA` value.
        nodata: f64,
    },
    /// A height that 16-bit centimetres above the datum cannot hold.
    #[error(
        "{}: expected heights within {datum_m}..={} m (16-bit cm above datum {datum_m} m), \
         found {value_m} m at pixel ({}, {})",
        path.display(), datum_m + DEM_CM_MAX_M, pixel.0, pixel.1
    )]
    HeightOutOfRange {
        /// File concerned (`<DEM in memory>` when converting a raster not yet written).
        path: PathBuf,
        /// First offending pixel (column, row).
        pixel: (usize, usize),
        /// The height found, metres.
        value_m: f32,
        /// The datum, metres.
        datum_m: f64,
    },
    /// A terrain-class raster holds a code other than 0 (no data), 1 (sand), 2 (soil) or
    /// 3 (bedrock).
    #[error(
        "{}: expected terrain codes 0..=3 (0 no data, 1 sand, 2 soil, 3 bedrock), found {code} at pixel ({}, {})",
        path.display(), pixel.0, pixel.1
    )]
    BadTerrainCode {
        /// File concerned.
        path: PathBuf,
        /// First offending pixel (column, row).
        pixel: (usize, usize),
        /// The code found.
        code: u8,
    },
}

impl RasterError {
    /// The file the error is about.
    #[must_use]
    pub fn path(&self) -> &std::path::Path {
        match self {
            RasterError::Io { path, .. }
            | RasterError::NotAFile { path, .. }
            | RasterError::OverBudget { path, .. }
            | RasterError::UnsupportedFormat { path, .. }
            | RasterError::Decode { path, .. }
            | RasterError::Encode { path, .. }
            | RasterError::WrongSampleFormat { path, .. }
            | RasterError::MissingGeoreference { path, .. }
            | RasterError::BadGeoreference { path, .. }
            | RasterError::BadNodata { path, .. }
            | RasterError::SizeMismatch { path, .. }
            | RasterError::ExtentMismatch { path, .. }
            | RasterError::EmptyRaster { path, .. }
            | RasterError::DataLength { path, .. }
            | RasterError::NonFinite { path, .. }
            | RasterError::NoData { path, .. }
            | RasterError::HeightOutOfRange { path, .. }
            | RasterError::BadTerrainCode { path, .. } => path,
        }
    }
}
