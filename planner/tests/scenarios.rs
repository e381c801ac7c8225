//! Hand-built scenarios: priority tiers, the anytime budget on a large instance, repair and
//! replanning after a late drive, campaign intents as in paper 003 Fig. 3, bad input and the
//! JSON format.

#![allow(clippy::unwrap_used)]

mod common;

use planner::{
    Activity, ActivityKind, Blocker, BoundKind, Campaign, CampaignIntent, Drive, GeneratorSettings,
    Instance, PlanError, PlanStatus, Problem, RepairOutcome, SearchSettings, State, generate,
    periodic_instances, plan, plan_from, repair, state_based_instances, validate_plan,
};

fn sol(activities: Vec<Activity>) -> Problem {
    Problem {
        start_s: 9 * 3600,
        end_s: 17 * 3600,
        battery_capacity_wh: 500.0,
        initial_energy_wh: 400.0,
        recharge_w: 20.0,
        data_capacity_mb: 1000.0,
        initial_data_mb: 0.0,
        activities,
        campaigns: Vec::new(),
    }
}

fn checked_plan(problem: &Problem, settings: &SearchSettings) -> planner::PlanOutcome {
    let out = plan(problem, settings).unwrap();
    let inst = Instance::new(problem).unwrap();
    let v = validate_plan(&inst, &State::initial(&inst), &out.plan);
    assert!(v.is_empty(), "{v:?}");
    out
}

#[test]
fn no_amount_of_tier_2_displaces_a_feasible_tier_1_goal() {
    // One 1-point tier-1 goal competes for the same hour with ten maximal tier-2 goals and
    // for the same energy with all of them.
    let mut acts = vec![Activity::task("apxs", 3600, [36_000, 36_000], 100.0, 1.0)];
    for i in 0..10 {
        let mut a = Activity::task(format!("bulk{i}"), 600, [35_000, 40_000], 100.0, 10_000.0);
        a.tier = 2;
        acts.push(a);
    }
    let mut p = sol(acts);
    p.recharge_w = 0.0;
    p.initial_energy_wh = 110.0;
    let out = checked_plan(&p, &SearchSettings::default());
    assert_eq!(out.status, PlanStatus::Optimal);
    assert_eq!(out.value.points(1), 1.0);
    // With the tier-1 goal in, 10 Wh are left: no 16.7 Wh bulk activity fits.
    assert_eq!(out.value.points(2), 0.0);
    // Demote it and the bulk activities win.
    p.activities[0].tier = 3;
    let out = checked_plan(&p, &SearchSettings::default());
    assert_eq!(out.value.points(3), 0.0);
    assert_eq!(out.value.points(2), 60_000.0);
}

#[test]
fn anytime_search_on_80_activities_is_feasible_and_honest() {
    let settings = GeneratorSettings {
        n_optional: 80,
        n_comm_passes: 2,
        n_precedences: 8,
        with_drive: true,
        with_campaign: true,
        ..GeneratorSettings::default()
    };
    let problem = generate(80, &settings);
    let small = SearchSettings {
        node_budget: Some(20),
        ..SearchSettings::default()
    };
    let out = checked_plan(&problem, &small);
    assert!(matches!(
        out.status,
        PlanStatus::Feasible | PlanStatus::Optimal
    ));
    assert!(!out.plan.steps.is_empty());
    assert!(out.best_bound >= out.value);
    assert!(out.gap_points().iter().all(|&g| g >= 0.0));
    assert!(out.stats.nodes_expanded <= 20);
    // Deterministic under a node budget.
    assert_eq!(plan(&problem, &small).unwrap().plan, out.plan);
    // A longer search never beats the short search's bound.
    let more = SearchSettings {
        node_budget: Some(80),
        ..SearchSettings::default()
    };
    let longer = checked_plan(&problem, &more);
    assert!(longer.value >= out.value);
    assert!(longer.value <= out.best_bound);
}

/// Heating, a three-segment drive with a state-based survey after 75 m, a science target and
/// a relay pass.
fn drive_day() -> Problem {
    let heat = Activity::task("heat", 900, [32_400, 40_000], 30.0, 0.0);
    let mut drive = Activity::task("drive", 0, [33_300, 40_000], 40.0, 30.0);
    drive.kind = ActivityKind::Drive(Drive {
        length_m: 150.0,
        rate_m_per_h: 100.0,
        min_segment_s: 600,
        max_segments: 4,
        split_at_m: vec![75.0],
        latest_end_s: None,
    });
    drive.preconditions = vec!["heat".into()];
    drive.data_mb = 50.0;
    let mut survey = Activity::task("survey", 600, [32_400, 57_000], 15.0, 0.0);
    survey.data_mb = 100.0;
    let surveys = state_based_instances(&survey, "survey", 75.0, 5.0, 150.0);
    let mut mastcam = Activity::task("mastcam", 1200, [50_000, 54_000], 20.0, 8.0);
    mastcam.preconditions = vec!["drive".into()];
    mastcam.data_mb = 200.0;
    let mut relay = Activity::task("relay", 600, [48_000, 48_000], 10.0, 0.0);
    relay.mandatory = true;
    relay.downlink_mb = 500.0;
    let mut acts = vec![heat, drive, mastcam, relay];
    acts.extend(surveys);
    let mut p = sol(acts);
    p.campaigns.push(Campaign {
        id: "survey".into(),
        intent: CampaignIntent::StateBased {
            every_m: 75.0,
            tolerance_m: 5.0,
        },
        tier: 1,
        min_count: 0,
        max_count: 2,
        utility: 5.0,
        decay: 1.0,
    });
    p
}

#[test]
fn state_based_survey_interleaves_with_the_split_drive() {
    let p = drive_day();
    let inst = Instance::new(&p).unwrap();
    let out = checked_plan(&p, &SearchSettings::default());
    assert_eq!(out.status, PlanStatus::Optimal);
    let names: Vec<&str> = out
        .plan
        .steps
        .iter()
        .map(|s| inst.task(s.task).name.as_str())
        .collect();
    let pos = |n: &str| names.iter().position(|x| *x == n).unwrap();
    assert!(pos("drive#1/2") < pos("survey-1") && pos("survey-1") < pos("drive#2/2"));
    assert!(pos("drive#2/2") < pos("survey-2"));
    assert!(pos("heat") < pos("drive#1/2"));
    assert_eq!(out.value.points(1), 5.0 + 5.0 + 30.0 + 8.0);
}

#[test]
fn periodic_instances_fall_in_their_windows() {
    let tau = Activity::task("tau", 300, [0, 0], 5.0, 0.0);
    let mut acts = periodic_instances(&tau, "tau", 9 * 3600 + 1200, 3 * 3600, 1200, 16 * 3600);
    assert_eq!(acts.len(), 3);
    acts.push(Activity::task(
        "long",
        6 * 3600,
        [9 * 3600, 9 * 3600 + 600],
        1.0,
        1.0,
    ));
    let mut p = sol(acts);
    p.campaigns.push(Campaign {
        id: "tau".into(),
        intent: CampaignIntent::Periodic {
            period_s: 3 * 3600,
            tolerance_s: 1200,
        },
        tier: 1,
        min_count: 0,
        max_count: 3,
        utility: 2.0,
        decay: 1.0,
    });
    let out = checked_plan(&p, &SearchSettings::default());
    // The long activity would block two of three tau instances: 6 points beat 1 + 2.
    assert_eq!(out.value.points(1), 6.0);
}

#[test]
fn a_late_drive_is_repaired_and_a_very_late_one_replanned() {
    let p = drive_day();
    let inst = Instance::new(&p).unwrap();
    let start = State::initial(&inst);
    let out = checked_plan(&p, &SearchSettings::default());
    let first_drive = out
        .plan
        .steps
        .iter()
        .position(|s| inst.task(s.task).name == "drive#1/2")
        .unwrap();
    let late = out.plan.steps[first_drive];
    // Ten minutes late: everything after shifts.
    match repair(&inst, &start, &out.plan, first_drive, late.end_s + 600).unwrap() {
        RepairOutcome::Repaired {
            state,
            plan,
            shifted,
        } => {
            assert_eq!(state.time_s, late.end_s + 600);
            assert!(shifted >= 1);
            assert_eq!(plan.steps.len(), out.plan.steps.len() - first_drive - 1);
            let v = validate_plan(&inst, &state, &plan);
            assert!(v.is_empty(), "{v:?}");
        }
        other => panic!("expected a repair, got {other:?}"),
    }
    // Four hours late: the relay pass at 13:20 is gone for this plan's order.
    let very_late = (late.end_s + 4 * 3600).min(p.end_s - 1);
    match repair(&inst, &start, &out.plan, first_drive, very_late).unwrap() {
        RepairOutcome::ReplanNeeded { state, reason, .. } => {
            // The relay's fixed time has passed.
            assert!(
                matches!(reason, Blocker::WindowMissed | Blocker::MandatoryLost(_)),
                "{reason:?}"
            );
            let again = plan_from(&inst, &state, &SearchSettings::default()).unwrap();
            // The relay pass cannot be made any more: honestly infeasible.
            assert_eq!(again.status, PlanStatus::Infeasible);
        }
        other => panic!("expected a replan, got {other:?}"),
    }
    // Forty minutes late: repair fails (the relay comes before the survey would) but a
    // replan from the new state finds a valid plan.
    let state = match repair(&inst, &start, &out.plan, first_drive, late.end_s + 2400).unwrap() {
        RepairOutcome::Repaired { state, .. } | RepairOutcome::ReplanNeeded { state, .. } => state,
    };
    let again = plan_from(&inst, &state, &SearchSettings::default()).unwrap();
    assert_eq!(again.status, PlanStatus::Optimal);
    let v = validate_plan(&inst, &state, &again.plan);
    assert!(v.is_empty(), "{v:?}");
}

#[test]
fn bad_input_names_the_activity_and_field() {
    let ok = || sol(vec![Activity::task("a", 600, [36_000, 40_000], 10.0, 1.0)]);

    let mut p = ok();
    p.activities[0].preconditions = vec!["ghost".into()];
    assert_eq!(
        Instance::new(&p).unwrap_err(),
        PlanError::UnknownPrecondition {
            activity: "a".into(),
            precondition: "ghost".into()
        }
    );

    let mut p = ok();
    p.activities[0].kind = ActivityKind::Task { duration_s: -5 };
    let e = Instance::new(&p).unwrap_err();
    assert!(
        matches!(&e, PlanError::InvalidActivity { activity, field: "duration_s", .. } if activity == "a"),
        "{e:?}"
    );
    assert!(e.to_string().contains("`a`") && e.to_string().contains("duration_s"));

    let mut p = ok();
    p.activities[0].latest_start_s = 35_000;
    assert_eq!(
        Instance::new(&p).unwrap_err(),
        PlanError::ImpossibleWindow {
            activity: "a".into(),
            earliest_start_s: 36_000,
            latest_start_s: 35_000
        }
    );

    let mut p = ok();
    p.activities[0].earliest_start_s = 1000;
    assert!(matches!(
        Instance::new(&p).unwrap_err(),
        PlanError::OutsideSol {
            field: "earliest_start_s",
            ..
        }
    ));

    let mut p = ok();
    p.activities[0].latest_start_s = p.end_s - 10;
    assert!(matches!(
        Instance::new(&p).unwrap_err(),
        PlanError::OutsideSol {
            field: "latest_start_s",
            ..
        }
    ));

    let mut p = ok();
    p.activities[0].power_w = f64::NAN;
    assert!(matches!(
        Instance::new(&p).unwrap_err(),
        PlanError::InvalidActivity {
            field: "power_w",
            ..
        }
    ));

    let mut p = ok();
    p.activities
        .push(Activity::task("b", 600, [36_000, 40_000], 10.0, 1.0));
    p.activities[0].preconditions = vec!["b".into()];
    p.activities[1].preconditions = vec!["a".into()];
    assert!(matches!(
        Instance::new(&p).unwrap_err(),
        PlanError::PreconditionCycle { .. }
    ));

    let mut p = ok();
    p.activities[0].campaign = Some("nope".into());
    assert!(matches!(
        Instance::new(&p).unwrap_err(),
        PlanError::UnknownCampaign { .. }
    ));

    let mut p = ok();
    p.battery_capacity_wh = -1.0;
    assert!(matches!(
        plan(&p, &SearchSettings::default()).unwrap_err(),
        PlanError::InvalidProblem {
            field: "battery_capacity_wh",
            ..
        }
    ));
}

#[test]
fn infeasible_mandatory_activities_are_an_outcome_not_an_error() {
    let mut a = Activity::task("relay1", 3600, [36_000, 36_000], 10.0, 0.0);
    a.mandatory = true;
    let mut b = Activity::task("relay2", 600, [36_600, 36_600], 10.0, 0.0);
    b.mandatory = true;
    let out = plan(&sol(vec![a, b]), &SearchSettings::default()).unwrap();
    assert_eq!(out.status, PlanStatus::Infeasible);
    assert!(out.plan.steps.is_empty());
}

#[test]
fn problems_round_trip_through_json_and_typos_are_rejected() {
    let settings = GeneratorSettings {
        with_drive: true,
        with_campaign: true,
        ..GeneratorSettings::default()
    };
    let p = generate(7, &settings);
    let json = serde_json::to_string_pretty(&p).unwrap();
    let back: Problem = serde_json::from_str(&json).unwrap();
    assert_eq!(back, p);
    let typo = json.replacen("\"recharge_w\"", "\"recharge_watts\"", 1);
    assert!(serde_json::from_str::<Problem>(&typo).is_err());
    // Generation is a pure function of the seed.
    assert_eq!(generate(7, &settings), p);
}

#[test]
fn every_bound_kind_finds_the_same_optimum() {
    let p = generate(
        11,
        &GeneratorSettings {
            n_optional: 9,
            with_campaign: true,
            ..GeneratorSettings::default()
        },
    );
    let values: Vec<_> = [BoundKind::Knapsack, BoundKind::Lp, BoundKind::Both]
        .into_iter()
        .map(|bound| {
            let out = checked_plan(
                &p,
                &SearchSettings {
                    node_budget: None,
                    bound,
                    ..SearchSettings::default()
                },
            );
            assert_eq!(out.status, PlanStatus::Optimal);
            out.value
        })
        .collect();
    assert!(values.windows(2).all(|w| w[0] == w[1]), "{values:?}");
}

#[test]
fn settings_defaults_match_their_docs() {
    let s = SearchSettings::default();
    assert_eq!(s.node_budget, Some(100_000));
    assert_eq!(s.time_budget, None);
    assert_eq!(s.bound, BoundKind::Knapsack);
    assert_eq!(s.resort_every, 64);
    assert_eq!(s.dive_nodes, 64);
    assert!(s.dominance);
    let g = GeneratorSettings::default();
    assert_eq!((g.n_optional, g.n_comm_passes, g.n_precedences), (20, 2, 3));
    assert_eq!((g.energy_fraction, g.data_fraction), (0.4, 0.5));
    assert!(!g.with_drive && !g.with_campaign);
}

/// Paper 003 Fig. 3: a long drive split to make room for a periodic opacity (tau)
/// measurement and for state-based surveys every 75 m.
#[test]
fn fig3_long_drive_pauses_for_tau_and_surveys() {
    let heat = Activity::task("heat", 900, [32_400, 40_000], 30.0, 0.0);
    let mut drive = Activity::task("drive", 0, [39_600, 45_000], 40.0, 30.0);
    drive.kind = ActivityKind::Drive(Drive {
        length_m: 300.0,
        rate_m_per_h: 100.0,
        min_segment_s: 600,
        max_segments: 4,
        split_at_m: vec![75.0, 150.0, 225.0],
        latest_end_s: None,
    });
    drive.preconditions = vec!["heat".into()];
    let survey = Activity::task("survey", 600, [32_400, 60_000], 15.0, 0.0);
    let tau = Activity::task("tau", 300, [0, 0], 5.0, 0.0);
    let mut acts = vec![heat, drive];
    acts.extend(state_based_instances(&survey, "survey", 75.0, 5.0, 300.0));
    acts.extend(periodic_instances(
        &tau,
        "tau",
        36_000,
        3 * 3600,
        1200,
        60_000,
    ));
    let mut p = sol(acts);
    for (id, intent, n) in [
        (
            "survey",
            CampaignIntent::StateBased {
                every_m: 75.0,
                tolerance_m: 5.0,
            },
            4,
        ),
        (
            "tau",
            CampaignIntent::Periodic {
                period_s: 3 * 3600,
                tolerance_s: 1200,
            },
            3,
        ),
    ] {
        p.campaigns.push(Campaign {
            id: id.into(),
            intent,
            tier: 1,
            min_count: 0,
            max_count: n,
            utility: 4.0,
            decay: 1.0,
        });
    }
    let inst = Instance::new(&p).unwrap();
    let out = checked_plan(&p, &SearchSettings::default());
    assert_eq!(out.status, PlanStatus::Optimal);
    // Everything fits: 30 for the drive, 4 surveys and 3 tau at 4 points each.
    assert_eq!(out.value.points(1), 30.0 + 7.0 * 4.0);
    let names: Vec<&str> = out
        .plan
        .steps
        .iter()
        .map(|s| inst.task(s.task).name.as_str())
        .collect();
    let first = names.iter().position(|n| n.starts_with("drive#")).unwrap();
    let last = names.iter().rposition(|n| n.starts_with("drive#")).unwrap();
    assert!(
        names[first..last].iter().any(|n| n.starts_with("tau")),
        "the drive is never paused for tau: {names:?}"
    );
}
