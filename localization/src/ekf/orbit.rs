//! The orbiting radio beacon: a two-body orbit in the MCI frame (paper 004 §3.2 eqs. 5-6),
//! propagated by RK4, and the circular orbit it starts from.

use nalgebra::Vector3;

use super::mars::{MARS_RADIUS_M, MU_MARS_M3_PER_S2, NavigationFrame};

/// Position and velocity of the orbiter in the MCI frame.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct OrbitState {
    /// Position, metres.
    pub position_mci_m: Vector3<f64>,
    /// Velocity, metres per second.
    pub velocity_mci_m_per_s: Vector3<f64>,
}

impl OrbitState {
    /// Two-body specific orbital energy `v²/2 − μ/r`, J/kg (m²/s²), for `mu_m3_per_s2`.
    pub fn specific_energy_j_per_kg(&self, mu_m3_per_s2: f64) -> f64 {
        0.5 * self.velocity_mci_m_per_s.norm_squared() - mu_m3_per_s2 / self.position_mci_m.norm()
    }

    /// The state `dt_s` seconds later under two-body gravity `μ` (m³/s²): one classical RK4 step
    /// of eqs. 5-6.
    pub fn rk4_step(&self, dt_s: f64, mu_m3_per_s2: f64) -> OrbitState {
        let accel = |r: &Vector3<f64>| -mu_m3_per_s2 / r.norm().powi(3) * r;
        let (r0, v0) = (self.position_mci_m, self.velocity_mci_m_per_s);
        let (k1r, k1v) = (v0, accel(&r0));
        let (k2r, k2v) = (v0 + 0.5 * dt_s * k1v, accel(&(r0 + 0.5 * dt_s * k1r)));
        let (k3r, k3v) = (v0 + 0.5 * dt_s * k2v, accel(&(r0 + 0.5 * dt_s * k2r)));
        let (k4r, k4v) = (v0 + dt_s * k3v, accel(&(r0 + dt_s * k3r)));
        OrbitState {
            position_mci_m: r0 + dt_s / 6.0 * (k1r + 2.0 * k2r + 2.0 * k3r + k4r),
            velocity_mci_m_per_s: v0 + dt_s / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v),
        }
    }
}

/// A circular orbit about Mars, by its elements at the epoch (t = 0).
///
/// The default is MRO-like: 300 km altitude (MRO's science orbit is 255 × 320 km), inclination
/// 92.65° (Sun-synchronous, near-polar), placed by [`CircularOrbit::pass_over`] so that it crosses
/// the site's latitude 5° of longitude west of [`crate::ekf::Site::JEZERO`] 500 s into the run.
/// A 300 km orbiter is above a site's horizon for at most ~15 min per pass (the horizon is 23° of
/// arc away and the period is 1h53), so a pass has to be *placed* in the 1000 s run; 5° off track
/// the pass peaks at 43° elevation, which changes the range's line of sight across the run and
/// so constrains both east and north (an overhead pass looks straight down at closest approach,
/// where range says nothing about horizontal position).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CircularOrbit {
    /// Altitude above the Mars sphere, metres (default: 300 000).
    pub altitude_m: f64,
    /// Inclination, degrees (default: 92.65).
    pub inclination_deg: f64,
    /// Right ascension of the ascending node in MCI at the epoch, degrees.
    pub raan_deg: f64,
    /// Argument of latitude (angle from the ascending node along the orbit) at the epoch, degrees.
    pub argument_of_latitude_deg: f64,
}

impl Default for CircularOrbit {
    fn default() -> Self {
        Self::pass_over(&NavigationFrame::default(), 300_000.0, 92.65, 500.0, 5.0)
    }
}

impl CircularOrbit {
    /// The circular orbit of `altitude_m` and `inclination_deg` that crosses `frame`'s site
    /// latitude northbound `west_offset_deg` degrees of longitude west of the site at `t_s`
    /// seconds after the epoch (Mars rotation included).
    ///
    /// # Panics
    /// If the site latitude is beyond the orbit's reach (|latitude| > inclination, or
    /// > 180° − inclination for a retrograde orbit).
    pub fn pass_over(
        frame: &NavigationFrame,
        altitude_m: f64,
        inclination_deg: f64,
        t_s: f64,
        west_offset_deg: f64,
    ) -> Self {
        let incl = inclination_deg.to_radians();
        let lat = frame.site.latitude_deg.to_radians();
        let sin_u = lat.sin() / incl.sin();
        assert!(
            sin_u.abs() <= 1.0,
            "the orbit (inclination {inclination_deg}°) never reaches latitude {}°",
            frame.site.latitude_deg
        );
        // Northbound crossing: argument of latitude in (-90°, 90°).
        let u_at_pass = sin_u.asin();
        let right_ascension = (frame.site.longitude_deg - west_offset_deg).to_radians()
            + frame.rotation_angle_rad(t_s);
        let raan = right_ascension - (incl.cos() * u_at_pass.sin()).atan2(u_at_pass.cos());
        let mut orbit = CircularOrbit {
            altitude_m,
            inclination_deg,
            raan_deg: raan.to_degrees().rem_euclid(360.0),
            argument_of_latitude_deg: 0.0,
        };
        let u0 = u_at_pass - orbit.mean_motion_rad_per_s() * t_s;
        orbit.argument_of_latitude_deg = u0.to_degrees().rem_euclid(360.0);
        orbit
    }

    /// Orbit radius, metres.
    pub fn radius_m(&self) -> f64 {
        MARS_RADIUS_M + self.altitude_m
    }

    /// Mean motion `√(μ/a³)`, rad/s.
    pub fn mean_motion_rad_per_s(&self) -> f64 {
        (MU_MARS_M3_PER_S2 / self.radius_m().powi(3)).sqrt()
    }

    /// Orbital period, seconds.
    pub fn period_s(&self) -> f64 {
        std::f64::consts::TAU / self.mean_motion_rad_per_s()
    }

    /// The exact (Keplerian) state `t_s` seconds after the epoch.
    pub fn state_at(&self, t_s: f64) -> OrbitState {
        let a = self.radius_m();
        let speed = (MU_MARS_M3_PER_S2 / a).sqrt();
        let (sin_raan, cos_raan) = self.raan_deg.to_radians().sin_cos();
        let (sin_i, cos_i) = self.inclination_deg.to_radians().sin_cos();
        let u = self.argument_of_latitude_deg.to_radians() + self.mean_motion_rad_per_s() * t_s;
        let (sin_u, cos_u) = u.sin_cos();
        // In-plane unit vectors: towards the ascending node, and 90° ahead of it.
        let node = Vector3::new(cos_raan, sin_raan, 0.0);
        let ahead = Vector3::new(-sin_raan * cos_i, cos_raan * cos_i, sin_i);
        OrbitState {
            position_mci_m: a * (cos_u * node + sin_u * ahead),
            velocity_mci_m_per_s: speed * (-sin_u * node + cos_u * ahead),
        }
    }
}

/// The orbiter's MCI states at whole seconds `0..=duration_s`, propagated from the epoch state by
/// RK4 with 1 s steps (paper 004 §3.2: perturbations neglected over a pass).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Ephemeris {
    states: Vec<OrbitState>,
}

impl Ephemeris {
    /// Propagates `initial` (at t = 0) to `duration_s` seconds under μ = [`MU_MARS_M3_PER_S2`].
    pub fn propagate(initial: OrbitState, duration_s: u32) -> Self {
        let mut states = Vec::with_capacity(duration_s as usize + 1);
        let mut s = initial;
        states.push(s);
        for _ in 0..duration_s {
            s = s.rk4_step(1.0, MU_MARS_M3_PER_S2);
            states.push(s);
        }
        Self { states }
    }

    /// The state at whole second `t_s`, or `None` past the propagated span.
    pub fn at(&self, t_s: u32) -> Option<&OrbitState> {
        self.states.get(t_s as usize)
    }

    /// All states, index = seconds after the epoch.
    pub fn states(&self) -> &[OrbitState] {
        &self.states
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rk4_conserves_energy_and_follows_kepler_over_the_run() {
        let orbit = CircularOrbit::default();
        let eph = Ephemeris::propagate(orbit.state_at(0.0), 1000);
        let e0 = eph.states()[0].specific_energy_j_per_kg(MU_MARS_M3_PER_S2);
        for (t, s) in eph.states().iter().enumerate() {
            let e = s.specific_energy_j_per_kg(MU_MARS_M3_PER_S2);
            assert!(
                ((e - e0) / e0).abs() < 1e-12,
                "t = {t} s: energy {e} vs {e0}"
            );
            let kepler = orbit.state_at(t as f64);
            let dr = (s.position_mci_m - kepler.position_mci_m).norm();
            assert!(dr < 1e-3, "t = {t} s: {dr} m from the Keplerian position");
        }
    }

    #[test]
    fn the_default_orbit_is_mro_like() {
        let orbit = CircularOrbit::default();
        let period_min = orbit.period_s() / 60.0;
        assert!((110.0..116.0).contains(&period_min), "{period_min} min");
        let s = orbit.state_at(1234.0);
        let h = s.position_mci_m.cross(&s.velocity_mci_m_per_s);
        let incl_deg = (h.z / h.norm()).acos().to_degrees();
        assert!((incl_deg - 92.65).abs() < 1e-9, "{incl_deg}");
        assert!((s.position_mci_m.norm() - orbit.radius_m()).abs() < 1e-6);
    }

    #[test]
    fn pass_over_crosses_the_site_latitude_at_the_given_time() {
        let frame = NavigationFrame::default();
        let orbit = CircularOrbit::pass_over(&frame, 300e3, 92.65, 500.0, 5.0);
        let r_fixed = frame.mci_from_fixed(500.0).inverse() * orbit.state_at(500.0).position_mci_m;
        let lat = (r_fixed.z / r_fixed.norm()).asin().to_degrees();
        let lon = r_fixed.y.atan2(r_fixed.x).to_degrees();
        assert!((lat - frame.site.latitude_deg).abs() < 1e-9, "{lat}");
        assert!(
            (lon - (frame.site.longitude_deg - 5.0)).abs() < 1e-9,
            "{lon}"
        );
        assert!(
            orbit.state_at(500.0).velocity_mci_m_per_s.z > 0.0,
            "northbound"
        );
    }
}
