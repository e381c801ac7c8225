//! The two external measurements of paper 004 §3: the radio range to the orbiting beacon
//! (eqs. 7-9) and the terrain-matching position fix (§3.3), with their models `h(x)` and
//! Jacobians `H = ∂h/∂x`.
//!
//! **Range.** `ρ = |r_mci(p, t) − r_o(t)|`, where `r_mci` is the rover's ENU position carried to
//! the Mars-fixed frame and turned by Mars's rotation ([`NavigationFrame::position_mci_m`]) and
//! `r_o` the orbiter's ephemeris position (known to the rover: the paper uploads the beacon's
//! orbit). It is the instantaneous geometric range (no light time: the simulated truth is the
//! same model). Only `e` and `n` enter: `∂ρ/∂p = uᵀ·[Ê N̂]_mci` with `u` the unit vector from the
//! orbiter to the rover. A range exists only while the orbiter is above the elevation mask.
//!
//! **Terrain fix.** Matching the rover's camera images to an orbital image gives the rover's
//! position in the map with an error set by the image resolution (paper 004 Table 1); here the fix
//! is `z = p + ζ`, `ζ ~ N(0, σ²I)` with σ = one pixel of the orbital image, and `H = [I₂ 0]`. The
//! paper measures the image-plane coordinates of two matched landmarks (eqs. 10-11) instead; the
//! position they imply is what the filter uses here, because the paper gives neither the
//! camera nor the landmarks.

use nalgebra::{Matrix2, RowSVector, SMatrix, Vector2, Vector3};

use super::mars::NavigationFrame;
use super::state::{STATE_DIM, StateVector, ix};

/// A range from the rover to the orbiting beacon.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RangeMeasurement {
    /// Seconds since the start of the run.
    pub t_s: u32,
    /// Measured range, metres.
    pub range_m: f64,
    /// The orbiter's position in MCI at `t_s` (from the ephemeris), metres.
    pub orbiter_position_mci_m: Vector3<f64>,
}

/// A terrain-matching position fix.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PositionFix {
    /// Seconds since the start of the run.
    pub t_s: u32,
    /// Measured position (east, north) in the navigation frame, metres.
    pub position_enu_m: Vector2<f64>,
}

/// The predicted range `h(x)`, metres, from ENU position `p_enu_m` at `t_s` to an orbiter at
/// `orbiter_mci_m`.
pub fn predicted_range_m(
    frame: &NavigationFrame,
    t_s: f64,
    p_enu_m: &Vector2<f64>,
    orbiter_mci_m: &Vector3<f64>,
) -> f64 {
    (frame.position_mci_m(t_s, p_enu_m) - orbiter_mci_m).norm()
}

/// `∂ρ/∂x` (1×8): the range's sensitivity to the state, nonzero in east and north only
/// (dimensionless, m/m).
pub fn range_jacobian(
    frame: &NavigationFrame,
    t_s: f64,
    p_enu_m: &Vector2<f64>,
    orbiter_mci_m: &Vector3<f64>,
) -> RowSVector<f64, STATE_DIM> {
    let line = frame.position_mci_m(t_s, p_enu_m) - orbiter_mci_m;
    let d_range_d_p = line.transpose() / line.norm() * frame.mci_from_enu_horizontal(t_s);
    let mut h = RowSVector::<f64, STATE_DIM>::zeros();
    h[ix::EAST] = d_range_d_p[0];
    h[ix::NORTH] = d_range_d_p[1];
    h
}

/// Elevation of the orbiter above the local horizon seen from `p_enu_m` at `t_s`, radians
/// (the horizon is the plane normal to the site's up; negative below it).
pub fn elevation_rad(
    frame: &NavigationFrame,
    t_s: f64,
    p_enu_m: &Vector2<f64>,
    orbiter_mci_m: &Vector3<f64>,
) -> f64 {
    let to_orbiter = orbiter_mci_m - frame.position_mci_m(t_s, p_enu_m);
    let up = frame.up_mci(t_s);
    let vertical = to_orbiter.dot(&up);
    // atan2 rather than asin(vertical / |d|): exact at the zenith, where the ratio rounds past 1.
    vertical.atan2((to_orbiter - vertical * up).norm())
}

/// `H = [I₂ 0]` (2×8) of a position fix.
pub fn position_fix_jacobian() -> SMatrix<f64, 2, STATE_DIM> {
    let mut h = SMatrix::<f64, 2, STATE_DIM>::zeros();
    h[(0, ix::EAST)] = 1.0;
    h[(1, ix::NORTH)] = 1.0;
    h
}

/// The predicted fix `h(x) = p`, metres.
pub fn predicted_fix_m(x: &StateVector) -> Vector2<f64> {
    Vector2::new(x[ix::EAST], x[ix::NORTH])
}

/// The fix covariance for an orbital image of `resolution_m` metres per pixel: `σ² I₂` with σ one
/// pixel, m².
pub fn fix_covariance_m2(resolution_m: f64) -> Matrix2<f64> {
    Matrix2::identity() * resolution_m * resolution_m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ekf::orbit::CircularOrbit;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn the_range_jacobian_matches_central_differences() {
        let frame = NavigationFrame::default();
        let orbit = CircularOrbit::default();
        let mut rng = ChaCha8Rng::seed_from_u64(14);
        for _ in 0..200 {
            let t = rng.random_range(0.0..1000.0);
            let p = Vector2::new(
                rng.random_range(-300.0..300.0),
                rng.random_range(-300.0..300.0),
            );
            let r_o = orbit.state_at(t).position_mci_m;
            let h = range_jacobian(&frame, t, &p, &r_o);
            // The range is ~1e6 m: steps of 1 m keep the rounding (1e-10 m / 1 m) far below the
            // curvature error (≈ Δ²/ρ ≈ 1e-6).
            let step = 1.0;
            for (k, unit) in [(ix::EAST, Vector2::x()), (ix::NORTH, Vector2::y())] {
                let fd = (predicted_range_m(&frame, t, &(p + step * unit), &r_o)
                    - predicted_range_m(&frame, t, &(p - step * unit), &r_o))
                    / (2.0 * step);
                assert!((h[k] - fd).abs() < 1e-8, "t {t}, p {p:?}: {} vs {fd}", h[k]);
            }
            let others: f64 = (2..STATE_DIM).map(|k| h[k].abs()).sum();
            assert_eq!(others, 0.0);
        }
    }

    #[test]
    fn an_orbiter_straight_up_is_at_90_degrees() {
        let frame = NavigationFrame::default();
        let above = frame.position_mci_m(10.0, &Vector2::zeros()) * 1.1;
        let el = elevation_rad(&frame, 10.0, &Vector2::zeros(), &above);
        assert!((el - std::f64::consts::FRAC_PI_2).abs() < 1e-6, "{el}");
    }
}
