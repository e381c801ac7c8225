//! Every drive sol is planned by the `planner` crate, and no plan breaks a window, the battery
//! or the data volume — as judged by the planner's validator, which re-simulates each plan
//! independently of the search. Under the onboard strategies the localization chain follows
//! the drive on every drive sol (issue 4).

use std::path::Path;

use sim::Strategy;
use sim::sol_plan::LOCALIZATION_CHAIN;
use solsim::regress;
use solsim::scenario::Scenario;

fn scenario(file: &str) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(file);
    Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_drive_sol_of_the_rapid_traverse_has_a_valid_plan_with_the_chain_under_onboard() {
    let s = scenario("rapid-traverse-379-409.toml");
    let (_, runs) = regress::run_strategies(&s, &s.strategies());
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
                matches!(plan.status, "optimal" | "feasible"),
                "{strategy:?} sol {}: {}",
                sol.sol,
                plan.status
            );
            let names: Vec<&str> = plan.timeline.iter().map(|t| t.activity.as_str()).collect();
            let at = |n: &str| names.iter().position(|a| a.starts_with(n));
            let drive = at("drive").unwrap_or_else(|| panic!("sol {}: {names:?}", sol.sol));
            assert!(at("heating") < Some(drive), "{names:?}");
            assert!(at("post_drive_imaging") > Some(drive), "{names:?}");
            // The timeline is in time order, the executed drive ends when AutoNav stopped.
            for w in plan.timeline.windows(2) {
                assert!(w[0].end_s <= w[1].start_s, "sol {}: {names:?}", sol.sol);
            }
            let d = &plan.timeline[drive];
            assert!(
                ((d.end_s - d.start_s) as f64 - sol.drive_time_s).abs() <= 1.0,
                "sol {}: drive {}..{} vs {} s",
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
