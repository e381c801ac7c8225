//! `Settings::validate` accepts what the loader builds and refuses hand-built settings the
//! runner could not trust.

use sim::{FieldError, SettingsError};
use study::Scenario;

fn scenario() -> Scenario {
    Scenario::load("../scenarios/sol717-719.toml".as_ref()).expect("bundled scenario loads")
}

#[test]
fn a_loaded_campaign_is_valid_and_broken_ones_are_named() {
    let s = scenario();
    assert_eq!(s.settings.validate(), Ok(()));

    let mut c = s.settings.clone();
    c.route.truncate(1);
    assert_eq!(
        c.validate(),
        Err(SettingsError::RouteTooShort { waypoints: 1 })
    );

    let mut c = s.settings.clone();
    c.route[1] = [1e9, 0.0];
    assert!(matches!(
        c.validate(),
        Err(SettingsError::WaypointOffGrid { index: 1, .. })
    ));

    let mut c = s.settings.clone();
    c.rover.step_m = f64::NAN;
    let e = c.validate().expect_err("NaN step");
    assert_eq!(
        e.to_string(),
        "rover.step_m: expected 0.25 ..= 10 metres, got NaN"
    );

    let mut c = s.settings.clone();
    c.calendar.sols[1].sol += 5;
    assert!(matches!(
        c.validate(),
        Err(SettingsError::Field(FieldError { field, .. })) if field == "calendar.sols[1].sol"
    ));

    let mut c = s.settings.clone();
    c.calendar.drive_end = c.calendar.drive_start;
    assert!(matches!(
        c.validate(),
        Err(SettingsError::Field(FieldError { field, .. })) if field == "calendar.drive_end"
    ));

    let mut c = s.settings.clone();
    c.model.k_novo = -0.5;
    assert!(matches!(
        c.validate(),
        Err(SettingsError::Field(FieldError { field, .. })) if field == "model.k_novo"
    ));
}

/// Each settings struct holds a code-built value to the range a scenario file is held to,
/// under the struct's own field names.
#[test]
fn code_built_settings_meet_the_files_ranges() {
    let s = scenario();
    let message = |edit: &dyn Fn(&mut sim::Settings)| {
        let mut c = s.settings.clone();
        edit(&mut c);
        c.validate().expect_err("out of range").to_string()
    };
    assert_eq!(
        message(&|c| c.model.k_vo = 2.0),
        "model.k_vo: expected 0 ..= 1 metres per metre, got 2"
    );
    assert_eq!(
        message(&|c| c.rover.errors.vo_failure.sand = 1.5),
        "rover.errors.vo_failure.sand: expected a fraction between 0 and 1, got 1.5"
    );
    assert_eq!(
        message(&|c| c.rules.ground_lookahead_plans = 13),
        "rules.ground_lookahead_plans: expected 1 ..= 12 plans, got 13"
    );
    assert_eq!(
        message(&|c| c.sol_plan.imaging_s = 100_000),
        "sol_plan.imaging_s: expected at most a sol (88775 s), got 100000"
    );
    assert_eq!(
        message(&|c| c.operator_margin_m = -1.0),
        "operator_margin_m: expected 0 ..= 1000 metres, got -1"
    );
    assert_eq!(
        message(
            &|c| c.calendar.sols[2].historic = Some(sim::operations::calendar::HistoricSol {
                distance_m: 10.0,
                novo_m: 12.0,
                ended_in_fault: false,
            })
        ),
        "calendar.sols[2].historic.novo_m: expected at most distance_m (10 m), got 12"
    );
}
