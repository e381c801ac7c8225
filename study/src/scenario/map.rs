//! `[map]`: the orthoimage, DEM, terrain-class and zones files, resolved against the scenario's
//! folder, the DEM's datum and where PNG layers lie → [`MapFiles`] (read by
//! `Scenario::build`).

use std::path::{Path, PathBuf};

use maps::GeoTransform;

use super::raw::RawMap;
use crate::check::FieldCheck;
use crate::error::ScenarioError;
use crate::pair::Pair;
use crate::ranges;

/// The `[map]` section: files resolved against the scenario's folder.
#[derive(Clone, Debug)]
pub struct MapFiles {
    /// Orthoimage (u8), PNG or GeoTIFF.
    pub appearance: PathBuf,
    /// DEM: 16-bit centimetres above `dem_datum_m`, or f32 metres.
    pub dem: PathBuf,
    /// Terrain classes (u8).
    pub terrain: PathBuf,
    /// Keep-in / keep-out zones, GeoJSON.
    pub zones: PathBuf,
    /// Datum of a 16-bit centimetre DEM, metres.
    pub dem_datum_m: f64,
    /// Placement of PNG layers (GeoTIFFs carry their own).
    pub georef: Option<GeoTransform>,
}

/// The map files `[map]` names, relative paths resolved against `base` (the scenario's
/// folder), without reading them.
///
/// # Errors
/// A [`ScenarioError`] naming the first `map.…` field at fault.
pub(crate) fn map_files(
    c: &FieldCheck<'_>,
    raw: &RawMap,
    base: &Path,
) -> Result<MapFiles, ScenarioError> {
    let resolve = |p: &Path| {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            base.join(p)
        }
    };
    let georef = match (raw.resolution_m_per_px, raw.origin_m) {
        (None, None) => None,
        (Some(res), Some(Pair(o))) => {
            c.range(
                ranges::MAP_RESOLUTION_M_PER_PX,
                "map.resolution_m_per_px",
                res,
            )?;
            for (i, v) in o.iter().enumerate() {
                c.range(ranges::COORDINATE_M, &format!("map.origin_m[{i}]"), *v)?;
            }
            Some(GeoTransform::new(o[0], o[1], res))
        }
        (Some(_), None) => {
            return Err(c.err(
                "map.origin_m",
                "[x, y] of the north-west corner, given with resolution_m_per_px",
                "nothing",
            ));
        }
        (None, Some(_)) => {
            return Err(c.err(
                "map.resolution_m_per_px",
                "metres per pixel, given with origin_m",
                "nothing",
            ));
        }
    };
    c.range(ranges::DEM_DATUM_M, "map.dem_datum_m", raw.dem_datum_m)?;
    Ok(MapFiles {
        appearance: resolve(&raw.appearance),
        dem: resolve(&raw.dem),
        terrain: resolve(&raw.terrain),
        zones: resolve(&raw.zones),
        dem_datum_m: raw.dem_datum_m,
        georef,
    })
}
