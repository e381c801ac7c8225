//! Issue 16: the bounds rule out what no completion can run — a task whose precondition
//! cannot end before its latest start, the state-based instances a drive that cannot run
//! was to reach, their successors — and start the release rows at each candidate's
//! precedence-tightened earliest start. Against the exhaustive reference planner, on small
//! drive-and-survey sols built to hit those cases: the search's value is the optimum with
//! every bound kind, every bound at every random replanning state is admissible, and when
//! the drive cannot run the root bound of tier 1 is exactly the optimum (0).

#![allow(clippy::unwrap_used)]

mod common;

use common::{exhaustive, random_states};
use planner::{
    Activity, ActivityKind, BoundKind, Campaign, CampaignIntent, Drive, Instance, PlanStatus,
    Problem, SearchSettings, State, optimistic_bound, plan_from, state_based_instances,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const KINDS: [BoundKind; 3] = [BoundKind::Both, BoundKind::Knapsack, BoundKind::Lp];

/// Heating, a 108 m drive that needs it (split at 54 m), two survey instances at 54 and
/// 108 m (a tier-1 state-based campaign), a tier-1 task that needs the first survey, and a
/// tier-2 filler. Windows are drawn so that in many sols heating cannot end before the
/// drive's latest start. Returns the problem and whether the drive can run at all
/// (heating's earliest end ≤ the drive's latest start).
fn drive_and_surveys(seed: u64) -> (Problem, bool) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x16);
    let t0 = 8 * 3600;
    let heat_s = 60 * rng.random_range(10..=30i64);
    let heat_open = t0 + 60 * rng.random_range(0..=90i64);
    let heat = Activity::task("heat", heat_s, [heat_open, heat_open + 3600], 96.0, 0.0);
    let drive_open = t0 + 60 * rng.random_range(0..=60i64);
    let drive_close = drive_open + 60 * rng.random_range(0..=90i64);
    let mut drive = Activity::task("drive", 0, [drive_open, drive_close], 176.0, 0.0);
    drive.kind = ActivityKind::Drive(Drive {
        length_m: 108.0,
        rate_m_per_h: 90.0,
        min_segment_s: 600,
        max_segments: 2,
        split_at_m: vec![54.0],
        latest_end_s: None,
    });
    drive.preconditions = vec!["heat".into()];
    drive.mandatory = rng.random_bool(0.2);
    let survey = Activity::task("survey", 480, [t0, t0 + 4 * 3600], 33.0, 0.0);
    let surveys = state_based_instances(&survey, "survey", 54.0, 5.0, 108.0);
    let mut after = Activity::task(
        "after",
        600,
        [t0, t0 + 4 * 3600],
        20.0,
        f64::from(rng.random_range(1..=5u32)),
    );
    after.preconditions = vec!["survey-1".into()];
    let filler = Activity::task(
        "filler",
        60 * rng.random_range(10..=60i64),
        [t0, t0 + 3 * 3600],
        f64::from(rng.random_range(20..=110u32)),
        f64::from(rng.random_range(1..=9u32)),
    );
    let mut filler = filler;
    filler.tier = 2;
    let mut activities = vec![heat, drive, after, filler];
    activities.extend(surveys);
    let can_drive = heat_open + heat_s <= drive_close;
    let problem = Problem {
        start_s: t0,
        end_s: t0 + 5 * 3600,
        battery_capacity_wh: 700.0,
        initial_energy_wh: f64::from(rng.random_range(150..=480u32)),
        recharge_w: 30.0,
        data_capacity_mb: 500.0,
        initial_data_mb: 0.0,
        activities,
        campaigns: vec![Campaign {
            id: "survey".into(),
            intent: CampaignIntent::StateBased {
                every_m: 54.0,
                tolerance_m: 5.0,
            },
            tier: 1,
            min_count: 0,
            max_count: 2,
            utility: 7.0,
            decay: 1.0,
        }],
    };
    (problem, can_drive)
}

#[test]
fn propagated_bounds_stay_admissible_and_close_unreachable_drives() {
    let (mut optimal, mut blocked, mut states) = (0, 0, 0);
    for seed in 0..240u64 {
        let (problem, can_drive) = drive_and_surveys(seed);
        let inst = Instance::new(&problem).unwrap();
        assert!(
            inst.tasks().len() <= 8,
            "seed {seed}: too many tasks to enumerate"
        );
        let start = State::initial(&inst);
        let reference = exhaustive(&inst, &start);
        for kind in KINDS {
            let settings = SearchSettings {
                node_budget: None,
                bound: kind,
                ..SearchSettings::default()
            };
            let out = plan_from(&inst, &start, &settings).unwrap();
            match &reference {
                None => assert_eq!(out.status, PlanStatus::Infeasible, "seed {seed} {kind:?}"),
                Some((best, _)) => {
                    assert_eq!(out.status, PlanStatus::Optimal, "seed {seed} {kind:?}");
                    assert_eq!(out.value, *best, "seed {seed} {kind:?}");
                }
            }
            if let (false, Some((best, _))) = (can_drive, &reference) {
                // Nothing drives: no survey, nothing after one; tier 1 is 0 and the root
                // bound says so (the fillers are tier 2).
                assert_eq!(best.tiers_micro[0], 0, "seed {seed}");
                let root = optimistic_bound(&inst, &start, kind).unwrap().unwrap();
                assert_eq!(root.tiers_micro[0], 0, "seed {seed} {kind:?}: root {root}");
            }
        }
        if reference.is_some() {
            optimal += 1;
            blocked += usize::from(!can_drive);
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for state in random_states(&inst, &mut rng, 3) {
            let Some((best, _)) = exhaustive(&inst, &state) else {
                continue;
            };
            states += 1;
            for kind in KINDS {
                let b = optimistic_bound(&inst, &state, kind)
                    .unwrap()
                    .unwrap_or_else(|| panic!("seed {seed} {kind:?}: feasible node killed"));
                for tier in 0..planner::MAX_TIERS {
                    assert!(
                        b.tiers_micro[tier] >= best.tiers_micro[tier],
                        "seed {seed} {kind:?} tier {}: bound {b} < optimum {best}",
                        tier + 1
                    );
                }
            }
        }
    }
    // The family must exercise both sides.
    assert!(optimal >= 150, "only {optimal} feasible sols");
    assert!(
        blocked >= 40,
        "only {blocked} feasible sols whose drive cannot run"
    );
    assert!(
        optimal - blocked >= 40,
        "only {} that can drive",
        optimal - blocked
    );
    assert!(states >= 400, "only {states} replanning states");
}
