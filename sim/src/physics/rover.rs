//! A six-wheel rover in rapier, driving on a plane slope: the first building block of the slip
//! profiles of issue 15.
//!
//! The linkage is the simplest one that can be defended on a plane: a rigid chassis carrying
//! six wheels (three per side) on revolute joints, each with a velocity motor. On a plane all
//! six wheels touch without a suspension. A rocker-bogie is needed for the DEM heightfield and
//! is not built yet.
//!
//! The contact is rigid Coulomb friction, so slip is a step. While the wheels' traction holds
//! it stays small: rapier's regularised friction creeps, up to 5 % uphill at 25° for μ = 0.5.
//! It becomes total once gravity along the slope beats friction (tan θ > μ for the whole
//! rover). Graded slip on sand needs a soil-shear law on top; that is the next step. `tests`
//! show the step.

use rapier3d_f64::prelude::*;

use super::{PhysicsError, Slope, check, check_experiment};

/// Where the rover heads relative to the slope.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Heading {
    /// Straight uphill.
    UpSlope,
    /// Straight downhill.
    DownSlope,
    /// Along the contour, the slope falling to the rover's right.
    CrossSlope,
}

impl Heading {
    /// The yaw from the uphill direction in the slope plane, radians (counter-clockwise seen
    /// from above the slope).
    fn yaw_rad(self) -> f64 {
        match self {
            Heading::UpSlope => 0.0,
            Heading::CrossSlope => std::f64::consts::FRAC_PI_2,
            Heading::DownSlope => std::f64::consts::PI,
        }
    }
}

/// The rover's geometry and mass (plain struct; defaults on each field, a rover of the Athena
/// test rover's size used in paper 003's demonstration).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoverBody {
    /// Wheel radius, metres (default: 0.25).
    pub wheel_radius_m: f64,
    /// Wheel width, metres (default: 0.2).
    pub wheel_width_m: f64,
    /// Chassis half-extents (forward, up, left), metres (default: 0.6, 0.1, 0.4).
    pub chassis_half_m: [f64; 3],
    /// Wheel centres ahead of the chassis centre, front to back, metres (default: 0.55, 0, −0.55).
    pub wheel_x_m: [f64; 3],
    /// Wheel centres left and right of the chassis centre, metres (default: 0.55).
    pub half_track_m: f64,
    /// Chassis centre above the wheel centres, metres (default: 0.3).
    pub clearance_m: f64,
    /// Chassis density, kg/m³ (default: 300: 58 kg).
    pub chassis_density_kg_per_m3: f64,
    /// Wheel density, kg/m³ (default: 500: 20 kg per wheel).
    pub wheel_density_kg_per_m3: f64,
}

impl Default for RoverBody {
    fn default() -> Self {
        Self {
            wheel_radius_m: 0.25,
            wheel_width_m: 0.2,
            chassis_half_m: [0.6, 0.1, 0.4],
            wheel_x_m: [0.55, 0.0, -0.55],
            half_track_m: 0.55,
            clearance_m: 0.3,
            chassis_density_kg_per_m3: 300.0,
            wheel_density_kg_per_m3: 500.0,
        }
    }
}

/// What a drive on the slope measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlopeDrive {
    /// Distance the chassis moved along its commanded heading, metres.
    pub progress_m: f64,
    /// Distance the wheels' rotation commanded (ω r t), metres.
    pub commanded_m: f64,
    /// `1 − progress / commanded` (0: no slip; 1: no progress; above 1: sliding back).
    pub slip: f64,
    /// Sideways drift of the chassis, to its left positive, metres.
    pub drift_left_m: f64,
    /// Tilt of the chassis at the end: the angle between its up axis and the vertical, degrees.
    pub tilt_deg: f64,
}

/// Drive `body` for `duration_s` at `speed_m_per_s` (the wheels' rim speed) on a plane slope of
/// `slope_deg` with friction `friction`, heading `heading`.
///
/// # Errors
/// [`PhysicsError::Invalid`] for a parameter out of range (as [`super::incline_slide`]; speed
/// 0 < v ≤ 1 m/s).
pub fn drive_on_slope(
    body: &RoverBody,
    slope_deg: f64,
    heading: Heading,
    friction: f64,
    speed_m_per_s: f64,
    duration_s: f64,
) -> Result<SlopeDrive, PhysicsError> {
    check_experiment(slope_deg, friction, duration_s)?;
    check(
        "speed_m_per_s",
        speed_m_per_s,
        "0 < speed ≤ 1 m/s",
        speed_m_per_s > 0.0 && speed_m_per_s <= 1.0,
    )?;
    // The slab tilts about z with +x uphill; the rover is yawed about the slab's normal.
    let slope = Slope::uphill_x(slope_deg, friction);
    let mut world = slope.world();
    let pose = slope.tilt * Rotation::from_rotation_y(heading.yaw_rad());
    let r = body.wheel_radius_m;
    let centre = slope.normal() * (super::SLAB_HALF_THICKNESS_M + r + body.clearance_m);
    let [hx, hy, hz] = body.chassis_half_m;
    let (chassis, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .translation(centre)
            .rotation(pose.to_scaled_axis()),
        slope.material(ColliderBuilder::cuboid(hx, hy, hz).density(body.chassis_density_kg_per_m3)),
    );
    let omega = speed_m_per_s / r;
    for x in body.wheel_x_m {
        for z in [body.half_track_m, -body.half_track_m] {
            let local = Vector::new(x, -body.clearance_m, z);
            let (wheel, _) = world.insert(
                RigidBodyBuilder::dynamic()
                    .translation(centre + pose * local)
                    .rotation(pose.to_scaled_axis()),
                // Rapier's cylinder runs along y: turn it to the axle, the body's z.
                slope.material(
                    ColliderBuilder::cylinder(0.5 * body.wheel_width_m, r)
                        .rotation(Vector::X * std::f64::consts::FRAC_PI_2)
                        .density(body.wheel_density_kg_per_m3),
                ),
            );
            // Rolling forward (+x) turns a wheel clockwise about +z: a negative rate.
            let axle = RevoluteJointBuilder::new(Vector::Z)
                .local_anchor1(local)
                .local_anchor2(Vector::ZERO)
                .motor_velocity(-omega, 1e4)
                .contacts_enabled(false);
            world.insert_impulse_joint(chassis, wheel, axle);
        }
    }
    let start = world.bodies[chassis].translation();
    let steps = (duration_s / world.integration_parameters.dt).round() as usize;
    for _ in 0..steps {
        world.step();
    }
    let t = steps as f64 * world.integration_parameters.dt;
    let moved = world.bodies[chassis].translation() - start;
    let progress_m = moved.dot(pose * Vector::X);
    let commanded_m = speed_m_per_s * t;
    let up = world.bodies[chassis].rotation() * Vector::Y;
    Ok(SlopeDrive {
        progress_m,
        commanded_m,
        slip: 1.0 - progress_m / commanded_m,
        drift_left_m: moved.dot(pose * Vector::Z),
        tilt_deg: up.dot(Vector::Y).clamp(-1.0, 1.0).acos().to_degrees(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rigid Coulomb contact, μ = 0.5 (friction angle 26.57°), 0.05 m/s for 20 s. Measured
    /// (opt-level 2): slip 1.6 % on the flat (the start from rest); uphill it creeps up to 5.2 %
    /// at 25°, downhill it falls to −2.0 % (skid), across the slope the sideways drift grows to
    /// 3 cm; at 27.5° the rover slides back, runs away or slides sideways. The chassis tilts by
    /// the slope.
    #[test]
    fn slip_is_a_step_at_the_friction_angle_on_rigid_ground() {
        let body = RoverBody::default();
        let drive = |slope_deg: f64, heading| {
            drive_on_slope(&body, slope_deg, heading, 0.5, 0.05, 20.0).expect("valid")
        };
        let below = [0.0, 5.0, 10.0, 15.0, 20.0, 25.0];
        for heading in [Heading::UpSlope, Heading::DownSlope, Heading::CrossSlope] {
            let runs: Vec<SlopeDrive> = below.iter().map(|&s| drive(s, heading)).collect();
            for (s, d) in below.iter().zip(&runs) {
                assert!((d.tilt_deg - s).abs() < 0.5, "{s}° {heading:?}: {d:?}");
                assert!(d.slip.abs() < 0.1, "{s}° {heading:?}: {d:?}");
            }
            assert!(runs[0].slip.abs() < 0.03, "flat: {:?}", runs[0]);
            let slips: Vec<f64> = runs.iter().map(|d| d.slip).collect();
            let drifts: Vec<f64> = runs.iter().map(|d| d.drift_left_m.abs()).collect();
            let past = drive(27.5, heading);
            match heading {
                Heading::UpSlope => {
                    assert!(slips.windows(2).all(|w| w[1] > w[0]), "{slips:?}");
                    assert!(past.slip > 1.0, "27.5° up: {past:?}");
                }
                Heading::DownSlope => {
                    assert!(slips.windows(2).all(|w| w[1] < w[0]), "{slips:?}");
                    assert!(past.slip < -1.0, "27.5° down: {past:?}");
                }
                Heading::CrossSlope => {
                    assert!(drifts[5] > drifts[1] && drifts[5] < 0.05, "{drifts:?}");
                    assert!(past.drift_left_m < -1.0, "27.5° across: {past:?}");
                }
            }
        }
    }

    #[test]
    fn a_bad_speed_is_refused() {
        let e = drive_on_slope(&RoverBody::default(), 10.0, Heading::UpSlope, 0.5, 0.0, 1.0)
            .expect_err("refused");
        assert!(e.to_string().starts_with("speed_m_per_s"), "{e}");
    }
}
