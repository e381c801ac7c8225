//! Corridor geometry: distances from points and rectangles to the route polyline, and the
//! per-row masks of the pixels within the corridor's half-width.

use crate::raster::{GeoTransform, Raster};

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

/// Distance from the closed rectangle `[x0, y0, x1, y1]` to the polyline `route` (0 if they
/// meet); infinite for an empty route.
#[must_use]
pub fn distance_rect_to_route_m(rect: [f64; 4], route: &[[f64; 2]]) -> f64 {
    let [x0, y0, x1, y1] = rect;
    let point_to_rect = |p: [f64; 2]| {
        let dx = (x0 - p[0]).max(p[0] - x1).max(0.0);
        let dy = (y0 - p[1]).max(p[1] - y1).max(0.0);
        dx.hypot(dy)
    };
    let corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    match route {
        [] => f64::INFINITY,
        [only] => point_to_rect(*only),
        _ => route
            .windows(2)
            .map(|w| {
                if segment_meets_rect(w[0], w[1], rect) {
                    return 0.0;
                }
                // Disjoint convex sets: the closest pair has an endpoint or a corner in it.
                let ends = point_to_rect(w[0]).min(point_to_rect(w[1]));
                corners
                    .iter()
                    .map(|&c| distance_to_route_m(c, w))
                    .fold(ends, f64::min)
            })
            .fold(f64::INFINITY, f64::min),
    }
}

/// Whether segment `a`–`b` meets the closed rectangle (Liang–Barsky clipping).
fn segment_meets_rect(a: [f64; 2], b: [f64; 2], rect: [f64; 4]) -> bool {
    let [x0, y0, x1, y1] = rect;
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a[0] - x0),
        (dx, x1 - a[0]),
        (-dy, a[1] - y0),
        (dy, y1 - a[1]),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

/// Which pixel centres of row `row` (`width` pixels of `geo`) lie within `half_width_m` of the
/// route. Only the route segments that can reach the row are tested.
pub(super) fn row_mask(
    geo: &GeoTransform,
    row: usize,
    width: usize,
    route: &[[f64; 2]],
    half_width_m: f64,
) -> Vec<bool> {
    let y = geo.center_of(0, row).1;
    let near: Vec<[f64; 2]> = match route {
        [only] => vec![*only],
        _ => Vec::new(),
    };
    let segments: Vec<[[f64; 2]; 2]> = route
        .windows(2)
        .filter(|w| {
            w[0][1].min(w[1][1]) - half_width_m <= y && y <= w[0][1].max(w[1][1]) + half_width_m
        })
        .map(|w| [w[0], w[1]])
        .collect();
    (0..width)
        .map(|col| {
            let x = geo.center_of(col, row).0;
            segments
                .iter()
                .any(|s| distance_to_route_m([x, y], s) <= half_width_m)
                || near
                    .iter()
                    .any(|p| (x - p[0]).hypot(y - p[1]) <= half_width_m)
        })
        .collect()
}

/// Masks `r` to the corridor in place: kept pixels become `keep(v)`, the others `fill`.
/// Returns the number kept.
pub(super) fn mask_in_place<T: Copy>(
    r: &mut Raster<T>,
    route: &[[f64; 2]],
    half_width_m: f64,
    keep: impl Fn(T) -> T,
    fill: T,
) -> usize {
    let mut kept = 0;
    for row in 0..r.height {
        let mask = row_mask(&r.geo, row, r.width, route, half_width_m);
        for (v, inside) in r.data[row * r.width..(row + 1) * r.width]
            .iter_mut()
            .zip(mask)
        {
            if inside {
                *v = keep(*v);
                kept += 1;
            } else {
                *v = fill;
            }
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_a_polyline() {
        let route = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]];
        assert_eq!(distance_to_route_m([5.0, 3.0], &route), 3.0);
        assert_eq!(distance_to_route_m([13.0, 5.0], &route), 3.0);
        assert_eq!(distance_to_route_m([-3.0, -4.0], &route), 5.0);
        assert_eq!(distance_to_route_m([1.0, 1.0], &[]), f64::INFINITY);
    }

    #[test]
    fn rectangle_to_route_distance() {
        let rect = [0.0, 0.0, 10.0, 10.0];
        assert_eq!(
            distance_rect_to_route_m(rect, &[[5.0, 5.0], [6.0, 6.0]]),
            0.0
        );
        // Crosses the rectangle with both ends outside.
        assert_eq!(
            distance_rect_to_route_m(rect, &[[-5.0, 5.0], [15.0, 5.0]]),
            0.0
        );
        assert_eq!(
            distance_rect_to_route_m(rect, &[[13.0, -5.0], [13.0, 20.0]]),
            3.0
        );
        assert_eq!(distance_rect_to_route_m(rect, &[[13.0, 14.0]]), 5.0);
        // A diagonal passing the corner (10, 10) at √2 × 2 / 2 = 1.414… m.
        let d = distance_rect_to_route_m(rect, &[[12.0, 10.0], [10.0, 12.0]]);
        assert!((d - std::f64::consts::SQRT_2).abs() < 1e-12, "{d}");
        assert_eq!(distance_rect_to_route_m(rect, &[]), f64::INFINITY);
    }
}
