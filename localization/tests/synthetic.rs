//! Synthetic imagery for global localization: determinism, the rover's coverage model
//! (wedges, range, rover body, occlusion), the orbital DEM, and a sanity check that the rover
//! orthomosaic and the orbital image agree at the true position.
#![allow(clippy::unwrap_used)]

use localization::synthetic::{
    ORTHO_SIZE_PX, OrbitalProducts, OrbitalSettings, ROVER_DEM_BLOCK_PX, RoverImagingSettings,
    RoverObservation, SyntheticError, TruthPatch, render_orbital, render_rover, truth_patch,
};
use maps::procedural::{TerrainSettings, generate};
use maps::{GeoTransform, MapLayers, Raster};
use md5::{Digest, Md5};

/// A 300 m procedural map (1 m pixels, x and y in 0..300 m).
fn procedural_map(seed: u64) -> MapLayers {
    generate(&TerrainSettings {
        seed,
        width_px: 300,
        height_px: 300,
        geo: GeoTransform::new(0.0, 300.0, 1.0),
        ..TerrainSettings::default()
    })
}

/// A hand-made 200 m map that depends on nothing but this file: a tilted plane with a bump,
/// bedrock in the west, soil in the middle, sand in the east.
fn hand_map() -> MapLayers {
    let geo = GeoTransform::new(1000.0, 2000.0, 1.0);
    let n = 200;
    let mut dem = Raster::filled(n, n, geo, 0.0f32);
    let mut terrain = Raster::filled(n, n, geo, 2u8);
    for row in 0..n {
        for col in 0..n {
            let (x, y) = (col as f32 - 100.0, row as f32 - 100.0);
            dem.set(
                col,
                row,
                50.0 + 0.02 * x + 2.0 * (-(x * x + y * y) / 800.0).exp(),
            );
            terrain.set(
                col,
                row,
                if col < 70 {
                    3
                } else if col < 140 {
                    2
                } else {
                    1
                },
            );
        }
    }
    MapLayers {
        appearance: Raster::filled(n, n, geo, 0),
        dem,
        terrain,
    }
}

struct Scene {
    patch: TruthPatch,
    orbital: OrbitalProducts,
    rover: RoverObservation,
}

fn scene(layers: &MapLayers, rover_m: [f64; 2], rover: &RoverImagingSettings, seed: u64) -> Scene {
    let patch = truth_patch(layers, rover_m, 60.0, seed).unwrap();
    let orbital = render_orbital(&patch, &OrbitalSettings::default(), seed + 1).unwrap();
    let rover = render_rover(&patch, rover_m, rover, seed + 2).unwrap();
    Scene {
        patch,
        orbital,
        rover,
    }
}

fn digest(s: &Scene) -> String {
    let mut h = Md5::new();
    for v in s.patch.height_m.data.iter().chain(&s.patch.albedo.data) {
        h.update(v.to_le_bytes());
    }
    h.update(&s.orbital.appearance.data);
    for v in &s.orbital.dem.data {
        h.update(v.to_le_bytes());
    }
    h.update(&s.rover.ortho.data);
    h.update(
        s.rover
            .valid
            .iter()
            .map(|&v| u8::from(v))
            .collect::<Vec<_>>(),
    );
    for v in &s.rover.dem.data {
        h.update(v.to_le_bytes());
    }
    h.update(
        s.rover
            .dem_valid
            .iter()
            .map(|&v| u8::from(v))
            .collect::<Vec<_>>(),
    );
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// Ortho pixel centres with their range from the rover.
fn ortho_ranges(obs: &RoverObservation) -> impl Iterator<Item = (usize, f64)> + '_ {
    let [rx, ry] = obs.true_position_m;
    (0..obs.valid.len()).map(move |i| {
        let (x, y) = obs
            .ortho
            .geo
            .center_of(i % obs.ortho.width, i / obs.ortho.width);
        (i, (x - rx).hypot(y - ry))
    })
}

/// Pearson correlation between the valid rover ortho pixels and the orbital image sampled at
/// the same map points shifted by `offset_m`.
fn pearson(obs: &RoverObservation, orbital: &Raster<u8>, offset_m: [f64; 2]) -> f64 {
    let mut pairs = Vec::new();
    for (i, &ok) in obs.valid.iter().enumerate() {
        if !ok {
            continue;
        }
        let (x, y) = obs
            .ortho
            .geo
            .center_of(i % obs.ortho.width, i / obs.ortho.width);
        if let Some(o) = orbital.sample_nearest(x + offset_m[0], y + offset_m[1]) {
            pairs.push((f64::from(obs.ortho.data[i]), f64::from(o)));
        }
    }
    let n = pairs.len() as f64;
    let (ma, mb) = pairs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (a, b) in &pairs {
        sab += (a - ma) * (b - mb);
        saa += (a - ma) * (a - ma);
        sbb += (b - mb) * (b - mb);
    }
    sab / (saa * sbb).sqrt()
}

#[test]
fn same_seed_gives_identical_bytes_and_another_seed_does_not() {
    let layers = procedural_map(4);
    let p = RoverImagingSettings::default();
    let a = scene(&layers, [150.2, 149.7], &p, 11);
    let b = scene(&layers, [150.2, 149.7], &p, 11);
    assert_eq!(digest(&a), digest(&b));
    assert_eq!(a.rover, b.rover);
    let c = scene(&layers, [150.2, 149.7], &p, 12);
    assert_ne!(a.rover.ortho.data, c.rover.ortho.data);
    assert_ne!(a.orbital.appearance.data, c.orbital.appearance.data);
}

#[test]
fn one_and_two_threads_give_identical_bytes() {
    let layers = procedural_map(5);
    let p = RoverImagingSettings::default();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| digest(&scene(&layers, [140.0, 160.0], &p, 3)))
    };
    assert_eq!(run(1), run(2));
}

/// Golden digest of a scene on [`hand_map`]. A mismatch means the synthetic imagery changed:
/// every stored benchmark image and every localization result computed from synthetic scenes
/// changes with it. If the change is intended, update the constant and say so in the commit.
/// (Per-pixel noise uses integer hashing only, but the geometry and responses use libm `sin`,
/// `cos`, `atan2`, `exp`, `powf`: another platform's libm may legitimately differ.)
#[test]
fn golden_digest_of_a_hand_made_scene() {
    let s = scene(
        &hand_map(),
        [1100.0, 1900.0],
        &RoverImagingSettings::default(),
        1,
    );
    assert_eq!(digest(&s), GOLDEN_DIGEST);
}

/// MD5 of the truth patch, orbital products and rover observation of the golden scene.
/// Changed 2026-11-25 for the sand path only (the hand map's eastern sand): wavy, multi-train
/// ripples and interdune lag / bedrock on the sand class (`synthetic::truth`).
const GOLDEN_DIGEST: &str = "cff694f42aace0d59a7a91b865ac049c";

#[test]
fn valid_fraction_is_plausible_and_grows_with_the_wedge_count() {
    let layers = procedural_map(6);
    let mut fractions = Vec::new();
    for wedge_count in [3, 4, 5] {
        let p = RoverImagingSettings {
            wedge_count,
            ..RoverImagingSettings::default()
        };
        let mean: f64 = (0..4)
            .map(|k| {
                let rover_m = [120.0 + 20.0 * k as f64, 150.0 - 10.0 * k as f64];
                let s = scene(&layers, rover_m, &p, 20 + k);
                s.rover.valid_fraction()
            })
            .sum::<f64>()
            / 4.0;
        fractions.push(mean);
    }
    eprintln!("valid fraction with 3, 4, 5 wedges: {fractions:?}");
    assert!((0.25..0.75).contains(&fractions[1]), "{fractions:?}");
    assert!(fractions[0] < fractions[1] - 0.05, "{fractions:?}");
    // Four 96° wedges already cover every azimuth: five add overlap, not coverage.
    assert!(fractions[2] >= fractions[1] - 0.01, "{fractions:?}");
}

#[test]
fn rover_body_and_far_pixels_are_invalid_near_pixels_mostly_valid() {
    let layers = procedural_map(7);
    let s = scene(&layers, [160.3, 140.9], &RoverImagingSettings::default(), 5);
    let obs = &s.rover;
    assert_eq!(obs.valid.len(), ORTHO_SIZE_PX * ORTHO_SIZE_PX);
    let (mut near, mut near_valid) = (0, 0);
    for (i, range_m) in ortho_ranges(obs) {
        // The range limits apply to the ground a pixel shows; with the mosaic's scale, heading
        // and centre errors that is a few cm from the pixel's own position.
        if !(1.3..=30.3).contains(&range_m) {
            assert!(!obs.valid[i], "pixel {i} at {range_m} m is valid");
            assert_eq!(obs.ortho.data[i], 0);
        } else if range_m < 6.0 {
            near += 1;
            near_valid += usize::from(obs.valid[i]);
        }
    }
    // Four 96° wedges cover every azimuth; close in, little is hidden.
    assert!(near_valid as f64 > 0.8 * near as f64, "{near_valid}/{near}");
    // The DEM cell under the rover is invalid, and the DEM is valid where the ortho mostly is.
    let m = obs.dem.width;
    assert!(!obs.dem_valid[(m / 2) * m + m / 2]);
    let dem_fraction = obs.dem_valid.iter().filter(|&&v| v).count() as f64 / (m * m) as f64;
    assert!(dem_fraction > 0.8 * obs.valid_fraction(), "{dem_fraction}");
}

#[test]
fn pixels_behind_a_wall_are_occluded() {
    // Flat ground at 10 m with a wall 3 m high, 0.5 m thick and 10 m long (north–south),
    // 5–5.5 m east of the rover.
    let n = 200;
    let geo = GeoTransform::new(0.0, 50.0, 0.25);
    let mut height = Raster::filled(n, n, geo, 10.0f32);
    let rover_m = [25.0, 25.0];
    for row in 0..n {
        for col in 0..n {
            let (x, y) = geo.center_of(col, row);
            if (30.0..30.5).contains(&x) && (20.0..30.0).contains(&y) {
                height.set(col, row, 13.0);
            }
        }
    }
    let patch = TruthPatch::from_rasters(height, Raster::filled(n, n, geo, 0.2f32));
    let p = RoverImagingSettings {
        stereo_dropout_at_max_range: 0.0,
        heading_sigma_deg: 0.0,
        scale_sigma: 0.0,
        mosaic_offset_sigma_m: 0.0,
        ..RoverImagingSettings::default()
    };
    let obs = render_rover(&patch, rover_m, &p, 1).unwrap();
    let valid_at = |x: f64, y: f64| {
        let (c, r) = obs.ortho.geo.pixel_of(x, y);
        obs.valid[r as usize * ORTHO_SIZE_PX + c as usize]
    };
    for dy in [-2.0, 0.0, 3.0] {
        let y = rover_m[1] + dy;
        assert!(valid_at(28.0, y), "in front of the wall");
        assert!(valid_at(30.2, y), "top of the wall");
        assert!(!valid_at(31.0, y), "just behind the wall");
        assert!(!valid_at(40.0, y), "far behind the wall");
        assert!(valid_at(15.0, y), "west of the rover");
    }
    // Sight lines that pass north of the wall's end are clear.
    assert!(valid_at(35.0, 45.0));
    assert!(!valid_at(35.0, 29.0));
}

#[test]
fn orbital_dem_is_the_block_mean_of_the_truth() {
    let layers = procedural_map(8);
    let patch = truth_patch(&layers, [150.0, 150.0], 30.0, 2).unwrap();
    let sigma = OrbitalSettings::default().dem_noise_sigma_m;
    let check = |p: &OrbitalSettings, tol: f64| {
        let o = render_orbital(&patch, p, 3).unwrap();
        assert_eq!((o.dem.width, o.dem.height), (60, 60));
        assert_eq!(o.dem.geo.resolution_m_per_px, 1.0);
        assert_eq!(o.dem.geo.origin_m, patch.height_m.geo.origin_m);
        let mut sum_err = 0.0;
        for br in 0..60 {
            for bc in 0..60 {
                let mut mean = 0.0;
                for r in 4 * br..4 * br + 4 {
                    for c in 4 * bc..4 * bc + 4 {
                        mean += f64::from(patch.height_m.get(c, r)) / 16.0;
                    }
                }
                let err = f64::from(o.dem.get(bc, br)) - mean;
                assert!(err.abs() <= tol, "cell ({bc}, {br}): {err}");
                sum_err += err;
            }
        }
        sum_err / 3600.0
    };
    let bias = check(&OrbitalSettings::default(), 5.0 * sigma);
    assert!(bias.abs() < 4.0 * sigma / 60.0, "{bias}");
    // Without DEM noise and without the ripples moving between epochs (the DTM is of the
    // orbital epoch), the DEM is exactly the block mean of the truth.
    let exact = OrbitalSettings {
        dem_noise_sigma_m: 0.0,
        ripple_migration_m: 0.0,
        ..OrbitalSettings::default()
    };
    check(&exact, 1e-4);
}

#[test]
fn rover_dem_matches_the_truth_within_stereo_noise_growing_with_range() {
    let layers = procedural_map(11);
    let s = scene(&layers, [150.6, 150.2], &RoverImagingSettings::default(), 8);
    let obs = &s.rover;
    let (n, m, b) = (ORTHO_SIZE_PX, obs.dem.width, ROVER_DEM_BLOCK_PX);
    let (mut near, mut far) = (Vec::new(), Vec::new());
    for cell in (0..m * m).filter(|&i| obs.dem_valid[i]) {
        let (bc, br) = (cell % m, cell / m);
        // The truth under the same valid ortho pixels the rover averaged.
        let (mut sum, mut count) = (0.0, 0);
        for row in br * b..(br + 1) * b {
            for col in bc * b..(bc + 1) * b {
                if obs.valid[row * n + col] {
                    let (x, y) = obs.ortho.geo.center_of(col, row);
                    sum += f64::from(s.patch.height_m.sample_bilinear(x, y).unwrap());
                    count += 1;
                }
            }
        }
        let err = f64::from(obs.dem.data[cell]) - sum / f64::from(count);
        let (x, y) = obs.dem.geo.center_of(bc, br);
        let range_m = (x - obs.true_position_m[0]).hypot(y - obs.true_position_m[1]);
        if range_m < 10.0 {
            near.push(err);
        } else if range_m > 20.0 {
            far.push(err);
        }
    }
    let rms = |v: &[f64]| (v.iter().map(|e| e * e).sum::<f64>() / v.len() as f64).sqrt();
    let (near_rms, far_rms) = (rms(&near), rms(&far));
    eprintln!("rover DEM error RMS: {near_rms:.3} m within 10 m, {far_rms:.3} m beyond 20 m");
    assert!(near.len() > 100 && far.len() > 300);
    assert!(near_rms < 0.05, "{near_rms}");
    assert!(far_rms > 2.0 * near_rms && far_rms < 0.5, "{far_rms}");
    // Invalid cells hold 0.
    assert!(
        obs.dem_valid
            .iter()
            .zip(&obs.dem.data)
            .all(|(&ok, &h)| ok || h == 0.0)
    );
}

#[test]
fn rover_ortho_correlates_with_the_orbital_image_at_the_true_position() {
    let layers = procedural_map(9);
    for (k, rover_m) in [[150.0, 150.0], [100.4, 190.3], [210.7, 95.1]]
        .into_iter()
        .enumerate()
    {
        let s = scene(
            &layers,
            rover_m,
            &RoverImagingSettings::default(),
            40 + k as u64,
        );
        let at_truth = pearson(&s.rover, &s.orbital.appearance, [0.0, 0.0]);
        let offsets = [[5.0, 0.0], [0.0, -5.0], [-3.0, 4.0]];
        let shifted: Vec<f64> = offsets
            .iter()
            .map(|&o| pearson(&s.rover, &s.orbital.appearance, o))
            .collect();
        eprintln!("rover at {rover_m:?}: r = {at_truth:.3} at truth, {shifted:.3?} at 5 m");
        assert!(at_truth > 0.2, "{at_truth}");
        assert!(shifted.iter().all(|&r| r < at_truth - 0.1), "{shifted:?}");
    }
}

#[test]
fn bad_input_is_an_error() {
    let layers = procedural_map(10);
    assert!(matches!(
        truth_patch(&layers, [290.0, 150.0], 30.0, 1),
        Err(SyntheticError::PatchOutsideMap { .. })
    ));
    let patch = truth_patch(&layers, [150.0, 150.0], 20.0, 1).unwrap();
    assert!(matches!(
        render_rover(&patch, [100.0, 150.0], &RoverImagingSettings::default(), 1),
        Err(SyntheticError::RoverOutsidePatch { .. })
    ));
    let mut torn = patch.clone();
    torn.albedo.data.pop();
    assert!(matches!(
        render_orbital(&torn, &OrbitalSettings::default(), 1),
        Err(SyntheticError::MalformedPatch { .. })
    ));
    let bad = OrbitalSettings {
        sun_elevation_deg: f64::NAN,
        ..OrbitalSettings::default()
    };
    let err = render_orbital(&patch, &bad, 1).unwrap_err();
    assert!(
        err.to_string().starts_with("sun_elevation_deg = NaN"),
        "{err}"
    );
    assert!(!err.to_string().contains('\n'));
}

/// Every default the field docs state (rapier's docs drifted from its `Default`).
#[test]
fn documented_defaults() {
    let o = OrbitalSettings::default();
    assert_eq!(
        (
            o.sun_azimuth_deg,
            o.sun_elevation_deg,
            o.ambient,
            o.white_level
        ),
        (250.0, 35.0, 0.2, 0.35)
    );
    assert_eq!(
        (
            o.blur_sigma_px,
            o.noise_sigma_dn,
            o.gamma,
            o.dem_noise_sigma_m
        ),
        (1.0, 2.0, 0.8, 0.05)
    );
    assert_eq!(
        (
            o.albedo_change_sigma,
            o.dust_devil_tracks_per_ha,
            o.dust_devil_track_width_m,
            o.dust_devil_track_darkening
        ),
        (0.05, 0.5, [1.0, 6.0], [0.05, 0.15])
    );
    assert_eq!(
        (
            o.ripple_migration_m,
            o.ortho_displacement_sigma_m,
            o.ortho_displacement_wavelength_m
        ),
        (0.75, 0.2, 40.0)
    );
    let r = RoverImagingSettings::default();
    assert_eq!(
        (r.wedge_count, r.wedge_width_deg, r.mast_height_m),
        (4, 96.0, 2.0)
    );
    assert_eq!((r.min_range_m, r.max_range_m), (1.5, 30.0));
    assert_eq!(r.sun_azimuth_range_deg, [240.0, 300.0]);
    assert_eq!(r.sun_elevation_range_deg, [12.0, 30.0]);
    assert_eq!((r.ambient, r.white_level), (0.2, 0.25));
    assert_eq!(r.gain_range, [0.75, 1.25]);
    assert_eq!(r.offset_range_dn, [-15.0, 15.0]);
    assert_eq!(r.gamma_range, [0.75, 1.35]);
    assert_eq!((r.noise_sigma_dn, r.pixel_ifov_mrad), (2.0, 0.8));
    assert_eq!(
        (r.range_sigma_m_at_10m, r.height_sigma_m_at_10m),
        (0.05, 0.02)
    );
    assert_eq!((r.stereo_dropout_at_max_range, r.dem_min_samples), (0.3, 4));
    assert_eq!(
        (r.heading_sigma_deg, r.scale_sigma, r.mosaic_offset_sigma_m),
        (0.5, 0.003, 0.03)
    );
}

/// The rover's geometric errors are drawn from the seed at the documented scale, recorded, and
/// all exactly zero when their sigmas are.
#[test]
fn rover_geometry_errors_are_seeded_recorded_and_switchable() {
    let layers = procedural_map(12);
    let patch = truth_patch(&layers, [150.0, 150.0], 40.0, 1).unwrap();
    let p = RoverImagingSettings::default();
    let (mut heading, mut scale, mut offset) = (0.0f64, 0.0f64, 0.0f64);
    for seed in 0..16 {
        let e = render_rover(&patch, [150.0, 150.0], &p, seed)
            .unwrap()
            .geometry_errors;
        heading = heading.max(e.heading_error_deg.abs());
        scale = scale.max((e.scale - 1.0).abs());
        offset = offset.max(e.mosaic_offset_m[0].hypot(e.mosaic_offset_m[1]));
    }
    assert!((0.3..2.5).contains(&heading), "{heading}");
    assert!((0.001..0.015).contains(&scale), "{scale}");
    assert!((0.02..0.15).contains(&offset), "{offset}");
    let exact = RoverImagingSettings {
        heading_sigma_deg: 0.0,
        scale_sigma: 0.0,
        mosaic_offset_sigma_m: 0.0,
        ..p
    };
    let e = render_rover(&patch, [150.0, 150.0], &exact, 3)
        .unwrap()
        .geometry_errors;
    assert_eq!(
        (e.heading_error_deg, e.scale, e.mosaic_offset_m),
        (0.0, 1.0, [0.0, 0.0])
    );
}

/// Each orbital epoch change alters the image, and switching all of them off restores the
/// old "same truth, perfect geometry" image exactly.
#[test]
fn orbital_epoch_changes_alter_the_image_and_switch_off() {
    // Sand in the east of the hand map: ripples live there.
    let patch = truth_patch(&hand_map(), [1170.0, 1900.0], 25.0, 2).unwrap();
    assert!(patch.sand.data.iter().any(|&s| s > 0.99));
    let none = OrbitalSettings {
        albedo_change_sigma: 0.0,
        dust_devil_tracks_per_ha: 0.0,
        ripple_migration_m: 0.0,
        ortho_displacement_sigma_m: 0.0,
        ..OrbitalSettings::default()
    };
    let base = render_orbital(&patch, &none, 5).unwrap().appearance.data;
    for changed in [
        OrbitalSettings {
            albedo_change_sigma: 0.1,
            ..none
        },
        OrbitalSettings {
            dust_devil_tracks_per_ha: 20.0,
            ..none
        },
        OrbitalSettings {
            ripple_migration_m: 1.5,
            ..none
        },
        OrbitalSettings {
            ortho_displacement_sigma_m: 0.3,
            ..none
        },
    ] {
        let img = render_orbital(&patch, &changed, 5).unwrap().appearance.data;
        let differing = img.iter().zip(&base).filter(|(a, b)| a != b).count();
        assert!(differing > base.len() / 50, "{changed:?}: {differing}");
    }
    // The ripples are no longer one periodic train (several trains of different spacing,
    // warped crests): a shift of the mean wavelength (3 m) is not "no migration" any more.
    let full = OrbitalSettings {
        ripple_migration_m: 3.0,
        ..none
    };
    let img = render_orbital(&patch, &full, 5).unwrap().appearance.data;
    let differing = img.iter().zip(&base).filter(|(a, b)| a != b).count();
    assert!(differing > base.len() / 50, "{differing}");
}
