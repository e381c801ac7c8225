//! The rover on a scenario's own terrain: a patch of the map's DEM as a rapier heightfield, each
//! wheel on the soil of the terrain class under it.
//!
//! The slip profiles are measured on planes ([`super::drive_on_slope`]); the traverse applies
//! them to the DEM's slope under each step ([`crate::rover::slip_profile::SlipTable`]). This drive checks
//! that transfer: the rover runs over the real heightfield, each wheel's soil following the
//! terrain class beneath it, and [`DemDrive`] reports the slip it measured beside the slip the
//! profile predicts along the same path. The chassis is the rigid one of [`super::RoverBody`]:
//! at the maps' 1 m DEM resolution the ground under the 1.1 m wheelbase departs from a plane by
//! centimetres on the bundled maps, which a rocker-bogie would follow and a rigid frame rides
//! over on five or six wheels.

use maps::{Raster, TerrainClass};
use rapier3d_f64::prelude::*;

use super::rover::{SoilHook, assemble, insert_ground, tilt_deg};
use super::{PhysicsError, RoverBody, Soil, check, check_speed};
use crate::rover::slip_profile::{SlipTable, along_across};
use localization::ekf::MARS_SURFACE_GRAVITY_M_PER_S2;

/// What a drive over the DEM measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DemDrive {
    /// Distance the chassis moved along its own forward axis over the second half of the drive,
    /// summed step by step, metres.
    pub progress_m: f64,
    /// Distance the wheels commanded over that half, metres.
    pub commanded_m: f64,
    /// `1 − progress / commanded`.
    pub slip: f64,
    /// The profile's predicted slip ([`SlipTable::slip`]) at the chassis' position and heading,
    /// averaged over the same steps.
    pub predicted_slip: f64,
    /// Where the chassis ended, map metres (x east, y north).
    pub end_m: [f64; 2],
    /// Mean chassis tilt over the measured half, degrees.
    pub mean_tilt_deg: f64,
}

/// Drive `body` from `start_m` (map metres) heading `heading_deg` (counter-clockwise from east)
/// for `duration_s` at `speed_m_per_s`, on the patch of `dem` within `speed × duration + 10 m` of
/// the start, each wheel on the soil of `terrain`'s class beneath it (no data: soil).
///
/// # Errors
/// [`PhysicsError::Invalid`] for a speed or duration out of range, or a start whose patch does
/// not fit on the DEM.
pub fn drive_on_dem(
    body: &RoverBody,
    dem: &Raster<f32>,
    terrain: &Raster<u8>,
    start_m: [f64; 2],
    heading_deg: f64,
    speed_m_per_s: f64,
    duration_s: f64,
) -> Result<DemDrive, PhysicsError> {
    check_speed(speed_m_per_s)?;
    check(
        "duration_s",
        duration_s,
        "0 < duration ≤ 120 s",
        duration_s > 0.0 && duration_s <= 120.0,
    )?;
    let res = dem.geo.resolution_m_per_px;
    let half = ((speed_m_per_s * duration_s + 10.0) / res).ceil() as usize;
    let (c0, r0) = dem.geo.pixel_of(start_m[0], start_m[1]);
    let fits = c0 >= half as f64
        && r0 >= half as f64
        && c0 + (half as f64) < dem.width as f64
        && r0 + (half as f64) < dem.height as f64;
    check(
        "start_m",
        start_m[0],
        "a start whose patch (speed × duration + 10 m around it) lies on the DEM",
        fits,
    )?;
    let (cc, rc) = (c0.floor() as usize, r0.floor() as usize);
    let (col0, row0, n) = (cc - half, rc - half, 2 * half + 1);
    // The patch's centre pixel is the world origin; x east, y up, z south.
    let (origin_x, origin_y) = dem.geo.center_of(cc, rc);
    let base = f64::from(dem.get(cc, rc));
    let mut heights = Array2::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            let at = heights.flat_index(i, j);
            heights.data_mut()[at] = f64::from(dem.get(col0 + j, row0 + i)) - base;
        }
    }
    let extent = (n - 1) as f64 * res;
    let to_world = |m: [f64; 2]| (m[0] - origin_x, origin_y - m[1]);
    let to_map = |v: Vector| [v.x + origin_x, origin_y - v.z];
    let gradient = dem.gradient();
    let slope_at = |m: [f64; 2]| {
        gradient
            .sample_nearest(m[0], m[1])
            .unwrap_or([0.0; 2])
            .map(f64::from)
    };
    // The ground's unit normal in the world frame: (−∂z/∂x, 1, +∂z/∂y_north).
    let normal_at = |v: Vector| {
        let g = slope_at(to_map(v));
        Vector::new(-g[0], 1.0, g[1]).normalize()
    };
    let class_at = |v: Vector| {
        let [x, y] = to_map(v);
        terrain
            .sample_nearest(x, y)
            .and_then(TerrainClass::from_code)
            .unwrap_or(TerrainClass::Soil)
    };

    let mut world = PhysicsWorld {
        gravity: Vector::new(0.0, -MARS_SURFACE_GRAVITY_M_PER_S2, 0.0),
        ..PhysicsWorld::default()
    };
    let ground = insert_ground(
        &mut world,
        heights,
        Vector::new(extent, 1.0, extent),
        &Soil::SOIL,
    );
    let (sx, sz) = to_world(start_m);
    // Heights between pixel centres are interpolated (the heightfield's vertices are the
    // pixel centres): a rover set down on the nearest pixel's height sinks into a slope.
    let ground_y = dem
        .sample_bilinear(start_m[0], start_m[1])
        .map_or(0.0, f64::from)
        - base;
    let start_ground = Vector::new(sx, ground_y, sz);
    let up = normal_at(start_ground);
    let psi = heading_deg.to_radians();
    let level_forward = Vector::new(psi.cos(), 0.0, -psi.sin());
    let forward = (level_forward - up * level_forward.dot(up)).normalize();
    let side = forward.cross(up);
    let pose = Rotation::from_mat3(&Matrix::from_cols(forward, up, side));
    let r = body.wheel_radius_m;
    // Set down 5 cm above the ground: the wheels settle in the first half of the drive.
    let centre = start_ground + up * (r + body.clearance_m + 0.05);
    let rover = assemble(&mut world, body, centre, pose, speed_m_per_s);
    let weight_n = body.mass_kg() * MARS_SURFACE_GRAVITY_M_PER_S2 / 6.0;
    let contact_of =
        |soil: &Soil, normal: Vector| soil.contact(weight_n * normal.y, r, body.wheel_width_m);
    let mut hooks = SoilHook::new(
        &world,
        ground,
        &rover,
        r,
        Soil::SOIL,
        contact_of(&Soil::SOIL, up),
    );
    let table = SlipTable::bundled();
    let dt = world.integration_parameters.dt;
    let steps = (duration_s / dt).round() as usize;
    let settle = steps / 2;
    let (mut progress_m, mut predicted, mut tilt) = (0.0, 0.0, 0.0);
    for step in 0..steps {
        for (k, &w) in rover.wheels.iter().enumerate() {
            let at = world.bodies[w].translation();
            let soil = Soil::of(class_at(at));
            hooks.set_soil(k, soil, contact_of(&soil, normal_at(at)));
        }
        let chassis = &world.bodies[rover.chassis];
        let before = chassis.translation();
        let fwd = chassis.rotation() * Vector::X;
        if step >= settle {
            let m = to_map(before);
            let g = slope_at(m).map(|v| v as f32);
            let u = Vector::new(fwd.x, 0.0, fwd.z).normalize_or_zero();
            // The heading on the map: x east, y north = −z.
            let (along, across) = along_across(g, u.x as f32, -u.z as f32);
            predicted += f64::from(table.slip(class_at(before), along, across));
            tilt += tilt_deg(*chassis.rotation());
        }
        hooks.before_step(&mut world, &rover, speed_m_per_s, normal_at);
        world.step_with_events(&hooks, &());
        if step >= settle {
            progress_m += (world.bodies[rover.chassis].translation() - before).dot(fwd);
        }
    }
    let measured = (steps - settle) as f64;
    let commanded_m = speed_m_per_s * measured * dt;
    Ok(DemDrive {
        progress_m,
        commanded_m,
        slip: 1.0 - progress_m / commanded_m,
        predicted_slip: predicted / measured,
        end_m: to_map(world.bodies[rover.chassis].translation()),
        mean_tilt_deg: tilt / measured,
    })
}
