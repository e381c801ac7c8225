//! The AutoNav rate of a scenario built from the public record (issue 27) is the record's own:
//! each historic drive sol drives at its distance over its window, from the spacecraft clock, so
//! the re-simulated ground strategy drives close to the record's metres per drive sol without any
//! calibration (AutoNav's detours cost a few per cent: 206.6 m against 216.2 m over the sols
//! both drove to their end, 50 runs); and `solsim calibrate drive-rate` says there is nothing to
//! calibrate there. On a scenario without per-sol speeds (the hand-built crater-floor passage) it
//! still solves the rate at which ground drives the record's metres per drive sol.

use study::Scenario;
use study::calibrate::{CalibrationError, calibrate_drive_rate};

fn load(name: &str) -> Scenario {
    Scenario::load(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenarios")
            .join(name)
            .as_path(),
    )
    .expect("the bundled scenario loads")
}

#[test]
fn the_rapid_traverse_drives_the_records_own_speeds() {
    let s = load("rapid-traverse-379-409.toml");
    match calibrate_drive_rate(&s, 10) {
        Err(CalibrationError::OwnSpeeds(name)) => assert_eq!(name, "rapid-traverse-379-409"),
        other => panic!("expected OwnSpeeds, got {other:?}"),
    }
    // Ground, re-simulated, over the sols it and the record drove to their end.
    let cal = &s.settings.calendar;
    let (mut ground_m, mut record_m, mut n) = (0.0, 0.0, 0u32);
    for run in 0..50 {
        let o = s.run_index(sim::Strategy::Ground, run);
        for (g, e) in o.sols.iter().zip(&cal.sols) {
            if let Some(h) = e.historic
                && h.distance_m > 0.0
                && !h.ended_in_fault
                && g.drove
                && g.fault.is_none()
            {
                ground_m += g.distance_m;
                record_m += h.distance_m;
                n += 1;
            }
        }
    }
    let ratio = ground_m / record_m;
    eprintln!(
        "ground {:.1} m against the record's {:.1} m per drive sol over {n} sols: {ratio:.3}",
        ground_m / f64::from(n),
        record_m / f64::from(n)
    );
    assert!(
        (0.9..=1.0).contains(&ratio),
        "ground drives {ratio:.3} of the record's metres"
    );
}

#[test]
fn a_scenario_without_per_sol_speeds_is_still_calibrated() {
    let s = load("crater-floor-passage.toml");
    let c = calibrate_drive_rate(&s, 10).expect("a record without per-sol speeds");
    assert!(c.calibrated_rate_m_per_h > 0.0, "{c:?}");
    assert!(
        (c.ground_m_per_drive_sol_at_calibrated_rate - c.record_m_per_drive_sol).abs() < 3.0,
        "{c:?}"
    );
}
