//! Issue 16: a bound that an optimum reaches exactly must prove it. The bounds turned an
//! `f64` bound into whole micro-points by a ceiling, so an exact bound of 7 400 000 became
//! 7 400 001: one micro-point above the optimum. With integer-point utilities the tier grain
//! (10⁶) hid it; a drive's utility split over its segments (199 774 + 265 447 + …) makes the
//! grain 1, and the search then had to exhaust the tree to prove what it found in 10 nodes.
//! On the self-reliant campaign's onboard sol 385 (the simulator's own problem, dumped by
//! `study/examples/dump_sol_problems.rs`) that was 8 210 nodes and ≈ 80 ms, slower than CP-SAT
//! with one worker; now 10 nodes.

#![allow(clippy::unwrap_used)]

use planner::{
    Activity, ActivityKind, BoundKind, Campaign, CampaignIntent, Drive, Instance, PlanStatus,
    Problem, SearchSettings, State, optimistic_bound, plan,
};

fn proof(problem: &Problem, bound: BoundKind) -> planner::PlanOutcome {
    plan(
        problem,
        &SearchSettings {
            node_budget: Some(100_000),
            bound,
            ..SearchSettings::default()
        },
    )
    .unwrap()
}

#[test]
fn the_simulators_sol_385_is_proven_where_it_is_found() {
    let text = include_str!(
        "../../peers/planner_fixtures/sol_problems/self-reliant-campaign_onboard_sol385.json"
    );
    let problem: Problem = serde_json::from_str(text).unwrap();
    let inst = Instance::new(&problem).unwrap();
    for kind in [BoundKind::Knapsack, BoundKind::Lp, BoundKind::Both] {
        let out = proof(&problem, kind);
        assert_eq!(out.status, PlanStatus::Optimal, "{kind:?}");
        // 7.4 points in tier 1 (the drive's 1 and the outcrop's 6.4), 25 in tier 2; CP-SAT
        // proves the same optimum (peers/planner_cpsat.py).
        assert_eq!(
            out.value.tiers_micro[..2],
            [7_400_000, 25_000_000],
            "{kind:?}"
        );
        let root = optimistic_bound(&inst, &State::initial(&inst), kind)
            .unwrap()
            .unwrap();
        assert_eq!(root, out.value, "{kind:?}: the root bound is the optimum");
        assert!(
            out.stats.nodes_expanded <= 50,
            "{kind:?}: {} nodes to prove an optimum equal to the root bound",
            out.stats.nodes_expanded
        );
    }
}

#[test]
fn a_drive_split_into_uneven_utility_shares_is_proven_at_its_bound() {
    // One optional drive worth 1 point split at uneven distances (segment utilities of
    // 333 333 / 333 334 / … micro-points: tier grain 1) and a goal-set member worth 2.5: all
    // of it fits, so the optimum is the root bound and the search proves it at once.
    let mut drive = Activity::task("drive", 0, [9 * 3600, 10 * 3600], 50.0, 1.0);
    drive.kind = ActivityKind::Drive(Drive {
        length_m: 100.0,
        rate_m_per_h: 100.0,
        min_segment_s: 300,
        max_segments: 3,
        split_at_m: vec![100.0 / 3.0, 200.0 / 3.0],
        latest_end_s: None,
    });
    let mut sample = Activity::task("sample", 600, [9 * 3600, 16 * 3600], 20.0, 0.0);
    sample.campaign = Some("goal".into());
    let filler = Activity::task("filler", 900, [9 * 3600, 16 * 3600], 10.0, 0.7);
    let problem = Problem {
        start_s: 9 * 3600,
        end_s: 17 * 3600,
        battery_capacity_wh: 1000.0,
        initial_energy_wh: 800.0,
        recharge_w: 20.0,
        data_capacity_mb: 1000.0,
        initial_data_mb: 0.0,
        activities: vec![drive, sample, filler],
        campaigns: vec![Campaign {
            id: "goal".into(),
            intent: CampaignIntent::GoalSet,
            tier: 1,
            min_count: 0,
            max_count: 1,
            utility: 2.5,
            decay: 1.0,
        }],
    };
    let inst = Instance::new(&problem).unwrap();
    let shares: Vec<i64> = inst.tasks().iter().map(|t| t.utility_micro).collect();
    assert!(
        shares.iter().any(|u| u % 1_000 != 0),
        "the drive's shares must not be whole milli-points: {shares:?}"
    );
    for kind in [BoundKind::Knapsack, BoundKind::Lp, BoundKind::Both] {
        let out = proof(&problem, kind);
        assert_eq!(out.status, PlanStatus::Optimal, "{kind:?}");
        assert_eq!(out.value.tiers_micro[0], 4_200_000, "{kind:?}");
        assert!(
            out.stats.nodes_expanded <= 5,
            "{kind:?}: {} nodes",
            out.stats.nodes_expanded
        );
    }
}
