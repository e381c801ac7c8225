//! What `solsim map generate` says of a map it made from a [`Recipe`]: its size, pixel size and
//! extent in map metres, seed, DEM datum and where it lies on Mars.

use std::path::Path;

use maps::MapLayers;

use crate::recipe::Recipe;

/// A generated map, described (`solsim map generate --json` holds these fields).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct GeneratedMap {
    /// Width and height, pixels.
    pub size_px: [usize; 2],
    /// Pixel size, metres.
    pub resolution_m_per_px: f64,
    /// West and east edges, map metres.
    pub x_m: [f64; 2],
    /// South and north edges, map metres.
    pub y_m: [f64; 2],
    /// The recipe's seed.
    pub seed: u64,
    /// Height of DEM value 0, metres.
    pub dem_datum_m: f64,
    /// Where the map lies on Mars (`null`: map metres only).
    pub crs: Option<MapOnMars>,
}

/// Where a generated map lies on Mars.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MapOnMars {
    /// The CRS's name.
    pub name: String,
    /// West and east edges, degrees east.
    pub lon_deg: [f64; 2],
    /// South and north edges, degrees north.
    pub lat_deg: [f64; 2],
}

impl GeneratedMap {
    /// The map `layers` generated from `recipe`.
    #[must_use]
    pub fn of(recipe: &Recipe, layers: &MapLayers) -> Self {
        let params = &recipe.terrain;
        let (x0, y0, x1, y1) = layers.dem.extent_m();
        let crs = match &recipe.crs {
            maps::MapCrs::Mars(crs) => {
                let [lon0, lat0] = crs.lonlat_from_map([x0, y0]);
                let [lon1, lat1] = crs.lonlat_from_map([x1, y1]);
                Some(MapOnMars {
                    name: crs.name().to_string(),
                    lon_deg: [lon0, lon1],
                    lat_deg: [lat0, lat1],
                })
            }
            _ => None,
        };
        Self {
            size_px: [params.width_px, params.height_px],
            resolution_m_per_px: params.geo.resolution_m_per_px,
            x_m: [x0, x1],
            y_m: [y0, y1],
            seed: params.seed,
            dem_datum_m: recipe.dem_datum_m,
            crs,
        }
    }

    /// The printed summary of the map written in `dir`.
    #[must_use]
    pub fn text(&self, dir: &Path) -> String {
        let ([x0, x1], [y0, y1]) = (self.x_m, self.y_m);
        let mut t = format!(
            "wrote {}/{{appearance,dem,terrain}}.tif: {} × {} px at {} m/px, x {x0:.1}..{x1:.1} m, y {y0:.1}..{y1:.1} m (seed {})\n",
            dir.display(),
            self.size_px[0],
            self.size_px[1],
            self.resolution_m_per_px,
            self.seed
        );
        if let Some(crs) = &self.crs {
            let ([lon0, lon1], [lat0, lat1]) = (crs.lon_deg, crs.lat_deg);
            t.push_str(&format!(
                "CRS: {} (lon {lon0:.5}..{lon1:.5}° E, lat {lat0:.5}..{lat1:.5}° N)\n",
                crs.name
            ));
        }
        t
    }
}
