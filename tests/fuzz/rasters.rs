//! The raster targets: seeds (small rasters from solsim's own writers, crops of the bundled
//! maps, hand-built files of layouts it never writes) and the read of one input in the
//! scenario loader's order: header, memory budget, then every reader.

use std::path::Path;

use maps::raster_io::{self, RasterHeader};
use maps::{GeoTransform, MemoryBudget, Raster};

use super::kinds::{raster_kind, variant};
use super::seeds::{Georef, TiffSpec};

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Memory budget of the raster reads: the header is checked against it before decoding.
pub const RASTER_BUDGET: MemoryBudget = MemoryBudget::new(64 << 20);
/// Most heap one raster input may hold: twice the budget for the decode, plus the 256 MiB the
/// tiff crate may reserve for one tag value while `Decoder::new` reads the first IFD under its
/// default limits (before a caller can set its own; mostly untouched pages).
pub const RASTER_MEMORY_LIMIT: usize = (256 << 20) + 2 * (RASTER_BUDGET.limit_bytes as usize);

/// Writes `input` to a new file `input-<n>.<ext>` in `dir` and reads it as the scenario loader
/// does: header, budget, then the readers. Accepted when any reader accepts it. (A new file
/// each time: rewriting one file in place makes ext4 flush it to disk on every input.)
pub fn read_raster_file(dir: &Path, ext: &str, n: &mut usize, input: &[u8]) -> Result<(), String> {
    *n += 1;
    let path = dir.join(format!("input-{n}.{ext}"));
    std::fs::write(&path, input).expect("write raster input");
    let result = read_raster(&path);
    std::fs::remove_file(&path).expect("remove raster input");
    result
}

pub fn read_raster(path: &Path) -> Result<(), String> {
    let header: RasterHeader =
        raster_io::read_header(path).map_err(|e| format!("header: {}", raster_kind(&e)))?;
    // As `Scenario::build` counts a DEM: f32 metres, its 16-bit decode buffer and its slopes.
    let need = header.bytes_as(10).max(header.decoded_bytes());
    header
        .check(path, need, RASTER_BUDGET)
        .map_err(|e| format!("budget: {}", variant(&e)))?;
    let geo = Some(GeoTransform::new(100.0, 500.0, 2.0));
    let tif = path.extension().is_some_and(|e| e == "tif");
    let georef_from_file = if tif { None } else { geo };
    let mut outcomes = vec![
        raster_io::read_raster::<u8>(path, georef_from_file).map(|r| r.data.len()),
        raster_io::read_raster::<u16>(path, geo).map(|r| r.data.len()),
        raster_io::read_dem(path, 0.0, georef_from_file).map(|r| r.data.len()),
        raster_io::read_dem_with_holes(path, -50.0, geo).map(|r| r.data.len()),
        raster_io::read_raster_with_nodata::<u8>(path, geo).map(|r| r.0.data.len()),
    ];
    if tif {
        outcomes.push(raster_io::read_geotiff::<f32>(path, None).map(|g| g.raster.data.len()));
    }
    let px = header.width.saturating_mul(header.height);
    let mut kinds = Vec::new();
    let mut accepted = false;
    for o in &outcomes {
        match o {
            Ok(n) => {
                assert_eq!(
                    *n as u64, px,
                    "samples read for a {}×{} header",
                    header.width, header.height
                );
                accepted = true;
                kinds.push("ok".to_owned());
            }
            Err(e) => kinds.push(raster_kind(e)),
        }
    }
    if accepted {
        Ok(())
    } else {
        Err(kinds.join("/"))
    }
}

/// PNG and TIFF seeds: small rasters from solsim's own writers (including crops of the bundled
/// maps) and hand-built files of layouts it never writes.
pub fn raster_seeds(scratch: &Path, root: &Path) -> (Vec<Vec<u8>>, Vec<Vec<u8>>) {
    let dir = scratch.join("seeds");
    std::fs::create_dir_all(&dir).expect("seed dir");
    let geo = GeoTransform::new(100.0, 500.0, 2.0);
    let gradient_u8 = |w: usize, h: usize| Raster {
        width: w,
        height: h,
        geo,
        data: (0..w * h).map(|i| (i * 7 % 251) as u8).collect(),
    };
    let dem = |w: usize, h: usize| Raster {
        width: w,
        height: h,
        geo,
        data: (0..w * h)
            .map(|i| 100.0 + (i % 37) as f32 * 0.5)
            .collect::<Vec<f32>>(),
    };
    let written = |name: &str, write: &dyn Fn(&Path)| {
        let p = dir.join(name);
        write(&p);
        read(&p)
    };

    let mut png = vec![
        raster_io::encode_png(&gradient_u8(1, 1), &dir.join("a.png")).expect("png"),
        raster_io::encode_png(&gradient_u8(33, 17), &dir.join("b.png")).expect("png"),
        written("dem.png", &|p| {
            raster_io::write_dem(p, &dem(20, 24), 0.0).expect("dem png")
        }),
    ];
    for (w, h, color, bits) in [
        (9, 7, 0, 8),
        (9, 7, 0, 16),
        (5, 4, 0, 1),
        (6, 5, 2, 8),
        (6, 5, 3, 4),
        (4, 4, 4, 8),
        (4, 3, 6, 16),
    ] {
        png.push(super::seeds::png(w, h, color, bits, &[], None));
    }
    let text = super::mutate::png_chunk(b"tEXt", b"Comment\0fuzz seed");
    png.push(super::seeds::png(16, 16, 0, 8, &[text], None));
    // Image data that inflates far past what the header needs.
    png.push(super::seeds::png(16, 16, 0, 8, &[], Some(2_000_000)));

    let crater = root.join("maps/assets/crater-floor");
    let crop_dem = raster_io::read_dem(&crater.join("dem.tif"), 0.0, None)
        .expect("bundled DEM")
        .try_crop(200, 300, 40, 30)
        .expect("crop");
    let crop_app = raster_io::read_raster::<u8>(&crater.join("appearance.tif"), None)
        .expect("bundled appearance")
        .try_crop(200, 300, 40, 30)
        .expect("crop");
    let mut tiff = vec![
        written("dem-crop.tif", &|p| {
            raster_io::write_dem(p, &crop_dem, 0.0).expect("dem")
        }),
        written("app-crop.tif", &|p| {
            raster_io::write_raster(p, &crop_app).expect("tif")
        }),
        written("f32.tif", &|p| {
            raster_io::write_raster(p, &dem(13, 11)).expect("tif")
        }),
        written("nodata.tif", &|p| {
            raster_io::write_geotiff(p, &gradient_u8(12, 9), Some(0.0)).expect("tif");
        }),
        read(&crater.join("terrain.tif")),
    ];
    let base = TiffSpec {
        big_endian: false,
        width: 9,
        height: 7,
        bits: 8,
        sample_format: 1,
        samples_per_pixel: 1,
        tile: None,
        rows_per_strip: 3,
        nodata: None,
        georef: Georef::ScaleTiepoint,
    };
    for spec in [
        base,
        TiffSpec {
            big_endian: true,
            bits: 16,
            nodata: Some("65535"),
            ..base
        },
        TiffSpec {
            bits: 32,
            sample_format: 3,
            georef: Georef::Transformation,
            nodata: Some("-9999"),
            ..base
        },
        TiffSpec {
            big_endian: true,
            bits: 32,
            sample_format: 3,
            tile: Some(16),
            width: 20,
            height: 18,
            ..base
        },
        TiffSpec {
            tile: Some(16),
            georef: Georef::None,
            ..base
        },
        TiffSpec {
            samples_per_pixel: 3,
            ..base
        },
        TiffSpec {
            bits: 16,
            rows_per_strip: 1,
            nodata: Some("nan"),
            ..base
        },
    ] {
        tiff.push(super::seeds::tiff(&spec));
    }
    (png, tiff)
}
