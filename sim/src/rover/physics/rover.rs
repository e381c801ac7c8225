//! A six-wheel rover in rapier, driving on a plane slope built as a heightfield: what the slip
//! profiles of issue 15 measure ([`crate::rover::slip_profile`]).
//!
//! The linkage is the simplest one that can be defended on a plane: a rigid chassis carrying
//! six wheels (three per side) on revolute joints, each with a velocity motor. On a plane all
//! six wheels touch without a suspension. A rocker-bogie, which would keep six wheels loaded on
//! rough ground, is not built ([`super::drive_on_dem`] drives this rigid rover on a DEM).
//!
//! On rigid ground the contact is rapier's Coulomb friction, so slip is a step: while the
//! wheels' traction holds it stays small (rapier's regularised friction creeps, up to 5 %
//! uphill at 25° for μ = 0.5), and it becomes total once gravity along the slope beats friction
//! (`tests` show the step). On sand and soil a contact hook ([`SoilHook`]) sets each wheel's
//! friction from the terramechanics of [`super::soil`], and slip grows with slope.

use rapier3d_f64::prelude::*;

use localization::ekf::MARS_SURFACE_GRAVITY_M_PER_S2;

use super::soil::{Contact, Soil};
use super::{PhysicsError, check_experiment, check_speed};

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

impl RoverBody {
    /// Total mass, kilograms: the chassis box and six solid wheel cylinders at their densities
    /// (the defaults: 57.6 kg + 6 × 19.6 kg = 175.4 kg).
    #[must_use]
    pub fn mass_kg(&self) -> f64 {
        let [hx, hy, hz] = self.chassis_half_m;
        let wheel = std::f64::consts::PI * self.wheel_radius_m.powi(2) * self.wheel_width_m;
        8.0 * hx * hy * hz * self.chassis_density_kg_per_m3
            + 6.0 * wheel * self.wheel_density_kg_per_m3
    }
}

/// What a drive on the slope measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlopeDrive {
    /// Distance the chassis moved along its commanded heading over the measured (second) half
    /// of the drive, metres.
    pub progress_m: f64,
    /// Distance the wheels' rotation commanded (ω r t) over that half, metres.
    pub commanded_m: f64,
    /// `1 − progress / commanded` (0: no slip; 1: no progress; above 1: sliding back).
    pub slip: f64,
    /// Sideways drift of the chassis over the whole drive, to its left positive, metres.
    pub drift_left_m: f64,
    /// Tilt of the chassis at the end: the angle between its up axis and the vertical, degrees.
    pub tilt_deg: f64,
    /// Static sinkage of a wheel in the soil (Bekker), metres; 0 on rigid ground.
    pub sinkage_m: f64,
}

/// Drive `body` on `soil` for `duration_s` at `speed_m_per_s` (the wheels' rim speed), on a
/// plane slope of `slope_deg` built as a heightfield collider, heading `heading`. Slip is
/// measured over the second half of the drive, once the start from rest has settled.
///
/// Rigid soil (bedrock) is rapier's Coulomb contact with `μ = tan φ`. On deformable soil each
/// wheel–ground contact's friction is set every step, through a rapier contact hook, to the
/// Janosi–Hanamoto traction the soil gives at the wheel's slip ([`Soil::traction_coefficient`]).
/// The slip is the sliding speed of the wheel's lowest point over the rim speed, as the soil's
/// shear follows it: relaxed towards the current value over the time a soil element takes to
/// cross the contact patch, `l / (ω r)` (about 2 s on sand). Each wheel is also held back by
/// its compaction resistance `R_c` along the rover's forward axis. The load behind both is the
/// wheel's static share of the rover's weight normal to the slope.
///
/// # Errors
/// [`PhysicsError::Invalid`] for a parameter out of range (slope 0 ≤ θ < 90°, speed
/// 0 < v ≤ 1 m/s, duration 0 < t ≤ 60 s).
pub fn drive_on_slope(
    body: &RoverBody,
    slope_deg: f64,
    heading: Heading,
    soil: &Soil,
    speed_m_per_s: f64,
    duration_s: f64,
) -> Result<SlopeDrive, PhysicsError> {
    check_experiment(slope_deg, soil.tan_phi(), duration_s)?;
    check_speed(speed_m_per_s)?;
    let theta = slope_deg.to_radians();
    // The ground: a heightfield rising along +x, 40 m square, centred on the rover's start.
    let tilt = Rotation::from_rotation_z(theta);
    let mut world = PhysicsWorld {
        gravity: Vector::new(0.0, -MARS_SURFACE_GRAVITY_M_PER_S2, 0.0),
        ..PhysicsWorld::default()
    };
    let (side_m, cells) = (40.0, 40);
    let mut heights = Array2::zeros(cells + 1, cells + 1);
    for i in 0..=cells {
        for j in 0..=cells {
            let x = side_m * (j as f64 / cells as f64 - 0.5);
            let at = heights.flat_index(i, j);
            heights.data_mut()[at] = x * theta.tan();
        }
    }
    let ground = insert_ground(&mut world, heights, Vector::new(side_m, 1.0, side_m), soil);
    let pose = tilt * Rotation::from_rotation_y(heading.yaw_rad());
    let r = body.wheel_radius_m;
    let centre = (tilt * Vector::Y) * (r + body.clearance_m);
    let rover = assemble(&mut world, body, centre, pose, speed_m_per_s);
    let chassis = rover.chassis;
    let load_n = body.mass_kg() * MARS_SURFACE_GRAVITY_M_PER_S2 * theta.cos() / 6.0;
    let contact = soil.contact(load_n, r, body.wheel_width_m);
    let mut hooks = SoilHook::new(&world, ground, &rover, r, *soil, contact);
    let normal = tilt * Vector::Y;
    let dt = world.integration_parameters.dt;
    let steps = (duration_s / dt).round() as usize;
    let settle = steps / 2;
    let mut from = world.bodies[chassis].translation();
    let start = from;
    for step in 0..steps {
        if step == settle {
            from = world.bodies[chassis].translation();
        }
        hooks.before_step(&mut world, &rover, speed_m_per_s, |_| normal);
        world.step_with_events(&hooks, &());
    }
    let measured_s = (steps - settle) as f64 * dt;
    let end = world.bodies[chassis].translation();
    let along = pose * Vector::X;
    let progress_m = (end - from).dot(along);
    let commanded_m = speed_m_per_s * measured_s;
    Ok(SlopeDrive {
        progress_m,
        commanded_m,
        slip: 1.0 - progress_m / commanded_m,
        drift_left_m: (end - start).dot(pose * Vector::Z),
        tilt_deg: tilt_deg(*world.bodies[chassis].rotation()),
        sinkage_m: contact.sinkage_m,
    })
}

/// The angle between a body's up axis under `rotation` and the vertical, degrees.
pub(super) fn tilt_deg(rotation: Rotation) -> f64 {
    (rotation * Vector::Y)
        .dot(Vector::Y)
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// The ground collider: a heightfield of `heights` (rows north to south, columns west to east)
/// spanning `scale` (x, height factor, z), centred on the origin, whose contacts go through the
/// soil hook.
pub(super) fn insert_ground(
    world: &mut PhysicsWorld,
    heights: Array2<f64>,
    scale: Vector,
    soil: &Soil,
) -> ColliderHandle {
    let ground = ColliderBuilder::heightfield(heights, scale)
        .friction(soil.tan_phi())
        .friction_combine_rule(CoefficientCombineRule::Min)
        .restitution(0.0)
        .active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
    world.insert(RigidBodyBuilder::fixed(), ground).1
}

/// The rover's bodies in a world.
pub(super) struct Assembled {
    /// The chassis.
    pub(super) chassis: RigidBodyHandle,
    /// The six wheels, front to back, left before right.
    pub(super) wheels: Vec<RigidBodyHandle>,
}

/// Build `body` with its chassis centre at `centre` and orientation `pose` (x forward, y up,
/// z left), every wheel motor turning for a rim speed of `speed_m_per_s`. Bodies never sleep
/// (a sleeping rover would stop measuring).
pub(super) fn assemble(
    world: &mut PhysicsWorld,
    body: &RoverBody,
    centre: Vector,
    pose: Rotation,
    speed_m_per_s: f64,
) -> Assembled {
    let material = |c: ColliderBuilder| {
        c.friction(10.0)
            .friction_combine_rule(CoefficientCombineRule::Min)
            .restitution(0.0)
    };
    let r = body.wheel_radius_m;
    let [hx, hy, hz] = body.chassis_half_m;
    let (chassis, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .can_sleep(false)
            .translation(centre)
            .rotation(pose.to_scaled_axis()),
        material(ColliderBuilder::cuboid(hx, hy, hz).density(body.chassis_density_kg_per_m3)),
    );
    let omega = speed_m_per_s / r;
    let mut wheels = Vec::with_capacity(6);
    for x in body.wheel_x_m {
        for z in [body.half_track_m, -body.half_track_m] {
            let local = Vector::new(x, -body.clearance_m, z);
            let (wheel, _) = world.insert(
                RigidBodyBuilder::dynamic()
                    .can_sleep(false)
                    .translation(centre + pose * local)
                    .rotation(pose.to_scaled_axis()),
                // Rapier's cylinder runs along y: turn it to the axle, the body's z.
                material(
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
            wheels.push(wheel);
        }
    }
    Assembled { chassis, wheels }
}

/// The soil contact: each step, the friction of a wheel's contact with the ground is the
/// traction its soil gives at its slip, as the soil's shear has followed it.
pub(super) struct SoilHook {
    ground: ColliderHandle,
    wheel_radius_m: f64,
    /// Each wheel's collider, in wheel order.
    wheel_colliders: Vec<ColliderHandle>,
    /// Each wheel's soil and static contact, in wheel order.
    soils: Vec<(Soil, Contact)>,
    /// Each wheel's slip as the soil's shear has followed it.
    shear_slip: Vec<f64>,
}

impl SoilHook {
    /// Every wheel of `rover` (built in `world`, wheels of `wheel_radius_m`) on `soil` with
    /// `contact`.
    pub(super) fn new(
        world: &PhysicsWorld,
        ground: ColliderHandle,
        rover: &Assembled,
        wheel_radius_m: f64,
        soil: Soil,
        contact: Contact,
    ) -> Self {
        Self {
            ground,
            wheel_radius_m,
            wheel_colliders: rover
                .wheels
                .iter()
                .map(|&w| world.bodies[w].colliders()[0])
                .collect(),
            soils: vec![(soil, contact); rover.wheels.len()],
            shear_slip: vec![0.0; rover.wheels.len()],
        }
    }

    /// Wheel `k` now rests on `soil` with `contact`.
    pub(super) fn set_soil(&mut self, k: usize, soil: Soil, contact: Contact) {
        self.soils[k] = (soil, contact);
    }

    /// Before a step: update each wheel's slip (the sliding speed of its lowest point, below it
    /// along the ground's normal there, over the rim speed), relaxed over the time a soil
    /// element takes to cross its contact patch (Janosi–Hanamoto's shear `j = s x` accumulates
    /// along it), and push it back by its compaction resistance along the chassis' forward axis.
    pub(super) fn before_step(
        &mut self,
        world: &mut PhysicsWorld,
        rover: &Assembled,
        speed_m_per_s: f64,
        normal_at: impl Fn(Vector) -> Vector,
    ) {
        let dt = world.integration_parameters.dt;
        let forward = world.bodies[rover.chassis].rotation() * Vector::X;
        for (k, &w) in rover.wheels.iter().enumerate() {
            let (_, contact) = self.soils[k];
            let wheel = &mut world.bodies[w];
            let centre = wheel.translation();
            let normal = normal_at(centre);
            let bottom = centre - normal * self.wheel_radius_m;
            let v = wheel.velocity_at_point(bottom);
            let slip = ((v - normal * v.dot(normal)).length() / speed_m_per_s).min(1.0);
            let relax = if contact.length_m > 0.0 {
                (dt * speed_m_per_s / contact.length_m).min(1.0)
            } else {
                1.0
            };
            self.shear_slip[k] += relax * (slip - self.shear_slip[k]);
            wheel.reset_forces(false);
            wheel.add_force(-forward * contact.resistance_n, true);
        }
    }
}

impl PhysicsHooks for SoilHook {
    fn modify_solver_contacts(&self, ctx: &mut ContactModificationContext) {
        let wheel = if ctx.collider1 == self.ground {
            ctx.collider2
        } else {
            ctx.collider1
        };
        let Some(k) = self.wheel_colliders.iter().position(|&c| c == wheel) else {
            return;
        };
        let (soil, contact) = &self.soils[k];
        let friction = soil.traction_coefficient(contact, self.shear_slip[k]);
        if let Some(manifold) = ctx.rigid_mut() {
            *manifold.friction = friction;
        }
    }
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
            drive_on_slope(&body, slope_deg, heading, &Soil::rigid(0.5), 0.05, 20.0).expect("valid")
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
        let e = drive_on_slope(
            &RoverBody::default(),
            10.0,
            Heading::UpSlope,
            &Soil::SAND,
            0.0,
            1.0,
        )
        .expect_err("refused");
        assert!(e.to_string().starts_with("speed_m_per_s"), "{e}");
    }
}
