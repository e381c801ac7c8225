//! Round trips and error cases of the PNG / GeoTIFF readers and writers and of `MapLayers`,
//! including hand-made GeoTIFFs shaped like GDAL output (tiepoint away from pixel (0, 0),
//! PixelIsPoint, ModelTransformation) and malformed georeferences.
#![allow(clippy::unwrap_used)]

use std::fs;
use std::path::{Path, PathBuf};

use maps::raster_io::{
    GeoTiff, read_dem, read_geotiff, read_png, read_raster, write_dem, write_geotiff, write_png,
    write_raster,
};
use maps::{GeoTransform, MapLayers, Raster, RasterError};
use tiff::encoder::{TiffEncoder, colortype};
use tiff::tags::Tag;

fn geo() -> GeoTransform {
    GeoTransform::new(4321.5, 98765.25, 0.25)
}

fn ramp<T>(w: usize, h: usize, f: impl Fn(usize) -> T) -> Raster<T> {
    Raster {
        width: w,
        height: h,
        geo: geo(),
        data: (0..w * h).map(f).collect(),
    }
}

fn one_line(e: &RasterError, path: &Path) -> String {
    let msg = e.to_string();
    assert!(!msg.contains('\n'), "multi-line message: {msg}");
    assert!(
        msg.starts_with(&path.display().to_string()),
        "message does not name the file: {msg}"
    );
    msg
}

#[test]
fn geotiff_round_trips_u8_u16_f32_with_georef_and_nodata() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (37, 23);

    let p8 = dir.path().join("a.tif");
    let r8 = ramp(w, h, |i| (i * 7 % 256) as u8);
    write_geotiff(&p8, &r8, Some(0.0)).unwrap();
    let g8: GeoTiff<u8> = read_geotiff(&p8, None).unwrap();
    assert_eq!(g8.raster, r8);
    assert_eq!(g8.nodata, Some(0.0));

    let p16 = dir.path().join("b.TIFF");
    let r16 = ramp(w, h, |i| (i * 977 % 65536) as u16);
    write_geotiff(&p16, &r16, None).unwrap();
    let g16: GeoTiff<u16> = read_geotiff(&p16, None).unwrap();
    assert_eq!(g16.raster, r16);
    assert_eq!(g16.nodata, None);

    let p32 = dir.path().join("c.tif");
    let r32 = ramp(w, h, |i| i as f32 * 0.37 - 100.0);
    write_geotiff(&p32, &r32, Some(-32768.0)).unwrap();
    let g32: GeoTiff<f32> = read_geotiff(&p32, None).unwrap();
    assert_eq!(g32.raster, r32);
    assert_eq!(g32.nodata, Some(-32768.0));

    // NaN no-data survives as NaN.
    write_geotiff(&p32, &r32, Some(f64::NAN)).unwrap();
    assert!(
        read_geotiff::<f32>(&p32, None)
            .unwrap()
            .nodata
            .unwrap()
            .is_nan()
    );

    // The dispatching reader gives the same raster; an override replaces the georeference.
    assert_eq!(read_raster::<u16>(&p16, None).unwrap(), r16);
    let other = GeoTransform::new(0.0, 10.0, 2.0);
    assert_eq!(read_raster::<u16>(&p16, Some(other)).unwrap().geo, other);
}

#[test]
fn geotiff_is_deflate_compressed() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("flat.tif");
    write_geotiff(&p, &ramp(500, 500, |i| (i % 500) as u16), None).unwrap();
    let size = fs::metadata(&p).unwrap().len();
    assert!(size < 20_000, "500x500 u16 ramp took {size} bytes");
}

#[test]
fn png_round_trips_u8_and_u16_and_refuses_other_layouts() {
    let dir = tempfile::tempdir().unwrap();
    let p8 = dir.path().join("a.png");
    let r8 = ramp(31, 17, |i| (i % 251) as u8);
    write_png(&p8, &r8).unwrap();
    assert_eq!(read_png::<u8>(&p8, geo()).unwrap(), r8);

    let p16 = dir.path().join("b.png");
    let r16 = ramp(31, 17, |i| (i * 2111 % 65536) as u16);
    write_raster(&p16, &r16).unwrap();
    assert_eq!(read_raster::<u16>(&p16, Some(geo())).unwrap(), r16);

    // No silent narrowing or widening.
    let e = read_png::<u16>(&p8, geo()).unwrap_err();
    let msg = one_line(&e, &p8);
    assert!(
        msg.ends_with("expected a single-band 16-bit unsigned raster, found 8-bit gray"),
        "{msg}"
    );
    assert!(matches!(
        read_png::<u8>(&p16, geo()),
        Err(RasterError::WrongSampleFormat { .. })
    ));

    let rgb = dir.path().join("rgb.png");
    image::RgbImage::new(4, 4).save(&rgb).unwrap();
    let e = read_png::<u8>(&rgb, geo()).unwrap_err();
    assert!(one_line(&e, &rgb).ends_with("found 8-bit RGB"), "{e}");

    // PNG has no georeference and no float samples.
    let e = read_raster::<u8>(&p8, None).unwrap_err();
    assert!(matches!(e, RasterError::MissingGeoreference { .. }));
    one_line(&e, &p8);
    let e = write_raster(&dir.path().join("f.png"), &ramp(2, 2, |i| i as f32)).unwrap_err();
    assert!(matches!(e, RasterError::UnsupportedFormat { .. }), "{e}");
    let e = read_raster::<f32>(&p8, Some(geo())).unwrap_err();
    assert!(matches!(e, RasterError::UnsupportedFormat { .. }), "{e}");
}

#[test]
fn wrong_tiff_sample_formats_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("rgb.tif");
    let f = fs::File::create(&p).unwrap();
    TiffEncoder::new(f)
        .unwrap()
        .write_image::<colortype::RGB8>(2, 2, &[0u8; 12])
        .unwrap();
    let e = read_dem(&p, 0.0, Some(geo())).unwrap_err();
    let msg = one_line(&e, &p);
    assert!(
        msg.ends_with("expected a single-band 16-bit unsigned (cm) or 32-bit float (m) DEM, found 8-bit unsigned RGB"),
        "{msg}"
    );

    let p16 = dir.path().join("u16.tif");
    write_geotiff(&p16, &ramp(3, 3, |i| i as u16), None).unwrap();
    let e = read_geotiff::<u8>(&p16, None).unwrap_err();
    assert!(
        one_line(&e, &p16).ends_with("found 16-bit unsigned gray"),
        "{e}"
    );
    assert!(matches!(
        read_geotiff::<f32>(&p16, None),
        Err(RasterError::WrongSampleFormat { .. })
    ));

    let pi16 = dir.path().join("i16.tif");
    let f = fs::File::create(&pi16).unwrap();
    TiffEncoder::new(f)
        .unwrap()
        .write_image::<colortype::GrayI16>(2, 2, &[0i16; 4])
        .unwrap();
    let e = read_geotiff::<u16>(&pi16, Some(geo())).unwrap_err();
    assert!(
        one_line(&e, &pi16).ends_with("found 16-bit signed gray"),
        "{e}"
    );
}

#[test]
fn corrupt_and_missing_files_are_errors_not_panics() {
    let dir = tempfile::tempdir().unwrap();
    let junk = dir.path().join("junk.tif");
    fs::write(&junk, b"II*\0garbage that is not a tiff at all").unwrap();
    let e = read_geotiff::<u8>(&junk, None).unwrap_err();
    assert!(
        matches!(e, RasterError::Decode { .. } | RasterError::Io { .. }),
        "{e}"
    );
    one_line(&e, &junk);

    // A valid file cut in half.
    let good = dir.path().join("good.tif");
    write_geotiff(&good, &ramp(64, 64, |i| (i * 31 % 65536) as u16), None).unwrap();
    let bytes = fs::read(&good).unwrap();
    let cut = dir.path().join("cut.tif");
    fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    assert!(read_geotiff::<u16>(&cut, None).is_err());

    let junk_png = dir.path().join("junk.png");
    fs::write(&junk_png, b"\x89PNG\r\n\x1a\nnope").unwrap();
    let e = read_png::<u8>(&junk_png, geo()).unwrap_err();
    one_line(&e, &junk_png);

    let missing = dir.path().join("missing.tif");
    let e = read_geotiff::<u8>(&missing, None).unwrap_err();
    assert!(matches!(e, RasterError::Io { .. }));
    one_line(&e, &missing);
}

#[test]
fn geotiff_carries_a_mars_crs_and_reads_local_files_as_local() {
    use maps::raster_io::{read_map_crs, write_geotiff_with_crs};
    use maps::{MapAnchor, MapCrs, MarsEquirectangular};
    let dir = tempfile::tempdir().unwrap();
    let mars = MarsEquirectangular::jezero(&MapAnchor {
        anchor_m: [600.0, 600.0],
        lon_deg: 77.4508,
        lat_deg: 18.4447,
    });
    let r = ramp(9, 7, |i| i as u16);
    let p = dir.path().join("mars.tif");
    write_geotiff_with_crs(&p, &r, None, &MapCrs::Mars(mars)).unwrap();
    let g: GeoTiff<u16> = read_geotiff(&p, None).unwrap();
    assert_eq!(g.raster, r);
    assert_eq!(g.crs, MapCrs::Mars(mars));
    assert_eq!(read_map_crs(&p).unwrap(), MapCrs::Mars(mars));
    // A caller's georeference overrides the file's tags, CRS included.
    assert_eq!(
        read_geotiff::<u16>(&p, Some(geo())).unwrap().crs,
        MapCrs::Local
    );
    // Files in the local frame (all GeoTIFFs before the Mars CRS) read as before.
    let old = dir.path().join("old.tif");
    write_geotiff(&old, &r, None).unwrap();
    let g: GeoTiff<u16> = read_geotiff(&old, None).unwrap();
    assert_eq!((g.raster, g.crs), (r.clone(), MapCrs::Local));
    assert_eq!(read_map_crs(&old).unwrap(), MapCrs::Local);
    assert_eq!(
        read_map_crs(&dir.path().join("x.png")).unwrap(),
        MapCrs::Local
    );
    // Same raster and CRS, same bytes.
    let again = dir.path().join("again.tif");
    write_geotiff_with_crs(&again, &r, None, &MapCrs::Mars(mars)).unwrap();
    assert_eq!(fs::read(&p).unwrap(), fs::read(&again).unwrap());
}

#[test]
fn a_gdal_style_equirectangular_mars_file_is_understood() {
    // Keys as GDAL writes them for eqc with a latitude of origin of 10° (folded into the false
    // northing), natural-origin keys instead of centre keys; then a Earth ellipsoid (local).
    let dir = tempfile::tempdir().unwrap();
    #[rustfmt::skip]
    let keys: [u16; 4 + 4 * 9] = [
        1, 1, 0, 9,
        1024, 0, 1, 1,
        2054, 0, 1, 9102,
        2057, 34736, 1, 0,
        2058, 34736, 1, 1,
        3075, 0, 1, 17,
        3076, 0, 1, 9001,
        3078, 34736, 1, 2,
        3080, 34736, 1, 3,
        3081, 34736, 1, 4,
    ];
    let tags = |a: f64| {
        vec![
            (Tag::ModelPixelScaleTag, vec![2.0, 2.0, 0.0]),
            (
                Tag::ModelTiepointTag,
                vec![0.0, 0.0, 0.0, 100.0, 200.0, 0.0],
            ),
            (Tag::GeoDoubleParamsTag, vec![a, a, 18.4663, 77.0, 10.0]),
        ]
    };
    let p = tmp(&dir, "gdal-mars.tif");
    tiff_with_tags(&p, &tags(3_396_190.0), Some(&keys), None);
    let crs = maps::raster_io::read_map_crs(&p).unwrap();
    let maps::MapCrs::Mars(m) = crs else {
        panic!("{crs:?}")
    };
    assert_eq!(
        (m.central_meridian_deg, m.true_scale_latitude_deg),
        (77.0, 18.4663)
    );
    assert_eq!(m.false_easting_m, 0.0);
    let [_, lat] = m.lonlat_from_map([0.0, 0.0]);
    assert!((lat - 10.0).abs() < 1e-12, "{lat}");
    let p = tmp(&dir, "gdal-earth.tif");
    tiff_with_tags(&p, &tags(6_378_137.0), Some(&keys), None);
    assert_eq!(
        maps::raster_io::read_map_crs(&p).unwrap(),
        maps::MapCrs::Local
    );
    // Georeference unaffected either way.
    assert_eq!(
        read_geotiff::<u16>(&p, None).unwrap().raster.geo,
        GeoTransform::new(100.0, 200.0, 2.0)
    );
}

/// Writes a 4x3 u16 TIFF with arbitrary georeferencing tags, as other tools would.
fn tiff_with_tags(
    path: &Path,
    tags: &[(Tag, Vec<f64>)],
    geokeys: Option<&[u16]>,
    nodata: Option<&str>,
) {
    let f = fs::File::create(path).unwrap();
    let mut enc = TiffEncoder::new(f).unwrap();
    let mut img = enc.new_image::<colortype::Gray16>(4, 3).unwrap();
    for (tag, values) in tags {
        img.encoder().write_tag(*tag, values.as_slice()).unwrap();
    }
    if let Some(keys) = geokeys {
        img.encoder()
            .write_tag(Tag::GeoKeyDirectoryTag, keys)
            .unwrap();
    }
    if let Some(text) = nodata {
        img.encoder().write_tag(Tag::GdalNodata, text).unwrap();
    }
    img.write_data(&(0..12).collect::<Vec<u16>>()).unwrap();
}

fn tmp(dir: &tempfile::TempDir, name: &str) -> PathBuf {
    dir.path().join(name)
}

#[test]
fn gdal_like_georeferences_are_understood() {
    let dir = tempfile::tempdir().unwrap();
    let scale = (Tag::ModelPixelScaleTag, vec![2.0, 2.0, 0.0]);

    // Tiepoint at raster point (10, 20), not at pixel (0, 0).
    let p = tmp(&dir, "tie.tif");
    tiff_with_tags(
        &p,
        &[
            scale.clone(),
            (
                Tag::ModelTiepointTag,
                vec![10.0, 20.0, 0.0, 500.0, 800.0, 0.0],
            ),
        ],
        None,
        None,
    );
    let g = read_geotiff::<u16>(&p, None).unwrap().raster.geo;
    assert_eq!(g, GeoTransform::new(480.0, 840.0, 2.0));

    // Several tiepoints on one grid are fine.
    let p = tmp(&dir, "ties.tif");
    let ties = vec![
        0.0, 0.0, 0.0, 480.0, 840.0, 0.0, 4.0, 3.0, 0.0, 488.0, 834.0, 0.0,
    ];
    tiff_with_tags(
        &p,
        &[scale.clone(), (Tag::ModelTiepointTag, ties)],
        None,
        None,
    );
    assert_eq!(
        read_geotiff::<u16>(&p, None).unwrap().raster.geo,
        GeoTransform::new(480.0, 840.0, 2.0)
    );

    // PixelIsPoint: the tiepoint is the centre of pixel (0, 0).
    let p = tmp(&dir, "point.tif");
    let keys = [1, 1, 0, 2, 1024, 0, 1, 1, 1025, 0, 1, 2];
    tiff_with_tags(
        &p,
        &[
            scale.clone(),
            (
                Tag::ModelTiepointTag,
                vec![0.0, 0.0, 0.0, 481.0, 839.0, 0.0],
            ),
        ],
        Some(&keys),
        None,
    );
    assert_eq!(
        read_geotiff::<u16>(&p, None).unwrap().raster.geo,
        GeoTransform::new(480.0, 840.0, 2.0)
    );

    // ModelTransformation without rotation.
    let p = tmp(&dir, "matrix.tif");
    let m = vec![
        2.0, 0.0, 0.0, 480.0, 0.0, -2.0, 0.0, 840.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];
    tiff_with_tags(&p, &[(Tag::ModelTransformationTag, m)], None, None);
    assert_eq!(
        read_geotiff::<u16>(&p, None).unwrap().raster.geo,
        GeoTransform::new(480.0, 840.0, 2.0)
    );
}

/// (file name, tags, GeoKey directory, expected words in the message).
type Case = (
    &'static str,
    Vec<(Tag, Vec<f64>)>,
    Option<Vec<u16>>,
    &'static str,
);

#[test]
fn unusable_georeferences_are_rejected_clearly() {
    let dir = tempfile::tempdir().unwrap();
    let tie = (
        Tag::ModelTiepointTag,
        vec![0.0, 0.0, 0.0, 480.0, 840.0, 0.0],
    );
    let cases: Vec<Case> = vec![
        (
            "nonsquare",
            vec![(Tag::ModelPixelScaleTag, vec![2.0, 1.0, 0.0]), tie.clone()],
            None,
            "non-square pixels",
        ),
        (
            "flipped",
            vec![(Tag::ModelPixelScaleTag, vec![2.0, -2.0, 0.0]), tie.clone()],
            None,
            "flipped",
        ),
        (
            "scale_only",
            vec![(Tag::ModelPixelScaleTag, vec![2.0, 2.0, 0.0])],
            None,
            "without a ModelTiepoint",
        ),
        ("gcps", vec![tie.clone()], None, "ground control points"),
        (
            "gcp_grid",
            vec![
                (Tag::ModelPixelScaleTag, vec![2.0, 2.0, 0.0]),
                (
                    Tag::ModelTiepointTag,
                    vec![
                        0.0, 0.0, 0.0, 480.0, 840.0, 0.0, 3.0, 0.0, 0.0, 499.0, 840.0, 0.0,
                    ],
                ),
            ],
            None,
            "do not lie on one grid",
        ),
        (
            "rotated",
            vec![(
                Tag::ModelTransformationTag,
                vec![
                    1.7, 1.0, 0.0, 480.0, 1.0, -1.7, 0.0, 840.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
                    1.0,
                ],
            )],
            None,
            "rotated",
        ),
        (
            "degrees",
            vec![
                (Tag::ModelPixelScaleTag, vec![0.001, 0.001, 0.0]),
                tie.clone(),
            ],
            Some(vec![1, 1, 0, 1, 1024, 0, 1, 2]),
            "geographic",
        ),
        (
            "feet",
            vec![(Tag::ModelPixelScaleTag, vec![2.0, 2.0, 0.0]), tie.clone()],
            Some(vec![1, 1, 0, 1, 3076, 0, 1, 9002]),
            "ProjLinearUnitsGeoKey = 9002",
        ),
    ];
    for (name, tags, keys, needle) in cases {
        let p = tmp(&dir, &format!("{name}.tif"));
        tiff_with_tags(&p, &tags, keys.as_deref(), None);
        let e = read_geotiff::<u16>(&p, None).unwrap_err();
        assert!(
            matches!(e, RasterError::BadGeoreference { .. }),
            "{name}: {e}"
        );
        let msg = one_line(&e, &p);
        assert!(msg.contains(needle), "{name}: {msg}");
        // An override makes any of them usable.
        assert_eq!(
            read_geotiff::<u16>(&p, Some(geo())).unwrap().raster.geo,
            geo()
        );
    }

    let p = tmp(&dir, "plain.tif");
    tiff_with_tags(&p, &[], None, None);
    let e = read_geotiff::<u16>(&p, None).unwrap_err();
    assert!(matches!(e, RasterError::MissingGeoreference { .. }), "{e}");
    one_line(&e, &p);
    assert_eq!(
        read_geotiff::<u16>(&p, Some(geo())).unwrap().raster.geo,
        geo()
    );
    let bad = GeoTransform::new(0.0, 0.0, 0.0);
    assert!(matches!(
        read_geotiff::<u16>(&p, Some(bad)),
        Err(RasterError::BadGeoreference { .. })
    ));

    let p = tmp(&dir, "nodata.tif");
    tiff_with_tags(&p, &[], None, Some("none"));
    let e = read_geotiff::<u16>(&p, Some(geo())).unwrap_err();
    assert!(matches!(e, RasterError::BadNodata { .. }), "{e}");
    one_line(&e, &p);
    tiff_with_tags(&p, &[], None, Some(" -9999 "));
    assert_eq!(
        read_geotiff::<u16>(&p, Some(geo())).unwrap().nodata,
        Some(-9999.0)
    );
}

#[test]
fn dems_read_from_cm_png_cm_tiff_and_metre_tiff() {
    let dir = tempfile::tempdir().unwrap();
    let dem = ramp(20, 10, |i| 100.0 + i as f32 * 0.013);
    let datum = -50.0;

    for name in ["dem.png", "dem.tif"] {
        let p = tmp(&dir, name);
        write_dem(&p, &dem, datum).unwrap();
        let back = read_dem(&p, datum, Some(geo())).unwrap();
        assert_eq!(back.geo, geo());
        for (a, b) in back.data.iter().zip(&dem.data) {
            assert!((a - b).abs() <= 0.005 + 1e-4, "{name}: {a} vs {b}");
        }
    }
    let p = tmp(&dir, "dem_m.tif");
    write_geotiff(&p, &dem, None).unwrap();
    assert_eq!(read_dem(&p, datum, None).unwrap(), dem);

    // Holes are bad input.
    let mut holed = dem.clone();
    holed.data[13] = f32::NAN;
    write_geotiff(&p, &holed, None).unwrap();
    let e = read_dem(&p, datum, None).unwrap_err();
    assert!(
        matches!(e, RasterError::NonFinite { pixel: (13, 0), .. }),
        "{e}"
    );
    one_line(&e, &p);
    holed.data[13] = -9999.0;
    write_geotiff(&p, &holed, Some(-9999.0)).unwrap();
    let e = read_dem(&p, datum, None).unwrap_err();
    assert!(
        matches!(e, RasterError::NoData { pixel: (13, 0), .. }),
        "{e}"
    );
    let p16 = tmp(&dir, "holed_cm.tif");
    write_geotiff(
        &p16,
        &ramp(4, 4, |i| if i == 5 { 0u16 } else { 100 }),
        Some(0.0),
    )
    .unwrap();
    assert!(matches!(
        read_dem(&p16, datum, None),
        Err(RasterError::NoData { pixel: (1, 1), .. })
    ));

    // 8-bit is not a DEM; out-of-range heights are not written.
    let p8 = tmp(&dir, "dem8.tif");
    write_geotiff(&p8, &ramp(2, 2, |_| 1u8), None).unwrap();
    assert!(matches!(
        read_dem(&p8, datum, None),
        Err(RasterError::WrongSampleFormat { .. })
    ));
    let e = write_dem(&tmp(&dir, "high.tif"), &ramp(2, 2, |_| 700.0), 0.0).unwrap_err();
    assert!(matches!(e, RasterError::HeightOutOfRange { .. }), "{e}");
    assert!(
        one_line(&e, &tmp(&dir, "high.tif")).contains("0..=655.35 m"),
        "{e}"
    );
    assert!(!tmp(&dir, "high.tif").exists());
}

fn sample_layers() -> MapLayers {
    let g = GeoTransform::new(1000.0, 5000.0, 1.0);
    MapLayers {
        appearance: Raster {
            width: 40,
            height: 30,
            geo: g,
            data: (0..1200).map(|i| (i % 256) as u8).collect(),
        },
        // Half the resolution, same extent.
        dem: Raster {
            width: 20,
            height: 15,
            geo: g.scaled(2.0),
            data: (0..300).map(|i| 120.0 + i as f32 * 0.01).collect(),
        },
        terrain: Raster {
            width: 40,
            height: 30,
            geo: g,
            data: (0..1200).map(|i| (i % 4) as u8).collect(),
        },
    }
}

#[test]
fn map_layers_write_dir_and_load_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nested/map");
    let layers = sample_layers();
    layers.write_dir(&out, 100.0, &maps::MapCrs::Local).unwrap();
    let names: Vec<_> = {
        let mut v: Vec<_> = fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        v.sort();
        v
    };
    assert_eq!(names, ["appearance.tif", "dem.tif", "terrain.tif"]);
    let back = MapLayers::load(
        &out.join(MapLayers::APPEARANCE_FILE),
        &out.join(MapLayers::DEM_FILE),
        &out.join(MapLayers::TERRAIN_FILE),
        100.0,
        None,
    )
    .unwrap();
    assert_eq!(back.appearance, layers.appearance);
    assert_eq!(back.terrain, layers.terrain);
    assert_eq!(back.dem.geo, layers.dem.geo);
    for (a, b) in back.dem.data.iter().zip(&layers.dem.data) {
        assert!((a - b).abs() <= 0.005 + 1e-4);
    }
    // The terrain layer declares 0 as no data.
    assert_eq!(
        read_geotiff::<u8>(&out.join("terrain.tif"), None)
            .unwrap()
            .nodata,
        Some(0.0)
    );
}

#[test]
fn map_layers_reject_mismatched_extents_and_bad_codes() {
    let dir = tempfile::tempdir().unwrap();
    let (a, d, t) = (tmp(&dir, "a.tif"), tmp(&dir, "d.tif"), tmp(&dir, "t.tif"));
    let layers = sample_layers();
    write_geotiff(&a, &layers.appearance, None).unwrap();
    write_geotiff(&d, &layers.dem, None).unwrap();
    write_geotiff(&t, &layers.terrain, None).unwrap();
    MapLayers::load(&a, &d, &t, 0.0, None).unwrap();

    // Shifted by less than half a coarse pixel (1 m): accepted; by more: rejected.
    let mut dem = layers.dem.clone();
    dem.geo.origin_m[0] += 0.9;
    write_geotiff(&d, &dem, None).unwrap();
    MapLayers::load(&a, &d, &t, 0.0, None).unwrap();
    dem.geo.origin_m[0] += 0.2;
    write_geotiff(&d, &dem, None).unwrap();
    let e = MapLayers::load(&a, &d, &t, 0.0, None).unwrap_err();
    assert!(matches!(e, RasterError::ExtentMismatch { .. }), "{e}");
    let msg = one_line(&e, &d);
    assert!(
        msg.contains(&a.display().to_string()) && msg.contains("within 1 m"),
        "{msg}"
    );
    write_geotiff(&d, &layers.dem, None).unwrap();

    let mut terrain = layers.terrain.clone();
    terrain.data[45] = 7;
    write_geotiff(&t, &terrain, None).unwrap();
    let e = MapLayers::load(&a, &d, &t, 0.0, None).unwrap_err();
    assert!(
        matches!(
            e,
            RasterError::BadTerrainCode {
                code: 7,
                pixel: (5, 1),
                ..
            }
        ),
        "{e}"
    );
    assert!(
        one_line(&e, &t).contains("expected terrain codes 0..=3"),
        "{e}"
    );

    // write_dir validates everything before writing anything.
    let out = tmp(&dir, "out");
    let bad = MapLayers {
        terrain,
        ..layers.clone()
    };
    assert!(matches!(
        bad.write_dir(&out, 0.0, &maps::MapCrs::Local),
        Err(RasterError::BadTerrainCode { .. })
    ));
    let e = layers
        .write_dir(&out, 200.0, &maps::MapCrs::Local)
        .unwrap_err();
    assert!(matches!(e, RasterError::HeightOutOfRange { .. }), "{e}");
    one_line(&e, &out.join("dem.tif"));
    assert!(!out.exists());

    // PNG layers share one GeoTransform, so they must share a pixel size.
    let (ap, dp, tp) = (tmp(&dir, "a.png"), tmp(&dir, "d.png"), tmp(&dir, "t.png"));
    write_png(&ap, &layers.appearance).unwrap();
    write_dem(&dp, &layers.dem, 0.0).unwrap();
    write_png(&tp, &layers.terrain).unwrap();
    let e = MapLayers::load(&ap, &dp, &tp, 0.0, Some(layers.appearance.geo)).unwrap_err();
    assert!(
        matches!(
            e,
            RasterError::SizeMismatch {
                expected: (40, 30),
                found: (20, 15),
                ..
            }
        ),
        "{e}"
    );
    one_line(&e, &dp);
    assert!(matches!(
        MapLayers::load(&ap, &dp, &tp, 0.0, None),
        Err(RasterError::MissingGeoreference { .. })
    ));
}
