//! Georeference sidecars for rasters that carry none themselves (PNG): an Esri world file
//! (`.pgw`), which places the pixels, and a GDAL PAM file (`.png.aux.xml`), which names the CRS.
//! With both beside a PNG, `gdalinfo` and QGIS report its CRS and extent.
//!
//! ## References
//! - Esri, "World files for raster datasets" (six lines: A, D, B, E, C, F).
//! - GDAL, "PAM (Persistent Auxiliary Metadata)": `<PAMDataset><SRS>…</SRS></PAMDataset>`.

use crate::mars_crs::MarsEquirectangular;
use crate::raster::GeoTransform;

/// The world file of a raster placed by `geo`: pixel width, rotation terms 0 and 0, minus the
/// pixel height, then the map position of the **centre** of the top-left pixel (the world
/// file's convention, where `geo` holds its corner). Numbers are written shortest-exact, so
/// they read back bit for bit.
#[must_use]
pub fn world_file(geo: &GeoTransform) -> String {
    let res = geo.resolution_m_per_px;
    let (cx, cy) = geo.center_of(0, 0);
    format!("{res:?}\n0.0\n0.0\n{:?}\n{cx:?}\n{cy:?}\n", -res)
}

/// The GDAL PAM file naming `crs` as the raster's CRS (its WKT2, XML-escaped), east-north axis
/// order.
#[must_use]
pub fn pam_aux_xml(crs: &MarsEquirectangular) -> String {
    let wkt = crs
        .wkt2()
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;");
    format!("<PAMDataset>\n  <SRS dataAxisToSRSAxisMapping=\"1,2\">{wkt}</SRS>\n</PAMDataset>\n")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mars_crs::{DEFAULT_ANCHOR, MarsEquirectangular};

    #[test]
    fn world_file_names_the_centre_of_the_top_left_pixel() {
        let text = world_file(&GeoTransform::new(1000.0, 2000.0, 0.25));
        assert_eq!(text, "0.25\n0.0\n0.0\n-0.25\n1000.125\n1999.875\n");
        assert_eq!(text.lines().count(), 6);
    }

    #[test]
    fn pam_file_escapes_the_wkt() {
        let xml = pam_aux_xml(&MarsEquirectangular::jezero(&DEFAULT_ANCHOR));
        assert!(xml.starts_with("<PAMDataset>"));
        assert!(xml.contains("PROJCRS[&quot;Mars (2015)"));
        assert!(!xml.contains("[\""));
    }
}
