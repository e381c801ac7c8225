//! Reading and checking a [`LocalizeRequest`]: the options first, then the memory budget from
//! the raster headers, then each raster, its georeference and validity, and last the search
//! window on the map.

use std::path::Path;

use maps::MemoryBudget;
use maps::raster_io::{read_dem_with_holes, read_raster, read_raster_with_nodata};

use super::error::LocalizeInputError;
use super::inputs::{
    DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX, LocalizeInputs, LocalizeRequest, MAX_RADIUS_M,
};
use super::read::{ResolutionSource, check_budget, read_mask, read_placed, read_rover, same};
use crate::matcher::{MatchSettings, Method};

/// An unusable option value.
fn option(input: &str, expected: impl Into<String>, got: String) -> LocalizeInputError {
    LocalizeInputError::Option {
        input: input.to_owned(),
        expected: expected.into(),
        got,
    }
}

/// Checks that the numeric options are usable before any file is read.
fn check_flags(a: &LocalizeRequest) -> Result<Method, LocalizeInputError> {
    let Some(method) = Method::from_name(&a.method) else {
        return Err(option(
            "--method",
            "census, ncc or mi",
            format!("{:?}", a.method),
        ));
    };
    if !(a.radius.is_finite() && a.radius > 0.0 && a.radius <= MAX_RADIUS_M) {
        return Err(option(
            "--radius",
            format!("a search radius in (0, {MAX_RADIUS_M}] metres"),
            a.radius.to_string(),
        ));
    }
    if !(a.latitude.is_finite() && a.latitude.abs() < 90.0) {
        return Err(option(
            "--latitude",
            "degrees strictly between -90 and 90",
            a.latitude.to_string(),
        ));
    }
    for (flag, xy) in [
        ("--prior", Some(a.prior)),
        ("--map-origin", a.map_origin),
        ("--map-dem-origin", a.map_dem_origin),
    ] {
        if let Some([x, y]) = xy
            && !(x.is_finite() && y.is_finite())
        {
            return Err(option(
                flag,
                "finite map coordinates X,Y in metres",
                format!("{x},{y}"),
            ));
        }
    }
    for (flag, res) in [
        ("--map-resolution", a.map_resolution),
        ("--map-dem-resolution", a.map_dem_resolution),
        ("--ortho-resolution", a.ortho_resolution),
        ("--rover-dem-resolution", a.rover_dem_resolution),
    ] {
        if let Some(r) = res
            && !(r.is_finite() && r > 0.0)
        {
            return Err(option(
                flag,
                "a positive pixel size in metres per pixel",
                r.to_string(),
            ));
        }
    }
    if a.rover_dem_valid.is_some() && a.rover_dem.is_none() {
        return Err(LocalizeInputError::WithoutPartner {
            input: "--rover-dem-valid".to_owned(),
            partner: "--rover-dem",
        });
    }
    if a.map_dem.is_none() && (a.map_dem_origin.is_some() || a.map_dem_resolution.is_some()) {
        return Err(LocalizeInputError::WithoutPartner {
            input: "--map-dem-origin / --map-dem-resolution".to_owned(),
            partner: "--map-dem",
        });
    }
    Ok(method)
}

/// A file or option that holds something else than expected.
fn found(input: String, expected: String, found: String) -> LocalizeInputError {
    LocalizeInputError::Found {
        input,
        expected,
        found,
    }
}

/// Reads and checks every file and option; each failure is one line naming the file or option.
///
/// # Errors
/// Unreadable or missing files, wrong pixel types, missing or contradictory georeferences,
/// masks of the wrong size, no valid pixels, resolution mismatches, a prior off the map, a
/// search window leaving the map, non-finite or out-of-range options, rasters over `budget`.
pub fn load(
    a: &LocalizeRequest,
    budget: MemoryBudget,
) -> Result<LocalizeInputs, LocalizeInputError> {
    let method = check_flags(a)?;
    check_budget(a, budget)?;
    let appearance = read_placed(
        "--map-appearance",
        &a.map_appearance,
        (
            "--map-origin",
            a.map_origin,
            "--map-resolution",
            a.map_resolution,
        ),
        |g| read_raster::<u8>(&a.map_appearance, g),
        |r| r.geo,
    )?;
    let map_res = appearance.geo.resolution_m_per_px;
    let map_dem = match &a.map_dem {
        Some(path) => Some(read_placed(
            "--map-dem",
            path,
            (
                "--map-dem-origin",
                a.map_dem_origin,
                "--map-dem-resolution",
                a.map_dem_resolution,
            ),
            |g| read_dem_with_holes(path, 0.0, g),
            |r| r.geo,
        )?),
        None => None,
    };

    let ((mut ortho, nodata), ortho_res_source) = read_rover(
        "--ortho",
        &a.ortho,
        ("--ortho-resolution", a.ortho_resolution),
        map_res,
        |g| read_raster_with_nodata::<u8>(&a.ortho, g),
        |(r, _)| &mut r.geo,
    )?;
    let ortho_res = ortho.geo.resolution_m_per_px;
    if !same(ortho_res, map_res) {
        let from = match ortho_res_source {
            ResolutionSource::File => "from its GeoTIFF tags",
            ResolutionSource::Flag => "from --ortho-resolution",
            ResolutionSource::Default => "the default",
        };
        return Err(found(
            format!("--ortho {}", a.ortho.display()),
            format!(
                "the orbital orthoimage's resolution {map_res} m/px ({})",
                a.map_appearance.display()
            ),
            format!("{ortho_res} m/px ({from}); resample one of them"),
        ));
    }
    // The matcher compares to 1e-9 m/px; pin the orthomosaic to the map's exact value.
    ortho.geo.resolution_m_per_px = map_res;
    let ortho_valid = match &a.ortho_valid {
        Some(path) => {
            let v = read_mask(
                "--ortho-valid",
                path,
                (ortho.width, ortho.height),
                ("--ortho", &a.ortho),
            )?;
            if !v.contains(&true) {
                return Err(found(
                    format!("--ortho-valid {}", path.display()),
                    "at least one valid (nonzero) pixel".to_owned(),
                    "none".to_owned(),
                ));
            }
            v
        }
        None => {
            let invalid = nodata.unwrap_or(0.0);
            let v: Vec<bool> = ortho
                .data
                .iter()
                .map(|&p| f64::from(p) != invalid)
                .collect();
            if !v.contains(&true) {
                return Err(found(
                    format!("--ortho {}", a.ortho.display()),
                    "at least one valid pixel".to_owned(),
                    format!(
                        "every pixel equal to the no-data value {invalid} (give --ortho-valid \
                         MASK if 0 is real data)"
                    ),
                ));
            }
            v
        }
    };

    let rover_dem = match &a.rover_dem {
        Some(path) => {
            let (mut dem, source) = read_rover(
                "--rover-dem",
                path,
                ("--rover-dem-resolution", a.rover_dem_resolution),
                DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX,
                |g| read_dem_with_holes(path, 0.0, g),
                |r| &mut r.geo,
            )?;
            if let Some(mdem) = &map_dem {
                let (rres, mres) = (dem.geo.resolution_m_per_px, mdem.geo.resolution_m_per_px);
                if !same(rres, mres) {
                    let from = match source {
                        ResolutionSource::File => "from its GeoTIFF tags",
                        ResolutionSource::Flag => "from --rover-dem-resolution",
                        ResolutionSource::Default => "the default; set --rover-dem-resolution",
                    };
                    return Err(found(
                        format!("--rover-dem {}", path.display()),
                        format!(
                            "the orbital DEM's resolution {mres} m/px ({})",
                            a.map_dem.as_deref().unwrap_or(Path::new("")).display()
                        ),
                        format!("{rres} m/px ({from})"),
                    ));
                }
                dem.geo.resolution_m_per_px = mres;
            }
            let mut valid: Vec<bool> = dem.data.iter().map(|h| h.is_finite()).collect();
            if let Some(mpath) = &a.rover_dem_valid {
                let m = read_mask(
                    "--rover-dem-valid",
                    mpath,
                    (dem.width, dem.height),
                    ("--rover-dem", path),
                )?;
                for (v, m) in valid.iter_mut().zip(m) {
                    *v &= m;
                }
            }
            if !valid.contains(&true) {
                return Err(found(
                    format!("--rover-dem {}", path.display()),
                    format!(
                        "at least one valid cell (finite, not no-data{})",
                        if a.rover_dem_valid.is_some() {
                            ", nonzero in --rover-dem-valid"
                        } else {
                            ""
                        }
                    ),
                    "none".to_owned(),
                ));
            }
            Some((dem, valid))
        }
        None => None,
    };

    let params = MatchSettings {
        search_radius_m: a.radius,
        latitude_deg: a.latitude,
        method,
        ..MatchSettings::default()
    };
    let inputs = LocalizeInputs {
        appearance,
        map_dem,
        ortho,
        ortho_valid,
        rover_dem,
        params,
        prior_m: a.prior,
    };
    check_window(&inputs, &a.map_appearance)?;
    Ok(inputs)
}

/// The prior must be on the map and the search window (prior ± radius ± half the
/// orthomosaic) inside it; the arithmetic mirrors [`localize`](crate::matcher::localize)'s own
/// check.
fn check_window(inp: &LocalizeInputs, map_path: &Path) -> Result<(), LocalizeInputError> {
    let map = &inp.appearance;
    let [px, py] = inp.prior_m;
    let (x0, y0, x1, y1) = map.extent_m();
    let extent = format!("x {x0}..{x1} m, y {y0}..{y1} m");
    if !map.contains_point(px, py) {
        return Err(found(
            format!("--prior {px},{py}"),
            format!(
                "a point on the orbital orthoimage {} ({extent})",
                map_path.display()
            ),
            "one off it".to_owned(),
        ));
    }
    let res = map.geo.resolution_m_per_px;
    let radius_px = (inp.params.search_radius_m / res).ceil();
    let (tw, th) = (inp.ortho.width as f64, inp.ortho.height as f64);
    let (pc, pr) = map.geo.pixel_of(px, py);
    let c0 = pc - tw / 2.0 - radius_px;
    let r0 = pr - th / 2.0 - radius_px;
    let cols = tw + 2.0 * radius_px;
    let rows = th + 2.0 * radius_px;
    let mut sides = Vec::new();
    for (side, px_out) in [
        ("west", -c0),
        ("north", -r0),
        ("east", c0.round() + cols - map.width as f64),
        ("south", r0.round() + rows - map.height as f64),
    ] {
        if px_out > 0.0 {
            sides.push(format!("{:.2} m on the {side}", px_out * res));
        }
    }
    if !sides.is_empty() {
        let radius_m = inp.params.search_radius_m;
        return Err(found(
            format!("--prior {px},{py} / --radius {radius_m}"),
            format!(
                "the search window (the prior ± {radius_m} m search radius ± half the {} m × {} m \
                 orthomosaic) inside the orbital orthoimage {} ({extent})",
                tw * res,
                th * res,
                map_path.display()
            ),
            format!(
                "it leaving by {}; move the prior or reduce --radius",
                sides.join(" and ")
            ),
        ));
    }
    Ok(())
}
