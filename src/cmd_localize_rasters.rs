//! `solsim localize`: one onboard global localization (paper 000 §5) on rasters the user
//! supplies — an orbital orthoimage (and DEM) and the rover's orthomosaic (and DEM) — around a
//! prior position, printed as a table or JSON.
//!
//! Reading is two-stage: every file and flag is checked here and turned into one `error:` line
//! naming the file or flag and what was expected (exit 2); only then does
//! [`localization::matcher::localize`] run. A match rejected by its validity checks is a result
//! (exit 0), not an error.
//!
//! Conventions (also in `--help` and the README): map metres, x east, y north; a raster's
//! origin is the north-west corner of pixel (0, 0) and row 0 is the north edge; the rover is at
//! the centre of its orthomosaic; the orthomosaic has the orbital appearance's resolution.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::bail;
use localization::matcher::{
    JEZERO_TRUE_SCALE_LATITUDE_DEG, LocalizeError, MatchParams, MatchResult, Method, OrbitalMap,
    RoverImages, localize,
};
use maps::MemoryBudget;
use maps::raster_io::{read_dem_with_holes, read_header, read_raster, read_raster_with_nodata};
use maps::{GeoTransform, Raster, RasterError};
use serde_json::json;

/// Largest search radius accepted, metres (paper 000 §4: the matcher searches up to 100 m).
pub const MAX_RADIUS_M: f64 = 100.0;
/// Default search radius, metres.
pub const DEFAULT_RADIUS_M: f64 = 30.0;
/// Default rover DEM resolution when neither the file nor `--rover-dem-resolution` gives one,
/// metres per pixel (the flight rover DEM's 1 m cells).
pub const DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX: f64 = 1.0;

/// Two resolutions or origins closer than this (relative) are the same.
const SAME_TOLERANCE: f64 = 1e-9;

/// Arguments of `solsim localize`.
#[derive(Debug, clap::Args)]
#[command(after_long_help = "\
Conventions: map coordinates are metres, x east, y north. A raster's origin is the north-west \
corner of its pixel (0, 0); row 0 is the north edge; pixels are square. The rover is at the \
centre of its orthomosaic (the corner between the middle pixels). Georeferenced GeoTIFFs place \
themselves; a PNG (or a GeoTIFF without georeference tags) needs the --*-origin and \
--*-resolution flags. Flags that contradict a GeoTIFF's own georeference are an error.

Output: position (E, N metres), correction from the prior, sigma (1-sigma, metres), best score \
(lower is better), peak ratio (the best other local minimum outside the peak's 2 m neighbourhood / best; higher is more distinctive), \
valid fraction of the orthomosaic, and the verdict: ACCEPTED, or REJECTED with the reason. \
Exit 0 for either verdict, 2 for bad input.")]
pub struct LocalizeArgs {
    /// Orbital orthoimage: single-band 8-bit PNG or GeoTIFF.
    #[arg(long, value_name = "FILE")]
    pub map_appearance: PathBuf,
    /// North-west corner of the orbital orthoimage, map metres "X,Y" (x east, y north), for a
    /// PNG or an untagged GeoTIFF.
    #[arg(long, value_name = "X,Y", value_parser = parse_xy, allow_hyphen_values = true)]
    pub map_origin: Option<[f64; 2]>,
    /// Pixel size of the orbital orthoimage, metres per pixel, for a PNG or an untagged GeoTIFF.
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub map_resolution: Option<f64>,
    /// Orbital DEM (optional): 32-bit float GeoTIFF in metres, or 16-bit PNG / GeoTIFF in
    /// centimetres. The datum does not matter: heights are compared after removing their mean
    /// offset. GDAL_NODATA or NaN cells are holes and are skipped.
    #[arg(long, value_name = "FILE")]
    pub map_dem: Option<PathBuf>,
    /// North-west corner of the orbital DEM, map metres "X,Y", for a PNG or an untagged GeoTIFF.
    #[arg(long, value_name = "X,Y", value_parser = parse_xy, allow_hyphen_values = true)]
    pub map_dem_origin: Option<[f64; 2]>,
    /// Pixel size of the orbital DEM, metres per pixel, for a PNG or an untagged GeoTIFF.
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub map_dem_resolution: Option<f64>,
    /// Rover orthomosaic: single-band 8-bit PNG or GeoTIFF, centred on the rover, at the
    /// orbital orthoimage's resolution. Its georeference, if any, is used only for the pixel
    /// size.
    #[arg(long, value_name = "FILE")]
    pub ortho: PathBuf,
    /// Pixel size of the orthomosaic, metres per pixel [default: the GeoTIFF's, else the
    /// orbital orthoimage's]. Must equal the orbital orthoimage's.
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub ortho_resolution: Option<f64>,
    /// Validity mask of the orthomosaic: 8-bit PNG or GeoTIFF of the same size, nonzero = valid.
    /// Without it, orthomosaic pixels equal to 0 (or to the GeoTIFF's GDAL_NODATA value, if it
    /// declares one) are invalid and all others valid.
    #[arg(long, value_name = "FILE")]
    pub ortho_valid: Option<PathBuf>,
    /// Rover DEM (optional), centred on the rover like the orthomosaic: 32-bit float GeoTIFF in
    /// metres, or 16-bit PNG / GeoTIFF in centimetres (any datum: the mean offset is removed).
    /// Used only with --map-dem, whose resolution it must have.
    #[arg(long, value_name = "FILE")]
    pub rover_dem: Option<PathBuf>,
    /// Pixel size of the rover DEM, metres per pixel [default: the GeoTIFF's, else 1].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub rover_dem_resolution: Option<f64>,
    /// Validity mask of the rover DEM: 8-bit PNG or GeoTIFF of the same size, nonzero = valid.
    /// Without it every finite cell not equal to the GeoTIFF's GDAL_NODATA value is valid.
    #[arg(long, value_name = "FILE")]
    pub rover_dem_valid: Option<PathBuf>,
    /// Prior rover position, map metres "X,Y" (x east, y north); the search is centred on it.
    #[arg(long, value_name = "X,Y", value_parser = parse_xy, allow_hyphen_values = true)]
    pub prior: [f64; 2],
    /// Search radius around the prior, metres, in (0, 100]. The search window (prior ± radius ±
    /// half the orthomosaic) must lie on the orbital orthoimage.
    #[arg(long, value_name = "M", default_value_t = DEFAULT_RADIUS_M, allow_negative_numbers = true)]
    pub radius: f64,
    /// Appearance score: census (flight method), ncc or mi.
    #[arg(long, default_value = "census")]
    pub method: String,
    /// Site latitude, degrees, for the easting scale of an equirectangular map with true scale
    /// at Jezero's 18.4663° (the default: no correction).
    #[arg(long, value_name = "DEG", default_value_t = JEZERO_TRUE_SCALE_LATITUDE_DEG, allow_hyphen_values = true)]
    pub latitude: f64,
    /// Print the result as JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Parses `"X,Y"` (two numbers, metres). Finiteness is checked later, with the other flags,
/// so every bad value gets the same one-line error.
fn parse_xy(s: &str) -> Result<[f64; 2], String> {
    let bad = || format!("expected two numbers \"X,Y\" in metres, got {s:?}");
    let (x, y) = s.split_once(',').ok_or_else(bad)?;
    let x: f64 = x.trim().parse().map_err(|_| bad())?;
    let y: f64 = y.trim().parse().map_err(|_| bad())?;
    Ok([x, y])
}

/// `true` if `a` and `b` agree to [`SAME_TOLERANCE`] (relative).
fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME_TOLERANCE * a.abs().max(b.abs()).max(1.0)
}

/// Checks that the numeric flags are usable before any file is read.
fn check_flags(a: &LocalizeArgs) -> anyhow::Result<Method> {
    let Some(method) = Method::from_name(&a.method) else {
        bail!("--method: expected census, ncc or mi, got {:?}", a.method);
    };
    if !(a.radius.is_finite() && a.radius > 0.0 && a.radius <= MAX_RADIUS_M) {
        bail!(
            "--radius: expected a search radius in (0, {MAX_RADIUS_M}] metres, got {}",
            a.radius
        );
    }
    if !(a.latitude.is_finite() && a.latitude.abs() < 90.0) {
        bail!(
            "--latitude: expected degrees strictly between -90 and 90, got {}",
            a.latitude
        );
    }
    for (flag, xy) in [
        ("--prior", Some(a.prior)),
        ("--map-origin", a.map_origin),
        ("--map-dem-origin", a.map_dem_origin),
    ] {
        if let Some([x, y]) = xy
            && !(x.is_finite() && y.is_finite())
        {
            bail!("{flag}: expected finite map coordinates X,Y in metres, got {x},{y}");
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
            bail!("{flag}: expected a positive pixel size in metres per pixel, got {r}");
        }
    }
    if a.rover_dem_valid.is_some() && a.rover_dem.is_none() {
        bail!("--rover-dem-valid: expected together with --rover-dem, which is missing");
    }
    if a.map_dem.is_none() && (a.map_dem_origin.is_some() || a.map_dem_resolution.is_some()) {
        bail!(
            "--map-dem-origin / --map-dem-resolution: expected together with --map-dem, which is missing"
        );
    }
    Ok(method)
}

/// Reads a map-frame raster: the GeoTIFF's georeference, else the flags'.
fn read_placed<R>(
    flag: &str,
    path: &Path,
    flags: (&str, Option<[f64; 2]>, &str, Option<f64>),
    read: impl Fn(Option<GeoTransform>) -> Result<R, RasterError>,
    geo_of: impl Fn(&R) -> GeoTransform,
) -> anyhow::Result<R> {
    let (origin_flag, origin, res_flag, res) = flags;
    let given = match (origin, res) {
        (Some([x, y]), Some(r)) => Some(GeoTransform::new(x, y, r)),
        (None, None) => None,
        (Some(_), None) => bail!("{res_flag}: expected together with {origin_flag}, missing"),
        (None, Some(_)) => bail!("{origin_flag}: expected together with {res_flag}, missing"),
    };
    let r = match read(None) {
        Ok(r) => r,
        Err(RasterError::MissingGeoreference { .. }) => match given {
            Some(g) => read(Some(g)).map_err(|e| anyhow::anyhow!("{flag} {e}"))?,
            None => bail!(
                "{flag} {}: expected a georeference, found none (a PNG never has one): give \
                 {origin_flag} X,Y and {res_flag} M",
                path.display()
            ),
        },
        Err(e) => bail!("{flag} {e}"),
    };
    let file_geo = geo_of(&r);
    if let Some(g) = given
        && !(same(g.origin_m[0], file_geo.origin_m[0])
            && same(g.origin_m[1], file_geo.origin_m[1])
            && same(g.resolution_m_per_px, file_geo.resolution_m_per_px))
    {
        bail!(
            "{flag} {}: the GeoTIFF's own georeference (origin {},{} m, {} m/px) contradicts \
             {origin_flag} {},{} / {res_flag} {}: expected them to agree (drop the flags)",
            path.display(),
            file_geo.origin_m[0],
            file_geo.origin_m[1],
            file_geo.resolution_m_per_px,
            g.origin_m[0],
            g.origin_m[1],
            g.resolution_m_per_px
        );
    }
    Ok(r)
}

/// Where a rover raster's pixel size came from, for error messages.
#[derive(Clone, Copy, Debug)]
enum ResolutionSource {
    File,
    Flag,
    Default,
}

/// Reads a rover-frame raster, whose only georeferencing is its pixel size: the flag's, else
/// the GeoTIFF's, else `default`; a flag that contradicts the GeoTIFF is an error.
fn read_rover<R>(
    flag: &str,
    path: &Path,
    res_flag: (&str, Option<f64>),
    default_m_per_px: f64,
    read: impl Fn(Option<GeoTransform>) -> Result<R, RasterError>,
    geo_of: impl Fn(&mut R) -> &mut GeoTransform,
) -> anyhow::Result<(R, ResolutionSource)> {
    let (res_flag, res) = res_flag;
    let placed = |r: f64| GeoTransform::new(0.0, 0.0, r);
    match read(None) {
        Ok(mut r) => {
            let file_res = geo_of(&mut r).resolution_m_per_px;
            if let Some(given) = res
                && !same(given, file_res)
            {
                bail!(
                    "{flag} {}: the GeoTIFF's pixel size {file_res} m/px contradicts {res_flag} \
                     {given}: expected them to agree",
                    path.display()
                );
            }
            Ok((r, ResolutionSource::File))
        }
        Err(RasterError::MissingGeoreference { .. }) => {
            let (res, source) = match res {
                Some(r) => (r, ResolutionSource::Flag),
                None => (default_m_per_px, ResolutionSource::Default),
            };
            let r = read(Some(placed(res))).map_err(|e| anyhow::anyhow!("{flag} {e}"))?;
            Ok((r, source))
        }
        Err(e) => bail!("{flag} {e}"),
    }
}

/// Reads a validity mask (8-bit, nonzero = valid) that must be `width × height` like `of`.
fn read_mask(
    flag: &str,
    path: &Path,
    (width, height): (usize, usize),
    of: (&str, &Path),
) -> anyhow::Result<Vec<bool>> {
    let (mask, _) = read_raster_with_nodata::<u8>(path, Some(GeoTransform::new(0.0, 0.0, 1.0)))
        .map_err(|e| anyhow::anyhow!("{flag} {e}"))?;
    if (mask.width, mask.height) != (width, height) {
        bail!(
            "{flag} {}: expected {width}x{height} px like {} {}, found {}x{} px",
            path.display(),
            of.0,
            of.1.display(),
            mask.width,
            mask.height
        );
    }
    Ok(mask.data.iter().map(|&v| v != 0).collect())
}

/// Checks every raster input against `budget` from its header, before any is decoded: the
/// rasters as held (u8 images and masks with their decode buffers and validity masks, 2 bytes
/// per pixel; DEMs as f32 with their 16-bit decode buffer and hole mask, 7) plus the matcher's
/// census and score planes over the orbital orthoimage (8 bytes per map pixel). Over it, the
/// largest input is named.
fn check_budget(a: &LocalizeArgs, budget: MemoryBudget) -> anyhow::Result<()> {
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
        let h = read_header(path).map_err(|e| anyhow::anyhow!("{flag} {e}"))?;
        sized.push((flag, path, h, h.bytes_as(bytes_per_px)));
    }
    let total = sized.iter().fold(0u64, |t, s| t.saturating_add(s.3));
    match sized.iter().max_by_key(|s| s.3) {
        Some((flag, path, h, need)) if !budget.allows(total) => {
            bail!("{flag} {}", h.over_budget(path, *need, budget))
        }
        _ => Ok(()),
    }
}

/// Everything `localize` needs, read and checked.
#[derive(Debug)]
pub struct LocalizeInputs {
    /// Orbital orthoimage.
    pub appearance: Raster<u8>,
    /// Orbital DEM (metres; NaN in holes), if given.
    pub map_dem: Option<Raster<f32>>,
    /// Rover orthomosaic (its resolution is the map's).
    pub ortho: Raster<u8>,
    /// Validity of each orthomosaic pixel.
    pub ortho_valid: Vec<bool>,
    /// Rover DEM (metres) and its validity, if given.
    pub rover_dem: Option<(Raster<f32>, Vec<bool>)>,
    /// Matcher settings from the flags.
    pub params: MatchParams,
    /// Prior position, map metres.
    pub prior_m: [f64; 2],
}

impl LocalizeInputs {
    /// The matcher's view of the orbital map.
    #[must_use]
    pub fn orbital(&self) -> OrbitalMap<'_> {
        OrbitalMap {
            appearance: &self.appearance,
            dem: self.map_dem.as_ref(),
        }
    }

    /// The matcher's view of the rover's images.
    #[must_use]
    pub fn rover(&self) -> RoverImages<'_> {
        RoverImages {
            ortho: &self.ortho,
            ortho_valid: &self.ortho_valid,
            dem: self.rover_dem.as_ref().map(|(d, v)| (d, v.as_slice())),
        }
    }

    /// Whether the DEM term takes part: both DEMs given and the map DEM covers the search
    /// window with the rover DEM around it. This mirrors the condition under which
    /// [`localize`] adds the DEM term (it silently skips it otherwise).
    #[must_use]
    pub fn dem_used(&self) -> bool {
        let (Some(mdem), Some((rdem, _))) = (&self.map_dem, &self.rover_dem) else {
            return false;
        };
        let map = &self.appearance;
        let res = map.geo.resolution_m_per_px;
        let radius_px = (self.params.search_radius_m / res).ceil() as usize;
        let (pc, pr) = map.geo.pixel_of(self.prior_m[0], self.prior_m[1]);
        let c0 = (pc - self.ortho.width as f64 / 2.0 - radius_px as f64).round();
        let r0 = (pr - self.ortho.height as f64 / 2.0 - radius_px as f64).round();
        if c0 < 0.0 || r0 < 0.0 {
            return false;
        }
        let (x0, y0) = map.geo.center_of(c0 as usize, r0 as usize);
        let k = (mdem.geo.resolution_m_per_px / res).round().max(1.0) as usize;
        let (dc, dr) = mdem.geo.pixel_of(x0, y0);
        let (dc0, dr0) = (dc.floor(), dr.floor());
        let dcols = rdem.width + 2 * (radius_px / k) + 2;
        let drows = rdem.height + 2 * (radius_px / k) + 2;
        dc0 >= 0.0
            && dr0 >= 0.0
            && dc0 as usize + dcols <= mdem.width
            && dr0 as usize + drows <= mdem.height
    }
}

/// Reads and checks every file and flag; each failure is one line naming the file or flag.
///
/// # Errors
/// Unreadable or missing files, wrong pixel types, missing or contradictory georeferences,
/// masks of the wrong size, no valid pixels, resolution mismatches, a prior off the map, a
/// search window leaving the map, non-finite or out-of-range flags.
pub fn load(a: &LocalizeArgs, budget: MemoryBudget) -> anyhow::Result<LocalizeInputs> {
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
        bail!(
            "--ortho {}: expected the orbital orthoimage's resolution {map_res} m/px ({}), found \
             {ortho_res} m/px ({from}); resample one of them",
            a.ortho.display(),
            a.map_appearance.display()
        );
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
                bail!(
                    "--ortho-valid {}: expected at least one valid (nonzero) pixel, found none",
                    path.display()
                );
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
                bail!(
                    "--ortho {}: expected at least one valid pixel, found every pixel equal to \
                     the no-data value {invalid} (give --ortho-valid MASK if 0 is real data)",
                    a.ortho.display()
                );
            }
            v
        }
    };

    let rover_dem = match &a.rover_dem {
        Some(path) => {
            let (dem, source) = read_rover(
                "--rover-dem",
                path,
                ("--rover-dem-resolution", a.rover_dem_resolution),
                DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX,
                |g| read_dem_with_holes(path, 0.0, g),
                |r| &mut r.geo,
            )?;
            let mut dem = dem;
            if let Some(mdem) = &map_dem {
                let (rres, mres) = (dem.geo.resolution_m_per_px, mdem.geo.resolution_m_per_px);
                if !same(rres, mres) {
                    let from = match source {
                        ResolutionSource::File => "from its GeoTIFF tags",
                        ResolutionSource::Flag => "from --rover-dem-resolution",
                        ResolutionSource::Default => "the default; set --rover-dem-resolution",
                    };
                    bail!(
                        "--rover-dem {}: expected the orbital DEM's resolution {mres} m/px ({}), \
                         found {rres} m/px ({from})",
                        path.display(),
                        a.map_dem.as_deref().unwrap_or(Path::new("")).display()
                    );
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
                bail!(
                    "--rover-dem {}: expected at least one valid cell (finite, not no-data{}), \
                     found none",
                    path.display(),
                    if a.rover_dem_valid.is_some() {
                        ", nonzero in --rover-dem-valid"
                    } else {
                        ""
                    }
                );
            }
            Some((dem, valid))
        }
        None => None,
    };

    let params = MatchParams {
        search_radius_m: a.radius,
        latitude_deg: a.latitude,
        method,
        ..MatchParams::default()
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
/// orthomosaic) inside it; the arithmetic mirrors [`localize`]'s own check.
fn check_window(inp: &LocalizeInputs, map_path: &Path) -> anyhow::Result<()> {
    let map = &inp.appearance;
    let [px, py] = inp.prior_m;
    let (x0, y0, x1, y1) = map.extent_m();
    let extent = format!("x {x0}..{x1} m, y {y0}..{y1} m");
    if !map.contains_point(px, py) {
        bail!(
            "--prior {px},{py}: expected a point on the orbital orthoimage {} ({extent}), found \
             one off it",
            map_path.display()
        );
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
        bail!(
            "--prior {px},{py} / --radius {}: expected the search window (the prior ± {} m \
             search radius ± half the {} m × {} m orthomosaic) inside the orbital orthoimage {} ({extent}), found it \
             leaving by {}; move the prior or reduce --radius",
            inp.params.search_radius_m,
            inp.params.search_radius_m,
            tw * res,
            th * res,
            map_path.display(),
            sides.join(" and ")
        );
    }
    Ok(())
}

/// `ACCEPTED` or `REJECTED: reason`.
#[must_use]
pub fn verdict(m: &MatchResult) -> String {
    match &m.rejection {
        None => "ACCEPTED".to_owned(),
        Some(r) => format!("REJECTED: {r}"),
    }
}

/// The result as a table.
#[must_use]
pub fn table(inp: &LocalizeInputs, m: &MatchResult, dem_used: bool) -> String {
    let [px, py] = inp.prior_m;
    let [x, y] = m.position_m;
    let [dx, dy] = m.correction_m;
    let terms = match (dem_used, inp.map_dem.is_some() && inp.rover_dem.is_some()) {
        (true, _) => "appearance + DEM",
        (false, true) => "appearance only (the map DEM does not cover the search window)",
        (false, false) => "appearance only",
    };
    format!(
        "solsim localize: {} around the prior (E {px:.3}, N {py:.3}) m, search radius {} m\n\
         \x20 score terms     {terms}\n\
         \x20 position        E {x:.3} m, N {y:.3} m\n\
         \x20 correction      E {dx:+.3} m, N {dy:+.3} m ({:.3} m)\n\
         \x20 sigma           {:.3} m\n\
         \x20 best score      {:.4} (lower is better)\n\
         \x20 peak ratio      {:.3} (runner-up minimum / best)\n\
         \x20 valid fraction  {:.3}\n\
         \x20 verdict         {}\n",
        inp.params.method,
        inp.params.search_radius_m,
        dx.hypot(dy),
        m.sigma_m,
        m.best_score,
        m.peak_ratio,
        m.valid_fraction,
        verdict(m)
    )
}

/// The result as a JSON document: the inputs, `result` (the matcher's [`MatchResult`] as
/// serialized), `accepted`, `verdict` and `dem_used`.
#[must_use]
pub fn json_doc(a: &LocalizeArgs, inp: &LocalizeInputs, m: &MatchResult) -> serde_json::Value {
    let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
    json!({
        "solsim_version": env!("CARGO_PKG_VERSION"),
        "inputs": {
            "map_appearance": a.map_appearance.display().to_string(),
            "map_dem": path(&a.map_dem),
            "ortho": a.ortho.display().to_string(),
            "ortho_valid": path(&a.ortho_valid),
            "rover_dem": path(&a.rover_dem),
            "rover_dem_valid": path(&a.rover_dem_valid),
            "resolution_m_per_px": inp.appearance.geo.resolution_m_per_px,
            "prior_m": inp.prior_m,
            "params": inp.params,
        },
        "result": m,
        "accepted": m.rejection.is_none(),
        "verdict": verdict(m),
        "dem_used": inp.dem_used(),
    })
}

/// Reads the rasters, localizes, and prints the table (or JSON) on `out`; warnings go to `err`.
///
/// # Errors
/// Bad input (see [`load`]) and failed writes; a rejected match is not an error.
pub fn run(
    a: &LocalizeArgs,
    budget: MemoryBudget,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> anyhow::Result<MatchResult> {
    let inp = load(a, budget)?;
    match (&a.map_dem, &a.rover_dem) {
        (Some(_), None) => writeln!(
            err,
            "warning: --map-dem given without --rover-dem: the DEM term is not used"
        )?,
        (None, Some(_)) => writeln!(
            err,
            "warning: --rover-dem given without --map-dem: the DEM term is not used"
        )?,
        _ => {}
    }
    let dem_used = inp.dem_used();
    if let (Some(path), Some(_), false) = (&a.map_dem, &a.rover_dem, dem_used) {
        writeln!(
            err,
            "warning: --map-dem {} does not cover the search window with the rover DEM around \
             it: the DEM term is not used",
            path.display()
        )?;
    }
    let m = localize(&inp.orbital(), &inp.rover(), inp.prior_m, &inp.params).map_err(|e| {
        // The checks in `load` rule these out; name the inputs if one slips through.
        match e {
            LocalizeError::ResolutionMismatch { .. } | LocalizeError::Census(_) => {
                anyhow::anyhow!("--ortho {}: {e}", a.ortho.display())
            }
            LocalizeError::WindowOffMap { .. } => anyhow::anyhow!("--prior / --radius: {e}"),
            // The orthomosaic's own validity was checked in `load`: here no offset could be
            // scored, e.g. the valid rover DEM cells overlap valid map DEM cells nowhere.
            LocalizeError::NoValidPixels => anyhow::anyhow!(
                "--ortho / --rover-dem / --map-dem: expected some offset in the search window \
                 to be scorable, found none (do the valid rover DEM cells overlap valid map DEM \
                 cells?)"
            ),
        }
    })?;
    if a.json {
        write!(out, "{}", crate::report::pretty(&json_doc(a, &inp, &m)))?;
    } else {
        write!(out, "{}", table(&inp, &m, dem_used))?;
    }
    Ok(m)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn xy_pairs_parse_and_reject_garbage() {
        assert_eq!(parse_xy("1.5,-2").unwrap(), [1.5, -2.0]);
        assert_eq!(parse_xy(" 3 , 4 ").unwrap(), [3.0, 4.0]);
        assert!(parse_xy("3").is_err());
        assert!(parse_xy("3,x").is_err());
        // NaN parses here and is refused by `check_flags`, with the flag's name.
        assert!(parse_xy("nan,1").unwrap()[0].is_nan());
    }

    #[test]
    fn defaults_match_the_documentation() {
        assert_eq!(DEFAULT_RADIUS_M, MatchParams::default().search_radius_m);
        assert_eq!(MAX_RADIUS_M, 100.0);
        assert_eq!(DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX, 1.0);
    }
}
