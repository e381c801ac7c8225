//! Issue 1: a replanning state whose energy was a rounding error below zero
//! (`-3.6e-15` Wh, produced by simulating a plan that drains the battery exactly) was
//! rejected as `PlanError::InvalidState { field: "energy_wh" }`. States within
//! `ENERGY_EPS_WH` of the range are now accepted and clamped.

#![allow(clippy::unwrap_used)]

use planner::{Activity, Instance, Problem, SearchSettings, State, plan_from};

#[test]
fn a_state_a_rounding_error_below_empty_is_accepted() {
    let problem = Problem {
        start_s: 0,
        end_s: 7200,
        battery_capacity_wh: 10.0,
        initial_energy_wh: 10.0,
        recharge_w: 0.0,
        data_capacity_mb: 10.0,
        initial_data_mb: 0.0,
        activities: vec![Activity::task("a", 600, [0, 6000], 5.0, 1.0)],
        campaigns: Vec::new(),
    };
    let inst = Instance::new(&problem).unwrap();
    let state = State {
        energy_wh: -3.552_713_678_800_501e-15,
        ..State::initial(&inst)
    };
    let out = plan_from(&inst, &state, &SearchSettings::default()).unwrap();
    assert!(out.plan.steps.is_empty());
    let too_low = State {
        energy_wh: -1e-3,
        ..State::initial(&inst)
    };
    assert!(plan_from(&inst, &too_low, &SearchSettings::default()).is_err());
}
