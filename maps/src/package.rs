//! Onboard map packages: the orbital map masked to a corridor around the strategic route, the DEM
//! as 16-bit centimetres, compressed losslessly (PNG) — what would be uplinked for onboard global
//! localization (paper 000 §5: "a few megabytes" for a long traverse).
//!
//! Pixels farther than the corridor half-width from the route polyline are set to 0 (no data), so
//! the lossless encoder spends almost nothing on them; the package keeps full resolution inside.

use std::path::{Path, PathBuf};

use crate::raster::Raster;
use crate::raster_io::{RasterError, dem_to_cm, write_png};

/// Distance from `p` to the polyline `route` (map metres); infinite for an empty route.
#[must_use]
pub fn distance_to_route_m(p: [f64; 2], route: &[[f64; 2]]) -> f64 {
    match route {
        [] => f64::INFINITY,
        [only] => (p[0] - only[0]).hypot(p[1] - only[1]),
        _ => route
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let len2 = dx * dx + dy * dy;
                let t = if len2 > 0.0 {
                    (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
            })
            .fold(f64::INFINITY, f64::min),
    }
}

/// Which pixels of `raster` lie within `half_width_m` of the route (pixel centres).
#[must_use]
pub fn corridor_mask<T: Copy>(
    raster: &Raster<T>,
    route: &[[f64; 2]],
    half_width_m: f64,
) -> Vec<bool> {
    let mut mask = vec![false; raster.width * raster.height];
    for row in 0..raster.height {
        for col in 0..raster.width {
            let (x, y) = raster.geo.center_of(col, row);
            mask[row * raster.width + col] = distance_to_route_m([x, y], route) <= half_width_m;
        }
    }
    mask
}

/// A copy of `raster` with every pixel outside `mask` set to `fill`.
#[must_use]
pub fn masked<T: Copy>(raster: &Raster<T>, mask: &[bool], fill: T) -> Raster<T> {
    let data = raster
        .data
        .iter()
        .zip(mask)
        .map(|(&v, &keep)| if keep { v } else { fill })
        .collect();
    Raster {
        data,
        ..raster.clone()
    }
}

/// Sizes of a written map package.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PackageReport {
    /// Files written, with their sizes in bytes.
    pub files: Vec<(PathBuf, u64)>,
    /// Sum of the file sizes, bytes.
    pub total_bytes: u64,
    /// Pixels kept inside the corridor, per layer (appearance, DEM).
    pub kept_px: [usize; 2],
}

/// Write the corridor-masked appearance (8-bit PNG, 0 = no data) and DEM (16-bit PNG of
/// centimetres above `datum_m`; 0 is reserved for no data, so a kept height exactly at the datum
/// is written as 1 cm) into `dir`, and report the sizes.
///
/// # Errors
/// A DEM height outside the 16-bit centimetre range, or a write failure.
pub fn write_package(
    dir: &Path,
    appearance: &Raster<u8>,
    dem: &Raster<f32>,
    datum_m: f64,
    route: &[[f64; 2]],
    half_width_m: f64,
) -> Result<PackageReport, RasterError> {
    let app_mask = corridor_mask(appearance, route, half_width_m);
    let dem_mask = corridor_mask(dem, route, half_width_m);
    let app = masked(appearance, &app_mask, 0u8);
    let mut dem_cm = dem_to_cm(dem, datum_m)?;
    for (v, &keep) in dem_cm.data.iter_mut().zip(&dem_mask) {
        *v = if keep { (*v).max(1) } else { 0 };
    }
    std::fs::create_dir_all(dir).map_err(|source| RasterError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let app_path = dir.join("appearance.png");
    let dem_path = dir.join("dem_cm.png");
    write_png(&app_path, &app)?;
    write_png(&dem_path, &dem_cm)?;
    let mut files = Vec::new();
    for p in [app_path, dem_path] {
        let len = std::fs::metadata(&p)
            .map_err(|source| RasterError::Io {
                path: p.clone(),
                source,
            })?
            .len();
        files.push((p, len));
    }
    let total_bytes = files.iter().map(|(_, n)| n).sum();
    Ok(PackageReport {
        files,
        total_bytes,
        kept_px: [
            app_mask.iter().filter(|&&k| k).count(),
            dem_mask.iter().filter(|&&k| k).count(),
        ],
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::GeoTransform;

    #[test]
    fn distance_to_a_polyline() {
        let route = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]];
        assert_eq!(distance_to_route_m([5.0, 3.0], &route), 3.0);
        assert_eq!(distance_to_route_m([13.0, 5.0], &route), 3.0);
        assert_eq!(distance_to_route_m([-3.0, -4.0], &route), 5.0);
        assert_eq!(distance_to_route_m([1.0, 1.0], &[]), f64::INFINITY);
    }

    #[test]
    fn masking_shrinks_the_package_and_keeps_the_corridor() {
        let geo = GeoTransform::new(0.0, 200.0, 1.0);
        let mut app = Raster::filled(200, 200, geo, 0u8);
        for (i, v) in app.data.iter_mut().enumerate() {
            *v = (i.wrapping_mul(2_654_435_761) >> 13) as u8; // incompressible texture
        }
        let dem = Raster::filled(50, 50, geo.scaled(4.0), 100.0f32);
        let route = [[0.0, 100.0], [200.0, 100.0]];
        let dir = tempfile::tempdir().unwrap();
        let narrow =
            write_package(&dir.path().join("narrow"), &app, &dem, 0.0, &route, 10.0).unwrap();
        let wide = write_package(&dir.path().join("wide"), &app, &dem, 0.0, &route, 100.0).unwrap();
        assert_eq!(narrow.kept_px[0], 200 * 20);
        assert!(
            narrow.total_bytes * 4 < wide.total_bytes,
            "{narrow:?} vs {wide:?}"
        );
        let back = crate::raster_io::read_png::<u8>(&dir.path().join("narrow/appearance.png"), geo)
            .unwrap();
        assert_eq!(back.get(7, 95), app.get(7, 95));
        assert_eq!(back.get(7, 50), 0);
    }
}
