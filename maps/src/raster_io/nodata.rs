//! Rasters read together with their no-data cells, for inputs where holes are data (a rover's
//! orthomosaic and DEM, an orbital DEM with gaps): [`read_raster_with_nodata`] returns the
//! GeoTIFF's `GDAL_NODATA` value beside the samples, [`read_dem_with_holes`] turns no-data DEM
//! cells into NaN. [`read_raster`](super::read_raster) drops the no-data value and
//! [`read_dem`](super::read_dem) rejects a DEM that uses it: map layers must be complete.

use std::path::Path;

use super::sealed::Samples;
use super::{Format, RasterError, Sample, dem_from_cm, geotiff, png, read_geotiff, read_raster};
use crate::raster::{GeoTransform, Raster};

/// What a DEM file must hold, for error messages.
pub(super) const DEM_EXPECTED: &str = "a single-band 16-bit unsigned (cm) or 32-bit float (m) DEM";

/// Reads a single-band raster like [`read_raster`], with the GeoTIFF's no-data value (`None`
/// for a PNG, or a GeoTIFF that declares none).
///
/// # Errors
/// As [`read_raster`].
pub fn read_raster_with_nodata<T: Sample>(
    path: &Path,
    georef: Option<GeoTransform>,
) -> Result<(Raster<T>, Option<f64>), RasterError> {
    match Format::of(path)? {
        Format::GeoTiff => read_geotiff::<T>(path, georef).map(|g| (g.raster, g.nodata)),
        Format::Png => read_raster::<T>(path, georef).map(|r| (r, None)),
    }
}

/// Reads a DEM in metres whose no-data cells become holes (NaN): a 16-bit PNG or GeoTIFF of
/// centimetres above `datum_m`, or a 32-bit float GeoTIFF of metres (`datum_m` then unused).
/// A cell equal to the GeoTIFF's `GDAL_NODATA` value (compared as stored: centimetres or
/// metres) is a hole; NaN cells of a float file stay holes.
///
/// `georef` is required for PNG and overrides the file's georeference for GeoTIFF.
///
/// # Errors
/// As [`read_raster`]; [`RasterError::WrongSampleFormat`] naming the DEM formats for any other
/// sample type.
pub fn read_dem_with_holes(
    path: &Path,
    datum_m: f64,
    georef: Option<GeoTransform>,
) -> Result<Raster<f32>, RasterError> {
    match Format::of(path)? {
        Format::Png => {
            let geo = georef.ok_or_else(|| RasterError::MissingGeoreference {
                path: path.to_path_buf(),
            })?;
            let cm = png::read_png_any::<u16>(path, geo).map_err(|e| match e {
                RasterError::WrongSampleFormat { path, found, .. } => {
                    RasterError::WrongSampleFormat {
                        path,
                        expected: DEM_EXPECTED,
                        found,
                    }
                }
                e => e,
            })?;
            Ok(dem_from_cm(&cm, datum_m))
        }
        Format::GeoTiff => {
            let raw = geotiff::read_samples(path, georef, DEM_EXPECTED, |kind| {
                matches!(kind, geotiff::Kind::U16 | geotiff::Kind::F32)
            })?;
            let (width, height, geo) = (raw.width, raw.height, raw.geo);
            match raw.samples {
                Samples::U16(data) => {
                    let cm = Raster {
                        width,
                        height,
                        geo,
                        data,
                    };
                    let mut dem = dem_from_cm(&cm, datum_m);
                    if let Some(n) = raw.nodata {
                        for (h, &v) in dem.data.iter_mut().zip(&cm.data) {
                            if f64::from(v) == n {
                                *h = f32::NAN;
                            }
                        }
                    }
                    Ok(dem)
                }
                Samples::F32(mut data) => {
                    if let Some(n) = raw.nodata {
                        for h in &mut data {
                            if f64::from(*h) == n {
                                *h = f32::NAN;
                            }
                        }
                    }
                    Ok(Raster {
                        width,
                        height,
                        geo,
                        data,
                    })
                }
                Samples::U8(_) => Err(RasterError::WrongSampleFormat {
                    path: path.to_path_buf(),
                    expected: DEM_EXPECTED,
                    found: "8-bit unsigned gray".to_owned(),
                }),
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::raster_io::{write_geotiff, write_png};

    fn geo() -> GeoTransform {
        GeoTransform::new(1000.0, 2000.0, 1.0)
    }

    #[test]
    fn nodata_cells_become_holes_in_both_dem_formats() {
        let dir = tempfile::tempdir().unwrap();
        let cm = Raster {
            width: 3,
            height: 1,
            geo: geo(),
            data: vec![150u16, 9999, 250],
        };
        let p = dir.path().join("cm.tif");
        write_geotiff(&p, &cm, Some(9999.0)).unwrap();
        let dem = read_dem_with_holes(&p, 10.0, None).unwrap();
        assert_eq!(dem.geo, geo());
        assert_eq!(dem.data[0], 11.5);
        assert!(dem.data[1].is_nan());
        assert_eq!(dem.data[2], 12.5);

        let m = Raster {
            data: vec![1.5f32, -9999.0, f32::NAN],
            ..Raster::filled(3, 1, geo(), 0.0f32)
        };
        let p = dir.path().join("m.tif");
        write_geotiff(&p, &m, Some(-9999.0)).unwrap();
        let dem = read_dem_with_holes(&p, 10.0, None).unwrap();
        assert_eq!(dem.data[0], 1.5);
        assert!(dem.data[1].is_nan() && dem.data[2].is_nan());

        // A PNG holds centimetres and needs a georeference.
        let p = dir.path().join("cm.png");
        write_png(&p, &cm).unwrap();
        assert!(matches!(
            read_dem_with_holes(&p, 0.0, None),
            Err(RasterError::MissingGeoreference { .. })
        ));
        let dem = read_dem_with_holes(&p, 0.0, Some(geo())).unwrap();
        assert_eq!(dem.data[1], 99.99);
    }

    #[test]
    fn other_sample_types_name_the_dem_formats() {
        let dir = tempfile::tempdir().unwrap();
        let u8s = Raster::filled(2, 2, geo(), 7u8);
        for name in ["a.tif", "a.png"] {
            let p = dir.path().join(name);
            if name.ends_with("tif") {
                write_geotiff(&p, &u8s, None).unwrap();
            } else {
                write_png(&p, &u8s).unwrap();
            }
            match read_dem_with_holes(&p, 0.0, Some(geo())) {
                Err(RasterError::WrongSampleFormat {
                    expected, found, ..
                }) => {
                    assert_eq!(expected, DEM_EXPECTED);
                    assert!(found.starts_with("8-bit"), "{found}");
                }
                other => panic!("{name}: {other:?}"),
            }
        }
        assert!(matches!(
            read_dem_with_holes(Path::new("dem.asc"), 0.0, None),
            Err(RasterError::UnsupportedFormat { .. })
        ));
    }

    #[test]
    fn nodata_comes_with_a_geotiff_only() {
        let dir = tempfile::tempdir().unwrap();
        let r = Raster::filled(2, 1, geo(), 3u8);
        let tif = dir.path().join("o.tif");
        write_geotiff(&tif, &r, Some(0.0)).unwrap();
        assert_eq!(
            read_raster_with_nodata::<u8>(&tif, None).unwrap(),
            (r.clone(), Some(0.0))
        );
        let png = dir.path().join("o.png");
        write_png(&png, &r).unwrap();
        assert_eq!(
            read_raster_with_nodata::<u8>(&png, Some(geo())).unwrap(),
            (r, None)
        );
    }
}
