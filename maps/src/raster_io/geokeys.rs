//! GeoKeys (GeoTIFF 1.1 Annex B): the directory written for a [`MapCrs`], and the keys read
//! back and recognised as a Mars CRS (the `geotiff` module docs say what each case holds).

use std::collections::BTreeMap;
use std::io::{Read, Seek};
use std::path::Path;

use tiff::decoder::Decoder;
use tiff::tags::Tag;

use super::RasterError;
use super::tiff_tags::{read_f64s, tiff_error};
use crate::mars_crs::{MARS_RADIUS_M, MapCrs, MarsEquirectangular};

/// GeoKey ids and values used here (GeoTIFF 1.1 Annex B).
pub(super) const GT_MODEL_TYPE: u16 = 1024;
pub(super) const GT_RASTER_TYPE: u16 = 1025;
const GT_CITATION: u16 = 1026;
const GEOGRAPHIC_TYPE: u16 = 2048;
const GEOG_CITATION: u16 = 2049;
const GEOG_GEODETIC_DATUM: u16 = 2050;
const GEOG_ANGULAR_UNITS: u16 = 2054;
const GEOG_ELLIPSOID: u16 = 2056;
const GEOG_SEMI_MAJOR_AXIS: u16 = 2057;
const GEOG_SEMI_MINOR_AXIS: u16 = 2058;
const GEOG_INV_FLATTENING: u16 = 2059;
const GEOG_PRIME_MERIDIAN_LONG: u16 = 2061;
const PROJECTED_CS_TYPE: u16 = 3072;
const PROJECTION: u16 = 3074;
const PROJ_COORD_TRANS: u16 = 3075;
pub(super) const PROJ_LINEAR_UNITS: u16 = 3076;
const PROJ_STD_PARALLEL_1: u16 = 3078;
const PROJ_NAT_ORIGIN_LONG: u16 = 3080;
const PROJ_NAT_ORIGIN_LAT: u16 = 3081;
const PROJ_FALSE_EASTING: u16 = 3082;
const PROJ_FALSE_NORTHING: u16 = 3083;
const PROJ_CENTER_LONG: u16 = 3088;
const PROJ_CENTER_LAT: u16 = 3089;
const MODEL_TYPE_PROJECTED: u16 = 1;
pub(super) const MODEL_TYPE_GEOGRAPHIC: u16 = 2;
const RASTER_PIXEL_IS_AREA: u16 = 1;
pub(super) const RASTER_PIXEL_IS_POINT: u16 = 2;
const USER_DEFINED: u16 = 32767;
pub(super) const LINEAR_METRE: u16 = 9001;
const ANGULAR_DEGREE: u16 = 9102;
const CT_EQUIRECTANGULAR: u16 = 17;
const GEO_DOUBLE_PARAMS_TAG: u16 = 34736;
const GEO_ASCII_PARAMS_TAG: u16 = 34737;

/// Citation of the local frame in `GeoAsciiParamsTag` (`|` ends each GeoTIFF ASCII parameter).
const LOCAL_CITATION: &str = "solsim local map frame (metres, x east, y north)|";

/// The GeoKey directory of a [`MapCrs::Local`] file: header, then (key, location, count, value).
#[rustfmt::skip]
const LOCAL_GEO_KEYS: [u16; 24] = [
    1, 1, 0, 5, // version 1.1.0, five keys
    GT_MODEL_TYPE, 0, 1, MODEL_TYPE_PROJECTED,
    GT_RASTER_TYPE, 0, 1, RASTER_PIXEL_IS_AREA,
    GT_CITATION, GEO_ASCII_PARAMS_TAG, LOCAL_CITATION.len() as u16, 0,
    PROJECTED_CS_TYPE, 0, 1, USER_DEFINED,
    PROJ_LINEAR_UNITS, 0, 1, LINEAR_METRE,
];

/// The GeoKey directory, double parameters and ASCII parameters describing `crs`.
pub(super) struct GeoKeyTags {
    pub directory: Vec<u16>,
    pub doubles: Vec<f64>,
    pub ascii: String,
}

impl GeoKeyTags {
    pub fn of(crs: &MapCrs) -> Self {
        let MapCrs::Mars(mars) = crs else {
            return Self {
                directory: LOCAL_GEO_KEYS.to_vec(),
                doubles: Vec::new(),
                ascii: LOCAL_CITATION.to_owned(),
            };
        };
        let [pcs_citation, gcs_citation] = mars.geotiff_citations();
        let mut ascii = String::new();
        let mut doubles = Vec::new();
        let mut keys: Vec<[u16; 4]> = Vec::new();
        let mut text = |key: u16, value: &str, keys: &mut Vec<[u16; 4]>| {
            let offset = ascii.len() as u16;
            ascii.push_str(value);
            ascii.push('|');
            keys.push([key, GEO_ASCII_PARAMS_TAG, value.len() as u16 + 1, offset]);
        };
        let mut double = |key: u16, value: f64, keys: &mut Vec<[u16; 4]>| {
            keys.push([key, GEO_DOUBLE_PARAMS_TAG, 1, doubles.len() as u16]);
            doubles.push(value);
        };
        let short = |key: u16, value: u16| [key, 0, 1, value];
        keys.push(short(GT_MODEL_TYPE, MODEL_TYPE_PROJECTED));
        keys.push(short(GT_RASTER_TYPE, RASTER_PIXEL_IS_AREA));
        text(GT_CITATION, &pcs_citation, &mut keys);
        keys.push(short(GEOGRAPHIC_TYPE, USER_DEFINED));
        text(GEOG_CITATION, &gcs_citation, &mut keys);
        keys.push(short(GEOG_GEODETIC_DATUM, USER_DEFINED));
        keys.push(short(GEOG_ANGULAR_UNITS, ANGULAR_DEGREE));
        keys.push(short(GEOG_ELLIPSOID, USER_DEFINED));
        double(GEOG_SEMI_MAJOR_AXIS, MARS_RADIUS_M, &mut keys);
        double(GEOG_SEMI_MINOR_AXIS, MARS_RADIUS_M, &mut keys);
        double(GEOG_PRIME_MERIDIAN_LONG, 0.0, &mut keys);
        keys.push(short(PROJECTED_CS_TYPE, USER_DEFINED));
        keys.push(short(PROJECTION, USER_DEFINED));
        keys.push(short(PROJ_COORD_TRANS, CT_EQUIRECTANGULAR));
        keys.push(short(PROJ_LINEAR_UNITS, LINEAR_METRE));
        double(PROJ_STD_PARALLEL_1, mars.true_scale_latitude_deg, &mut keys);
        double(PROJ_FALSE_EASTING, mars.false_easting_m, &mut keys);
        double(PROJ_FALSE_NORTHING, mars.false_northing_m, &mut keys);
        double(PROJ_CENTER_LONG, mars.central_meridian_deg, &mut keys);
        double(PROJ_CENTER_LAT, 0.0, &mut keys);
        // Version 1.1.0, then the keys in increasing order (GeoTIFF 1.1 §7.1.3: sorted).
        let mut directory = vec![1, 1, 0, keys.len() as u16];
        directory.extend(keys.iter().flatten());
        Self {
            directory,
            doubles,
            ascii,
        }
    }
}

/// The GeoKeys of a file: inline short values, and values held in `GeoDoubleParamsTag`.
#[derive(Default)]
pub(super) struct GeoKeys {
    shorts: BTreeMap<u16, u16>,
    doubles: BTreeMap<u16, f64>,
}

impl GeoKeys {
    pub fn short(&self, id: u16) -> Option<u16> {
        self.shorts.get(&id).copied()
    }

    fn double(&self, id: u16) -> Option<f64> {
        self.doubles.get(&id).copied()
    }

    /// The map CRS the keys describe (see the module docs).
    pub fn crs(&self) -> MapCrs {
        let sphere = |v: Option<f64>| v.is_some_and(|a| (a - MARS_RADIUS_M).abs() <= 0.5);
        let is_mars = self.short(GT_MODEL_TYPE) == Some(MODEL_TYPE_PROJECTED)
            && self.short(PROJ_COORD_TRANS) == Some(CT_EQUIRECTANGULAR)
            && self
                .short(PROJ_LINEAR_UNITS)
                .is_none_or(|u| u == LINEAR_METRE)
            && self
                .short(GEOG_ANGULAR_UNITS)
                .is_none_or(|u| u == ANGULAR_DEGREE)
            && sphere(self.double(GEOG_SEMI_MAJOR_AXIS))
            && (self.double(GEOG_SEMI_MINOR_AXIS).is_none()
                || sphere(self.double(GEOG_SEMI_MINOR_AXIS)))
            && self.double(GEOG_INV_FLATTENING).is_none_or(|f| f == 0.0);
        if !is_mars {
            return MapCrs::Local;
        }
        let either = |a: u16, b: u16| self.double(a).or(self.double(b)).unwrap_or(0.0);
        let origin_lat_deg = either(PROJ_CENTER_LAT, PROJ_NAT_ORIGIN_LAT);
        MarsEquirectangular::try_new(
            either(PROJ_CENTER_LONG, PROJ_NAT_ORIGIN_LONG),
            self.double(PROJ_STD_PARALLEL_1).unwrap_or(0.0),
            self.double(PROJ_FALSE_EASTING).unwrap_or(0.0),
            // y = FN + R (φ − φ₀): a latitude of origin is a false northing of −R φ₀.
            self.double(PROJ_FALSE_NORTHING).unwrap_or(0.0)
                - MARS_RADIUS_M * origin_lat_deg.to_radians(),
        )
        .map_or(MapCrs::Local, MapCrs::Mars)
    }
}

pub(super) fn read_geokeys<R: Read + Seek>(
    dec: &mut Decoder<R>,
    path: &Path,
) -> Result<GeoKeys, RasterError> {
    let bad = |detail: String| RasterError::BadGeoreference {
        path: path.to_path_buf(),
        detail,
    };
    let Some(value) = dec
        .find_tag(Tag::GeoKeyDirectoryTag)
        .map_err(tiff_error(path, true))?
    else {
        return Ok(GeoKeys::default());
    };
    let dir = value.into_u16_vec().map_err(|e| {
        bad(format!(
            "a GeoKeyDirectory that is not a list of shorts ({e})"
        ))
    })?;
    let n = usize::from(dir.get(3).copied().unwrap_or(0));
    if dir.len() < 4 || dir.len() < 4 + 4 * n {
        return Err(bad(format!(
            "a truncated GeoKeyDirectory ({} values for {n} keys)",
            dir.len()
        )));
    }
    // The double parameters only place a CRS: an unreadable tag leaves the map local.
    let doubles = read_f64s(dec, path, Tag::GeoDoubleParamsTag)
        .ok()
        .flatten()
        .unwrap_or_default();
    let mut keys = GeoKeys::default();
    for entry in dir[4..4 + 4 * n].chunks_exact(4) {
        // Location 0: the value is inline; GeoDoubleParamsTag: `value` indexes the doubles.
        let (id, location, value) = (entry[0], entry[1], entry[3]);
        match location {
            0 => {
                keys.shorts.insert(id, value);
            }
            GEO_DOUBLE_PARAMS_TAG => {
                if let Some(&v) = doubles.get(usize::from(value)) {
                    keys.doubles.insert(id, v);
                }
            }
            _ => {}
        }
    }
    Ok(keys)
}
