//! The rapid traverse's AutoNav rate is calibrated, not chosen: `solsim calibrate drive-rate
//! scenarios/rapid-traverse-379-409.toml` solves the rate at which the re-simulated ground
//! strategy, driving each sol's window from the record's clock, drives the record's 216.2 m per
//! drive sol over the sols both drove to their end (4972.7 m in 23 sols: the public record with
//! paper 000's odometry on 386, 402, 404 and 405, sol 385's faulted 14 m left out), and the
//! scenario carries that rate (`solsim record import` calibrates it with 20 runs).

use study::Scenario;
use study::calibrate::calibrate_drive_rate;

#[test]
fn the_rapid_traverse_rate_is_the_calibrated_one() {
    let s = Scenario::load(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scenarios/rapid-traverse-379-409.toml"
        )
        .as_ref(),
    )
    .expect("the bundled scenario loads");
    let c = calibrate_drive_rate(&s, 50).expect("the rapid traverse has a record");
    assert!(
        (c.record_m_per_drive_sol - 4972.713 / 23.0).abs() < 1e-3,
        "{c:?}"
    );
    let rel = (c.calibrated_rate_m_per_h - c.scenario_rate_m_per_h).abs() / c.scenario_rate_m_per_h;
    assert!(
        rel < 0.01,
        "scenario {:.1} m/h, calibrated {:.2} m/h: re-run `solsim calibrate drive-rate scenarios/rapid-traverse-379-409.toml`",
        c.scenario_rate_m_per_h,
        c.calibrated_rate_m_per_h
    );
    // At the scenario's rate the ground strategy drives the record's metres per drive sol.
    assert!(
        (c.ground_m_per_drive_sol_at_scenario_rate - c.record_m_per_drive_sol).abs() < 3.0,
        "{c:?}"
    );
}
