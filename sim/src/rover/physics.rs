//! Rigid-body physics with rapier (issue 15, paper 003 §4): the known-answer checks the rover's
//! slip model will stand on.
//!
//! - [`incline_slide`]: a block on an incline under Mars gravity.
//! - [`rolling_wheel`]: a wheel rolling down it, without slip or slipping.
//! - [`drive_on_slope`]: a six-wheel rover ([`RoverBody`]) driving up, down or across a plane
//!   slope (a heightfield) on a terramechanics [`Soil`] or rigid ground;
//! - [`drive_on_dem`]: the same rover on a patch of a map's DEM, each wheel on the soil of the
//!   terrain class beneath it, its slip beside the slip profile's prediction.
//!
//! A block resting on a plane tilted by θ with Coulomb friction μ stays put when tan θ ≤ μ. Otherwise it
//! slides with acceleration `g (sin θ − μ cos θ)`, so it covers `½ a t²` in `t` seconds. Rapier's
//! contact friction is a regularised Coulomb cone solved iteratively, so the engine's answer is
//! not exact. What it gives (`physics::tests`) is:
//! - below the friction angle the block holds (under 1 mm in 2 s);
//! - from 4° above it the slid distance is within 2 % of `½ a t²`;
//! - in the first ~2° above the angle it barely moves (0.02 m against 0.27-0.33 m). The
//!   solver's static friction holds a little past the ideal threshold.
//!
//! ## References
//! Paper 003 §4 (slip on slopes); Mars surface gravity 3.711 m/s² (the value of
//! [`localization::ekf::MARS_SURFACE_GRAVITY_M_PER_S2`]).

use rapier3d_f64::prelude::*;

use localization::ekf::MARS_SURFACE_GRAVITY_M_PER_S2;

mod dem_drive;
mod rover;
pub mod soil;

pub use dem_drive::{DemDrive, drive_on_dem};
pub use rover::{Heading, RoverBody, SlopeDrive, drive_on_slope};
pub use soil::Soil;

/// What [`incline_slide`] or [`rolling_wheel`] measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InclineSlide {
    /// Distance the body's centre moved down the slope, metres.
    pub slid_m: f64,
    /// Coulomb's answer for the same time, metres (each function says which).
    pub analytic_m: f64,
}

/// Why a physics experiment could not run (bad input).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PhysicsError {
    /// A parameter is outside its range.
    #[error("{field} = {value}: expected {expected}")]
    Invalid {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
}

fn check(
    field: &'static str,
    value: f64,
    expected: &'static str,
    ok: bool,
) -> Result<(), PhysicsError> {
    if ok {
        Ok(())
    } else {
        Err(PhysicsError::Invalid {
            field,
            value,
            expected,
        })
    }
}

/// A 0.5 m cube released at rest on a 100 m × 10 m slab tilted by `slope_deg`, both with
/// friction `friction` (combined by minimum, so the pair's μ is `friction`), under Mars gravity
/// for `duration_s` seconds of rapier's default 60 Hz steps. Coulomb's answer is
/// `½ g (sin θ − μ cos θ) t²` when positive, else 0.
///
/// # Errors
/// [`PhysicsError::Invalid`] for a slope outside 0..90°, a negative or non-finite friction, or a
/// duration outside 0..=60 s.
pub fn incline_slide(
    slope_deg: f64,
    friction: f64,
    duration_s: f64,
) -> Result<InclineSlide, PhysicsError> {
    let (slid_m, t) = slide_down(
        slope_deg,
        friction,
        duration_s,
        0.25,
        Rotation::IDENTITY,
        ColliderBuilder::cuboid(0.25, 0.25, 0.25),
    )?;
    let (g, theta) = (MARS_SURFACE_GRAVITY_M_PER_S2, slope_deg.to_radians());
    let a = g * (theta.sin() - friction * theta.cos());
    Ok(InclineSlide {
        slid_m,
        analytic_m: if a > 0.0 { 0.5 * a * t * t } else { 0.0 },
    })
}

/// A wheel — a solid cylinder of radius 0.25 m and width 0.2 m, its axis across the slope —
/// released at rest on the tilted slab of [`incline_slide`], rolling down it for `duration_s`.
///
/// Coulomb's answer: a solid cylinder (I = ½ m r²) rolls without slipping with acceleration
/// `⅔ g sin θ` while μ ≥ ⅓ tan θ; below that it slips, its centre accelerating at
/// `g (sin θ − μ cos θ)`. Rapier's distance is within 2 % of it in both regimes (`tests`).
///
/// # Errors
/// As [`incline_slide`].
pub fn rolling_wheel(
    slope_deg: f64,
    friction: f64,
    duration_s: f64,
) -> Result<InclineSlide, PhysicsError> {
    let radius_m = 0.25;
    // Rapier's cylinder runs along y: turn it to z, across the slope.
    let (slid_m, t) = slide_down(
        slope_deg,
        friction,
        duration_s,
        radius_m,
        Rotation::from_rotation_x(std::f64::consts::FRAC_PI_2),
        ColliderBuilder::cylinder(0.1, radius_m),
    )?;
    let (g, theta) = (MARS_SURFACE_GRAVITY_M_PER_S2, slope_deg.to_radians());
    let a = if friction >= theta.tan() / 3.0 {
        2.0 / 3.0 * g * theta.sin()
    } else {
        g * (theta.sin() - friction * theta.cos())
    };
    Ok(InclineSlide {
        slid_m,
        analytic_m: 0.5 * a * t * t,
    })
}

/// Release `collider` at rest on the slab of `slope_deg` and `friction`, its centre
/// `half_height_m` above the surface and turned by `turn` in the slab's frame, and step it for
/// `duration_s`: the distance it moved downhill, metres, and the time simulated, seconds.
fn slide_down(
    slope_deg: f64,
    friction: f64,
    duration_s: f64,
    half_height_m: f64,
    turn: Rotation,
    collider: ColliderBuilder,
) -> Result<(f64, f64), PhysicsError> {
    check_experiment(slope_deg, friction, duration_s)?;
    let slope = Slope::new(slope_deg, friction);
    let mut world = slope.world();
    let start = slope.normal() * (SLAB_HALF_THICKNESS_M + half_height_m);
    let (body, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .translation(start)
            .rotation((slope.tilt * turn).to_scaled_axis()),
        slope.material(collider),
    );
    Ok(slope.run(&mut world, body, start, duration_s))
}

/// Half the thickness of the slab the experiments run on, metres.
const SLAB_HALF_THICKNESS_M: f64 = 0.5;

/// A 100 m × 10 m slab tilted by θ about z (so +x runs downhill) under Mars gravity, with one
/// friction for every collider (combined by minimum).
struct Slope {
    tilt: Rotation,
    friction: f64,
}

impl Slope {
    fn new(slope_deg: f64, friction: f64) -> Self {
        Self {
            tilt: Rotation::from_rotation_z(-slope_deg.to_radians()),
            friction,
        }
    }

    fn material(&self, c: ColliderBuilder) -> ColliderBuilder {
        c.friction(self.friction)
            .friction_combine_rule(CoefficientCombineRule::Min)
            .restitution(0.0)
    }

    /// The slab's outward normal.
    fn normal(&self) -> Vector {
        self.tilt * Vector::Y
    }

    fn world(&self) -> PhysicsWorld {
        let mut world = PhysicsWorld {
            gravity: Vector::new(0.0, -MARS_SURFACE_GRAVITY_M_PER_S2, 0.0),
            ..PhysicsWorld::default()
        };
        world.insert(
            RigidBodyBuilder::fixed().rotation(self.tilt.to_scaled_axis()),
            self.material(ColliderBuilder::cuboid(50.0, SLAB_HALF_THICKNESS_M, 5.0)),
        );
        world
    }

    /// Step `world` for `duration_s` (whole 60 Hz steps): the distance `body` moved downhill
    /// from `start`, metres, and the time simulated, seconds.
    fn run(
        &self,
        world: &mut PhysicsWorld,
        body: RigidBodyHandle,
        start: Vector,
        duration_s: f64,
    ) -> (f64, f64) {
        let steps = (duration_s / world.integration_parameters.dt).round() as usize;
        for _ in 0..steps {
            world.step();
        }
        let downhill = self.tilt * Vector::X;
        (
            (world.bodies[body].translation() - start).dot(downhill),
            steps as f64 * world.integration_parameters.dt,
        )
    }
}

/// `Ok` for a rover's rim speed 0 < v ≤ 1 m/s.
fn check_speed(speed_m_per_s: f64) -> Result<(), PhysicsError> {
    check(
        "speed_m_per_s",
        speed_m_per_s,
        "0 < speed ≤ 1 m/s",
        speed_m_per_s > 0.0 && speed_m_per_s <= 1.0,
    )
}

/// `Ok` if the experiment's parameters are in range.
fn check_experiment(slope_deg: f64, friction: f64, duration_s: f64) -> Result<(), PhysicsError> {
    check(
        "slope_deg",
        slope_deg,
        "0 ≤ slope < 90 degrees",
        (0.0..90.0).contains(&slope_deg),
    )?;
    check(
        "friction",
        friction,
        "a finite friction coefficient ≥ 0",
        friction.is_finite() && friction >= 0.0,
    )?;
    check(
        "duration_s",
        duration_s,
        "0 < duration ≤ 60 s",
        duration_s > 0.0 && duration_s <= 60.0,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// For μ = 0.3, 0.5, 0.8: 3° and 10° below the friction angle the block holds; 4°, 8° and
    /// 15° above it, it slides Coulomb's distance within 2 %.
    #[test]
    fn a_block_slides_when_tan_theta_exceeds_mu() {
        for mu in [0.3f64, 0.5, 0.8] {
            let critical = mu.atan().to_degrees();
            for below in [3.0, 10.0] {
                let r = incline_slide(critical - below, mu, 2.0).expect("valid");
                assert!(
                    r.analytic_m == 0.0 && r.slid_m.abs() < 1e-3,
                    "μ {mu}, −{below}°: {r:?}"
                );
            }
            for above in [4.0, 8.0, 15.0] {
                let r = incline_slide(critical + above, mu, 2.0).expect("valid");
                let rel = r.slid_m / r.analytic_m - 1.0;
                assert!(rel.abs() < 0.02, "μ {mu}, +{above}°: {r:?} ({rel:+.3})");
            }
        }
    }

    /// A wheel rolls without slipping at ⅔ g sin θ while μ ≥ ⅓ tan θ, and slips below: within
    /// 2 % of Coulomb's distance in both regimes.
    #[test]
    fn a_wheel_rolls_at_two_thirds_g_sin_theta_and_slips_below_the_friction_limit() {
        for (slope_deg, mu, slips) in [
            (10.0, 0.5, false),
            (20.0, 0.5, false),
            (30.0, 0.5, false),
            (30.0, 0.1, true),
            (45.0, 0.1, true),
        ] {
            assert_eq!(mu < f64::tan(f64::to_radians(slope_deg)) / 3.0, slips);
            let r = rolling_wheel(slope_deg, mu, 2.0).expect("valid");
            let rel = r.slid_m / r.analytic_m - 1.0;
            assert!(rel.abs() < 0.025, "{slope_deg}°, μ {mu}: {r:?} ({rel:+.3})");
        }
    }

    #[test]
    fn bad_input_names_the_parameter() {
        for (args, field) in [
            ((95.0, 0.5, 1.0), "slope_deg"),
            ((20.0, f64::NAN, 1.0), "friction"),
            ((20.0, 0.5, 0.0), "duration_s"),
        ] {
            let e = incline_slide(args.0, args.1, args.2).expect_err("refused");
            assert!(e.to_string().starts_with(field), "{e}");
        }
    }
}
