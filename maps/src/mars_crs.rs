//! Where a map lies on Mars: the IAU 2015 Mars sphere and the Jezero equirectangular projection,
//! whose projected metres **are** the map's metres.
//!
//! A georeferenced map's metres (x east, y north; see [`raster`](crate::raster)) are the
//! projected coordinates of an equirectangular (equidistant cylindrical, EPSG method 1028)
//! projection of the IAU 2015 Mars sphere (radius [`MARS_RADIUS_M`], the Mars 2000 sphere):
//!
//! ```text
//! x = FE + R · cos φ₁ · (λ − λ₀)        y = FN + R · φ        (angles in radians)
//! ```
//!
//! with λ the planetocentric east longitude, φ the planetocentric latitude, the latitude of
//! true scale φ₁ = [`JEZERO_TRUE_SCALE_LATITUDE_DEG`] (18.4663° N, the "Jezero Crater Projection"
//! of the Mars 2020 orbital maps, paper 000 §5), the central meridian λ₀ =
//! [`JEZERO_CENTRAL_MERIDIAN_DEG`] (77.4° E, a round meridian through Jezero) and a false
//! easting FE and northing FN chosen per map so that one documented map point, its
//! [`MapAnchor`], lands at a documented longitude and latitude. The map's rasters and vectors
//! therefore need no conversion: GDAL, QGIS and PROJ place them with the CRS alone.
//!
//! - [`MarsEquirectangular`]: one such CRS; [`MarsEquirectangular::lonlat_from_map`] and
//!   [`MarsEquirectangular::map_from_lonlat`] are the only conversions between map metres and
//!   Mars longitude/latitude; [`MarsEquirectangular::wkt2`] and
//!   [`MarsEquirectangular::wkt1_esri`] write it for GDAL (GeoTIFF PAM, GeoJSON `crs`) and for
//!   `.prj` files. [`GEOGRAPHIC_WKT2`], [`GEOGRAPHIC_WKT1_ESRI`] and [`GEOGRAPHIC_URN`] name
//!   the Mars longitude/latitude CRS (IAU_2015:49900).
//! - [`MapCrs`]: what a map file says about its place — a [`MarsEquirectangular`] CRS, or only
//!   local metres (files from before solsim georeferenced its maps, PNGs, other projections).
//!   [`MapCrs::mars_or_default`] places a local map at [`DEFAULT_ANCHOR`].
//!
//! Map metres are projected metres: along a parallel other than 18.4663° they differ from
//! ground metres by cos φ / cos φ₁ (1.00002 at 18.4447° N, 2 cm per km) — the easting scale
//! correction paper 000 §5 applies when matching.
//!
//! ## References
//! - B. A. Archinal et al., "Report of the IAU Working Group on Cartographic Coordinates and
//!   Rotational Elements: 2015", Celest. Mech. Dyn. Astron. 130, 2018 (the Mars sphere; PROJ's
//!   `IAU_2015:49900`).
//! - J. P. Snyder, "Map Projections — A Working Manual", USGS PP 1395, 1987, ch. 12
//!   (equidistant cylindrical).
//! - OGC 18-010r7, WKT for CRS (WKT2:2019); OGC GeoTIFF 1.1 (OGC 19-008r4), Annex B.

use std::fmt::Write as _;

/// Radius of the IAU 2015 Mars sphere (the Mars 2000 sphere), metres.
pub const MARS_RADIUS_M: f64 = 3_396_190.0;

/// Latitude of true scale of the Jezero Crater Projection, degrees north (paper 000 §5).
pub const JEZERO_TRUE_SCALE_LATITUDE_DEG: f64 = 18.4663;

/// Central meridian of the maps, degrees east: a round meridian through Jezero crater.
pub const JEZERO_CENTRAL_MERIDIAN_DEG: f64 = 77.4;

/// Where a map without a Mars georeference is placed: map point (0 m, 0 m) at the Octavia E.
/// Butler landing site of Perseverance, 18.4447° N, 77.4508° E (NASA's published landing
/// position), so its outputs still open in a Mars GIS, somewhere plausible.
pub const DEFAULT_ANCHOR: MapAnchor = MapAnchor {
    anchor_m: [0.0, 0.0],
    lon_deg: 77.4508,
    lat_deg: 18.4447,
};

/// The Mars longitude/latitude CRS as an OGC URN (GeoJSON 2008 `crs` member; PROJ ≥ 8.2 knows
/// it as `IAU_2015:49900`, "Mars (2015) - Sphere / Ocentric").
pub const GEOGRAPHIC_URN: &str = "urn:ogc:def:crs:IAU:2015:49900";

/// Name of the geographic CRS (IAU 2015 catalogue).
const GEOGRAPHIC_NAME: &str = "Mars (2015) - Sphere / Ocentric";
/// Name of the datum and of the sphere (IAU 2015 catalogue).
const DATUM_NAME: &str = "Mars (2015) - Sphere";
/// Name of the prime meridian (IAU 2015 catalogue: through Airy-0).
const PRIME_MERIDIAN_NAME: &str = "Reference Meridian";

/// The Mars longitude/latitude CRS, WKT2:2019 (longitude first is the GeoJSON and GIS order;
/// the CRS itself lists latitude first, as IAU_2015:49900 does).
pub const GEOGRAPHIC_WKT2: &str = concat!(
    r#"GEOGCRS["Mars (2015) - Sphere / Ocentric","#,
    r#"DATUM["Mars (2015) - Sphere",ELLIPSOID["Mars (2015) - Sphere",3396190,0,LENGTHUNIT["metre",1]]],"#,
    r#"PRIMEM["Reference Meridian",0,ANGLEUNIT["degree",0.0174532925199433]],"#,
    r#"CS[ellipsoidal,2],AXIS["geodetic latitude (Lat)",north,ORDER[1],ANGLEUNIT["degree",0.0174532925199433]],"#,
    r#"AXIS["geodetic longitude (Lon)",east,ORDER[2],ANGLEUNIT["degree",0.0174532925199433]],"#,
    r#"ID["IAU",49900,2015]]"#
);

/// The Mars longitude/latitude CRS, WKT1 as Esri writes it (for `.prj` files).
pub const GEOGRAPHIC_WKT1_ESRI: &str = concat!(
    r#"GEOGCS["GCS_Mars_2015_Sphere_Ocentric","#,
    r#"DATUM["D_Mars_2015_Sphere",SPHEROID["Mars_2015_Sphere",3396190.0,0.0]],"#,
    r#"PRIMEM["Reference_Meridian",0.0],UNIT["Degree",0.0174532925199433]]"#
);

/// A map point and where it lies on Mars (a recipe's `[georeference]` table).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapAnchor {
    /// The map point, map metres (x east, y north).
    pub anchor_m: [f64; 2],
    /// Its planetocentric longitude, degrees east (−180 to 360).
    pub lon_deg: f64,
    /// Its planetocentric latitude, degrees north (−89 to 89).
    pub lat_deg: f64,
}

impl MapAnchor {
    /// Whether the anchor can place a map: finite numbers, longitude in −180..=360° and
    /// latitude in −89..=89° (an equirectangular map near a pole is no map).
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.anchor_m.iter().all(|v| v.is_finite())
            && (-180.0..=360.0).contains(&self.lon_deg)
            && (-89.0..=89.0).contains(&self.lat_deg)
    }
}

/// An equirectangular projection of the IAU 2015 Mars sphere (see the module docs): the
/// projected CRS of a georeferenced map, whose projected coordinates are its map metres.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MarsEquirectangular {
    /// Central meridian λ₀, degrees east.
    pub central_meridian_deg: f64,
    /// Latitude of true scale φ₁, degrees north (|φ₁| < 90).
    pub true_scale_latitude_deg: f64,
    /// False easting FE: the x of the central meridian, map metres.
    pub false_easting_m: f64,
    /// False northing FN: the y of the equator, map metres.
    pub false_northing_m: f64,
}

/// Rounds to the millimetre, so a CRS derived from an anchor has the same digits on every
/// platform (a last-bit difference of `cos` cannot change them).
fn round_mm(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

impl MarsEquirectangular {
    /// The Jezero projection (φ₁ 18.4663° N, λ₀ 77.4° E) with the false easting and northing
    /// that put `anchor.anchor_m` at (`anchor.lon_deg`, `anchor.lat_deg`), rounded to the
    /// millimetre.
    #[must_use]
    pub fn jezero(anchor: &MapAnchor) -> Self {
        let mut crs = Self {
            central_meridian_deg: JEZERO_CENTRAL_MERIDIAN_DEG,
            true_scale_latitude_deg: JEZERO_TRUE_SCALE_LATITUDE_DEG,
            false_easting_m: 0.0,
            false_northing_m: 0.0,
        };
        let [x0, y0] = crs.map_from_lonlat([anchor.lon_deg, anchor.lat_deg]);
        crs.false_easting_m = round_mm(anchor.anchor_m[0] - x0);
        crs.false_northing_m = round_mm(anchor.anchor_m[1] - y0);
        crs
    }

    /// A projection from its parameters, or `None` unless all are finite and |φ₁| < 89°.
    #[must_use]
    pub fn try_new(
        central_meridian_deg: f64,
        true_scale_latitude_deg: f64,
        false_easting_m: f64,
        false_northing_m: f64,
    ) -> Option<Self> {
        let ok = [
            central_meridian_deg,
            true_scale_latitude_deg,
            false_easting_m,
            false_northing_m,
        ]
        .iter()
        .all(|v| v.is_finite())
            && true_scale_latitude_deg.abs() < 89.0;
        ok.then_some(Self {
            central_meridian_deg,
            true_scale_latitude_deg,
            false_easting_m,
            false_northing_m,
        })
    }

    /// Metres of easting per radian of longitude: R · cos φ₁.
    fn easting_m_per_rad(&self) -> f64 {
        MARS_RADIUS_M * self.true_scale_latitude_deg.to_radians().cos()
    }

    /// Planetocentric `[longitude east, latitude north]`, degrees, of map point `p_map`
    /// (metres). Longitudes are not wrapped: they run on from λ₀ either way.
    #[must_use]
    pub fn lonlat_from_map(&self, p_map: [f64; 2]) -> [f64; 2] {
        let dlon_rad = (p_map[0] - self.false_easting_m) / self.easting_m_per_rad();
        let lat_rad = (p_map[1] - self.false_northing_m) / MARS_RADIUS_M;
        [
            self.central_meridian_deg + dlon_rad.to_degrees(),
            lat_rad.to_degrees(),
        ]
    }

    /// Map metres of planetocentric `[longitude east, latitude north]` (degrees): the inverse of
    /// [`lonlat_from_map`](Self::lonlat_from_map).
    #[must_use]
    pub fn map_from_lonlat(&self, lonlat_deg: [f64; 2]) -> [f64; 2] {
        [
            self.false_easting_m
                + self.easting_m_per_rad()
                    * (lonlat_deg[0] - self.central_meridian_deg).to_radians(),
            self.false_northing_m + MARS_RADIUS_M * lonlat_deg[1].to_radians(),
        ]
    }

    /// The CRS's name: the projection and where the map's origin lies.
    #[must_use]
    pub fn name(&self) -> String {
        let [lon, lat] = self.lonlat_from_map([0.0, 0.0]);
        format!("Mars (2015) - Sphere / Jezero Equirectangular, map (0, 0) at {lon:.4}E {lat:.4}N")
    }

    /// The projected CRS as WKT2:2019 (GDAL ≥ 3 and PROJ ≥ 6 read it; its base CRS is
    /// IAU_2015:49900).
    #[must_use]
    pub fn wkt2(&self) -> String {
        let mut s = String::new();
        let _ = write!(
            s,
            r#"PROJCRS["{name}",BASEGEOGCRS["{GEOGRAPHIC_NAME}",DATUM["{DATUM_NAME}",ELLIPSOID["{DATUM_NAME}",{MARS_RADIUS_M},0,LENGTHUNIT["metre",1]]],PRIMEM["{PRIME_MERIDIAN_NAME}",0,ANGLEUNIT["degree",0.0174532925199433]],ID["IAU",49900,2015]],"#,
            name = self.name(),
        );
        let _ = write!(
            s,
            r#"CONVERSION["Jezero Equirectangular",METHOD["Equidistant Cylindrical",ID["EPSG",1028]],PARAMETER["Latitude of 1st standard parallel",{},ANGLEUNIT["degree",0.0174532925199433],ID["EPSG",8823]],PARAMETER["Longitude of natural origin",{},ANGLEUNIT["degree",0.0174532925199433],ID["EPSG",8802]],PARAMETER["False easting",{},LENGTHUNIT["metre",1],ID["EPSG",8806]],PARAMETER["False northing",{},LENGTHUNIT["metre",1],ID["EPSG",8807]]],"#,
            self.true_scale_latitude_deg,
            self.central_meridian_deg,
            self.false_easting_m,
            self.false_northing_m,
        );
        s.push_str(r#"CS[Cartesian,2],AXIS["easting (E)",east,ORDER[1],LENGTHUNIT["metre",1]],AXIS["northing (N)",north,ORDER[2],LENGTHUNIT["metre",1]]]"#);
        s
    }

    /// The projected CRS as Esri WKT1 (the `.prj` convention).
    #[must_use]
    pub fn wkt1_esri(&self) -> String {
        format!(
            r#"PROJCS["Mars_2015_Sphere_Jezero_Equirectangular",{GEOGRAPHIC_WKT1_ESRI},PROJECTION["Equidistant_Cylindrical"],PARAMETER["False_Easting",{:?}],PARAMETER["False_Northing",{:?}],PARAMETER["Central_Meridian",{:?}],PARAMETER["Standard_Parallel_1",{:?}],UNIT["Meter",1.0]]"#,
            self.false_easting_m,
            self.false_northing_m,
            self.central_meridian_deg,
            self.true_scale_latitude_deg,
        )
    }

    /// GeoTIFF citations (GeoTIFF 1.1 §7.1.4), as GDAL writes them: the projected CRS's name,
    /// and the geographic CRS with its datum, sphere and prime meridian.
    #[must_use]
    pub fn geotiff_citations(&self) -> [String; 2] {
        [
            self.name(),
            format!(
                "GCS Name = {GEOGRAPHIC_NAME}|Datum = {DATUM_NAME}|Ellipsoid = {DATUM_NAME}|Primem = {PRIME_MERIDIAN_NAME}|"
            ),
        ]
    }
}

/// What a map file says about where it lies.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum MapCrs {
    /// Local map metres with no place on Mars: GeoTIFFs written before solsim georeferenced its
    /// maps (GeoKey citation "solsim local map frame"), PNGs, other projections.
    #[default]
    Local,
    /// An equirectangular projection of the Mars sphere whose metres are the map's.
    Mars(MarsEquirectangular),
}

impl MapCrs {
    /// The map's Mars CRS; a local map is placed with [`DEFAULT_ANCHOR`] (map (0, 0) at the
    /// Perseverance landing site).
    #[must_use]
    pub fn mars_or_default(&self) -> MarsEquirectangular {
        match self {
            MapCrs::Mars(crs) => *crs,
            MapCrs::Local => MarsEquirectangular::jezero(&DEFAULT_ANCHOR),
        }
    }

    /// Whether the map carries a Mars CRS (not only local metres).
    #[must_use]
    pub fn is_mars(&self) -> bool {
        matches!(self, MapCrs::Mars(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PROJ 9.1 (`cs2cs +proj=eqc +lat_ts=18.4663 +lon_0=0 +R=3396190 +to +proj=longlat
    /// +R=3396190`, `-f %.12f`) for the projected point (1000 m, 1000 m).
    const PROJ_1KM_DLON_DEG: f64 = 0.017_786_425_748;
    const PROJ_1KM_DLAT_DEG: f64 = 0.016_870_604_858;

    fn crater_floor() -> MarsEquirectangular {
        MarsEquirectangular::jezero(&MapAnchor {
            anchor_m: [600.0, 600.0],
            lon_deg: 77.4508,
            lat_deg: 18.4447,
        })
    }

    #[test]
    fn the_anchor_lands_where_it_was_placed() {
        let crs = crater_floor();
        let [lon, lat] = crs.lonlat_from_map([600.0, 600.0]);
        // Within a millimetre (FE and FN are rounded to it): ~2e-8 degrees.
        assert!((lon - 77.4508).abs() < 2e-8, "{lon}");
        assert!((lat - 18.4447).abs() < 2e-8, "{lat}");
        assert_eq!(
            crs.false_easting_m,
            (crs.false_easting_m * 1e3).round() / 1e3
        );
    }

    #[test]
    fn one_km_east_and_north_match_proj() {
        let crs = crater_floor();
        let [lon0, lat0] = crs.lonlat_from_map([600.0, 600.0]);
        let [lon_e, lat_e] = crs.lonlat_from_map([1600.0, 600.0]);
        let [lon_n, lat_n] = crs.lonlat_from_map([600.0, 1600.0]);
        assert!(
            (lon_e - lon0 - PROJ_1KM_DLON_DEG).abs() < 1e-11,
            "{}",
            lon_e - lon0
        );
        assert!((lat_e - lat0).abs() < 1e-12);
        assert!(
            (lat_n - lat0 - PROJ_1KM_DLAT_DEG).abs() < 1e-11,
            "{}",
            lat_n - lat0
        );
        assert!((lon_n - lon0).abs() < 1e-12);
        // True scale at 18.4663°: a degree of longitude there is cos φ₁ of a degree of latitude.
        let ratio = PROJ_1KM_DLAT_DEG / PROJ_1KM_DLON_DEG;
        assert!(
            (ratio - 18.4663f64.to_radians().cos()).abs() < 1e-9,
            "{ratio}"
        );
    }

    #[test]
    fn forward_and_inverse_round_trip() {
        let crs = crater_floor();
        for p in [
            [0.0, 0.0],
            [1200.0, 1200.0],
            [-5000.0, 9600.0],
            [123.456, -789.012],
        ] {
            let back = crs.map_from_lonlat(crs.lonlat_from_map(p));
            assert!(
                (back[0] - p[0]).abs() < 1e-6 && (back[1] - p[1]).abs() < 1e-6,
                "{p:?} → {back:?}"
            );
        }
        for ll in [[77.4, 18.4663], [77.5, 18.3], [-10.0, 0.0], [200.0, -45.0]] {
            let back = crs.lonlat_from_map(crs.map_from_lonlat(ll));
            assert!((back[0] - ll[0]).abs() < 1e-12 && (back[1] - ll[1]).abs() < 1e-12);
        }
        // The central meridian at the equator is (FE, FN).
        let at = crs.map_from_lonlat([JEZERO_CENTRAL_MERIDIAN_DEG, 0.0]);
        assert_eq!(at, [crs.false_easting_m, crs.false_northing_m]);
    }

    #[test]
    fn parameters_out_of_range_are_refused() {
        assert!(MarsEquirectangular::try_new(77.4, 18.4663, 0.0, 0.0).is_some());
        assert!(MarsEquirectangular::try_new(77.4, 90.0, 0.0, 0.0).is_none());
        assert!(MarsEquirectangular::try_new(f64::NAN, 0.0, 0.0, 0.0).is_none());
        assert!(MarsEquirectangular::try_new(0.0, 0.0, f64::INFINITY, 0.0).is_none());
        assert!(DEFAULT_ANCHOR.is_valid());
        let mut bad = DEFAULT_ANCHOR;
        bad.lat_deg = 90.0;
        assert!(!bad.is_valid());
        bad = DEFAULT_ANCHOR;
        bad.anchor_m[0] = f64::NAN;
        assert!(!bad.is_valid());
    }

    #[test]
    fn a_local_map_is_placed_at_the_landing_site() {
        let crs = MapCrs::Local.mars_or_default();
        let [lon, lat] = crs.lonlat_from_map([0.0, 0.0]);
        assert!((lon - 77.4508).abs() < 2e-8 && (lat - 18.4447).abs() < 2e-8);
        assert!(!MapCrs::Local.is_mars());
        assert!(MapCrs::Mars(crs).is_mars());
    }

    #[test]
    fn wkt_carries_the_parameters() {
        let crs = crater_floor();
        let w2 = crs.wkt2();
        assert!(w2.starts_with("PROJCRS[") && w2.ends_with("]]"));
        assert!(w2.contains("3396190,0"));
        assert!(w2.contains(&format!("\"False easting\",{}", crs.false_easting_m)));
        assert_eq!(w2.matches('[').count(), w2.matches(']').count());
        let esri = crs.wkt1_esri();
        assert!(esri.contains("PARAMETER[\"Standard_Parallel_1\",18.4663]"));
        assert!(esri.contains("PARAMETER[\"Central_Meridian\",77.4]"));
        assert_eq!(esri.matches('[').count(), esri.matches(']').count());
        assert_eq!(
            GEOGRAPHIC_WKT2.matches('[').count(),
            GEOGRAPHIC_WKT2.matches(']').count()
        );
        assert!(crs.name().contains("77.4"));
    }
}
