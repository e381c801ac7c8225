//! [`MapLayers`]: the appearance, DEM and terrain-class layers of one map, loaded and written
//! together so they always cover the same ground.

use std::fs;
use std::path::Path;

use super::{
    RasterError, check_geo, check_shape, dem_to_cm_for, io_error, pixel_of_index, read_dem,
    read_raster, write_geotiff_with_crs,
};
use crate::mars_crs::MapCrs;
use crate::raster::{GeoTransform, Raster};
use crate::terrain::TerrainClass;

/// The three layers of one map. They may differ in resolution but cover the same extent.
#[derive(Clone, Debug, PartialEq)]
pub struct MapLayers {
    /// Orbital appearance (8-bit gray), what the localization matcher sees.
    pub appearance: Raster<u8>,
    /// Heights in metres.
    pub dem: Raster<f32>,
    /// Terrain-class codes (see [`TerrainClass::code`]; 0 = no data).
    pub terrain: Raster<u8>,
}

impl MapLayers {
    /// File name of the appearance layer written by [`MapLayers::write_dir`].
    pub const APPEARANCE_FILE: &'static str = "appearance.tif";
    /// File name of the DEM layer written by [`MapLayers::write_dir`].
    pub const DEM_FILE: &'static str = "dem.tif";
    /// File name of the terrain-class layer written by [`MapLayers::write_dir`].
    pub const TERRAIN_FILE: &'static str = "terrain.tif";

    /// Loads the three layers of a map (PNG or GeoTIFF each, by extension).
    ///
    /// The DEM is read as [`read_dem`] does (16-bit cm above `datum_m`, or f32 metres).
    /// `georef` is required if any layer is a PNG and then places **every** layer, so all must
    /// have the same pixel size; without it each GeoTIFF's own tags place it. The layers must
    /// cover the same extent within half a pixel of the coarsest layer.
    ///
    /// # Errors
    /// Any [`RasterError`] of the readers, plus [`RasterError::BadTerrainCode`] for terrain
    /// codes above 3, [`RasterError::SizeMismatch`] for layers of different pixel sizes under
    /// one `georef`, and [`RasterError::ExtentMismatch`] for layers covering different ground.
    pub fn load(
        appearance: &Path,
        dem: &Path,
        terrain: &Path,
        datum_m: f64,
        georef: Option<GeoTransform>,
    ) -> Result<Self, RasterError> {
        let layers = MapLayers {
            appearance: read_raster::<u8>(appearance, georef)?,
            dem: read_dem(dem, datum_m, georef)?,
            terrain: read_raster::<u8>(terrain, georef)?,
        };
        check_terrain_codes(terrain, &layers.terrain)?;
        if georef.is_some() {
            let expected = (layers.appearance.width, layers.appearance.height);
            for (path, found) in [
                (dem, (layers.dem.width, layers.dem.height)),
                (terrain, (layers.terrain.width, layers.terrain.height)),
            ] {
                if found != expected {
                    return Err(RasterError::SizeMismatch {
                        path: path.to_path_buf(),
                        expected,
                        found,
                    });
                }
            }
        }
        layers.check_extents(appearance, dem, terrain)?;
        Ok(layers)
    }

    /// Writes the map into `dir` (created if missing) as three GeoTIFFs:
    /// [`APPEARANCE_FILE`](Self::APPEARANCE_FILE) (u8),
    /// [`DEM_FILE`](Self::DEM_FILE) (u16 centimetres above `datum_m`) and
    /// [`TERRAIN_FILE`](Self::TERRAIN_FILE) (u8, `GDAL_NODATA` = 0), each carrying `crs` in
    /// its GeoKeys (see [`write_geotiff_with_crs`]).
    ///
    /// Everything is validated before the first file is written, and each file is replaced
    /// atomically, so bad layers leave `dir` untouched.
    ///
    /// # Errors
    /// [`RasterError::HeightOutOfRange`] / [`RasterError::NonFinite`] for a DEM that 16-bit cm
    /// above `datum_m` cannot hold, [`RasterError::BadTerrainCode`], [`RasterError::ExtentMismatch`]
    /// for layers covering different ground, malformed rasters, and I/O failures.
    pub fn write_dir(&self, dir: &Path, datum_m: f64, crs: &MapCrs) -> Result<(), RasterError> {
        let app_path = dir.join(Self::APPEARANCE_FILE);
        let dem_path = dir.join(Self::DEM_FILE);
        let terrain_path = dir.join(Self::TERRAIN_FILE);
        check_shape(&app_path, &self.appearance)?;
        check_geo(&app_path, &self.appearance.geo)?;
        check_shape(&dem_path, &self.dem)?;
        check_geo(&dem_path, &self.dem.geo)?;
        check_shape(&terrain_path, &self.terrain)?;
        check_geo(&terrain_path, &self.terrain.geo)?;
        check_terrain_codes(&terrain_path, &self.terrain)?;
        self.check_extents(&app_path, &dem_path, &terrain_path)?;
        let dem_cm = dem_to_cm_for(&self.dem, datum_m, &dem_path)?;

        fs::create_dir_all(dir).map_err(io_error(dir))?;
        write_geotiff_with_crs(&app_path, &self.appearance, None, crs)?;
        write_geotiff_with_crs(&dem_path, &dem_cm, None, crs)?;
        write_geotiff_with_crs(&terrain_path, &self.terrain, Some(0.0), crs)
    }

    /// Checks the DEM and terrain layers cover the appearance layer's extent within half a
    /// pixel of the coarsest layer.
    fn check_extents(
        &self,
        appearance: &Path,
        dem: &Path,
        terrain: &Path,
    ) -> Result<(), RasterError> {
        let coarsest = self
            .appearance
            .geo
            .resolution_m_per_px
            .max(self.dem.geo.resolution_m_per_px)
            .max(self.terrain.geo.resolution_m_per_px);
        let tolerance_m = 0.5 * coarsest;
        let expected = to_array(self.appearance.extent_m());
        for (path, found) in [
            (dem, to_array(self.dem.extent_m())),
            (terrain, to_array(self.terrain.extent_m())),
        ] {
            // A relative slack absorbs rounding in extents of large map coordinates.
            let slack = tolerance_m + 1e-9 * expected.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            if expected
                .iter()
                .zip(&found)
                .any(|(e, f)| (e - f).abs() > slack)
            {
                return Err(RasterError::ExtentMismatch {
                    path: path.to_path_buf(),
                    reference: appearance.to_path_buf(),
                    expected,
                    found,
                    tolerance_m,
                });
            }
        }
        Ok(())
    }
}

fn to_array((x0, y0, x1, y1): (f64, f64, f64, f64)) -> [f64; 4] {
    [x0, y0, x1, y1]
}

/// Rejects codes other than 0 (no data) and the [`TerrainClass`] codes.
fn check_terrain_codes(path: &Path, terrain: &Raster<u8>) -> Result<(), RasterError> {
    match terrain
        .data
        .iter()
        .position(|&c| c != 0 && TerrainClass::from_code(c).is_none())
    {
        Some(i) => Err(RasterError::BadTerrainCode {
            path: path.to_path_buf(),
            pixel: pixel_of_index(i, terrain.width),
            code: terrain.data[i],
        }),
        None => Ok(()),
    }
}
