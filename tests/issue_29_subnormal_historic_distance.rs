//! Issue 29 (found while moving the scenario checks into the simulator's settings):
//! a historic drive of 5e-324 m over its window gave a rate of 0 m/h (the division
//! underflows). The scenario passed the file's checks, and the simulator then refused what the
//! loader built ("sols[].drive_rate_m_per_h: expected a positive, finite rate"), an error the
//! loader is never to let through. A record distance too small for a rate now drives at the
//! rover's rate, as a sol the record did not drive does, and the scenario loads and runs.

use crate::common::{run_ok, scenario_copy};

/// Sol 386 of `scenarios/sol383-386.toml`: 245.37 m from 11:53 to 14:26 LMST.
fn sol386_of(distance: &str) -> (std::path::PathBuf, tempfile::TempDir) {
    scenario_copy("sol383-386.toml", |t| {
        t.replace(
            "historic_distance_m = 245.37",
            &format!("historic_distance_m = {distance}"),
        )
    })
}

#[test]
fn a_record_distance_too_small_for_a_rate_drives_at_the_rovers_rate() {
    let (path, _dir) = sol386_of("5e-324");
    let scenario = study::Scenario::load(&path).expect("loads");
    let sol386 = scenario.settings.calendar.sols.last().expect("sol 386");
    assert_eq!(sol386.sol, 386);
    assert_eq!(sol386.drive_rate_m_per_h, None);
    // As a sol without a record distance: the rover's own rate.
    let (zero, _zero_dir) = sol386_of("0.0");
    let zero = study::Scenario::load(&zero).expect("loads");
    assert_eq!(
        zero.settings
            .calendar
            .sols
            .last()
            .expect("sol 386")
            .drive_rate_m_per_h,
        None
    );
    // And the record's distance keeps the record's rate.
    let bundled = study::Scenario::load(&crate::common::root().join("scenarios/sol383-386.toml"))
        .expect("loads");
    let rate = bundled
        .settings
        .calendar
        .sols
        .last()
        .expect("sol 386")
        .drive_rate_m_per_h;
    assert!(rate.is_some_and(|r| r > 90.0 && r < 100.0), "{rate:?}");
    // The command line loads and runs it.
    let text = run_ok(
        &[
            "run",
            path.to_str().expect("utf-8"),
            "--strategy",
            "ground",
            "--no-files",
        ],
        &[],
    );
    assert!(text.contains("totals:"), "{text}");
}
