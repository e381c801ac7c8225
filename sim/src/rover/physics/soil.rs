//! Wheel–soil contact: Bekker's pressure–sinkage law and the Janosi–Hanamoto shear law, the
//! classical terramechanics of a rigid wheel on deformable ground (Wong 2008, ch. 2 and 4).
//!
//! Each terrain class of the maps carries one set of terrain values ([`Soil::of`]):
//!
//! | class | from | n | k_c kN/m^(n+1) | k_φ kN/m^(n+2) | c kPa | φ ° | K cm |
//! |---|---|---|---|---|---|---|---|
//! | sand | dry sand, Land Locomotion Laboratory (Wong Table 2.3) | 1.1 | 0.99 | 1528.43 | 1.04 | 28.0 | 1.0 |
//! | soil | sandy loam, 15 % moisture, LLL (Wong Table 2.3) | 0.7 | 5.27 | 1515.04 | 1.72 | 29.0 | 1.0 |
//! | bedrock | rigid: no sinkage, Coulomb friction μ = 0.8 (judgement) | | | | | | |
//!
//! K, the shear deformation modulus, is Wong's §2.4.3 figure for loose sand (about 1 cm), used
//! for both deformable classes. These are terrestrial measurements, the values rover studies and
//! Mars-yard tests use; Viking's Martian drift material is weaker (c = 1.6 kPa, φ = 18°, Moore et
//! al. 1987), so the sand profile is an optimistic Mars sand.
//!
//! A wheel of radius `r` and width `b` under a load `W` (newtons) sinks (Bekker, Wong eq. 4.x)
//! `z₀ = [3W / ((3 − n)(k_c + b k_φ) √(2r))]^(2/(2n+1))`, pays a compaction resistance
//! `R_c = (k_c + b k_φ) z₀^(n+1) / (n + 1)`, and shears the soil over an arc of length
//! `l = r acos(1 − (z₀ + h_g)/r)` to its grouser tips ([`GROUSER_HEIGHT_M`]), area `A = b l`. At slip `s` the soil's shear along that arc gives the
//! thrust (Janosi–Hanamoto, integrated over the contact)
//! `H(s) = (A c + W tan φ) [1 − K/(s l) (1 − e^(−s l/K))]`, so the net pull is `H(s) − R_c`.
//! [`Soil::steady_slip`] solves `H(s) − R_c = W sin θ` for the slip that carries the wheel's
//! share of the rover up a slope θ: the closed form the rapier rover ([`super::drive_on_slope`])
//! is checked against.
//!
//! ## References
//! - J. Y. Wong, *Theory of Ground Vehicles*, 4th ed., Wiley 2008: Table 2.3 (terrain values),
//!   §2.4.3 (K), §4.1 (rigid wheel: sinkage, compaction resistance).
//! - Z. Janosi and B. Hanamoto, "The analytical determination of drawbar pull as a function of
//!   slip for tracked vehicles in deformable soils", 1st ISTVS conference, Turin 1961.
//! - H. J. Moore, R. E. Hutton, G. D. Clow, C. R. Spitzer, *Physical properties of the surface
//!   materials at the Viking landing sites on Mars*, USGS Prof. Paper 1389, 1987.

use maps::TerrainClass;

/// Grouser height, metres: 7.5 mm, the height of the grousers on Curiosity's 0.5 m wheels
/// (the rover's default wheel is that size). The soil shears at the grouser tips, so they
/// lengthen the shearing arc; on firm soil, where a wheel sinks only millimetres, they are most
/// of it.
pub const GROUSER_HEIGHT_M: f64 = 0.0075;

/// Terrain values of one class (plain struct; [`Soil::of`] gives the cited sets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Soil {
    /// Sinkage exponent n (dimensionless).
    pub n: f64,
    /// Cohesive modulus k_c, N/m^(n+1).
    pub k_c: f64,
    /// Frictional modulus k_φ, N/m^(n+2).
    pub k_phi: f64,
    /// Cohesion c, pascals.
    pub cohesion_pa: f64,
    /// Angle of internal shearing resistance φ, degrees.
    pub friction_angle_deg: f64,
    /// Shear deformation modulus K, metres.
    pub shear_modulus_m: f64,
    /// `false` for rigid ground (bedrock): no sinkage, plain Coulomb friction `tan φ`.
    pub deformable: bool,
}

/// How a wheel rests on a soil: the static contact ([`Soil::contact`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Static sinkage z₀, metres.
    pub sinkage_m: f64,
    /// Contact arc length l, metres.
    pub length_m: f64,
    /// Contact area A = b l, square metres.
    pub area_m2: f64,
    /// Compaction (rolling) resistance R_c, newtons.
    pub resistance_n: f64,
    /// The load it was computed for, newtons.
    pub load_n: f64,
}

impl Soil {
    /// Dry sand (Wong Table 2.3, LLL), K = 1 cm.
    pub const SAND: Soil = Soil {
        n: 1.1,
        k_c: 0.99e3,
        k_phi: 1528.43e3,
        cohesion_pa: 1.04e3,
        friction_angle_deg: 28.0,
        shear_modulus_m: 0.01,
        deformable: true,
    };

    /// Sandy loam at 15 % moisture (Wong Table 2.3, LLL), K = 1 cm.
    pub const SOIL: Soil = Soil {
        n: 0.7,
        k_c: 5.27e3,
        k_phi: 1515.04e3,
        cohesion_pa: 1.72e3,
        friction_angle_deg: 29.0,
        shear_modulus_m: 0.01,
        deformable: true,
    };

    /// Rigid rock: Coulomb friction μ = 0.8 (atan 0.8 = 38.66°), a judgement for a grousered
    /// aluminium wheel on rough rock; no sinkage, no compaction resistance.
    pub const BEDROCK: Soil = Soil {
        n: 1.0,
        k_c: 0.0,
        k_phi: 0.0,
        cohesion_pa: 0.0,
        friction_angle_deg: 38.659_808_254_090_09,
        shear_modulus_m: 0.0,
        deformable: false,
    };

    /// Rigid ground with Coulomb friction `mu` (`φ = atan μ`).
    #[must_use]
    pub fn rigid(mu: f64) -> Soil {
        Soil {
            friction_angle_deg: mu.atan().to_degrees(),
            ..Self::BEDROCK
        }
    }

    /// The terrain values of a map's terrain class.
    #[must_use]
    pub fn of(class: TerrainClass) -> Soil {
        match class {
            TerrainClass::Sand => Self::SAND,
            TerrainClass::Soil => Self::SOIL,
            TerrainClass::Bedrock => Self::BEDROCK,
        }
    }

    /// `tan φ`: the Coulomb friction of a rigid soil, the asymptote of a deformable one.
    #[must_use]
    pub fn tan_phi(&self) -> f64 {
        self.friction_angle_deg.to_radians().tan()
    }

    /// The static contact of a rigid wheel of `radius_m` and `width_m` under `load_n` newtons.
    /// The shearing arc runs to the grouser tips: `l = r acos(1 − (z₀ + h_g)/r)` with grousers
    /// [`GROUSER_HEIGHT_M`] tall.
    #[must_use]
    pub fn contact(&self, load_n: f64, radius_m: f64, width_m: f64) -> Contact {
        if !self.deformable || load_n <= 0.0 {
            return Contact {
                sinkage_m: 0.0,
                length_m: 0.0,
                area_m2: 0.0,
                resistance_n: 0.0,
                load_n,
            };
        }
        let n = self.n;
        let k = self.k_c + width_m * self.k_phi;
        let z =
            (3.0 * load_n / ((3.0 - n) * k * (2.0 * radius_m).sqrt())).powf(2.0 / (2.0 * n + 1.0));
        let z = z.min(radius_m);
        let engaged = (z + GROUSER_HEIGHT_M).min(radius_m);
        let length_m = radius_m * (1.0 - engaged / radius_m).acos();
        Contact {
            sinkage_m: z,
            length_m,
            area_m2: width_m * length_m,
            resistance_n: k * z.powf(n + 1.0) / (n + 1.0),
            load_n,
        }
    }

    /// Janosi–Hanamoto thrust at slip `slip` (0…1; its magnitude is used) on `contact`, newtons.
    /// Rigid ground gives `W tan φ` at any slip.
    #[must_use]
    pub fn thrust_n(&self, contact: &Contact, slip: f64) -> f64 {
        let limit = contact.area_m2 * self.cohesion_pa + contact.load_n * self.tan_phi();
        if !self.deformable {
            return contact.load_n * self.tan_phi();
        }
        let j = slip.abs() * contact.length_m / self.shear_modulus_m;
        let developed = if j < 1e-9 {
            0.5 * j
        } else {
            1.0 - (1.0 - (-j).exp()) / j
        };
        limit * developed
    }

    /// The friction coefficient the soil offers a wheel sliding at `slip` on `contact`: the
    /// thrust over the load. The rapier rover sets it on each wheel's contact every step.
    #[must_use]
    pub fn traction_coefficient(&self, contact: &Contact, slip: f64) -> f64 {
        if contact.load_n <= 0.0 {
            return 0.0;
        }
        self.thrust_n(contact, slip) / contact.load_n
    }

    /// The steady slip at which one wheel of a rover of `mass_kg` on six wheels pulls its share
    /// up a slope of `slope_deg` (negative: downhill): `H(s) − R_c = (m g / 6) sin θ` with the
    /// normal load `(m g / 6) cos θ`. Downhill, where gravity outpulls the resistance, the wheel
    /// brakes and the slip is negative: `−s` with `H(s) + R_c = (m g / 6) sin|θ|`. `None` when
    /// no slip below 1 carries the load (the rover cannot climb, or slides down).
    #[must_use]
    pub fn steady_slip(
        &self,
        mass_kg: f64,
        radius_m: f64,
        width_m: f64,
        slope_deg: f64,
    ) -> Option<f64> {
        let weight = mass_kg * localization::ekf::MARS_SURFACE_GRAVITY_M_PER_S2 / 6.0;
        let theta = slope_deg.to_radians();
        let contact = self.contact(weight * theta.cos(), radius_m, width_m);
        let pull = weight * theta.sin() + contact.resistance_n;
        // Driving (pull ≥ 0) or braking (pull < 0) at slip magnitude s.
        let need = pull.abs();
        let sign = if pull >= 0.0 { 1.0 } else { -1.0 };
        if self.thrust_n(&contact, 1.0) < need {
            return None;
        }
        if !self.deformable {
            return Some(0.0);
        }
        // The thrust rises monotonically with slip: bisect.
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.thrust_n(&contact, mid) < need {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(sign * 0.5 * (lo + hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-computed from Wong's formulas for the default rover wheel (r 0.25 m, b 0.2 m) under
    /// 110 N (a 178 kg rover's sixth under Mars gravity) on dry sand: z₀ ≈ 11.6 mm,
    /// R_c ≈ 12.6 N, l ≈ 9.8 cm (to the grouser tips, 7.5 mm below the rim).
    #[test]
    fn sand_contact_matches_the_hand_computation() {
        let c = Soil::SAND.contact(110.0, 0.25, 0.2);
        assert!((c.sinkage_m - 0.0116).abs() < 0.0005, "{c:?}");
        assert!((c.resistance_n - 12.6).abs() < 0.6, "{c:?}");
        assert!((c.length_m - 0.098).abs() < 0.002, "{c:?}");
        let rock = Soil::BEDROCK.contact(110.0, 0.25, 0.2);
        assert_eq!((rock.sinkage_m, rock.resistance_n), (0.0, 0.0));
    }

    #[test]
    fn thrust_rises_with_slip_towards_the_mohr_coulomb_limit() {
        let c = Soil::SAND.contact(110.0, 0.25, 0.2);
        let limit = c.area_m2 * 1040.0 + 110.0 * 28f64.to_radians().tan();
        let h: Vec<f64> = [0.0, 0.05, 0.1, 0.3, 0.6, 1.0]
            .iter()
            .map(|&s| Soil::SAND.thrust_n(&c, s))
            .collect();
        assert_eq!(h[0], 0.0);
        assert!(h.windows(2).all(|w| w[1] > w[0]), "{h:?}");
        assert!(h[5] < limit && h[5] > 0.8 * limit, "{h:?} vs {limit}");
    }

    /// The closed form's own trend: slip grows with slope, sand slips more than soil, bedrock
    /// not at all until its friction angle; downhill the wheels brake (negative slip).
    #[test]
    fn steady_slip_grows_with_slope_and_orders_the_classes() {
        let slip = |soil: Soil, deg: f64| soil.steady_slip(178.0, 0.25, 0.2, deg);
        let sand: Vec<f64> = (0..=5)
            .map(|i| slip(Soil::SAND, 4.0 * f64::from(i)).expect("climbs"))
            .collect();
        assert!(sand.windows(2).all(|w| w[1] > w[0]), "{sand:?}");
        for deg in [0.0, 8.0, 16.0] {
            assert!(slip(Soil::SAND, deg) > slip(Soil::SOIL, deg), "{deg}°");
        }
        assert_eq!(slip(Soil::BEDROCK, 30.0), Some(0.0));
        assert_eq!(slip(Soil::BEDROCK, 40.0), None);
        assert!(slip(Soil::SAND, 35.0).is_none());
        assert!(slip(Soil::SAND, -20.0).expect("brakes") < 0.0);
    }
}
