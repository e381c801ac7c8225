//! GeoTIFF: single-band u8 / u16 / f32 with the georeference in the standard GeoTIFF tags.
//!
//! Written files carry `ModelPixelScaleTag` (33550) = `(res, res, 0)`, `ModelTiepointTag`
//! (33922) tying raster point (0, 0) — the north-west corner of pixel (0, 0), PixelIsArea — to
//! `origin_m`, and a `GeoKeyDirectoryTag` (34735). Data are Deflate-compressed (horizontal
//! predictor for integers). The GeoKeys describe the map's [`MapCrs`]:
//!
//! - [`MapCrs::Mars`]: the full user-defined CRS, laid out as GDAL writes it — geographic CRS,
//!   datum and ellipsoid user-defined with `GeogSemiMajorAxisGeoKey` = `GeogSemiMinorAxisGeoKey`
//!   = 3 396 190 m (the IAU 2015 Mars sphere), degrees; projection user-defined with
//!   `ProjCoordTransGeoKey` = 17 (CT_Equirectangular), `ProjStdParallel1GeoKey`,
//!   `ProjCenterLongGeoKey`, `ProjCenterLatGeoKey` = 0 and `ProjFalseEasting/NorthingGeoKey` in
//!   `GeoDoubleParamsTag` (34736); metres; citations naming the CRS, datum, sphere and prime
//!   meridian in `GeoAsciiParamsTag` (34737). `gdalinfo` then reports an equidistant
//!   cylindrical projection of the Mars sphere;
//! - [`MapCrs::Local`]: the minimal directory of files from before solsim georeferenced its
//!   maps — projected model, user-defined projected CRS, metres, citation "solsim local map
//!   frame".
//!
//! Readers accept what GDAL writes for north-up grids: a tiepoint at any raster point,
//! PixelIsPoint (shifted by half a pixel to the corner convention), or a
//! `ModelTransformationTag` without rotation. They reject rotated, sheared, flipped,
//! non-square and geographic (degree) georeferences, and ground-control-point sets. A file's
//! CRS is [`MapCrs::Mars`] when its keys describe an equirectangular projection of a sphere of
//! radius 3 396 190 m in degrees and metres (a latitude of origin is folded into the false
//! northing); anything else, including the old local frame, reads as [`MapCrs::Local`].
//!
//! ## References
//! OGC GeoTIFF Standard 1.1 (OGC 19-008r4), §7 (raster space, PixelIsArea / PixelIsPoint) and
//! Annex B (GeoKey codes).

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Seek};
use std::path::Path;

use tiff::ColorType;
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::encoder::colortype::{self, ColorType as EncColorType};
use tiff::encoder::{Compression, DeflateLevel, Predictor, TiffEncoder, TiffValue};
use tiff::tags::Tag;

use super::tiff_tags::{read_f64s, tiff_error};

use super::geokeys::{
    GT_MODEL_TYPE, GT_RASTER_TYPE, GeoKeyTags, LINEAR_METRE, MODEL_TYPE_GEOGRAPHIC,
    PROJ_LINEAR_UNITS, RASTER_PIXEL_IS_POINT, read_geokeys,
};
use super::sealed::{Samples, SamplesRef};
use super::{RasterError, Sample, check_geo, check_shape, write_atomic};
use crate::mars_crs::MapCrs;
use crate::raster::{GeoTransform, Raster};

/// Largest decoded image accepted, so a corrupt header cannot exhaust memory.
const MAX_DECODED_BYTES: usize = 2 << 30;

/// Largest tag value read (georeference, GeoKeys, no-data text): the tiff crate's own
/// per-value default.
const MAX_TAG_BYTES: usize = 1 << 20;

/// A raster read from a GeoTIFF, with the file's no-data value.
#[derive(Clone, Debug, PartialEq)]
pub struct GeoTiff<T> {
    /// The samples, placed by the file's georeference (or the caller's override).
    pub raster: Raster<T>,
    /// The `GDAL_NODATA` (42113) value, if the file declares one.
    pub nodata: Option<f64>,
    /// Where the map lies, from the file's GeoKeys ([`MapCrs::Local`] when the caller's
    /// georeference overrides the file's, or the keys describe no Mars CRS).
    pub crs: MapCrs,
}

/// Sample types a GeoTIFF may hold here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    U8,
    U16,
    F32,
}

/// A decoded file before it is narrowed to one sample type.
pub(super) struct RawTiff {
    pub samples: Samples,
    pub width: usize,
    pub height: usize,
    pub geo: GeoTransform,
    pub nodata: Option<f64>,
    pub crs: MapCrs,
}

/// Reads a single-band GeoTIFF of `T` (`u8`, `u16` unsigned, or `f32`).
///
/// The georeference comes from the file's tags unless `georef` overrides it (the tags are then
/// not read at all). Only the first image of the file is read.
///
/// # Errors
/// [`RasterError::WrongSampleFormat`] for another band count, bit depth or number type;
/// [`RasterError::MissingGeoreference`] / [`RasterError::BadGeoreference`] without a usable
/// north-up georeference; [`RasterError::BadNodata`] for a non-numeric `GDAL_NODATA`;
/// [`RasterError::Io`] / [`RasterError::Decode`] for unreadable files.
pub fn read_geotiff<T: Sample>(
    path: &Path,
    georef: Option<GeoTransform>,
) -> Result<GeoTiff<T>, RasterError> {
    let want = kind_of::<T>();
    let raw = read_samples(path, georef, T::EXPECTED, |k| k == want)?;
    let data = T::from_samples(raw.samples).ok_or_else(|| RasterError::Decode {
        path: path.to_path_buf(),
        detail: "decoded samples do not match the declared sample format".to_owned(),
    })?;
    Ok(GeoTiff {
        raster: Raster {
            width: raw.width,
            height: raw.height,
            geo: raw.geo,
            data,
        },
        nodata: raw.nodata,
        crs: raw.crs,
    })
}

/// The [`MapCrs`] a GeoTIFF's GeoKeys describe, without decoding its samples.
pub(super) fn read_crs(path: &Path) -> Result<MapCrs, RasterError> {
    let file = super::open_raster(path)?;
    let mut limits = Limits::default();
    limits.decoding_buffer_size = MAX_TAG_BYTES;
    let mut dec = Decoder::new(BufReader::new(file))
        .map_err(tiff_error(path, true))?
        .with_limits(limits);
    Ok(read_geokeys(&mut dec, path)?.crs())
}

/// Writes a single-band GeoTIFF atomically, Deflate-compressed, georeferenced by `raster.geo`
/// in the local map frame ([`MapCrs::Local`]), with `GDAL_NODATA` when `nodata` is given.
///
/// # Errors
/// As [`write_geotiff_with_crs`].
pub fn write_geotiff<T: Sample>(
    path: &Path,
    raster: &Raster<T>,
    nodata: Option<f64>,
) -> Result<(), RasterError> {
    write_geotiff_with_crs(path, raster, nodata, &MapCrs::Local)
}

/// Writes a single-band GeoTIFF atomically, Deflate-compressed, georeferenced by `raster.geo`
/// with the GeoKeys of `crs` (see the module docs), with `GDAL_NODATA` when `nodata` is given.
///
/// # Errors
/// [`RasterError::EmptyRaster`] / [`RasterError::DataLength`] for a malformed raster,
/// [`RasterError::BadGeoreference`] for a non-finite origin or non-positive pixel size,
/// [`RasterError::Io`] / [`RasterError::Encode`] when writing fails.
pub fn write_geotiff_with_crs<T: Sample>(
    path: &Path,
    raster: &Raster<T>,
    nodata: Option<f64>,
    crs: &MapCrs,
) -> Result<(), RasterError> {
    check_shape(path, raster)?;
    check_geo(path, &raster.geo)?;
    let too_big = |_| RasterError::Encode {
        path: path.to_path_buf(),
        detail: format!(
            "{}x{} px exceeds the TIFF limit of 2^32 - 1 px per side",
            raster.width, raster.height
        ),
    };
    let w = u32::try_from(raster.width).map_err(too_big)?;
    let h = u32::try_from(raster.height).map_err(too_big)?;
    let nodata_text = nodata.map(|v| format!("{v}"));
    let head = Header {
        path,
        w,
        h,
        geo: raster.geo,
        nodata: nodata_text.as_deref(),
        keys: GeoKeyTags::of(crs),
    };
    write_atomic(path, |out| match T::as_samples(&raster.data) {
        SamplesRef::U8(d) => encode::<colortype::Gray8>(out, &head, d, Predictor::Horizontal),
        SamplesRef::U16(d) => encode::<colortype::Gray16>(out, &head, d, Predictor::Horizontal),
        // The tiff crate cannot write the floating-point predictor.
        SamplesRef::F32(d) => encode::<colortype::Gray32Float>(out, &head, d, Predictor::None),
    })
}

/// What every image directory carries besides the samples.
struct Header<'a> {
    path: &'a Path,
    w: u32,
    h: u32,
    geo: GeoTransform,
    nodata: Option<&'a str>,
    keys: GeoKeyTags,
}

fn encode<C: EncColorType>(
    out: &mut BufWriter<File>,
    head: &Header<'_>,
    data: &[C::Inner],
    predictor: Predictor,
) -> Result<(), RasterError>
where
    [C::Inner]: TiffValue,
{
    let err = tiff_error(head.path, false);
    let res = head.geo.resolution_m_per_px;
    let [ox, oy] = head.geo.origin_m;
    let mut enc = TiffEncoder::new(out)
        .map_err(&err)?
        .with_compression(Compression::Deflate(DeflateLevel::Balanced))
        .with_predictor(predictor);
    let mut image = enc.new_image::<C>(head.w, head.h).map_err(&err)?;
    let dir = image.encoder();
    dir.write_tag(Tag::ModelPixelScaleTag, &[res, res, 0.0][..])
        .map_err(&err)?;
    dir.write_tag(Tag::ModelTiepointTag, &[0.0, 0.0, 0.0, ox, oy, 0.0][..])
        .map_err(&err)?;
    dir.write_tag(Tag::GeoKeyDirectoryTag, &head.keys.directory[..])
        .map_err(&err)?;
    if !head.keys.doubles.is_empty() {
        dir.write_tag(Tag::GeoDoubleParamsTag, &head.keys.doubles[..])
            .map_err(&err)?;
    }
    dir.write_tag(Tag::GeoAsciiParamsTag, head.keys.ascii.as_str())
        .map_err(&err)?;
    if let Some(text) = head.nodata {
        dir.write_tag(Tag::GdalNodata, text).map_err(&err)?;
    }
    image.write_data(data).map_err(&err)
}

fn kind_of<T: Sample>() -> Kind {
    match T::as_samples(&[]) {
        SamplesRef::U8(_) => Kind::U8,
        SamplesRef::U16(_) => Kind::U16,
        SamplesRef::F32(_) => Kind::F32,
    }
}

/// Reads the first image of a GeoTIFF whose sample kind `accept` allows (`expected` describes
/// what is allowed, for the error), with its georeference (or `georef`) and no-data value.
pub(super) fn read_samples(
    path: &Path,
    georef: Option<GeoTransform>,
    expected: &'static str,
    accept: impl Fn(Kind) -> bool,
) -> Result<RawTiff, RasterError> {
    let err = tiff_error(path, true);
    let file = super::open_raster(path)?;
    // The tiff crate bounds a tag's value by `decoding_buffer_size`: keep it small while the
    // tags are read (a 500-byte file may declare a 2 GB GDAL_NODATA string), and raise it to
    // the image limit only for `read_image`.
    let mut limits = Limits::default();
    limits.decoding_buffer_size = MAX_TAG_BYTES;
    let mut dec = Decoder::new(BufReader::new(file))
        .map_err(&err)?
        .with_limits(limits.clone());
    let (w, h) = dec.dimensions().map_err(&err)?;
    let color = dec.colortype().map_err(&err)?;
    let format = dec
        .find_tag_unsigned_vec::<u16>(Tag::SampleFormat)
        .map_err(&err)?
        .and_then(|v| v.first().copied())
        .unwrap_or(1);
    let kind = match (color, format) {
        (ColorType::Gray(8), 1) => Some(Kind::U8),
        (ColorType::Gray(16), 1) => Some(Kind::U16),
        (ColorType::Gray(32), 3) => Some(Kind::F32),
        _ => None,
    };
    if !kind.is_some_and(&accept) {
        return Err(RasterError::WrongSampleFormat {
            path: path.to_path_buf(),
            expected,
            found: describe(color, format),
        });
    }
    let (geo, crs) = match georef {
        Some(g) => {
            check_geo(path, &g)?;
            (g, MapCrs::Local)
        }
        None => read_georef(&mut dec, path)?,
    };
    let nodata = read_nodata(&mut dec, path)?;
    limits.decoding_buffer_size = MAX_DECODED_BYTES;
    dec = dec.with_limits(limits);
    let samples = match dec.read_image().map_err(&err)? {
        DecodingResult::U8(v) => Samples::U8(v),
        DecodingResult::U16(v) => Samples::U16(v),
        DecodingResult::F32(v) => Samples::F32(v),
        _ => {
            return Err(RasterError::WrongSampleFormat {
                path: path.to_path_buf(),
                expected,
                found: describe(color, format),
            });
        }
    };
    let (width, height) = (w as usize, h as usize);
    let len = match &samples {
        Samples::U8(v) => v.len(),
        Samples::U16(v) => v.len(),
        Samples::F32(v) => v.len(),
    };
    if len != width * height {
        return Err(RasterError::Decode {
            path: path.to_path_buf(),
            detail: format!("{len} samples decoded for {width}x{height} px"),
        });
    }
    Ok(RawTiff {
        samples,
        width,
        height,
        geo,
        nodata,
        crs,
    })
}

/// Human description of a TIFF sample layout, e.g. `8-bit unsigned RGB`.
fn describe(color: ColorType, sample_format: u16) -> String {
    let number = match sample_format {
        1 => "unsigned".to_owned(),
        2 => "signed".to_owned(),
        3 => "float".to_owned(),
        n => format!("sample-format-{n}"),
    };
    let layout = match color {
        ColorType::Gray(_) => "gray".to_owned(),
        ColorType::RGB(_) => "RGB".to_owned(),
        ColorType::Palette(_) => "palette".to_owned(),
        ColorType::GrayA(_) => "gray + alpha".to_owned(),
        ColorType::RGBA(_) => "RGBA".to_owned(),
        ColorType::CMYK(_) => "CMYK".to_owned(),
        ColorType::CMYKA(_) => "CMYK + alpha".to_owned(),
        ColorType::YCbCr(_) => "YCbCr".to_owned(),
        ColorType::Lab(_) => "CIE Lab".to_owned(),
        ColorType::Multiband { num_samples, .. } => format!("{num_samples}-band"),
        _ => format!("{color:?}"),
    };
    format!("{}-bit {number} {layout}", color.bit_depth())
}

/// The north-up square-pixel transform described by the file's GeoTIFF tags.
fn read_georef<R: Read + Seek>(
    dec: &mut Decoder<R>,
    path: &Path,
) -> Result<(GeoTransform, MapCrs), RasterError> {
    let bad = |detail: String| RasterError::BadGeoreference {
        path: path.to_path_buf(),
        detail,
    };
    let keys = read_geokeys(dec, path)?;
    if keys.short(GT_MODEL_TYPE) == Some(MODEL_TYPE_GEOGRAPHIC) {
        return Err(bad(
            "a geographic CRS in degrees (GTModelTypeGeoKey = 2); reproject to metres first"
                .to_owned(),
        ));
    }
    if let Some(units) = keys.short(PROJ_LINEAR_UNITS).filter(|&u| u != LINEAR_METRE) {
        return Err(bad(format!(
            "ProjLinearUnitsGeoKey = {units} (only 9001, metre, is supported)"
        )));
    }
    let scale = read_f64s(dec, path, Tag::ModelPixelScaleTag)?;
    let ties = read_f64s(dec, path, Tag::ModelTiepointTag)?;
    let matrix = read_f64s(dec, path, Tag::ModelTransformationTag)?;
    let (mut ox, mut oy, res) = match (scale, ties, matrix) {
        (Some(scale), Some(ties), _) => {
            let (sx, sy) = match scale.as_slice() {
                [sx, sy, ..] => (*sx, *sy),
                _ => {
                    return Err(bad(format!(
                        "a ModelPixelScale with {} values (need 3)",
                        scale.len()
                    )));
                }
            };
            if !(sx.is_finite() && sy.is_finite() && sx > 0.0 && sy > 0.0) {
                return Err(bad(format!(
                    "ModelPixelScale ({sx}, {sy}) (need two positive numbers; negative means flipped)"
                )));
            }
            check_square(sx, sy).map_err(bad)?;
            if ties.is_empty() || ties.len() % 6 != 0 {
                return Err(bad(format!(
                    "a ModelTiepoint with {} values (need 6 per tiepoint)",
                    ties.len()
                )));
            }
            // Tiepoint (I, J, K, X, Y, Z): raster point (I, J) lies at map (X, Y).
            let (i, j, x, y) = (ties[0], ties[1], ties[3], ties[4]);
            let (ox, oy) = (x - i * sx, y + j * sy);
            let tol = 1e-3 * sx;
            for t in ties.chunks_exact(6).skip(1) {
                if (ox + t[0] * sx - t[3]).abs() > tol || (oy - t[1] * sy - t[4]).abs() > tol {
                    return Err(bad(format!(
                        "{} tiepoints that do not lie on one grid (ground control points: warp the file first)",
                        ties.len() / 6
                    )));
                }
            }
            (ox, oy, sx)
        }
        (_, _, Some(m)) => {
            if m.len() != 16 {
                return Err(bad(format!(
                    "a ModelTransformation with {} values (need 16)",
                    m.len()
                )));
            }
            // Row-major 4x4: x = m0·I + m1·J + m3, y = m4·I + m5·J + m7.
            let (a, b, c, d, e, f) = (m[0], m[1], m[3], m[4], m[5], m[7]);
            if b != 0.0 || d != 0.0 {
                return Err(bad(format!(
                    "a rotated or sheared grid (ModelTransformation terms {b}, {d})"
                )));
            }
            if !(a > 0.0 && e < 0.0) {
                return Err(bad(format!(
                    "a flipped grid (pixel size {a} x {e} m; need x > 0, y < 0)"
                )));
            }
            check_square(a, -e).map_err(bad)?;
            (c, f, a)
        }
        (None, None, None) => {
            return Err(RasterError::MissingGeoreference {
                path: path.to_path_buf(),
            });
        }
        (Some(_), None, None) => {
            return Err(bad("a ModelPixelScale without a ModelTiepoint".to_owned()));
        }
        (None, Some(t), None) => {
            return Err(bad(format!(
                "{} tiepoint(s) without a ModelPixelScale (ground control points: warp the file first)",
                t.len() / 6
            )));
        }
    };
    if keys.short(GT_RASTER_TYPE) == Some(RASTER_PIXEL_IS_POINT) {
        // Raster point (0, 0) is the centre of pixel (0, 0); move to its north-west corner.
        ox -= 0.5 * res;
        oy += 0.5 * res;
    }
    let geo = GeoTransform::new(ox, oy, res);
    check_geo(path, &geo)?;
    Ok((geo, keys.crs()))
}

fn check_square(sx: f64, sy: f64) -> Result<(), String> {
    if (sx - sy).abs() > 1e-9 * sx.max(sy) {
        return Err(format!(
            "non-square pixels ({sx} x {sy} m); resample to square pixels first"
        ));
    }
    Ok(())
}

fn read_nodata<R: Read + Seek>(
    dec: &mut Decoder<R>,
    path: &Path,
) -> Result<Option<f64>, RasterError> {
    // A number's text is short: refuse a long tag before the tiff crate reads it (it would
    // allocate the declared length, and print a `dbg!` line past a limit).
    if let Some(entry) = dec.image_ifd().find_entry(Tag::GdalNodata)
        && entry.count() > 64
    {
        return Err(RasterError::BadNodata {
            path: path.to_path_buf(),
            found: format!("text of {} characters", entry.count()),
        });
    }
    let Some(value) = dec
        .find_tag(Tag::GdalNodata)
        .map_err(tiff_error(path, true))?
    else {
        return Ok(None);
    };
    let text = match value {
        tiff::decoder::ifd::Value::Ascii(s) => s,
        other => {
            return Err(RasterError::BadNodata {
                path: path.to_path_buf(),
                found: format!("{other:?}"),
            });
        }
    };
    let trimmed = text.trim_matches(|c: char| c.is_whitespace() || c == '\0');
    trimmed
        .parse::<f64>()
        .map(Some)
        .map_err(|_| RasterError::BadNodata {
            path: path.to_path_buf(),
            found: text.clone(),
        })
}
