//! Mars constants and the three frames of paper 004 §2.1: Mars-centred inertial (MCI), Mars-fixed,
//! and the navigation frame (east-north-up at the site).
//!
//! The navigation frame is the plane tangent to the Mars sphere at the site: a rover at ENU
//! position `p = (e, n)` metres is at `r_fixed = r_site + e·Ê + n·N̂` in the Mars-fixed frame
//! (over the 1000 s runs of paper 004, ~150 m, the tangent plane stands 3 mm above the sphere;
//! truth and filter share this map, so it is no error source). The Mars-fixed frame turns about
//! the MCI z axis at [`MARS_ROTATION_RAD_PER_S`]: `r_mci = Rz(θ0 + ω_M t) · r_fixed`.

use nalgebra::{Matrix3, Matrix3x2, Rotation3, Vector2, Vector3};

pub use maps::mars_crs::MARS_RADIUS_M;

/// Mars gravitational parameter μ_M, m³/s² (paper 004 §5 prints "4.282829×10¹³ km³/s²", a unit
/// slip: 4.282829×10¹³ m³/s² = 42 828.29 km³/s² is Mars's GM).
pub const MU_MARS_M3_PER_S2: f64 = 4.282_829e13;

/// Mars rotation rate ω_M, rad/s (paper 004 §5).
pub const MARS_ROTATION_RAD_PER_S: f64 = 7.0882e-5;

/// Mars surface gravity, m/s² (what a level accelerometer's z axis reads at rest).
pub const MARS_SURFACE_GRAVITY_M_PER_S2: f64 = 3.720_76;

/// Where the navigation frame is anchored: a point on the Mars sphere of radius [`MARS_RADIUS_M`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Site {
    /// Planetocentric latitude, degrees north (default: 18.4447, Jezero, the Perseverance landing
    /// site the bundled maps are anchored at).
    pub latitude_deg: f64,
    /// East longitude, degrees (default: 77.4508, Jezero).
    pub longitude_deg: f64,
}

impl Default for Site {
    fn default() -> Self {
        Self::JEZERO
    }
}

impl Site {
    /// The Perseverance landing site in Jezero crater (18.4447° N, 77.4508° E).
    pub const JEZERO: Site = Site {
        latitude_deg: 18.4447,
        longitude_deg: 77.4508,
    };

    /// The site in the Mars-fixed frame, metres.
    pub fn position_fixed_m(&self) -> Vector3<f64> {
        self.fixed_from_enu().column(2) * MARS_RADIUS_M
    }

    /// The rotation whose columns are the east, north and up unit vectors in the Mars-fixed frame:
    /// `v_fixed = fixed_from_enu · v_enu`.
    pub fn fixed_from_enu(&self) -> Matrix3<f64> {
        let (sin_lat, cos_lat) = self.latitude_deg.to_radians().sin_cos();
        let (sin_lon, cos_lon) = self.longitude_deg.to_radians().sin_cos();
        Matrix3::new(
            -sin_lon,
            -sin_lat * cos_lon,
            cos_lat * cos_lon,
            cos_lon,
            -sin_lat * sin_lon,
            cos_lat * sin_lon,
            0.0,
            cos_lat,
            sin_lat,
        )
    }
}

/// The navigation frame at a site on a rotating Mars: where an ENU position is in the MCI frame at
/// a given time.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct NavigationFrame {
    /// The frame's origin (default: [`Site::JEZERO`]).
    pub site: Site,
    /// Mars rotation rate, rad/s (default: [`MARS_ROTATION_RAD_PER_S`]).
    pub rotation_rad_per_s: f64,
    /// Angle from the MCI x axis (vernal equinox) to the prime meridian at t = 0, radians
    /// (default: 0; the true value depends on the date and only moves where in MCI the orbit
    /// must be placed for a pass, which [`crate::ekf::CircularOrbit::pass_over`] does).
    pub prime_meridian_at_epoch_rad: f64,
}

impl Default for NavigationFrame {
    fn default() -> Self {
        Self {
            site: Site::JEZERO,
            rotation_rad_per_s: MARS_ROTATION_RAD_PER_S,
            prime_meridian_at_epoch_rad: 0.0,
        }
    }
}

impl NavigationFrame {
    /// Mars's rotation angle θ(t) = θ0 + ω_M·t, radians, at `t_s` seconds after the epoch.
    pub fn rotation_angle_rad(&self, t_s: f64) -> f64 {
        self.prime_meridian_at_epoch_rad + self.rotation_rad_per_s * t_s
    }

    /// The rotation taking Mars-fixed vectors to MCI at `t_s` seconds after the epoch.
    pub fn mci_from_fixed(&self, t_s: f64) -> Rotation3<f64> {
        Rotation3::from_axis_angle(&Vector3::z_axis(), self.rotation_angle_rad(t_s))
    }

    /// The rover at ENU position `p_enu_m` (metres) in the MCI frame at `t_s`, metres.
    pub fn position_mci_m(&self, t_s: f64, p_enu_m: &Vector2<f64>) -> Vector3<f64> {
        let p_fixed = self.site.position_fixed_m() + self.fixed_from_enu_horizontal() * p_enu_m;
        self.mci_from_fixed(t_s) * p_fixed
    }

    /// `∂r_mci/∂p_enu` (3×2, dimensionless) at `t_s`: the east and north unit vectors in MCI.
    pub fn mci_from_enu_horizontal(&self, t_s: f64) -> Matrix3x2<f64> {
        self.mci_from_fixed(t_s).matrix() * self.fixed_from_enu_horizontal()
    }

    /// The local up unit vector in MCI at `t_s`.
    pub fn up_mci(&self, t_s: f64) -> Vector3<f64> {
        self.mci_from_fixed(t_s) * self.site.fixed_from_enu().column(2).into_owned()
    }

    /// East and north unit vectors in the Mars-fixed frame, as columns.
    fn fixed_from_enu_horizontal(&self) -> Matrix3x2<f64> {
        self.site
            .fixed_from_enu()
            .fixed_columns::<2>(0)
            .into_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_enu_basis_is_orthonormal_and_up_is_radial() {
        let m = Site::JEZERO.fixed_from_enu();
        assert!((m.transpose() * m - Matrix3::identity()).norm() < 1e-15);
        assert!((m.determinant() - 1.0).abs() < 1e-15, "right-handed");
        let up = Site::JEZERO.position_fixed_m() / MARS_RADIUS_M;
        assert!((up - m.column(2)).norm() < 1e-15);
    }

    #[test]
    fn the_site_turns_once_per_sidereal_day() {
        let f = NavigationFrame::default();
        let day_s = std::f64::consts::TAU / f.rotation_rad_per_s;
        let p = Vector2::new(12.0, -7.0);
        let a = f.position_mci_m(0.0, &p);
        let b = f.position_mci_m(day_s, &p);
        assert!((a - b).norm() < 1e-6, "{}", (a - b).norm());
        let half = f.position_mci_m(day_s / 2.0, &p);
        assert!((half.z - a.z).abs() < 1e-6 && (half.xy() + a.xy()).norm() < 1e-6);
    }
}
