//! What the belief says: mean, covariance, its ellipse, a conservative disc, and its modes.

use std::collections::BTreeMap;

/// The weighted mean and covariance of the particles, and the figures derived from them.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Posterior {
    /// Weighted mean position, map metres (x east, y north).
    pub mean_m: [f64; 2],
    /// Weighted covariance `Σ wᵢ (pᵢ − mean)(pᵢ − mean)ᵀ`, m², row/column order (x east,
    /// y north). The weights sum to 1 and no small-sample correction is applied (with an
    /// effective sample size of hundreds or more it would change it by under 1 %).
    pub covariance_m2: [[f64; 2]; 2],
    /// The 1σ ellipse of the covariance.
    pub ellipse: Ellipse,
    /// A disc that contains the belief conservatively, metres: `disc_sigmas` (3 by default,
    /// see [`super::MotionModel::disc_sigmas`]) × the 1σ semi-major axis. For a Gaussian belief
    /// it holds at least 98.9 % of it; for a multimodal one the covariance spans the modes, so
    /// the disc does too. This is the radius keep-out zones would grow by.
    pub disc_radius_m: f64,
    /// Effective sample size of the weights, `1 / Σ wᵢ²`.
    pub effective_sample_size: f64,
    /// Number of particles.
    pub particle_count: usize,
}

/// An uncertainty ellipse: semi-axes in metres and the orientation of the major axis.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Ellipse {
    /// Semi-major axis, metres (the square root of the larger covariance eigenvalue for a 1σ
    /// ellipse).
    pub semi_major_m: f64,
    /// Semi-minor axis, metres, ≤ `semi_major_m`.
    pub semi_minor_m: f64,
    /// Azimuth of the major axis, degrees clockwise from north (east of north), in `[0, 180)`:
    /// 0 = the ellipse is longest north-south, 90 = east-west.
    pub azimuth_deg: f64,
}

impl Ellipse {
    /// The 1σ ellipse of a 2×2 covariance (m², order x east, y north), or `None` if it is not
    /// finite, not symmetric (to 1e-9 relative) or not positive semi-definite (to rounding).
    #[must_use]
    pub fn try_from_covariance(cov: &[[f64; 2]; 2]) -> Option<Self> {
        let (a, b, c) = (cov[0][0], cov[0][1], cov[1][1]);
        let scale = a.abs().max(c.abs()).max(f64::MIN_POSITIVE);
        if !(a.is_finite() && b.is_finite() && c.is_finite() && cov[1][0].is_finite())
            || (cov[1][0] - b).abs() > 1e-9 * scale
        {
            return None;
        }
        let mean = 0.5 * (a + c);
        let half_diff = 0.5 * (a - c);
        let r = half_diff.hypot(b);
        let (l1, l2) = (mean + r, mean - r);
        let tol = 1e-12 * scale;
        if l1 < -tol || l2 < -tol {
            return None;
        }
        // Angle of the major axis counter-clockwise from east; azimuth is clockwise from north.
        let theta_deg = 0.5 * (2.0 * b).atan2(a - c).to_degrees();
        Some(Self {
            semi_major_m: l1.max(0.0).sqrt(),
            semi_minor_m: l2.max(0.0).sqrt(),
            azimuth_deg: (90.0 - theta_deg).rem_euclid(180.0),
        })
    }

    /// The same ellipse with both semi-axes times `k` (e.g. 3 for the 3σ ellipse).
    #[must_use]
    pub fn scaled(&self, k: f64) -> Self {
        Self {
            semi_major_m: k * self.semi_major_m,
            semi_minor_m: k * self.semi_minor_m,
            azimuth_deg: self.azimuth_deg,
        }
    }

    /// The angle MMGIS's uncertainty ellipses take with `xAxisProp` = the semi-major and
    /// `yAxisProp` = the semi-minor axis, degrees in `[0, 180)`: MMGIS draws them with Turf's
    /// `ellipse`, which lays the x semi-axis east and rotates the ellipse clockwise by the
    /// angle, so the angle is the azimuth minus 90°.
    #[must_use]
    pub fn mmgis_angle_deg(&self) -> f64 {
        (self.azimuth_deg - 90.0).rem_euclid(180.0)
    }

    /// The conservative disc of this 1σ ellipse: 3 × the semi-major axis, the circle around
    /// the whole 3σ ellipse (what the simulator's keep-out zones grow by after a filter fix).
    #[must_use]
    pub fn disc_radius_m(&self) -> f64 {
        3.0 * self.semi_major_m
    }
}

/// One cluster of the belief (see [`super::ParticleFilter::modes`]).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Mode {
    /// Weighted mean position of the cluster's particles, map metres.
    pub center_m: [f64; 2],
    /// Total weight of the cluster, 0..1.
    pub mass: f64,
}

/// Weighted mean and covariance of `positions_m` (weights summing to 1).
pub(super) fn mean_and_covariance(
    positions_m: &[[f64; 2]],
    weights: &[f64],
) -> ([f64; 2], [[f64; 2]; 2]) {
    let mut m = [0.0; 2];
    for (p, w) in positions_m.iter().zip(weights) {
        m[0] += w * p[0];
        m[1] += w * p[1];
    }
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (p, w) in positions_m.iter().zip(weights) {
        let (dx, dy) = (p[0] - m[0], p[1] - m[1]);
        sxx += w * dx * dx;
        sxy += w * dx * dy;
        syy += w * dy * dy;
    }
    (m, [[sxx, sxy], [sxy, syy]])
}

/// Greedy clusters of weighted particles on a grid of `cell_m` squares: cells in decreasing
/// order of weight each start a mode unless already taken, and take the untaken cells of their
/// 3 × 3 neighbourhood. Modes of mass at least `min_mass` are returned, heaviest first.
pub(super) fn modes(
    positions_m: &[[f64; 2]],
    weights: &[f64],
    cell_m: f64,
    min_mass: f64,
) -> Vec<Mode> {
    // (mass, Σ w·x, Σ w·y) per cell; a BTreeMap so ties and output never depend on hashing.
    let mut cells: BTreeMap<(i64, i64), (f64, f64, f64)> = BTreeMap::new();
    for (p, &w) in positions_m.iter().zip(weights) {
        if w > 0.0 {
            let key = (
                (p[0] / cell_m).floor() as i64,
                (p[1] / cell_m).floor() as i64,
            );
            let e = cells.entry(key).or_insert((0.0, 0.0, 0.0));
            e.0 += w;
            e.1 += w * p[0];
            e.2 += w * p[1];
        }
    }
    let mut order: Vec<((i64, i64), f64)> = cells.iter().map(|(k, v)| (*k, v.0)).collect();
    // Heaviest first; equal masses in key order (the sort is stable).
    order.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut out = Vec::new();
    for (key, _) in order {
        if !cells.contains_key(&key) {
            continue;
        }
        let (mut mass, mut sx, mut sy) = (0.0, 0.0, 0.0);
        for dy in -1..=1 {
            for dx in -1..=1 {
                if let Some((m, x, y)) = cells.remove(&(key.0 + dx, key.1 + dy)) {
                    mass += m;
                    sx += x;
                    sy += y;
                }
            }
        }
        if mass >= min_mass && mass > 0.0 {
            out.push(Mode {
                center_m: [sx / mass, sy / mass],
                mass,
            });
        }
    }
    out.sort_by(|a, b| b.mass.total_cmp(&a.mass));
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn ellipse_of_known_covariances() {
        // Axis-aligned, longer east-west: azimuth 90, MMGIS angle 0.
        let e = Ellipse::try_from_covariance(&[[9.0, 0.0], [0.0, 4.0]]).unwrap();
        assert!(close(e.semi_major_m, 3.0, 1e-12) && close(e.semi_minor_m, 2.0, 1e-12));
        assert!(close(e.azimuth_deg, 90.0, 1e-9) && close(e.mmgis_angle_deg(), 0.0, 1e-9));
        // Longer north-south: azimuth 0, MMGIS angle 90.
        let e = Ellipse::try_from_covariance(&[[1.0, 0.0], [0.0, 16.0]]).unwrap();
        assert!(close(e.semi_major_m, 4.0, 1e-12) && close(e.semi_minor_m, 1.0, 1e-12));
        assert!(close(e.azimuth_deg, 0.0, 1e-9) && close(e.mmgis_angle_deg(), 90.0, 1e-9));
        // R(θ) diag(σ₁², σ₂²) R(θ)ᵀ with the major axis θ = 30° counter-clockwise from east,
        // i.e. azimuth 60° (north-east-east): recovered exactly.
        for (theta_deg, s1, s2) in [
            (30.0f64, 5.0f64, 2.0f64),
            (-20.0, 3.0, 0.5),
            (135.0, 7.0, 7.0),
        ] {
            let t = theta_deg.to_radians();
            let (c, s) = (t.cos(), t.sin());
            let (l1, l2) = (s1 * s1, s2 * s2);
            let cov = [
                [c * c * l1 + s * s * l2, c * s * (l1 - l2)],
                [c * s * (l1 - l2), s * s * l1 + c * c * l2],
            ];
            let e = Ellipse::try_from_covariance(&cov).unwrap();
            assert!(close(e.semi_major_m, s1, 1e-9), "{e:?}");
            assert!(close(e.semi_minor_m, s2, 1e-9), "{e:?}");
            if s1 != s2 {
                let az = (90.0 - theta_deg).rem_euclid(180.0);
                assert!(close(e.azimuth_deg, az, 1e-9), "{e:?} vs {az}");
            }
        }
        let e3 = Ellipse::try_from_covariance(&[[4.0, 0.0], [0.0, 1.0]])
            .unwrap()
            .scaled(3.0);
        assert!(close(e3.semi_major_m, 6.0, 1e-12) && close(e3.semi_minor_m, 3.0, 1e-12));
    }

    #[test]
    fn degenerate_and_invalid_covariances() {
        // Rank one (all particles on a line north-east): minor axis 0, azimuth 45.
        let e = Ellipse::try_from_covariance(&[[1.0, 1.0], [1.0, 1.0]]).unwrap();
        assert!(close(e.semi_major_m, 2f64.sqrt(), 1e-12) && e.semi_minor_m == 0.0);
        assert!(close(e.azimuth_deg, 45.0, 1e-9));
        let zero = Ellipse::try_from_covariance(&[[0.0, 0.0], [0.0, 0.0]]).unwrap();
        assert_eq!((zero.semi_major_m, zero.semi_minor_m), (0.0, 0.0));
        assert!(Ellipse::try_from_covariance(&[[1.0, 2.0], [2.0, 1.0]]).is_none()); // indefinite
        assert!(Ellipse::try_from_covariance(&[[1.0, 0.5], [0.0, 1.0]]).is_none()); // asymmetric
        assert!(Ellipse::try_from_covariance(&[[f64::NAN, 0.0], [0.0, 1.0]]).is_none());
    }

    #[test]
    fn modes_separate_clusters_and_weigh_them() {
        // 30 % at (0, 0), 70 % at (12, 0), a speck of 0.1 % at (50, 50).
        let mut p = Vec::new();
        let mut w = Vec::new();
        for i in 0..100 {
            let d = (i % 10) as f64 * 0.05;
            p.push([d, -d]);
            w.push(0.003);
            p.push([12.0 + d, d]);
            w.push(0.007 - 1e-5);
        }
        p.push([50.0, 50.0]);
        w.push(1e-3);
        let m = modes(&p, &w, 3.0, 0.01);
        assert_eq!(m.len(), 2, "{m:?}");
        assert!(
            close(m[0].mass, 0.699, 1e-9) && close(m[1].mass, 0.3, 1e-9),
            "{m:?}"
        );
        assert!(close(m[0].center_m[0], 12.225, 1e-9) && close(m[1].center_m[0], 0.225, 1e-9));
        assert!(modes(&[], &[], 3.0, 0.0).is_empty());
    }

    #[test]
    fn mean_and_covariance_of_two_points() {
        let (m, c) = mean_and_covariance(&[[0.0, 0.0], [4.0, 2.0]], &[0.5, 0.5]);
        assert_eq!(m, [2.0, 1.0]);
        assert_eq!(c, [[4.0, 2.0], [2.0, 1.0]]);
    }
}
