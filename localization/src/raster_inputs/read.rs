//! Reading one input raster of a localization: placed on the map by its GeoTIFF tags or the
//! options, a rover raster by its pixel size, a validity mask by its size; and the memory
//! budget of them all, from their headers.

use std::path::Path;

use maps::raster_io::{read_header, read_raster_with_nodata};
use maps::{GeoTransform, MemoryBudget, RasterError};

use super::error::LocalizeInputError;
use super::inputs::LocalizeRequest;

/// Two resolutions or origins closer than this (relative) are the same.
const SAME_TOLERANCE: f64 = 1e-9;

/// `true` if `a` and `b` agree to [`SAME_TOLERANCE`] (relative).
pub(super) fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME_TOLERANCE * a.abs().max(b.abs()).max(1.0)
}

/// A raster read error, named by its option.
fn raster(input: &'static str) -> impl FnOnce(RasterError) -> LocalizeInputError {
    move |source| LocalizeInputError::Raster {
        input,
        source: Box::new(source),
    }
}

/// Reads a map-frame raster: the GeoTIFF's georeference, else the options'.
pub(super) fn read_placed<R>(
    flag: &'static str,
    path: &Path,
    flags: (&'static str, Option<[f64; 2]>, &'static str, Option<f64>),
    read: impl Fn(Option<GeoTransform>) -> Result<R, RasterError>,
    geo_of: impl Fn(&R) -> GeoTransform,
) -> Result<R, LocalizeInputError> {
    let (origin_flag, origin, res_flag, res) = flags;
    let half_pair = |input, partner| Err(LocalizeInputError::HalfPair { input, partner });
    let given = match (origin, res) {
        (Some([x, y]), Some(r)) => Some(GeoTransform::new(x, y, r)),
        (None, None) => None,
        (Some(_), None) => return half_pair(res_flag, origin_flag),
        (None, Some(_)) => return half_pair(origin_flag, res_flag),
    };
    let r = match read(None) {
        Ok(r) => r,
        Err(RasterError::MissingGeoreference { .. }) => match given {
            Some(g) => read(Some(g)).map_err(raster(flag))?,
            None => {
                return Err(LocalizeInputError::Found {
                    input: format!("{flag} {}", path.display()),
                    expected: "a georeference".to_owned(),
                    found: format!(
                        "none (a PNG never has one): give {origin_flag} X,Y and {res_flag} M"
                    ),
                });
            }
        },
        Err(e) => return Err(raster(flag)(e)),
    };
    let file_geo = geo_of(&r);
    if let Some(g) = given
        && !(same(g.origin_m[0], file_geo.origin_m[0])
            && same(g.origin_m[1], file_geo.origin_m[1])
            && same(g.resolution_m_per_px, file_geo.resolution_m_per_px))
    {
        return Err(LocalizeInputError::Contradiction {
            input: format!("{flag} {}", path.display()),
            conflict: format!(
                "the GeoTIFF's own georeference (origin {},{} m, {} m/px) contradicts \
                 {origin_flag} {},{} / {res_flag} {}",
                file_geo.origin_m[0],
                file_geo.origin_m[1],
                file_geo.resolution_m_per_px,
                g.origin_m[0],
                g.origin_m[1],
                g.resolution_m_per_px
            ),
            expected: "them to agree (drop the flags)".to_owned(),
        });
    }
    Ok(r)
}

/// Where a rover raster's pixel size came from, for error messages.
#[derive(Clone, Copy, Debug)]
pub(super) enum ResolutionSource {
    /// Its GeoTIFF tags.
    File,
    /// The option.
    Flag,
    /// The default.
    Default,
}

/// Reads a rover-frame raster, whose only georeferencing is its pixel size: the option's, else
/// the GeoTIFF's, else `default`; an option that contradicts the GeoTIFF is an error.
pub(super) fn read_rover<R>(
    flag: &'static str,
    path: &Path,
    res_flag: (&str, Option<f64>),
    default_m_per_px: f64,
    read: impl Fn(Option<GeoTransform>) -> Result<R, RasterError>,
    geo_of: impl Fn(&mut R) -> &mut GeoTransform,
) -> Result<(R, ResolutionSource), LocalizeInputError> {
    let (res_flag, res) = res_flag;
    let placed = |r: f64| GeoTransform::new(0.0, 0.0, r);
    match read(None) {
        Ok(mut r) => {
            let file_res = geo_of(&mut r).resolution_m_per_px;
            if let Some(given) = res
                && !same(given, file_res)
            {
                return Err(LocalizeInputError::Contradiction {
                    input: format!("{flag} {}", path.display()),
                    conflict: format!(
                        "the GeoTIFF's pixel size {file_res} m/px contradicts {res_flag} {given}"
                    ),
                    expected: "them to agree".to_owned(),
                });
            }
            Ok((r, ResolutionSource::File))
        }
        Err(RasterError::MissingGeoreference { .. }) => {
            let (res, source) = match res {
                Some(r) => (r, ResolutionSource::Flag),
                None => (default_m_per_px, ResolutionSource::Default),
            };
            let r = read(Some(placed(res))).map_err(raster(flag))?;
            Ok((r, source))
        }
        Err(e) => Err(raster(flag)(e)),
    }
}

/// Reads a validity mask (8-bit, nonzero = valid) that must be `width × height` like `of`.
pub(super) fn read_mask(
    flag: &'static str,
    path: &Path,
    (width, height): (usize, usize),
    of: (&str, &Path),
) -> Result<Vec<bool>, LocalizeInputError> {
    let (mask, _) = read_raster_with_nodata::<u8>(path, Some(GeoTransform::new(0.0, 0.0, 1.0)))
        .map_err(raster(flag))?;
    if (mask.width, mask.height) != (width, height) {
        return Err(LocalizeInputError::Found {
            input: format!("{flag} {}", path.display()),
            expected: format!("{width}x{height} px like {} {}", of.0, of.1.display()),
            found: format!("{}x{} px", mask.width, mask.height),
        });
    }
    Ok(mask.data.iter().map(|&v| v != 0).collect())
}

/// Checks every raster input against `budget` from its header, before any is decoded: the
/// rasters as held (u8 images and masks with their decode buffers and validity masks, 2 bytes
/// per pixel; DEMs as f32 with their 16-bit decode buffer and hole mask, 7) plus the matcher's
/// census and score planes over the orbital orthoimage (8 bytes per map pixel). Over it, the
/// largest input is named.
pub(super) fn check_budget(
    a: &LocalizeRequest,
    budget: MemoryBudget,
) -> Result<(), LocalizeInputError> {
    let mut inputs = vec![
        ("--map-appearance", &a.map_appearance, 2 + 8),
        ("--ortho", &a.ortho, 2),
    ];
    for (flag, path, bytes_per_px) in [
        ("--map-dem", &a.map_dem, 7),
        ("--ortho-valid", &a.ortho_valid, 2),
        ("--rover-dem", &a.rover_dem, 7),
        ("--rover-dem-valid", &a.rover_dem_valid, 2),
    ] {
        if let Some(path) = path {
            inputs.push((flag, path, bytes_per_px));
        }
    }
    let mut sized = Vec::with_capacity(inputs.len());
    for (flag, path, bytes_per_px) in inputs {
        let h = read_header(path).map_err(raster(flag))?;
        sized.push((flag, path, h, h.bytes_as(bytes_per_px)));
    }
    let total = sized.iter().fold(0u64, |t, s| t.saturating_add(s.3));
    match sized.iter().max_by_key(|s| s.3) {
        Some((flag, path, h, need)) if !budget.allows(total) => {
            Err(raster(flag)(h.over_budget(path, *need, budget)))
        }
        _ => Ok(()),
    }
}
