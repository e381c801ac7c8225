//! Distances along a polyline in map metres: how far along a point is, the point at a
//! distance — where `solsim record import` places waypoints, sols and passages on the route.

/// Metres along the polyline `points` (cumulative `cum`) of its point nearest `p`.
#[must_use]
pub fn project_onto(points: &[[f64; 2]], cum: &[f64], p: [f64; 2]) -> f64 {
    let mut best = (f64::MAX, 0.0);
    for k in 1..points.len() {
        let (a, b) = (points[k - 1], points[k]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = (dx * dx + dy * dy).max(1e-12);
        let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0);
        let q = [a[0] + t * dx, a[1] + t * dy];
        let d = (p[0] - q[0]).hypot(p[1] - q[1]);
        if d < best.0 {
            best = (d, cum[k - 1] + t * len2.sqrt());
        }
    }
    best.1
}

/// Metres along a polyline, at each of its points (the simulator's own route distances).
pub use sim::run::route::route_along_m as along;

/// The point `s` metres along a polyline, and the unit direction there.
pub(crate) fn point_at(points: &[[f64; 2]], cum: &[f64], s: f64) -> ([f64; 2], [f64; 2]) {
    let k = cum
        .partition_point(|&c| c < s)
        .clamp(1, points.len().max(2) - 1);
    let (a, b) = (points[k - 1], points[k.min(points.len() - 1)]);
    let len = (cum[k.min(cum.len() - 1)] - cum[k - 1]).max(1e-9);
    let t = ((s - cum[k - 1]) / len).clamp(0.0, 1.0);
    let d = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    ([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])], d)
}

pub(crate) fn round1(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}
