//! Every drive sol is planned by the `planner` crate, and no plan breaks a window, the battery
//! or the data volume — as judged by the planner's validator, which re-simulates each plan
//! independently of the search. Under the onboard strategies the localization chain follows
//! the drive on every drive sol (issue 4).

use std::path::Path;

use localization::hbs::HbsStep;
use sim::Strategy;
use sim::operations::sol_plan::{LOCALIZATION_CHAIN, SolPlanStatus};
use sim::run::outcome::{LocalizationStep, RejectionReason};
use std::collections::HashMap;

use sim::CampaignOutcome;
use study::Scenario;

fn scenario(file: &str) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(file);
    Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The runs of `strategies` under the scenario's seed, by strategy.
fn compare(s: &Scenario, strategies: &[Strategy]) -> HashMap<Strategy, CampaignOutcome> {
    strategies
        .iter()
        .copied()
        .zip(s.compare(strategies, s.seeds()))
        .collect()
}

#[test]
fn every_drive_sol_of_the_rapid_traverse_has_a_valid_plan_with_the_chain_under_onboard() {
    let s = scenario("rapid-traverse-379-409.toml");
    let runs = compare(&s, &s.strategies());
    for (strategy, outcome) in &runs {
        let mut drive_sols = 0;
        for sol in outcome.sols.iter().filter(|r| r.drove) {
            drive_sols += 1;
            let plan = sol
                .activity_plan
                .as_ref()
                .unwrap_or_else(|| panic!("{strategy:?} sol {}: no plan", sol.sol));
            assert!(
                plan.violations.is_empty(),
                "{strategy:?} sol {}: {:?}",
                sol.sol,
                plan.violations
            );
            assert!(
                matches!(
                    plan.status,
                    SolPlanStatus::Optimal | SolPlanStatus::Feasible
                ),
                "{strategy:?} sol {}: {}",
                sol.sol,
                plan.status
            );
            let names: Vec<&str> = plan.timeline.iter().map(|t| t.activity.as_str()).collect();
            let at = |n: &str| names.iter().position(|a| a.starts_with(n));
            let drive = at("drive").unwrap_or_else(|| panic!("sol {}: {names:?}", sol.sol));
            assert!(at("heating") < Some(drive), "{names:?}");
            assert!(at("post_drive_imaging") > Some(drive), "{names:?}");
            // The timeline is in start order and its main-timeline rows follow one another
            // (the co-processor chain's HBS-link rows overlap them); the executed drive ends
            // when AutoNav stopped.
            for w in plan.timeline.windows(2) {
                assert!(w[0].start_s <= w[1].start_s, "sol {}: {names:?}", sol.sol);
            }
            let main: Vec<_> = plan
                .timeline
                .iter()
                .filter(|t| t.timeline.uses_main())
                .collect();
            for w in main.windows(2) {
                assert!(w[0].end_s <= w[1].start_s, "sol {}: {names:?}", sol.sol);
            }
            let d = &plan.timeline[drive];
            assert!(
                ((d.end_s - d.start_s) as f64 - sol.drive_time_s).abs() <= 1.0,
                "sol {}: drive {:?}..{:?} vs {} s",
                sol.sol,
                d.start_s,
                d.end_s,
                sol.drive_time_s
            );
            assert!(plan.timeline.iter().all(|t| t.energy_wh_after >= 0.0));
            if strategy.onboard_localization() {
                // The localization in the sol log starts when the plan starts the transfer.
                let transfer = &plan.timeline[at("hbs_transfer").expect("transfer")];
                let event = sol.onboard_localization.as_ref().expect("onboard event");
                assert_eq!(
                    event.start_lmst.as_deref(),
                    Some(transfer.start_lmst.as_str()),
                    "sol {}",
                    sol.sol
                );
                let mut last = drive;
                for step in LOCALIZATION_CHAIN {
                    let i = at(step).unwrap_or_else(|| {
                        panic!("{strategy:?} sol {}: no {step} in {names:?}", sol.sol)
                    });
                    assert!(i > last, "{strategy:?} sol {}: {names:?}", sol.sol);
                    last = i;
                }
            } else {
                assert!(at("sunfind").is_none(), "{strategy:?}: {names:?}");
            }
        }
        assert!(drive_sols > 10, "{strategy:?}: {drive_sols} drive sols");
    }
    assert!(runs.contains_key(&Strategy::Onboard));
}

/// The paper 003 example run by the simulator: science executed between drive segments,
/// tau within its windows, a NO_PATH replanned, a new goal injected, every plan valid.
#[test]
fn the_self_reliant_campaign_executes_science_and_replans() {
    let s = scenario("self-reliant-campaign.toml");
    let runs = compare(&s, &[Strategy::Ground, Strategy::Onboard]);
    let lmst = |t: &str| sim::time::SolSeconds::parse_lmst(t).expect("lmst");
    let (first_due, period, tol) = (lmst("09:30"), 3 * 3600, 20 * 60);
    for (strategy, outcome) in &runs {
        for sol in outcome.sols.iter().filter(|r| r.drove) {
            let plan = sol.activity_plan.as_ref().expect("plan");
            assert!(
                plan.violations.is_empty(),
                "{strategy:?} {}: {:?}",
                sol.sol,
                plan.violations
            );
            let t = &plan.timeline;
            // Rows sharing a timeline never overlap (the HBS-link rows overlap main ones).
            for (i, a) in t.iter().enumerate() {
                for b in &t[i + 1..] {
                    assert!(
                        !a.timeline.shares(b.timeline)
                            || a.end_s <= b.start_s
                            || b.end_s <= a.start_s,
                        "{strategy:?} {}: {} overlaps {}",
                        sol.sol,
                        a.activity,
                        b.activity
                    );
                }
            }
            // Periodic instances start within ± 20 min of their due times.
            for step in t.iter().filter(|x| x.activity.starts_with("tau-")) {
                let k: i64 = step.activity["tau-".len()..]
                    .parse()
                    .expect("instance number");
                let due = first_due + k * period;
                assert!((step.start_s - due).abs() <= tol, "{step:?} due {due:?}");
            }
            // A survey runs between two drive segments on every sol that drives a full one.
            let is_drive = |i: usize| t.get(i).is_some_and(|x| x.activity.starts_with("drive#"));
            if sol.distance_m > 150.0 {
                assert!(
                    (0..t.len()).any(|i| t[i].activity.starts_with("survey-")
                        && (0..i).any(is_drive)
                        && (i + 1..t.len()).any(is_drive)),
                    "{strategy:?} {}: {:?}",
                    sol.sol,
                    t.iter().map(|x| &x.activity).collect::<Vec<_>>()
                );
            }
        }
    }
    // Under the calibrated error model the ground's predicted radius would close the passage on
    // sol 385: its planners shorten 384 and 385 does not drive (paper 000 §2), where without
    // that shortening 385's drive faulted NO_PATH at once.
    let ground = &runs[&Strategy::Ground];
    let skipped = ground.sol(385).expect("sol 385");
    assert!(
        !skipped.drove
            && skipped
                .skip_reason
                .is_some_and(|r| r.to_string().contains("would close the passage")),
        "{:?}",
        skipped.skip_reason
    );
    assert!(
        ground
            .sol(384)
            .is_some_and(|r| r.shortened_for_passage.is_some()),
        "sol 384 is shortened for the passage"
    );
    let onboard = &runs[&Strategy::Onboard];
    let injected = onboard
        .sol(384)
        .and_then(|r| r.activity_plan.as_ref())
        .expect("sol 384");
    assert!(
        injected
            .changes
            .iter()
            .any(|c| c.contains("aegis-384 added")),
        "{:?}",
        injected.changes
    );
    let aegis = injected
        .timeline
        .iter()
        .find(|x| x.activity == "aegis-384")
        .expect("observed");
    assert!(
        aegis.start_s >= lmst("15:30"),
        "after it was revealed: {aegis:?}"
    );
    assert!(
        aegis
            .outcome
            .as_deref()
            .is_some_and(|o| o.starts_with("observed"))
    );
    // The co-processor's actual durations are fed back: the chain's steps take what the log says.
    let event = injected_event(onboard, 384);
    let run_1 = injected
        .timeline
        .iter()
        .find(|x| x.activity == "hbs_run_1")
        .expect("run 1");
    let transfer = injected
        .timeline
        .iter()
        .find(|x| x.activity == "hbs_transfer")
        .expect("transfer");
    let log_run_1 = event
        .steps
        .iter()
        .find(|e| e.step == LocalizationStep::Onboard(HbsStep::Run1))
        .expect("RUN_1")
        .t_s;
    let log_transfer = event
        .steps
        .iter()
        .find(|e| e.step == LocalizationStep::Onboard(HbsStep::TransferToHbs))
        .expect("xfer")
        .t_s;
    assert_eq!(
        run_1.end_s - run_1.start_s,
        (log_run_1 - log_transfer).round() as i64
    );
    assert_eq!(
        transfer.end_s - transfer.start_s,
        log_transfer.round() as i64
    );
}

fn injected_event(o: &sim::CampaignOutcome, sol: u32) -> sim::run::outcome::LocalizationEvent {
    o.sol(sol)
        .and_then(|r| r.onboard_localization.clone())
        .expect("onboard localization")
}

/// A lost localization (here: rejected by its validity checks) is a big disruption: the rest of the sol is
/// replanned from the state after it, and the plan stays valid.
#[test]
fn a_lost_localization_replans_the_rest_of_the_sol() {
    let mut s = scenario("crater-floor-passage.toml");
    s.settings.localizer =
        sim::localizers::OnboardLocalizer::Statistical(sim::localizers::StatisticalLocalizer {
            failure_rate: 1.0,
            ..Default::default()
        });
    let run = s.run(Strategy::Onboard, s.seeds());
    let mut lost = 0;
    for sol in run.sols.iter().filter(|r| r.drove) {
        let plan = sol.activity_plan.as_ref().expect("plan");
        assert!(
            plan.violations.is_empty(),
            "{}: {:?}",
            sol.sol,
            plan.violations
        );
        let event = sol.onboard_localization.as_ref().expect("event");
        assert!(!event.applied);
        assert_eq!(
            event.reason,
            Some(RejectionReason::ModelledAmbiguousMatch),
            "{}",
            sol.sol
        );
        assert!(
            plan.changes.iter().any(|c| c
                .contains("localization lost: validity checks failed: ambiguous map match")
                && c.ends_with("replanned")),
            "{}: {:?}",
            sol.sol,
            plan.changes
        );
        lost += 1;
    }
    assert!(lost >= 2, "{lost} drive sols");
}

/// The sol log's typed outcomes are written as their `Display` text: the JSON string of each
/// enum value is exactly what tables and CSV print (the before/after outputs stay byte-identical).
#[test]
fn typed_outcomes_serialise_as_their_display_text() {
    use localization::hbs::LossReason;
    use localization::onboard::LostReason;
    use sim::FaultKind;
    use sim::run::outcome::{LocalizationKind, SkipReason};

    fn same<T: serde::Serialize + std::fmt::Display>(v: T, text: &str) {
        assert_eq!(v.to_string(), text);
        assert_eq!(
            serde_json::to_value(&v).expect("serialises"),
            serde_json::Value::String(text.into())
        );
    }
    for s in Strategy::ALL {
        same(s, s.name());
    }
    same(SolPlanStatus::Optimal, "optimal");
    same(SolPlanStatus::NoPlanFound, "no plan found");
    same(SolPlanStatus::NotPlanned, "not planned");
    same(LocalizationKind::Ground, "ground");
    same(LocalizationKind::Onboard, "onboard");
    same(
        LocalizationStep::GroundLocalizedHere,
        "MOB_GROUND_LOCALIZED_HERE",
    );
    same(
        LocalizationStep::Onboard(HbsStep::ApplyLocalization),
        "MOB_APPLY_ONBD_LOCALIZATION",
    );
    same(HbsStep::Run2, "RUN_2");
    same(FaultKind::NoPath, "NO_PATH");
    same(SkipReason::RouteComplete, "route complete");
    same(
        SkipReason::ExtensionLimit {
            sols_without_localization: 3,
        },
        "extension limit: 3 sols without a localization",
    );
    same(
        RejectionReason::ModelledAmbiguousMatch,
        "validity checks failed: ambiguous map match",
    );
    same(
        RejectionReason::Onboard(LostReason::Hbs(LossReason::Timeout { run: 2 })),
        "run 2 timed out (HBS stall)",
    );
    same(
        RejectionReason::Onboard(LostReason::Hbs(LossReason::Invalid {
            reason: "REJECTED: ambiguous match".into(),
        })),
        "validity checks failed: REJECTED: ambiguous match",
    );
}
