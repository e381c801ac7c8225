//! Issue 15: `solsim slip-profile` measures the slip-versus-slope tables with the rapier rover;
//! the simulator reads the bundled table, which must be what the model gives today; the
//! profile's trend against the closed-form terramechanics it stands on and the published record;
//! and the scenario's slip settings refused with the field named.

use sim::rover::physics::{Heading, RoverBody, Soil, drive_on_dem, drive_on_slope};
use sim::rover::slip_profile::{ProfileHeading, SlipProfile};

use maps::TerrainClass;

use crate::common::{self, assert_bad_input, replace_line, run_ok, scenario_copy, solsim};

/// The command's table at the defaults matches the bundled one the simulator reads: same rows,
/// every number within 0.002 (rapier's stepping is deterministic; the tolerance covers only a
/// platform's last-bit differences), and the figure and JSON are written beside it.
#[test]
fn the_bundled_table_is_what_slip_profile_measures() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("profile");
    let text = run_ok(&["slip-profile", "--out"], &[out.as_path()]);
    assert!(text.contains("slip % by slope"), "{text}");
    let csv = std::fs::read_to_string(out.join("slip_profile.csv")).expect("csv");
    let measured = SlipProfile::from_csv(&csv).expect("parses");
    let bundled = SlipProfile::bundled();
    assert_eq!(measured.rows.len(), bundled.rows.len());
    for (m, b) in measured.rows.iter().zip(&bundled.rows) {
        assert_eq!(
            (m.terrain, m.heading, m.slope_deg),
            (b.terrain, b.heading, b.slope_deg)
        );
        for (x, y) in [
            (m.slip, b.slip),
            (m.tilt_deg, b.tilt_deg),
            (m.sinkage_m, b.sinkage_m),
        ] {
            assert!(
                (x - y).abs() <= 0.002 * y.abs().max(1.0),
                "{m:?} vs bundled {b:?}"
            );
        }
    }
    let svg = std::fs::read_to_string(out.join("slip_profile.svg")).expect("svg");
    for label in ["sand", "soil", "bedrock", "slope (deg)", "slip (%)"] {
        assert!(svg.contains(label), "figure lacks {label}");
    }
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("slip_profile.json")).expect("json"))
            .expect("valid JSON");
    assert_eq!(
        json["rows"].as_array().map(Vec::len),
        Some(bundled.rows.len())
    );
}

/// The rapier rover against the closed form of the same soil model (Janosi–Hanamoto thrust
/// against Bekker compaction resistance plus the weight's pull, `Soil::steady_slip`): up and
/// down runs on the deformable soils agree within 4 slip points wherever the closed form has a
/// steady state below 70 % slip (measured: at most 3.3 points, the rover slipping more: it
/// starts from rest and its load shifts to the downhill wheels, which the closed form ignores).
#[test]
fn the_rapier_rover_follows_the_closed_form_terramechanics() {
    let mut compared = 0;
    for r in &SlipProfile::bundled().rows {
        if let Some(c) = r.closed_form_slip.filter(|c| c.abs() < 0.7)
            && r.terrain != TerrainClass::Bedrock
        {
            assert!((r.slip - c).abs() < 0.04, "{r:?}");
            compared += 1;
        }
    }
    assert!(compared >= 50, "{compared} rows compared");
}

/// The trend the published record shows. Uphill slip grows with slope on every class, and
/// orders the classes sand ≥ soil > bedrock. Bedrock holds under 10 % to 30° (Curiosity and Opportunity
/// climbed 20-30° bedrock slopes); sand passes 50 % slip before 30° (Opportunity met up to 50 %
/// slip on the sandy slopes inside Endurance crater, JPL PIA06835) and stops the rover
/// altogether short of its friction angle. Driving across a slope slips far less than up it,
/// and downhill the wheels brake (negative slip) — paper 003 §4's reason to plan by direction.
#[test]
fn the_profile_trends_as_the_record_does() {
    let p = SlipProfile::bundled();
    let up = |t| p.curve(t, ProfileHeading::Up);
    for t in TerrainClass::ALL {
        let c = up(t);
        for w in c.windows(2) {
            assert!(w[1].1 > w[0].1, "{t:?}: {w:?}");
        }
    }
    let (sand, soil, rock) = (
        up(TerrainClass::Sand),
        up(TerrainClass::Soil),
        up(TerrainClass::Bedrock),
    );
    for k in 0..sand.len() {
        assert!(
            sand[k].1 >= soil[k].1 - 0.02,
            "{} deg: sand {} soil {}",
            sand[k].0,
            sand[k].1,
            soil[k].1
        );
        assert!(
            soil[k].1 > rock[k].1,
            "{} deg: soil {} bedrock {}",
            soil[k].0,
            soil[k].1,
            rock[k].1
        );
        assert!(
            rock[k].1 < 0.10,
            "bedrock at {} deg: {}",
            rock[k].0,
            rock[k].1
        );
    }
    let half = sand
        .iter()
        .find(|s| s.1 >= 0.5)
        .expect("sand reaches 50 % slip");
    assert!(
        half.0 > 15.0 && half.0 < 30.0,
        "sand passes 50 % at {} deg",
        half.0
    );
    assert!(
        sand.last().expect("rows").1 >= 1.0,
        "sand stops the rover by 30 deg"
    );
    for t in [TerrainClass::Sand, TerrainClass::Soil] {
        let at20 = |h| p.predict(t, 20.0, h);
        assert!(at20(90.0) < 0.5 * at20(0.0), "{t:?} across vs up at 20 deg");
        assert!(at20(180.0) < 0.0, "{t:?} downhill brakes at 20 deg");
    }
}

#[test]
fn bad_arguments_name_the_flag() {
    let tmp = tempfile::tempdir().expect("tempdir");
    for (flag, value) in [
        ("--slope-step-deg", "0"),
        ("--max-slope-deg", "80"),
        ("--duration-s", "NaN"),
    ] {
        let o = solsim()
            .args(["slip-profile", "--out"])
            .arg(tmp.path().join("p"))
            .args([flag, value])
            .output()
            .expect("runs");
        assert_bad_input(&o, &[flag]);
    }
}

/// `[rover] slip_model` and its settings: a misspelt model and a setting without the profile
/// model are refused with the field named; a profile scenario validates.
#[test]
fn slip_settings_are_checked() {
    let cases: [(&str, &str); 4] = [
        ("slip_model = \"physics\"", "rover.slip_model"),
        ("slip_aware_routing = false", "rover.slip_aware_routing"),
        (
            "slip_model = \"profile\"\nslip_limit = 1.5",
            "rover.slip_limit",
        ),
        (
            "slip_model = \"profile\"\navoid_slip_above = -1",
            "rover.avoid_slip_above",
        ),
    ];
    for (extra, field) in cases {
        let (path, _dir) = scenario_copy("crater-floor-passage.toml", |t| {
            replace_line(&t, "step_m", &format!("step_m = 2.0\n{extra}"))
        });
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        assert_bad_input(&o, &[field]);
    }
    let (path, _dir) = scenario_copy("crater-floor-passage.toml", |t| {
        replace_line(&t, "step_m", "step_m = 2.0\nslip_model = \"profile\"")
    });
    let o = solsim().arg("validate").arg(&path).output().expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
}

/// The rover on a DEM (`drive_on_dem`: the DEM patch as a heightfield, each wheel on the soil of
/// its terrain class) driving up a plane DEM of sand slips as the plane profile says, and as the
/// profile's lookup along its path predicts: within 2 slip points at 0°, 10° and 20° (measured:
/// 6.02 / 5.95 / 5.95 %, 14.45 / 14.23 / 14.48 %, 31.06 / 30.32 / 29.87 %: DEM, plane,
/// predicted).
#[test]
fn the_rover_on_a_plane_dem_slips_as_the_profile_says() {
    let geo = maps::GeoTransform::new(0.0, 200.0, 1.0);
    let body = RoverBody::default();
    for slope_deg in [0.0f64, 10.0, 20.0] {
        let t = slope_deg.to_radians().tan();
        let mut dem = maps::Raster::filled(200, 200, geo, 0.0f32);
        for (k, h) in dem.data.iter_mut().enumerate() {
            // Rising to the west: heading west (180°) drives uphill.
            *h = (100.0 - (k % 200) as f64 * t) as f32;
        }
        let sand = maps::Raster::filled(200, 200, geo, TerrainClass::Sand.code());
        let d = drive_on_dem(&body, &dem, &sand, [100.0, 100.0], 180.0, 0.05, 20.0).expect("drive");
        let plane = drive_on_slope(&body, slope_deg, Heading::UpSlope, &Soil::SAND, 0.05, 20.0)
            .expect("plane");
        assert!(
            (d.slip - plane.slip).abs() < 0.02,
            "{slope_deg}°: {d:?} vs {plane:?}"
        );
        assert!(
            (d.slip - d.predicted_slip).abs() < 0.02,
            "{slope_deg}°: {d:?}"
        );
        assert!(
            (d.mean_tilt_deg - slope_deg).abs() < 0.2,
            "{slope_deg}°: {d:?}"
        );
    }
}

/// On the dune crossing's own DEM the order holds: from the foot of the dune's steep side
/// (395, 150), up it slips most, across it less, down it the wheels brake; on the level soil
/// near the start the rover barely slips. The size does not follow the plane profile: on this
/// 1 m heightfield the rover slips more than the profile predicts along its path (measured:
/// up 60.4 % against 36.1 % at a mean tilt of 22°; at the dune's foot 28.3 % against 11.6 %),
/// which the traverse, reading the profile, does not see (an open question of issue 15).
#[test]
fn the_rover_on_the_dune_dem_slips_most_uphill() {
    let dir = crate::common::root().join("maps/assets/dune-crossing");
    let dem = maps::raster_io::read_dem(&dir.join("dem.tif"), 0.0, None).expect("dem");
    let terrain =
        maps::raster_io::read_raster::<u8>(&dir.join("terrain.tif"), None).expect("terrain");
    let body = RoverBody::default();
    let drive = |start: [f64; 2], heading_deg: f64| {
        drive_on_dem(&body, &dem, &terrain, start, heading_deg, 0.05, 40.0).expect("drive")
    };
    let (up, across, down) = (
        drive([395.0, 150.0], 180.0),
        drive([395.0, 150.0], 90.0),
        drive([395.0, 150.0], 0.0),
    );
    assert!(up.mean_tilt_deg > 15.0, "{up:?}");
    assert!(
        up.slip > across.slip && across.slip > 0.0 && down.slip < 0.0,
        "{up:?} {across:?} {down:?}"
    );
    assert!(up.predicted_slip > across.predicted_slip && down.predicted_slip < 0.0);
    let level = drive([520.0, 150.0], 180.0);
    assert!(
        level.slip.abs() < 0.06 && level.predicted_slip.abs() < 0.06,
        "{level:?}"
    );
    let e = drive_on_dem(&body, &dem, &terrain, [3.0, 150.0], 180.0, 0.05, 40.0)
        .expect_err("a patch off the map");
    assert!(e.to_string().starts_with("start_m"), "{e}");
}
