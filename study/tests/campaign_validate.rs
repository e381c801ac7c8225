//! `Campaign::validate` accepts what the loader builds and refuses a hand-built campaign the
//! runner could not trust.

use sim::CampaignError;
use study::Scenario;

fn scenario() -> Scenario {
    Scenario::load("../scenarios/sol717-719.toml".as_ref()).expect("bundled scenario loads")
}

#[test]
fn a_loaded_campaign_is_valid_and_broken_ones_are_named() {
    let s = scenario();
    assert_eq!(s.campaign.validate(), Ok(()));

    let mut c = s.campaign.clone();
    c.route.truncate(1);
    assert_eq!(
        c.validate(),
        Err(CampaignError::RouteTooShort { waypoints: 1 })
    );

    let mut c = s.campaign.clone();
    c.route[1] = [1e9, 0.0];
    assert!(matches!(
        c.validate(),
        Err(CampaignError::WaypointOffGrid { index: 1, .. })
    ));

    let mut c = s.campaign.clone();
    c.rover.step_m = f64::NAN;
    let e = c.validate().expect_err("NaN step");
    assert_eq!(
        e.to_string(),
        "rover.step_m: expected 0.25 ..= 10 metres, got NaN"
    );

    let mut c = s.campaign.clone();
    c.calendar.sols[1].sol += 5;
    assert!(matches!(
        c.validate(),
        Err(CampaignError::SolsNotConsecutive { index: 1, .. })
    ));

    let mut c = s.campaign.clone();
    c.calendar.drive_end = c.calendar.drive_start;
    assert!(matches!(
        c.validate(),
        Err(CampaignError::DriveWindow { .. })
    ));

    let mut c = s.campaign.clone();
    c.model.k_novo = -0.5;
    assert!(matches!(
        c.validate(),
        Err(CampaignError::Parameter {
            name: "model.k_novo",
            ..
        })
    ));
}
