//! Zones grown and shrunk by a distance, as polygons: what the planners avoid at uncertainty
//! `r` — each keep-out grown by `r + footprint` (its Minkowski sum with a disc), the keep-in
//! union shrunk by as much — for maps and GIS layers.
//!
//! The distance queries of [`ZoneSet`] stay exact; these polygons approximate the round parts
//! (around convex corners of keep-outs, concave corners of the keep-in union) by chords of at
//! most [`ARC_STEP_RAD`] × the distance (geo's `Buffer` with round joins, computed by
//! i_overlay), so their boundary lies within 0.0004 × the distance inside the exact one: 1 cm
//! at 27 m. Rings are first simplified by [`SIMPLIFY_FRACTION`] × the distance (finer detail
//! cannot show in the offset but costs the boolean engine), so the boundary lies within
//! 0.0024 × the distance of the exact one; a zone that would still give the engine more than
//! [`MAX_OFFSET_SEGMENTS`] (saw teeth deeper than that) is simplified further, to its convex
//! hull at worst, and one of many parts is grown in halves that are then united.

use geo::algorithm::buffer::{BufferStyle, LineJoin};
use geo::orient::{Direction, Orient};
use geo::{Buffer, Coord, LineString, MultiPolygon, Polygon, unary_union};

use super::{Zone, ZoneHandle, ZoneKind, ZoneSet};

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

/// Largest distance between a ring as offset and as given, as a fraction of the offset
/// distance: rings are simplified this much before offsetting.
pub const SIMPLIFY_FRACTION: f64 = 2e-3;

/// Rings of at most this many vertices are offset as given.
const SIMPLIFY_ABOVE_VERTICES: usize = 16;

/// Most segments (edges, and chords of the round corners) the boolean engine is given for one
/// zone. Its time grows with the square of the segments that lie within twice the distance of
/// each other: a 20 000-vertex ring of saw teeth (650 000 segments with their corners) took
/// 100 s and 7.6 GB. A zone over it is simplified further (the tolerance doubled until it fits)
/// and, if its parts still do not fit together, offset part by part.
pub const MAX_OFFSET_SEGMENTS: usize = 20_000;

/// `area` grown by `distance_m` when it is positive and finite, else as it is (oriented).
fn grow(area: &MultiPolygon<f64>, distance_m: f64) -> MultiPolygon<f64> {
    if distance_m.is_finite() && distance_m > 0.0 {
        offset(area, distance_m)
    } else {
        area.clone().orient(Direction::Default)
    }
}

fn offset(area: &MultiPolygon<f64>, distance_m: f64) -> MultiPolygon<f64> {
    // Detail finer than a fraction of the distance cannot show in the offset, but every vertex
    // costs the boolean engine (superlinearly: a 100 000-vertex circle grown by 27 m took
    // 100 s): drop it first.
    let tolerance_m = SIMPLIFY_FRACTION * distance_m.abs();
    let parts: Vec<Polygon<f64>> = area
        .0
        .iter()
        .map(|p| offset_input(p, tolerance_m))
        .collect();
    grow_parts(parts, distance_m).orient(Direction::Default)
}

/// The union of `parts` offset by `distance_m`: at once when their segments fit
/// [`MAX_OFFSET_SEGMENTS`], else the two halves (split across the wider extent of the parts'
/// centres) offset on their own and united, so no call of the engine meets more segments than
/// that near each other (a MultiPolygon of 10 000 spiky parts took 125 s and 8 GB at once).
fn grow_parts(mut parts: Vec<Polygon<f64>>, distance_m: f64) -> MultiPolygon<f64> {
    use geo::{BooleanOps, BoundingRect};
    let segments: usize = parts.iter().map(offset_segments).sum();
    if parts.len() <= 1 || segments <= MAX_OFFSET_SEGMENTS {
        let style = BufferStyle::new(distance_m).line_join(LineJoin::Round(ARC_STEP_RAD));
        return MultiPolygon::new(parts).buffer_with_style(style);
    }
    let centre = |p: &Polygon<f64>| p.bounding_rect().map_or([0.0; 2], |b| b.center().into());
    let (lo, hi) = parts.iter().map(centre).fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), c| {
            (
                [lo[0].min(c[0]), lo[1].min(c[1])],
                [hi[0].max(c[0]), hi[1].max(c[1])],
            )
        },
    );
    let axis = usize::from(hi[1] - lo[1] > hi[0] - lo[0]);
    parts.sort_by(|a, b| centre(a)[axis].total_cmp(&centre(b)[axis]));
    let right = parts.split_off(parts.len() / 2);
    let (a, b) = rayon::join(
        || grow_parts(parts, distance_m),
        || grow_parts(right, distance_m),
    );
    a.union(&b)
}

/// `p` simplified for offsetting at `tolerance_m`, or coarser until it fits
/// [`MAX_OFFSET_SEGMENTS`] (its convex hull at worst).
fn offset_input(p: &Polygon<f64>, tolerance_m: f64) -> Polygon<f64> {
    use geo::{BoundingRect, ConvexHull};
    let simplified = |tolerance_m: f64| {
        let exterior = simplify_ring(p.exterior(), tolerance_m)?;
        // A hole that vanishes is narrower than the tolerance: the offset fills it anyway.
        let holes = p
            .interiors()
            .iter()
            .filter_map(|r| simplify_ring(r, tolerance_m))
            .collect();
        Some(Polygon::new(exterior, holes))
    };
    let first = simplified(tolerance_m).unwrap_or_else(|| p.clone());
    if offset_segments(&first) <= MAX_OFFSET_SEGMENTS {
        return first;
    }
    let diameter_m = p
        .bounding_rect()
        .map_or(0.0, |b| b.width().hypot(b.height()));
    let mut tolerance_m = tolerance_m.max(diameter_m * 1e-6);
    while tolerance_m < diameter_m {
        tolerance_m *= 2.0;
        match simplified(tolerance_m) {
            Some(q) if offset_segments(&q) <= MAX_OFFSET_SEGMENTS => return q,
            Some(_) => {}
            None => break,
        }
    }
    p.convex_hull()
}

/// Segments the boolean engine meets when offsetting `p`: its edges and, at most, the chords
/// of a round corner at every turn.
fn offset_segments(p: &Polygon<f64>) -> usize {
    std::iter::once(p.exterior())
        .chain(p.interiors())
        .map(|ring| {
            let c = &ring.0;
            let turning: f64 = (0..c.len().saturating_sub(1))
                .map(|i| {
                    let prev = if i == 0 { c[c.len() - 2] } else { c[i - 1] };
                    let (a, b) = (c[i] - prev, c[i + 1] - c[i]);
                    (a.x * b.y - a.y * b.x).atan2(a.x * b.x + a.y * b.y).abs()
                })
                .sum();
            c.len() + (turning / ARC_STEP_RAD).ceil() as usize
        })
        .sum()
}

/// A closed ring with the vertices dropped that lie within `tolerance_m` of the segment that
/// replaces them, in one pass (the sleeve of Zhao and Saalfeld, 1997): from an anchor, each
/// following vertex narrows the cone of directions a segment may take and still pass within
/// half the tolerance of every vertex so far; the vertex that would empty the cone, or step
/// back towards the anchor, starts the next segment. Linear time and no recursion, whatever
/// the ring. Rings of at most [`SIMPLIFY_ABOVE_VERTICES`] come back as given; `None` when the
/// ring would lose its area.
fn simplify_ring(ring: &LineString<f64>, tolerance_m: f64) -> Option<LineString<f64>> {
    let coords = &ring.0;
    if coords.len() <= SIMPLIFY_ABOVE_VERTICES || tolerance_m.is_nan() || tolerance_m <= 0.0 {
        return Some(ring.clone());
    }
    let half = 0.5 * tolerance_m;
    let mut out = vec![coords[0]];
    let mut anchor = coords[0];
    // The cone, as angles relative to `reference`; `far` the farthest accepted vertex.
    let (mut lo, mut hi, mut reference, mut far) = (f64::NEG_INFINITY, f64::INFINITY, 0.0, 0.0);
    let mut last: Option<Coord<f64>> = None;
    let mut i = 1;
    while i < coords.len() {
        let p = coords[i];
        let (dx, dy) = (p.x - anchor.x, p.y - anchor.y);
        let r = dx.hypot(dy);
        if r <= half {
            // Within reach of the anchor whatever the direction.
            last = Some(p);
            i += 1;
            continue;
        }
        let spread = (half / r).asin();
        let direction = dy.atan2(dx);
        let fits = if last.is_none() || lo == f64::NEG_INFINITY {
            reference = direction;
            Some((-spread, spread))
        } else {
            // The cone's copies are 2π apart and at most π wide: at most one meets [lo, hi].
            let centre = wrap_angle(direction - reference);
            [
                centre,
                centre - std::f64::consts::TAU,
                centre + std::f64::consts::TAU,
            ]
            .into_iter()
            .filter(|c| (lo..=hi).contains(c))
            .map(|c| ((c - spread).max(lo), (c + spread).min(hi)))
            .next()
        };
        match fits {
            Some((a, b)) if r >= far - half => {
                (lo, hi, far) = (a, b, r.max(far));
                last = Some(p);
                i += 1;
            }
            _ => {
                // `p` cannot join this segment: the last vertex that could ends it.
                let end = last.unwrap_or(p);
                out.push(end);
                anchor = end;
                (lo, hi, far, last) = (f64::NEG_INFINITY, f64::INFINITY, 0.0, None);
                if end == p {
                    i += 1;
                }
            }
        }
    }
    if let Some(end) = last {
        out.push(end);
    }
    (out.len() >= 4 && out.first() == out.last()).then(|| LineString::new(out))
}

/// `a` wrapped into (−π, π].
fn wrap_angle(a: f64) -> f64 {
    let w = a.rem_euclid(std::f64::consts::TAU);
    if w > std::f64::consts::PI {
        w - std::f64::consts::TAU
    } else {
        w
    }
}

impl Zone {
    /// The zone grown by `distance_m` (its Minkowski sum with a disc of that radius), exterior
    /// rings counter-clockwise, as [`ZoneSet::keep_outs_grown`] grows each keep-out: for a map
    /// that grows each zone by a radius of its own.
    ///
    /// # Units
    /// Metres, like the zone.
    #[must_use]
    pub fn grown(&self, distance_m: f64) -> MultiPolygon<f64> {
        grow(self.geometry(), distance_m)
    }
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
            .map(|(h, z)| (h, grow(z.geometry(), distance_m)))
            .collect()
    }

    /// [`ZoneSet::keep_outs_grown`] for the keep-outs whose bounding box comes within
    /// `reach_m` of `around_m` only (map metres): the zones that matter at one place, e.g.
    /// where a drive faulted, without growing every zone of the map.
    ///
    /// # Units
    /// Metres, like the zones.
    #[must_use]
    pub fn keep_outs_grown_near(
        &self,
        distance_m: f64,
        around_m: [f64; 2],
        reach_m: f64,
    ) -> Vec<(ZoneHandle, MultiPolygon<f64>)> {
        use geo::BoundingRect;
        self.keep_outs()
            .filter(|(_, z)| {
                z.geometry().bounding_rect().is_some_and(|b| {
                    let dx = (b.min().x - around_m[0])
                        .max(around_m[0] - b.max().x)
                        .max(0.0);
                    let dy = (b.min().y - around_m[1])
                        .max(around_m[1] - b.max().y)
                        .max(0.0);
                    dx.hypot(dy) <= reach_m
                })
            })
            .map(|(h, z)| (h, grow(z.geometry(), distance_m)))
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

    /// A keep-out circle of `n` vertices, radius 60 m around (400, 500).
    fn circle(n: usize) -> ZoneSet {
        let ring: Vec<String> = (0..=n)
            .map(|k| {
                let a = std::f64::consts::TAU * (k % n) as f64 / n as f64;
                format!("[{}, {}]", 400.0 + 60.0 * a.cos(), 500.0 + 60.0 * a.sin())
            })
            .collect();
        let text = format!(
            r#"{{"type": "FeatureCollection", "features": [{{"type": "Feature",
              "properties": {{"kind": "keep_out"}},
              "geometry": {{"type": "Polygon", "coordinates": [[{}]]}}}}]}}"#,
            ring.join(", ")
        );
        ZoneSet::from_geojson_str(&text, Path::new("c.geojson")).unwrap()
    }

    #[test]
    fn dense_rings_are_simplified_within_the_tolerance_before_growing() {
        let z = circle(50_000);
        let d = 27.0;
        let started = std::time::Instant::now();
        let grown = z.keep_outs_grown(d);
        let elapsed = started.elapsed();
        let area = &grown[0].1;
        let vertices = area.exterior_coords_iter().count();
        // 50 000 vertices in, a few hundred out (several seconds with every vertex).
        assert!(vertices < 2_000, "{vertices} vertices");
        assert!(elapsed.as_secs_f64() < 5.0, "{elapsed:?}");
        for c in area.exterior_coords_iter() {
            let dist = z.distance_to_keep_out_m([c.x, c.y]);
            let slack = (SIMPLIFY_FRACTION + 4e-4) * d;
            assert!((dist - d).abs() <= slack + 1e-9, "{c:?} at {dist}");
        }
    }

    #[test]
    fn intricate_rings_are_coarsened_to_a_bounded_offset() {
        // 8 000 saw teeth 1 m deep round a 60 m circle: the teeth survive the first
        // simplification (1 m > 0.002 × 27 m) and their corners would give the boolean engine
        // 260 000 segments.
        let n = 16_000;
        let ring: Vec<String> = (0..=n)
            .map(|k| {
                let a = std::f64::consts::TAU * (k % n) as f64 / n as f64;
                let r = if k % 2 == 1 { 59.0 } else { 60.0 };
                format!("[{}, {}]", 400.0 + r * a.cos(), 500.0 + r * a.sin())
            })
            .collect();
        let text = format!(
            r#"{{"type": "FeatureCollection", "features": [{{"type": "Feature",
              "properties": {{"kind": "keep_out"}},
              "geometry": {{"type": "Polygon", "coordinates": [[{}]]}}}}]}}"#,
            ring.join(", ")
        );
        let z = ZoneSet::from_geojson_str(&text, Path::new("saw.geojson")).unwrap();
        let started = std::time::Instant::now();
        let grown = z.keep_outs_grown(27.0);
        assert!(
            started.elapsed().as_secs_f64() < 5.0,
            "{:?}",
            started.elapsed()
        );
        let area = &grown[0].1;
        assert!(offset_segments(&area.0[0]) <= 2 * MAX_OFFSET_SEGMENTS);
        // Coarser, but still a ring about 27 m out (the teeth are 1 m deep).
        for c in area.exterior_coords_iter() {
            let dist = z.distance_to_keep_out_m([c.x, c.y]);
            assert!((dist - 27.0).abs() < 1.5, "{c:?} at {dist}");
        }
    }

    #[test]
    fn simplified_rings_stay_within_the_tolerance_of_every_dropped_vertex() {
        use geo::{Distance, Euclidean};
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(26);
        for trial in 0..200 {
            // A wobbly star: noise at every scale, some of it under the tolerance.
            let n = rng.random_range(17..400);
            let amp = rng.random_range(0.0..2.0);
            let mut coords: Vec<Coord<f64>> = (0..n)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / n as f64;
                    let r = 50.0 + rng.random_range(-amp..=amp);
                    Coord {
                        x: r * a.cos(),
                        y: r * a.sin(),
                    }
                })
                .collect();
            coords.push(coords[0]);
            let ring = LineString::new(coords);
            let tolerance = rng.random_range(0.01..1.0);
            let out = simplify_ring(&ring, tolerance).expect("a star keeps its area");
            assert_eq!(out.0.first(), out.0.last(), "trial {trial}: closed");
            assert!(out.0.len() >= 4 && out.0.len() <= ring.0.len());
            for c in &ring.0 {
                let d = out
                    .lines()
                    .map(|l| Euclidean.distance(*c, &l))
                    .fold(f64::INFINITY, f64::min);
                assert!(d <= tolerance * (1.0 + 1e-9), "trial {trial}: {c:?} at {d}");
            }
        }
        // Short rings and a zero tolerance stay as given.
        let square = LineString::from(vec![(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 0.0)]);
        assert_eq!(simplify_ring(&square, 10.0), Some(square));
    }

    #[test]
    fn only_keep_outs_within_reach_are_grown_near_a_point() {
        let z = zones();
        // The L spans x 0..40, y 0..30.
        assert_eq!(z.keep_outs_grown_near(5.0, [60.0, 10.0], 19.0).len(), 0);
        let near = z.keep_outs_grown_near(5.0, [60.0, 10.0], 20.0);
        assert_eq!(near.len(), 1);
        assert_eq!(near, z.keep_outs_grown(5.0));
        assert_eq!(z.keep_outs_grown_near(5.0, [10.0, 10.0], 0.0).len(), 1);
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
