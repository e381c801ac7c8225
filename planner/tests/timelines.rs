//! The second timeline (issue 12, item 3): activities on the HBS link run while the main
//! timeline runs others, two link activities never overlap, preconditions wait for their
//! predecessors' *ends*, overlapping powers add — and the validator catches every breach.
//!
//! The seeded properties compare the search with a reference written independently of it:
//! every order of every subset of the tasks, each task at its earliest start on its timelines
//! (no waiting for the battery), judged by the validator.

#![allow(clippy::unwrap_used)]

use planner::{
    Activity, BoundKind, Instance, Plan, PlanError, PlanStatus, PlanStep, Problem, Running,
    SearchSettings, State, TaskId, Timeline, Value, Violation, optimistic_bound, plan, plan_from,
    repair, step_resources, validate_plan,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn problem(activities: Vec<Activity>) -> Problem {
    Problem {
        start_s: 0,
        end_s: 20_000,
        battery_capacity_wh: 1_000.0,
        initial_energy_wh: 800.0,
        recharge_w: 40.0,
        data_capacity_mb: 1_000.0,
        initial_data_mb: 0.0,
        activities,
        campaigns: Vec::new(),
    }
}

fn on(timeline: Timeline, mut a: Activity) -> Activity {
    a.timeline = timeline;
    a
}

fn after(pre: &str, mut a: Activity) -> Activity {
    a.preconditions.push(pre.to_string());
    a
}

fn step<'a>(inst: &Instance, plan: &'a Plan, id: &str) -> &'a PlanStep {
    plan.steps
        .iter()
        .find(|s| inst.task(s.task).name == id)
        .unwrap_or_else(|| panic!("{id} not in {:?}", plan.describe(inst)))
}

fn overlap(a: &PlanStep, b: &PlanStep) -> bool {
    a.start_s < b.end_s && b.start_s < a.end_s
}

/// Two link transfers and three main-timeline activities: the transfers never overlap each
/// other, the main timeline runs during them, and the plan is shorter than in series.
#[test]
fn link_activities_never_overlap_and_the_main_timeline_runs_during_them() {
    let link = |id| {
        on(
            Timeline::HbsLink,
            Activity::task(id, 1_800, [0, 15_000], 15.0, 2.0),
        )
    };
    let main = |id| Activity::task(id, 900, [0, 15_000], 30.0, 1.0);
    let p = problem(vec![
        link("transfer_a"),
        link("transfer_b"),
        main("imaging"),
        main("science"),
        main("tau"),
    ]);
    let inst = Instance::new(&p).unwrap();
    let out = plan(&p, &SearchSettings::default()).unwrap();
    assert!(out.is_proven_optimal());
    assert_eq!(out.plan.steps.len(), 5, "{:?}", out.plan.describe(&inst));
    let v = validate_plan(&inst, &State::initial(&inst), &out.plan);
    assert!(v.is_empty(), "{v:?}");
    let (a, b) = (
        step(&inst, &out.plan, "transfer_a"),
        step(&inst, &out.plan, "transfer_b"),
    );
    assert!(!overlap(a, b), "{:?}", out.plan.describe(&inst));
    let mains = ["imaging", "science", "tau"].map(|id| *step(&inst, &out.plan, id));
    for (i, m) in mains.iter().enumerate() {
        for n in &mains[i + 1..] {
            assert!(!overlap(m, n), "{:?}", out.plan.describe(&inst));
        }
    }
    assert!(
        mains.iter().any(|m| overlap(m, a) || overlap(m, b)),
        "nothing ran during a transfer: {:?}",
        out.plan.describe(&inst)
    );
    let makespan = out.plan.steps.iter().map(|s| s.end_s).max().unwrap();
    assert!(makespan < 2 * 1_800 + 3 * 900, "{makespan}");
    // Steps come in start order.
    assert!(
        out.plan
            .steps
            .windows(2)
            .all(|w| w[0].start_s <= w[1].start_s)
    );
}

/// The onboard localization chain: the runs wait for the transfer, the comparison on the
/// main timeline waits for the second run's end, and a comm pass fixed inside the transfer
/// runs during it.
#[test]
fn the_chain_waits_for_its_transfer_while_a_pass_runs_during_it() {
    let mut pass = Activity::task("comm_pass", 600, [2_000, 2_000], 10.0, 0.0);
    pass.mandatory = true;
    let mandatory = |mut a: Activity| {
        a.mandatory = true;
        a
    };
    let p = problem(vec![
        mandatory(Activity::task("sunfind", 300, [1_000, 15_000], 20.0, 0.0)),
        mandatory(after(
            "sunfind",
            on(
                Timeline::HbsLink,
                Activity::task("hbs_transfer", 1_800, [0, 15_000], 15.0, 0.0),
            ),
        )),
        mandatory(after(
            "hbs_transfer",
            on(
                Timeline::HbsLink,
                Activity::task("hbs_run_1", 32, [0, 15_000], 15.0, 0.0),
            ),
        )),
        mandatory(after(
            "hbs_run_1",
            Activity::task("compare_apply", 60, [0, 15_000], 5.0, 0.0),
        )),
        pass,
    ]);
    let inst = Instance::new(&p).unwrap();
    let out = plan(&p, &SearchSettings::default()).unwrap();
    assert_eq!(out.status, PlanStatus::Optimal);
    let v = validate_plan(&inst, &State::initial(&inst), &out.plan);
    assert!(v.is_empty(), "{v:?}");
    let s = |id| *step(&inst, &out.plan, id);
    assert_eq!(s("hbs_transfer").start_s, s("sunfind").end_s);
    assert_eq!(s("hbs_run_1").start_s, s("hbs_transfer").end_s);
    assert_eq!(s("compare_apply").start_s, s("hbs_run_1").end_s);
    assert!(overlap(&s("comm_pass"), &s("hbs_transfer")));
    // Battery and data after each step, as the validator re-simulates them: the pass and the
    // transfer draw together.
    let r = step_resources(&inst, &State::initial(&inst), &out.plan);
    assert_eq!(r.len(), out.plan.steps.len());
    assert!(
        r.iter()
            .all(|x| x.energy_wh_after > 0.0 && x.energy_wh_after <= 1_000.0)
    );
}

#[test]
fn the_validator_catches_overlapping_link_steps_and_unfinished_preconditions() {
    let p = problem(vec![
        on(
            Timeline::HbsLink,
            Activity::task("transfer", 1_800, [0, 15_000], 15.0, 1.0),
        ),
        after(
            "transfer",
            on(
                Timeline::HbsLink,
                Activity::task("run", 60, [0, 15_000], 15.0, 1.0),
            ),
        ),
        Activity::task("imaging", 900, [0, 15_000], 30.0, 1.0),
    ]);
    let inst = Instance::new(&p).unwrap();
    let start = State::initial(&inst);
    let at = |t: u32, s: i64, d: i64| PlanStep {
        task: TaskId(t),
        start_s: s,
        end_s: s + d,
    };
    // The imaging during the transfer is fine; the run after it is too.
    let good = Plan {
        steps: vec![at(0, 0, 1_800), at(2, 100, 900), at(1, 1_800, 60)],
    };
    assert!(validate_plan(&inst, &start, &good).is_empty());
    // The run starts while the transfer holds the link (and before it has ended).
    let bad = Plan {
        steps: vec![at(0, 0, 1_800), at(2, 100, 900), at(1, 1_000, 60)],
    };
    let v = validate_plan(&inst, &start, &bad);
    assert!(
        v.contains(&Violation::LinkOverlap {
            step: 2,
            other: TaskId(0)
        }),
        "{v:?}"
    );
    assert!(
        v.contains(&Violation::MissingPrecondition {
            step: 2,
            precondition: TaskId(0)
        }),
        "{v:?}"
    );
    // Two main-timeline steps still may not overlap.
    let p2 = problem(vec![
        on(
            Timeline::HbsLink,
            Activity::task("transfer", 1_800, [0, 15_000], 15.0, 1.0),
        ),
        Activity::task("a", 900, [0, 15_000], 30.0, 1.0),
        Activity::task("b", 900, [0, 15_000], 30.0, 1.0),
    ]);
    let inst2 = Instance::new(&p2).unwrap();
    let v = validate_plan(
        &inst2,
        &State::initial(&inst2),
        &Plan {
            steps: vec![at(0, 0, 1_800), at(1, 0, 900), at(2, 500, 900)],
        },
    );
    assert_eq!(v, vec![Violation::Overlap { step: 2 }]);
}

/// Overlapping powers add: two activities the battery carries one after the other but not
/// together. The validator flags the overlap; the search waits for the first to end.
#[test]
fn overlapping_activities_draw_the_battery_together() {
    let mut p = problem(vec![
        on(
            Timeline::HbsLink,
            Activity::task("transfer", 3_600, [0, 0], 100.0, 1.0),
        ),
        Activity::task("heater", 3_600, [0, 15_000], 100.0, 1.0),
    ]);
    p.recharge_w = 0.0;
    p.initial_energy_wh = 150.0;
    p.battery_capacity_wh = 150.0;
    p.activities[0].mandatory = true;
    let inst = Instance::new(&p).unwrap();
    let start = State::initial(&inst);
    let together = Plan {
        steps: vec![
            PlanStep {
                task: TaskId(0),
                start_s: 0,
                end_s: 3_600,
            },
            PlanStep {
                task: TaskId(1),
                start_s: 0,
                end_s: 3_600,
            },
        ],
    };
    let v = validate_plan(&inst, &start, &together);
    assert!(
        v.iter()
            .any(|x| matches!(x, Violation::BatteryEmpty { .. })),
        "{v:?}"
    );
    // 150 Wh carry one 100 Wh activity, not two: the heater cannot run at all.
    let out = plan(&p, &SearchSettings::default()).unwrap();
    assert!(validate_plan(&inst, &start, &out.plan).is_empty());
    assert_eq!(out.plan.steps.len(), 1, "{:?}", out.plan.describe(&inst));
    // With recharge the heater waits for the transfer's end, then for the battery.
    p.recharge_w = 20.0;
    let inst = Instance::new(&p).unwrap();
    let out = plan(&p, &SearchSettings::default()).unwrap();
    let v = validate_plan(&inst, &State::initial(&inst), &out.plan);
    assert!(v.is_empty(), "{v:?}");
    let heater = step(&inst, &out.plan, "heater");
    assert!(heater.start_s >= 3_600, "{:?}", out.plan.describe(&inst));
}

/// A replan while a link activity is still running: it keeps the link busy and its
/// successor waits for its end.
#[test]
fn a_replan_waits_for_a_running_transfer() {
    let p = problem(vec![
        on(
            Timeline::HbsLink,
            Activity::task("transfer", 1_800, [0, 15_000], 15.0, 1.0),
        ),
        after(
            "transfer",
            on(
                Timeline::HbsLink,
                Activity::task("run", 60, [0, 15_000], 15.0, 1.0),
            ),
        ),
        Activity::task("imaging", 900, [0, 15_000], 30.0, 1.0),
    ]);
    let inst = Instance::new(&p).unwrap();
    let state = State {
        time_s: 600,
        done: vec![TaskId(0)],
        running: vec![Running {
            task: TaskId(0),
            start_s: 0,
            end_s: 1_800,
        }],
        ..State::initial(&inst)
    };
    let out = plan_from(&inst, &state, &SearchSettings::default()).unwrap();
    let v = validate_plan(&inst, &state, &out.plan);
    assert!(v.is_empty(), "{v:?}");
    assert_eq!(step(&inst, &out.plan, "run").start_s, 1_800);
    assert_eq!(step(&inst, &out.plan, "imaging").start_s, 600);
    // Repair after the imaging ran late: the state keeps the transfer running until its end
    // (the imaging still runs too), and the run still waits for the transfer.
    let imaging = out.plan.steps[0];
    assert_eq!(inst.task(imaging.task).name, "imaging");
    match repair(&inst, &state, &out.plan, 0, imaging.end_s + 300).unwrap() {
        planner::RepairOutcome::Repaired {
            state: after, plan, ..
        } => {
            assert!(after.time_s >= imaging.start_s);
            assert!(validate_plan(&inst, &after, &plan).is_empty());
            assert_eq!(plan.steps[0].start_s, 1_800);
        }
        other => panic!("{other:?}"),
    }
    // A running task on a single-timeline problem is refused.
    let single =
        Instance::new(&problem(vec![Activity::task("a", 60, [0, 100], 1.0, 1.0)])).unwrap();
    let bad = State {
        done: vec![TaskId(0)],
        running: vec![Running {
            task: TaskId(0),
            start_s: 0,
            end_s: 60,
        }],
        ..State::initial(&single)
    };
    assert!(matches!(
        plan_from(&single, &bad, &SearchSettings::default()),
        Err(PlanError::InvalidState {
            field: "running",
            ..
        })
    ));
}

#[test]
fn link_activities_produce_no_data_and_do_not_drive() {
    let mut a = on(
        Timeline::HbsLink,
        Activity::task("transfer", 60, [0, 100], 1.0, 1.0),
    );
    a.data_mb = 5.0;
    let e = Instance::new(&problem(vec![a.clone()])).unwrap_err();
    assert!(
        matches!(
            e,
            PlanError::InvalidLinkActivity {
                field: "data_mb",
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("hbs_link"), "{e}");
    // Holding both timelines, it may.
    a.timeline = Timeline::MainAndHbsLink;
    assert!(Instance::new(&problem(vec![a])).is_ok());
    // The timeline is a JSON field, "main" by default and left out then.
    let json = r#"{"id": "t", "kind": {"type": "task", "duration_s": 60}, "earliest_start_s": 0,
        "latest_start_s": 100, "power_w": 1.0, "timeline": "hbs_link"}"#;
    let a: Activity = serde_json::from_str(json).unwrap();
    assert_eq!(a.timeline, Timeline::HbsLink);
    let main = Activity::task("m", 60, [0, 100], 1.0, 1.0);
    assert!(!serde_json::to_string(&main).unwrap().contains("timeline"));
}

/// A random small problem with link and main activities (≤ 6 tasks).
fn small_link_problem(seed: u64) -> Problem {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x11_4b);
    let n = rng.random_range(3..=6usize);
    let mut activities = Vec::new();
    for i in 0..n {
        let timeline = [Timeline::Main, Timeline::HbsLink, Timeline::MainAndHbsLink]
            [rng.random_range(0..3usize)];
        let d = 60 * rng.random_range(5..=40i64);
        let lo = 60 * rng.random_range(0..=60i64);
        let hi = (lo + 60 * rng.random_range(0..=120i64)).min(14_400 - d);
        let mut a = Activity::task(
            format!("a{i}"),
            d,
            [lo.min(hi), hi],
            f64::from(rng.random_range(0..=60u32)),
            f64::from(rng.random_range(0..=5u32)),
        );
        a.timeline = timeline;
        if timeline.uses_main() {
            a.data_mb = f64::from(rng.random_range(0..=3u32)) * 10.0;
        }
        if i > 0 && rng.random_bool(0.3) {
            a.preconditions = vec![format!("a{}", rng.random_range(0..i))];
        }
        a.mandatory = rng.random_bool(0.15);
        activities.push(a);
    }
    Problem {
        start_s: 0,
        end_s: 14_400,
        battery_capacity_wh: 100.0,
        initial_energy_wh: f64::from(rng.random_range(20..=100u32)),
        recharge_w: [0.0, 10.0, 40.0, 400.0][rng.random_range(0..4usize)],
        data_capacity_mb: 50.0,
        initial_data_mb: 0.0,
        activities,
        campaigns: Vec::new(),
    }
}

/// The reference: the best value over every order of every subset, each task at its earliest
/// start on its timelines after its preconditions' ends (no battery waits), that the
/// validator accepts.
fn reference(inst: &Instance) -> Option<Value> {
    let n = inst.tasks().len();
    let start = State::initial(inst);
    let mut best: Option<Value> = None;
    let mut order = Vec::new();
    fn dfs(
        inst: &Instance,
        start: &State,
        order: &mut Vec<usize>,
        n: usize,
        best: &mut Option<Value>,
    ) {
        // Schedule `order` on the two timelines.
        let (mut main, mut link) = (start.time_s, start.time_s);
        let mut ends = vec![None; n];
        let mut steps = Vec::new();
        for &i in order.iter() {
            let t = inst.task(TaskId(i as u32));
            let mut s = t.earliest_start_s;
            if t.timeline.uses_main() {
                s = s.max(main);
            }
            if t.timeline.uses_link() {
                s = s.max(link);
            }
            for q in &t.preconditions {
                s = s.max(ends[q.index()].unwrap_or(i64::MAX));
            }
            let e = s.saturating_add(t.duration_s);
            if t.timeline.uses_main() {
                main = e;
            }
            if t.timeline.uses_link() {
                link = e;
            }
            ends[i] = Some(e);
            steps.push(PlanStep {
                task: TaskId(i as u32),
                start_s: s,
                end_s: e,
            });
        }
        steps.sort_by_key(|s| s.start_s);
        let plan = Plan { steps };
        if !validate_plan(inst, start, &plan).is_empty() {
            return;
        }
        let mut v = Value::ZERO;
        for s in &plan.steps {
            let t = inst.task(s.task);
            v.tiers_micro[t.tier] += t.utility_micro;
        }
        if best.is_none_or(|b| v > b) {
            *best = Some(v);
        }
        for i in 0..n {
            if !order.contains(&i) {
                order.push(i);
                dfs(inst, start, order, n, best);
                order.pop();
            }
        }
    }
    dfs(inst, &start, &mut order, n, &mut best);
    best
}

/// On random small problems with link activities: every plan the search returns is valid,
/// worth at least the reference optimum (which never waits for the battery), equal to it
/// when the battery never binds, and every bound is at least the reference optimum.
#[test]
fn search_is_valid_and_at_least_the_reference_on_random_link_problems() {
    let mut compared = 0;
    let mut equal = 0;
    for seed in 0..600u64 {
        let p = small_link_problem(seed);
        let inst = Instance::new(&p).unwrap();
        let start = State::initial(&inst);
        let settings = SearchSettings {
            node_budget: None,
            bound: [BoundKind::Knapsack, BoundKind::Lp, BoundKind::Both][seed as usize % 3],
            dominance: seed % 2 == 0,
            ..SearchSettings::default()
        };
        let out = plan_from(&inst, &start, &settings).unwrap();
        // The proof phase from the first node (the time-indexed bounds, with link tasks free
        // on the main timeline's path) proves the same.
        let proof_only = SearchSettings {
            dive_nodes: 0,
            ..settings.clone()
        };
        let proof = plan_from(&inst, &start, &proof_only).unwrap();
        assert_eq!(
            (proof.status, proof.value),
            (out.status, out.value),
            "seed {seed}: dive_nodes 0"
        );
        let reference = reference(&inst);
        if out.status == PlanStatus::Infeasible {
            assert!(reference.is_none(), "seed {seed}: reference {reference:?}");
            continue;
        }
        let v = validate_plan(&inst, &start, &out.plan);
        assert!(
            v.is_empty(),
            "seed {seed}: {v:?} in {:?}",
            out.plan.describe(&inst)
        );
        let Some(best) = reference else {
            continue;
        };
        compared += 1;
        assert!(
            matches!(out.status, PlanStatus::Optimal),
            "seed {seed}: {:?}",
            out.status
        );
        assert!(
            out.value >= best,
            "seed {seed}: search {} < reference {best}",
            out.value
        );
        // Recharge above every power together: the battery never falls, nothing waits.
        let ample = p.activities.iter().map(|a| a.power_w).sum::<f64>() <= p.recharge_w;
        if ample {
            assert_eq!(out.value, best, "seed {seed}");
            equal += 1;
        }
        for kind in [BoundKind::Knapsack, BoundKind::Lp, BoundKind::Both] {
            let b = optimistic_bound(&inst, &start, kind).unwrap();
            let b = b.unwrap_or_else(|| panic!("seed {seed} {kind:?}: feasible root killed"));
            assert!(
                b >= out.value,
                "seed {seed} {kind:?}: bound {b} < {}",
                out.value
            );
        }
        // Same input, same plan.
        assert_eq!(plan_from(&inst, &start, &settings).unwrap().plan, out.plan);
    }
    assert!(compared >= 250, "only {compared} feasible problems");
    assert!(
        equal >= 30,
        "only {equal} problems where the battery never binds"
    );
}
