//! Zones grown and shrunk by a distance, as polygons: what the planners avoid at uncertainty
//! `r` — each keep-out grown by `r + footprint` (its Minkowski sum with a disc), the keep-in
//! union shrunk by as much — for maps and GIS layers.
//!
//! The distance queries of [`ZoneSet`] stay exact; these polygons approximate the round parts
//! (around convex corners of keep-outs, concave corners of the keep-in union) by chords of at
//! most [`ARC_STEP_RAD`] × the distance (geo's `Buffer` with round joins, computed by
//! i_overlay), so their boundary lies within 0.0004 × the distance inside the exact one: 1 cm
//! at 27 m.

use geo::algorithm::buffer::{BufferStyle, LineJoin};
use geo::orient::{Direction, Orient};
use geo::{Buffer, MultiPolygon, unary_union};

use super::{ZoneHandle, ZoneKind, ZoneSet};

/// Longest chord of a grown corner's arc, as a fraction of the growth distance (radians of arc
/// per chord).
pub const ARC_STEP_RAD: f64 = 0.05;

/// The rings of each polygon of `area` as coordinate lists (map metres): exterior first,
/// exteriors counter-clockwise and holes clockwise (RFC 7946 §3.1.6), each ring closed.
#[must_use]
pub fn polygon_rings_m(area: &MultiPolygon<f64>) -> Vec<Vec<Vec<[f64; 2]>>> {
    let ring = |l: &geo::LineString<f64>| l.0.iter().map(|c| [c.x, c.y]).collect::<Vec<_>>();
    area.orient(Direction::Default)
        .0
        .iter()
        .map(|p| {
            std::iter::once(ring(p.exterior()))
                .chain(p.interiors().iter().map(ring))
                .collect()
        })
        .collect()
}

fn offset(area: &MultiPolygon<f64>, distance_m: f64) -> MultiPolygon<f64> {
    let style = BufferStyle::new(distance_m).line_join(LineJoin::Round(ARC_STEP_RAD));
    area.buffer_with_style(style).orient(Direction::Default)
}

impl ZoneSet {
    /// Each keep-out zone grown by `distance_m` (its Minkowski sum with a disc of that radius),
    /// in file order, exterior rings counter-clockwise. A distance that is not positive and
    /// finite leaves the zones as they are.
    ///
    /// # Units
    /// Metres, like the zones.
    #[must_use]
    pub fn keep_outs_grown(&self, distance_m: f64) -> Vec<(ZoneHandle, MultiPolygon<f64>)> {
        self.keep_outs()
            .map(|(h, z)| {
                let area = if distance_m.is_finite() && distance_m > 0.0 {
                    offset(z.geometry(), distance_m)
                } else {
                    z.geometry().clone().orient(Direction::Default)
                };
                (h, area)
            })
            .collect()
    }

    /// The union of the keep-in zones shrunk by `distance_m` (the points at least that far
    /// inside its edge; empty when nothing is), exterior rings counter-clockwise; `None` when
    /// there are no keep-ins (everywhere is allowed). A distance that is not positive and
    /// finite gives the union itself.
    ///
    /// # Units
    /// Metres, like the zones.
    #[must_use]
    pub fn keep_in_shrunk(&self, distance_m: f64) -> Option<MultiPolygon<f64>> {
        let parts: Vec<&MultiPolygon<f64>> = self
            .iter()
            .filter(|(_, z)| z.kind() == ZoneKind::KeepIn)
            .map(|(_, z)| z.geometry())
            .collect();
        if parts.is_empty() {
            return None;
        }
        let union = unary_union(parts);
        Some(if distance_m.is_finite() && distance_m > 0.0 {
            offset(&union, -distance_m)
        } else {
            union.orient(Direction::Default)
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use geo::{Area, CoordsIter};
    use std::path::Path;

    fn zones() -> ZoneSet {
        let text = r#"{"type": "FeatureCollection", "features": [
          {"type": "Feature", "properties": {"kind": "keep_out", "name": "L"},
           "geometry": {"type": "Polygon", "coordinates":
             [[[0, 0], [40, 0], [40, 10], [10, 10], [10, 30], [0, 30], [0, 0]]]}},
          {"type": "Feature", "properties": {"kind": "keep_in", "name": "a"},
           "geometry": {"type": "Polygon", "coordinates":
             [[[-100, -100], [100, -100], [100, 100], [-100, 100], [-100, -100]]]}},
          {"type": "Feature", "properties": {"kind": "keep_in", "name": "b"},
           "geometry": {"type": "Polygon", "coordinates":
             [[[50, 50], [250, 50], [250, 150], [50, 150], [50, 50]]]}}]}"#;
        ZoneSet::from_geojson_str(text, Path::new("t.geojson")).unwrap()
    }

    #[test]
    fn grown_keep_outs_lie_at_the_distance_from_the_zone() {
        let z = zones();
        let d = 7.5;
        let grown = z.keep_outs_grown(d);
        assert_eq!(grown.len(), 1);
        let (h, area) = &grown[0];
        assert_eq!(z.get(*h).unwrap().name(), "L");
        let mut n = 0;
        for c in area.exterior_coords_iter() {
            let dist = z.distance_to_keep_out_m([c.x, c.y]);
            // On the exact offset, or inside it by at most the chord sag (d (1 − cos 0.025)).
            assert!(
                dist <= d + 1e-6 && dist >= d * (1.0 - 4e-4) - 1e-6,
                "{c:?} at {dist}"
            );
            n += 1;
        }
        assert!(n > 30, "round corners have many vertices ({n})");
        // Area: the L (600 m²), a strip d wide along its 140 m of edges, a quarter disc at each
        // of its five convex corners, less the square where the strips of the reflex corner
        // overlap.
        let exact = 600.0 + 140.0 * d + 1.25 * std::f64::consts::PI * d * d - d * d;
        let got = area.unsigned_area();
        assert!((got - exact).abs() < 1e-3 * exact, "{got} vs {exact}");
    }

    #[test]
    fn the_keep_in_union_shrinks_by_the_distance() {
        let z = zones();
        let d = 12.0;
        let shrunk = z.keep_in_shrunk(d).unwrap();
        for c in shrunk.exterior_coords_iter() {
            let dist = z.distance_to_keep_in_edge_m([c.x, c.y]);
            assert!((dist - d).abs() < 1e-3 * d + 1e-6, "{c:?} at {dist}");
        }
        // One union: the two squares overlap, so the shrunk area is one polygon.
        assert_eq!(shrunk.0.len(), 1);
        // Not positive: the union itself (40 000 + 20 000 − 2 500 overlap).
        let union = z.keep_in_shrunk(0.0).unwrap();
        assert!((union.unsigned_area() - 57_500.0).abs() < 1e-6);
        assert!(z.keep_in_shrunk(1e6).unwrap().0.is_empty());
    }

    #[test]
    fn rings_are_closed_and_oriented_for_geojson() {
        let z = zones();
        let (_, l) = z.keep_outs().next().unwrap();
        let rings = polygon_rings_m(l.geometry());
        assert_eq!(rings.len(), 1);
        let ring = &rings[0][0];
        assert_eq!(ring.first(), ring.last());
        let twice_area: f64 = ring
            .windows(2)
            .map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1])
            .sum();
        assert!((twice_area - 1200.0).abs() < 1e-9, "{twice_area}");
    }

    #[test]
    fn degenerate_distances_and_empty_sets() {
        let z = zones();
        let same = z.keep_outs_grown(f64::NAN);
        assert!((same[0].1.unsigned_area() - 600.0).abs() < 1e-9);
        assert!(ZoneSet::default().keep_outs_grown(3.0).is_empty());
        assert!(ZoneSet::default().keep_in_shrunk(3.0).is_none());
    }
}
