//! Scanline rasterisation of polygons onto the simulator grid: a cell is marked when its centre is
//! inside, found per row by the even-odd crossings of the row's centre line with the polygon's
//! rings.
//!
//! Each polygon is filled on its own and the results OR-ed, so overlapping polygons add up to their
//! union (a single even-odd pass over all rings would cancel overlaps). A centre exactly on an edge
//! follows the half-open crossing rule and may land on either side. Rows are filled in parallel;
//! each row is computed independently, so the result does not depend on the thread count.

use super::geometry::P;
use super::polygons::{Polygons, ring_edges};
use crate::raster::GeoTransform;
use rayon::prelude::*;

/// One polygon's edges, and the first and last rows whose centre lines its box reaches.
type Shape = (Vec<(P, P)>, usize, usize);

/// Mark (set to `true`) the cells of a `width × height` grid placed by `geo` whose centres lie in
/// any of `polygons`. `mask` is row-major, row 0 north, and `width * height` long.
pub(super) fn fill_polygons(
    polygons: &Polygons,
    geo: GeoTransform,
    width: usize,
    mask: &mut [bool],
) {
    let res = geo.resolution_m_per_px;
    if width == 0 || polygons.is_empty() || !(res.is_finite() && res > 0.0) {
        return;
    }
    // Per polygon: its edges and the rows its box covers.
    let shapes: Vec<Shape> = (0..polygons.len())
        .filter_map(|i| {
            let bb = polygons.entries()[i].aabb;
            // Row r has its centre at y = oy − (r + ½)·res; keep rows with centres in [min_y, max_y].
            let first = ((geo.origin_m[1] - bb.max[1]) / res - 0.5).ceil().max(0.0);
            let last = ((geo.origin_m[1] - bb.min[1]) / res - 0.5).floor();
            if last.is_nan() || last < first {
                return None;
            }
            let edges: Vec<(P, P)> = polygons.rings(i).flat_map(ring_edges).collect();
            Some((edges, first as usize, last as usize))
        })
        .collect();
    mask.par_chunks_mut(width).enumerate().for_each_init(
        Vec::new,
        |xs: &mut Vec<f64>, (row, cells)| {
            let y = geo.origin_m[1] - (row as f64 + 0.5) * res;
            for (edges, first, last) in &shapes {
                if row < *first || row > *last {
                    continue;
                }
                xs.clear();
                for &(a, b) in edges {
                    if (a[1] > y) != (b[1] > y) {
                        xs.push(a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]));
                    }
                }
                xs.sort_by(f64::total_cmp);
                for pair in xs.chunks_exact(2) {
                    // Cells whose centre x = ox + (c + ½)·res lies in [x0, x1).
                    let c0 = ((pair[0] - geo.origin_m[0]) / res - 0.5)
                        .ceil()
                        .clamp(0.0, width as f64) as usize;
                    let c1 = ((pair[1] - geo.origin_m[0]) / res - 0.5)
                        .ceil()
                        .clamp(0.0, width as f64) as usize;
                    if c0 < c1 {
                        cells[c0..c1].fill(true);
                    }
                }
            }
        },
    );
}
