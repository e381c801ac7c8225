//! What one localization on user rasters is asked ([`LocalizeRequest`]) and what it runs on,
//! read and checked ([`LocalizeInputs`]).

use std::path::PathBuf;

use maps::Raster;

use super::error::LocalizeInputError;
use crate::matcher::{
    LocalizeError, MatchResult, MatchSettings, OrbitalMap, RoverImages, localize,
};

/// Largest search radius accepted, metres (paper 000 §4: the matcher searches up to 100 m).
pub const MAX_RADIUS_M: f64 = 100.0;
/// Default search radius, metres.
pub const DEFAULT_RADIUS_M: f64 = 30.0;
/// Default rover DEM resolution when neither the file nor `--rover-dem-resolution` gives one,
/// metres per pixel (the flight rover DEM's 1 m cells).
pub const DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX: f64 = 1.0;

/// The files and options of one localization, as given (`solsim localize`'s flags; each is
/// named by its flag in errors). Nothing is checked until [`load`](super::load).
#[derive(Clone, Debug, PartialEq)]
pub struct LocalizeRequest {
    /// Orbital orthoimage: single-band 8-bit PNG or GeoTIFF (`--map-appearance`).
    pub map_appearance: PathBuf,
    /// North-west corner of the orbital orthoimage, map metres, for a PNG or an untagged
    /// GeoTIFF (`--map-origin`).
    pub map_origin: Option<[f64; 2]>,
    /// Pixel size of the orbital orthoimage, metres per pixel (`--map-resolution`).
    pub map_resolution: Option<f64>,
    /// Orbital DEM, metres (float) or centimetres (16-bit) (`--map-dem`).
    pub map_dem: Option<PathBuf>,
    /// North-west corner of the orbital DEM, map metres (`--map-dem-origin`).
    pub map_dem_origin: Option<[f64; 2]>,
    /// Pixel size of the orbital DEM, metres per pixel (`--map-dem-resolution`).
    pub map_dem_resolution: Option<f64>,
    /// Rover orthomosaic, centred on the rover (`--ortho`).
    pub ortho: PathBuf,
    /// Pixel size of the orthomosaic, metres per pixel (`--ortho-resolution`; default the
    /// GeoTIFF's, else the orbital orthoimage's).
    pub ortho_resolution: Option<f64>,
    /// Validity mask of the orthomosaic, nonzero = valid (`--ortho-valid`).
    pub ortho_valid: Option<PathBuf>,
    /// Rover DEM, centred on the rover (`--rover-dem`).
    pub rover_dem: Option<PathBuf>,
    /// Pixel size of the rover DEM, metres per pixel (`--rover-dem-resolution`; default the
    /// GeoTIFF's, else [`DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX`]).
    pub rover_dem_resolution: Option<f64>,
    /// Validity mask of the rover DEM, nonzero = valid (`--rover-dem-valid`).
    pub rover_dem_valid: Option<PathBuf>,
    /// Prior rover position, map metres (`--prior`).
    pub prior: [f64; 2],
    /// Search radius around the prior, metres, in (0, [`MAX_RADIUS_M`]] (`--radius`).
    pub radius: f64,
    /// Appearance score: census, ncc or mi (`--method`).
    pub method: String,
    /// Site latitude, degrees, for the easting scale (`--latitude`).
    pub latitude: f64,
}

/// Everything [`localize`] needs, read and checked.
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
    /// Matcher settings from the options.
    pub params: MatchSettings,
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

    /// Localizes: the matcher on these inputs (read from `request`'s files).
    ///
    /// # Errors
    /// What the checks of [`load`](super::load) rule out, should one slip through, named by
    /// the options at fault; a rejected match is a result, not an error.
    pub fn localize(&self, request: &LocalizeRequest) -> Result<MatchResult, LocalizeInputError> {
        localize(&self.orbital(), &self.rover(), self.prior_m, &self.params).map_err(|e| match e {
            LocalizeError::ResolutionMismatch { .. } | LocalizeError::Census(_) => {
                LocalizeInputError::Match {
                    input: format!("--ortho {}", request.ortho.display()),
                    source: e,
                }
            }
            LocalizeError::WindowOffMap { .. } => LocalizeInputError::Match {
                input: "--prior / --radius".to_owned(),
                source: e,
            },
            // The orthomosaic's own validity was checked in `load`: here no offset could be
            // scored, e.g. the valid rover DEM cells overlap valid map DEM cells nowhere.
            LocalizeError::NoValidPixels => LocalizeInputError::NothingScorable,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_match_the_documentation() {
        assert_eq!(DEFAULT_RADIUS_M, MatchSettings::default().search_radius_m);
        assert_eq!(MAX_RADIUS_M, 100.0);
        assert_eq!(DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX, 1.0);
    }
}
