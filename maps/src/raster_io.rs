//! Reading and writing map rasters: PNG (8/16-bit gray) and GeoTIFF (u8, u16, f32), plus the
//! DEM conventions of the flight maps and [`MapLayers`], the three layers of one map.
//!
//! - Format follows the extension: `.png`, or `.tif` / `.tiff` (any case); anything else is
//!   [`RasterError::UnsupportedFormat`].
//! - PNG carries no georeference, so its readers take a [`GeoTransform`] from the caller;
//!   [`world_file`] and [`pam_aux_xml`] write the sidecars that place it for GDAL and QGIS.
//!   GeoTIFF carries one in the standard tags (`ModelPixelScaleTag`, `ModelTiepointTag`,
//!   `GeoKeyDirectoryTag`); a caller-supplied transform overrides them.
//! - DEMs are stored as 16-bit unsigned **centimetres above a datum** ([`dem_to_cm`],
//!   [`dem_from_cm`]) or as 32-bit float metres (GeoTIFF only); in memory a DEM is always
//!   `Raster<f32>` in metres.
//! - Every writer is atomic: it writes a temporary file in the target directory and renames it
//!   over the target, so a crash never leaves a half-written map.
//! - Bad files never panic: every failure is a [`RasterError`] naming the file.

mod error;
mod geokeys;
mod geotiff;
mod header;
mod map_layers;
mod nodata;
mod png;
mod sidecar;
mod tiff_tags;

use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::mars_crs::MapCrs;
use crate::raster::{GeoTransform, Raster};

pub use error::{DEM_CM_MAX_M, RasterError};
pub use geotiff::{GeoTiff, read_geotiff, write_geotiff, write_geotiff_with_crs};
pub use header::{RasterHeader, read_header};
pub use map_layers::MapLayers;
pub use nodata::{read_dem_with_holes, read_raster_with_nodata};
pub use png::{encode_png, read_png, write_png};
pub use sidecar::{pam_aux_xml, world_file};

/// Placeholder path in errors about a raster that has no file yet.
const IN_MEMORY: &str = "<DEM in memory>";

mod sealed {
    /// Owned samples of one of the supported types.
    pub enum Samples {
        U8(Vec<u8>),
        U16(Vec<u16>),
        F32(Vec<f32>),
    }

    /// Borrowed samples of one of the supported types.
    pub enum SamplesRef<'a> {
        U8(&'a [u8]),
        U16(&'a [u16]),
        F32(&'a [f32]),
    }

    /// Conversions between a sample type and the type-erased buffers the codecs use.
    pub trait Sealed: Copy + Sized {
        /// What a file must hold to be read as this type, for error messages.
        const EXPECTED: &'static str;
        /// The buffer, if it holds this type.
        fn from_samples(samples: Samples) -> Option<Vec<Self>>;
        /// The type-erased view of a buffer.
        fn as_samples(data: &[Self]) -> SamplesRef<'_>;
    }

    impl Sealed for u8 {
        const EXPECTED: &'static str = "a single-band 8-bit unsigned raster";
        fn from_samples(samples: Samples) -> Option<Vec<Self>> {
            if let Samples::U8(v) = samples {
                Some(v)
            } else {
                None
            }
        }
        fn as_samples(data: &[Self]) -> SamplesRef<'_> {
            SamplesRef::U8(data)
        }
    }

    impl Sealed for u16 {
        const EXPECTED: &'static str = "a single-band 16-bit unsigned raster";
        fn from_samples(samples: Samples) -> Option<Vec<Self>> {
            if let Samples::U16(v) = samples {
                Some(v)
            } else {
                None
            }
        }
        fn as_samples(data: &[Self]) -> SamplesRef<'_> {
            SamplesRef::U16(data)
        }
    }

    impl Sealed for f32 {
        const EXPECTED: &'static str = "a single-band 32-bit float raster";
        fn from_samples(samples: Samples) -> Option<Vec<Self>> {
            if let Samples::F32(v) = samples {
                Some(v)
            } else {
                None
            }
        }
        fn as_samples(data: &[Self]) -> SamplesRef<'_> {
            SamplesRef::F32(data)
        }
    }
}

/// A sample type the readers and writers support: `u8`, `u16` (PNG and GeoTIFF) and `f32`
/// (GeoTIFF only). Sealed: the set is closed.
pub trait Sample: sealed::Sealed {}
impl Sample for u8 {}
impl Sample for u16 {}
impl Sample for f32 {}

/// A sample type PNG can hold: `u8` (8-bit gray) and `u16` (16-bit gray).
pub trait PngSample: Sample {}
impl PngSample for u8 {}
impl PngSample for u16 {}

/// File formats, chosen by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Png,
    GeoTiff,
}

const ANY_FORMAT: &str = "a .png, .tif or .tiff file";

impl Format {
    fn of(path: &Path) -> Result<Self, RasterError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        match ext.as_str() {
            "png" => Ok(Format::Png),
            "tif" | "tiff" => Ok(Format::GeoTiff),
            _ => Err(RasterError::UnsupportedFormat {
                path: path.to_path_buf(),
                expected: ANY_FORMAT,
                found: ext_of(path),
            }),
        }
    }
}

/// Opens a raster through the input gate ([`crate::input_file::open_input`]): a FIFO, a device
/// or a directory is refused on the opened descriptor (a named pipe would block the reader); a
/// missing or unreadable file is an [`RasterError::Io`]. The decoders bound what they allocate
/// (image limits, tag limits), so the file's size is not capped here.
fn open_raster(path: &Path) -> Result<std::fs::File, RasterError> {
    use crate::input_file::{Follow, InputFileError, open_input};
    match open_input(path, u64::MAX, Follow::Yes) {
        Ok((file, _)) => Ok(file),
        Err(InputFileError::Io { error }) => Err(RasterError::Io {
            path: path.to_path_buf(),
            source: error,
        }),
        Err(error) => Err(RasterError::NotAFile {
            path: path.to_path_buf(),
            error,
        }),
    }
}

fn ext_of(path: &Path) -> String {
    path.extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default()
}

/// Reads a single-band raster, choosing the format by extension.
///
/// `georef` is required for PNG and overrides the file's georeference for GeoTIFF. A GeoTIFF's
/// no-data value is dropped here; use [`read_geotiff`] to get it.
///
/// # Errors
/// See [`RasterError`]; in particular [`RasterError::UnsupportedFormat`] for `f32` from a PNG.
pub fn read_raster<T: Sample>(
    path: &Path,
    georef: Option<GeoTransform>,
) -> Result<Raster<T>, RasterError> {
    match Format::of(path)? {
        Format::GeoTiff => read_geotiff(path, georef).map(|g| g.raster),
        Format::Png => {
            let geo = georef.ok_or_else(|| RasterError::MissingGeoreference {
                path: path.to_path_buf(),
            })?;
            png::read_png_any::<T>(path, geo)
        }
    }
}

/// The [`MapCrs`] of a raster file without decoding its samples: a GeoTIFF's GeoKeys (see
/// [`read_geotiff`]); a PNG carries none and is [`MapCrs::Local`].
///
/// # Errors
/// [`RasterError::UnsupportedFormat`], [`RasterError::NotAFile`], [`RasterError::Io`] /
/// [`RasterError::Decode`] for an unreadable file, [`RasterError::BadGeoreference`] for a
/// malformed GeoKey directory.
pub fn read_map_crs(path: &Path) -> Result<MapCrs, RasterError> {
    match Format::of(path)? {
        Format::GeoTiff => geotiff::read_crs(path),
        Format::Png => Ok(MapCrs::Local),
    }
}

/// Writes a single-band raster atomically, choosing the format by extension (a PNG loses the
/// georeference; a GeoTIFF keeps it, without a no-data value).
///
/// # Errors
/// See [`RasterError`]; in particular [`RasterError::UnsupportedFormat`] for `f32` to a PNG.
pub fn write_raster<T: Sample>(path: &Path, raster: &Raster<T>) -> Result<(), RasterError> {
    match Format::of(path)? {
        Format::GeoTiff => write_geotiff(path, raster, None),
        Format::Png => png::write_png_any(path, raster),
    }
}

/// Converts a 16-bit centimetre DEM to metres: `datum_m + cm / 100`.
///
/// # Units
/// Input centimetres above `datum_m`; output metres.
#[must_use]
pub fn dem_from_cm(r: &Raster<u16>, datum_m: f64) -> Raster<f32> {
    let data = r
        .data
        .iter()
        .map(|&cm| (datum_m + f64::from(cm) / 100.0) as f32)
        .collect();
    Raster {
        width: r.width,
        height: r.height,
        geo: r.geo,
        data,
    }
}

/// Converts a metre DEM to 16-bit centimetres above `datum_m`, rounding to the nearest cm.
///
/// # Errors
/// [`RasterError::NonFinite`] for NaN or infinity, [`RasterError::HeightOutOfRange`] for a
/// height below the datum or more than [`DEM_CM_MAX_M`] above it (after rounding).
///
/// # Units
/// Input metres; output centimetres above `datum_m`.
pub fn dem_to_cm(r: &Raster<f32>, datum_m: f64) -> Result<Raster<u16>, RasterError> {
    dem_to_cm_for(r, datum_m, Path::new(IN_MEMORY))
}

/// [`dem_to_cm`] with errors naming `path`.
fn dem_to_cm_for(r: &Raster<f32>, datum_m: f64, path: &Path) -> Result<Raster<u16>, RasterError> {
    let mut data = Vec::with_capacity(r.data.len());
    for (i, &h) in r.data.iter().enumerate() {
        let pixel = pixel_of_index(i, r.width);
        if !h.is_finite() {
            return Err(RasterError::NonFinite {
                path: path.to_path_buf(),
                pixel,
                value_m: h,
            });
        }
        let cm = ((f64::from(h) - datum_m) * 100.0).round();
        if !(0.0..=f64::from(u16::MAX)).contains(&cm) {
            return Err(RasterError::HeightOutOfRange {
                path: path.to_path_buf(),
                pixel,
                value_m: h,
                datum_m,
            });
        }
        data.push(cm as u16);
    }
    Ok(Raster {
        width: r.width,
        height: r.height,
        geo: r.geo,
        data,
    })
}

/// Reads a DEM in metres: a 16-bit PNG or GeoTIFF of centimetres above `datum_m`, or a 32-bit
/// float GeoTIFF of metres (`datum_m` then unused).
///
/// `georef` is required for PNG and overrides the file's georeference for GeoTIFF. Pixels equal
/// to the file's `GDAL_NODATA` value are rejected: a DEM with holes is bad input.
///
/// # Errors
/// See [`RasterError`]; [`RasterError::WrongSampleFormat`] for any other sample type,
/// [`RasterError::NonFinite`] / [`RasterError::NoData`] for holes.
pub fn read_dem(
    path: &Path,
    datum_m: f64,
    georef: Option<GeoTransform>,
) -> Result<Raster<f32>, RasterError> {
    const EXPECTED: &str = nodata::DEM_EXPECTED;
    let dem = match Format::of(path)? {
        Format::Png => {
            let geo = georef.ok_or_else(|| RasterError::MissingGeoreference {
                path: path.to_path_buf(),
            })?;
            dem_from_cm(&png::read_png_any::<u16>(path, geo)?, datum_m)
        }
        Format::GeoTiff => {
            let raw = geotiff::read_samples(path, georef, EXPECTED, |kind| {
                matches!(kind, geotiff::Kind::U16 | geotiff::Kind::F32)
            })?;
            let (width, height, geo) = (raw.width, raw.height, raw.geo);
            match raw.samples {
                sealed::Samples::U16(data) => {
                    reject_nodata(path, &data, width, raw.nodata, f64::from)?;
                    dem_from_cm(
                        &Raster {
                            width,
                            height,
                            geo,
                            data,
                        },
                        datum_m,
                    )
                }
                sealed::Samples::F32(data) => {
                    reject_nodata(path, &data, width, raw.nodata, f64::from)?;
                    Raster {
                        width,
                        height,
                        geo,
                        data,
                    }
                }
                sealed::Samples::U8(_) => {
                    return Err(RasterError::WrongSampleFormat {
                        path: path.to_path_buf(),
                        expected: EXPECTED,
                        found: "8-bit unsigned gray".to_owned(),
                    });
                }
            }
        }
    };
    if let Some(i) = dem.data.iter().position(|h| !h.is_finite()) {
        return Err(RasterError::NonFinite {
            path: path.to_path_buf(),
            pixel: pixel_of_index(i, dem.width),
            value_m: dem.data[i],
        });
    }
    Ok(dem)
}

/// Rejects a DEM holding its own no-data value.
fn reject_nodata<T: Copy>(
    path: &Path,
    data: &[T],
    width: usize,
    nodata: Option<f64>,
    to_f64: impl Fn(T) -> f64,
) -> Result<(), RasterError> {
    let Some(nodata) = nodata else { return Ok(()) };
    match data.iter().position(|&v| to_f64(v) == nodata) {
        Some(i) => Err(RasterError::NoData {
            path: path.to_path_buf(),
            pixel: pixel_of_index(i, width),
            nodata,
        }),
        None => Ok(()),
    }
}

/// Writes a DEM (metres) atomically as 16-bit centimetres above `datum_m`: a 16-bit PNG (no
/// georeference) or a GeoTIFF, by extension.
///
/// # Errors
/// As [`dem_to_cm`] (naming `path`) and [`write_raster`].
pub fn write_dem(path: &Path, dem: &Raster<f32>, datum_m: f64) -> Result<(), RasterError> {
    check_shape(path, dem)?;
    let cm = dem_to_cm_for(dem, datum_m, path)?;
    write_raster(path, &cm)
}

/// (column, row) of flat index `i` in a raster `width` wide.
fn pixel_of_index(i: usize, width: usize) -> (usize, usize) {
    if width == 0 {
        (0, 0)
    } else {
        (i % width, i / width)
    }
}

/// Rejects rasters that cannot be encoded: empty, or `data` not `width * height` long.
fn check_shape<T>(path: &Path, r: &Raster<T>) -> Result<(), RasterError> {
    if r.width == 0 || r.height == 0 {
        return Err(RasterError::EmptyRaster {
            path: path.to_path_buf(),
            width: r.width,
            height: r.height,
        });
    }
    if r.width.checked_mul(r.height) != Some(r.data.len()) {
        return Err(RasterError::DataLength {
            path: path.to_path_buf(),
            width: r.width,
            height: r.height,
            len: r.data.len(),
        });
    }
    Ok(())
}

/// Rejects transforms that place nothing: non-finite origin, non-positive or non-finite pixel size.
fn check_geo(path: &Path, geo: &GeoTransform) -> Result<(), RasterError> {
    let res = geo.resolution_m_per_px;
    if !(geo.origin_m.iter().all(|v| v.is_finite()) && res.is_finite() && res > 0.0) {
        return Err(RasterError::BadGeoreference {
            path: path.to_path_buf(),
            detail: format!(
                "origin {:?} m, {res} m/px (need finite values and a positive pixel size)",
                geo.origin_m
            ),
        });
    }
    Ok(())
}

/// An I/O error met while decoding: a short or malformed file is a decoding problem, anything
/// else (permissions, disk) stays an I/O error.
fn read_io_error(path: &Path, source: std::io::Error) -> RasterError {
    use std::io::ErrorKind;
    match source.kind() {
        ErrorKind::UnexpectedEof => RasterError::Decode {
            path: path.to_path_buf(),
            detail: "the file is truncated".to_owned(),
        },
        ErrorKind::InvalidData => RasterError::Decode {
            path: path.to_path_buf(),
            detail: source.to_string(),
        },
        _ => RasterError::Io {
            path: path.to_path_buf(),
            source,
        },
    }
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> RasterError + '_ {
    move |source| RasterError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Writes `path` atomically: `fill` writes a temporary sibling file, which is flushed, synced
/// and renamed over `path` only if `fill` succeeded; otherwise it is removed.
fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<File>) -> Result<(), RasterError>,
) -> Result<(), RasterError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .ok_or_else(|| RasterError::UnsupportedFormat {
            path: path.to_path_buf(),
            expected: "a file path",
            found: String::new(),
        })?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let tmp = dir.join(format!(
        ".{}.{}-{n}.tmp",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let file = File::options()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(io_error(path))?;
        let mut out = BufWriter::new(file);
        fill(&mut out)?;
        out.flush().map_err(io_error(path))?;
        let file = out.into_inner().map_err(|e| RasterError::Io {
            path: path.to_path_buf(),
            source: e.into_error(),
        })?;
        file.sync_all().map_err(io_error(path))?;
        drop(file);
        fs::rename(&tmp, path).map_err(io_error(path))
    })();
    if result.is_err() {
        // Best effort: the temporary may not exist if creating it failed.
        let _ = fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn geo() -> GeoTransform {
        GeoTransform::new(1000.0, 2000.0, 0.5)
    }

    #[test]
    fn dem_cm_round_trip_and_range() {
        let dem = Raster {
            width: 3,
            height: 1,
            geo: geo(),
            data: vec![-10.0f32, -9.995, 645.35],
        };
        let cm = dem_to_cm(&dem, -10.0).unwrap();
        assert_eq!(cm.data, vec![0, 1, 65535]);
        let back = dem_from_cm(&cm, -10.0);
        for (a, b) in back.data.iter().zip(&dem.data) {
            assert!((a - b).abs() < 0.005 + 1e-4);
        }
        let low = Raster {
            width: 2,
            height: 1,
            geo: geo(),
            data: vec![0.0f32, -10.01],
        };
        let e = dem_to_cm(&low, -10.0).unwrap_err();
        assert!(
            matches!(e, RasterError::HeightOutOfRange { pixel: (1, 0), .. }),
            "{e}"
        );
        let high = Raster {
            width: 1,
            height: 1,
            geo: geo(),
            data: vec![655.36f32],
        };
        assert!(matches!(
            dem_to_cm(&high, 0.0),
            Err(RasterError::HeightOutOfRange { .. })
        ));
        let nan = Raster {
            width: 1,
            height: 1,
            geo: geo(),
            data: vec![f32::NAN],
        };
        assert!(matches!(
            dem_to_cm(&nan, 0.0),
            Err(RasterError::NonFinite { .. })
        ));
    }

    #[test]
    fn unknown_extension_is_a_clear_error() {
        let e = read_raster::<u8>(Path::new("maps/x.jpg"), Some(geo())).unwrap_err();
        let msg = e.to_string();
        assert_eq!(
            msg,
            "maps/x.jpg: expected a .png, .tif or .tiff file, found \".jpg\""
        );
        assert!(!msg.contains('\n'));
        let e = write_raster(Path::new("noext"), &Raster::filled(1, 1, geo(), 0u8)).unwrap_err();
        assert!(matches!(e, RasterError::UnsupportedFormat { .. }));
    }

    #[test]
    fn writers_reject_bad_shapes_and_leave_nothing_behind() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.tif");
        let empty = Raster::filled(0, 5, geo(), 0u8);
        assert!(matches!(
            write_raster(&p, &empty),
            Err(RasterError::EmptyRaster { .. })
        ));
        let mut short = Raster::filled(4, 4, geo(), 0u8);
        short.data.pop();
        assert!(matches!(
            write_raster(&p, &short),
            Err(RasterError::DataLength { len: 15, .. })
        ));
        let bad_geo = Raster::filled(2, 2, GeoTransform::new(0.0, 0.0, -1.0), 0u8);
        assert!(matches!(
            write_raster(&p, &bad_geo),
            Err(RasterError::BadGeoreference { .. })
        ));
        assert_eq!(
            fs::read_dir(dir.path()).unwrap().count(),
            0,
            "no file, no temporary"
        );
    }

    #[test]
    fn atomic_write_keeps_the_old_file_on_failure() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("keep.bin");
        fs::write(&p, b"old").unwrap();
        let r = write_atomic(&p, |out| {
            out.write_all(b"partial").map_err(io_error(&p))?;
            Err(RasterError::Encode {
                path: p.clone(),
                detail: "simulated".into(),
            })
        });
        assert!(r.is_err());
        assert_eq!(fs::read(&p).unwrap(), b"old");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
        write_atomic(&p, |out| out.write_all(b"new").map_err(io_error(&p))).unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"new");
    }

    #[test]
    fn read_dem_needs_georef_for_png_and_rejects_missing_files() {
        let e = read_dem(Path::new("nope.png"), 0.0, None).unwrap_err();
        assert!(matches!(e, RasterError::MissingGeoreference { .. }), "{e}");
        let e = read_dem(Path::new("nope.tif"), 0.0, None).unwrap_err();
        assert!(matches!(e, RasterError::Io { .. }), "{e}");
        assert!(e.to_string().starts_with("nope.tif: "));
    }
}
