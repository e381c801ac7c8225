//! `solsim localize`: one onboard global localization (paper 000 §5) on rasters the user
//! supplies — an orbital orthoimage (and DEM) and the rover's orthomosaic (and DEM) — around a
//! prior position, printed as a table or JSON. Reading, checking and the result's table and
//! JSON are [`localization::raster_inputs`]'s; a match rejected by its validity checks is a
//! result (exit 0), bad input one `error:` line (exit 2).

use std::io::Write;
use std::path::PathBuf;

use localization::matcher::{JEZERO_TRUE_SCALE_LATITUDE_DEG, MatchResult};
use localization::raster_inputs::{
    DEFAULT_RADIUS_M, LocalizeRequest, json_doc, load, table, warnings,
};
use maps::MemoryBudget;

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

impl LocalizeArgs {
    /// The files and options to read.
    #[must_use]
    pub fn request(&self) -> LocalizeRequest {
        LocalizeRequest {
            map_appearance: self.map_appearance.clone(),
            map_origin: self.map_origin,
            map_resolution: self.map_resolution,
            map_dem: self.map_dem.clone(),
            map_dem_origin: self.map_dem_origin,
            map_dem_resolution: self.map_dem_resolution,
            ortho: self.ortho.clone(),
            ortho_resolution: self.ortho_resolution,
            ortho_valid: self.ortho_valid.clone(),
            rover_dem: self.rover_dem.clone(),
            rover_dem_resolution: self.rover_dem_resolution,
            rover_dem_valid: self.rover_dem_valid.clone(),
            prior: self.prior,
            radius: self.radius,
            method: self.method.clone(),
            latitude: self.latitude,
        }
    }
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
    let request = a.request();
    let inp = load(&request, budget)?;
    for w in warnings(&request, &inp) {
        writeln!(err, "warning: {w}")?;
    }
    let m = inp.localize(&request)?;
    if a.json {
        writeln!(
            out,
            "{}",
            serde_json::to_string_pretty(&json_doc(&request, &inp, &m))?
        )?;
    } else {
        write!(out, "{}", table(&inp, &m))?;
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
}
