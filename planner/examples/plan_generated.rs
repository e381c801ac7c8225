//! Plans one generated instance and prints the plan, its value, the bound and the stats.
//!
//! `cargo run -p planner --release --example plan_generated [seed] [n_optional] [node_budget]
//! [bound: 0 knapsack, 1 lp, 2 both]`

#![allow(clippy::unwrap_used)]

use planner::{
    BoundKind, GeneratorSettings, Instance, SearchSettings, State, generate, plan_from,
    validate_plan,
};

fn main() {
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let seed = args.first().copied().unwrap_or(80);
    let n_optional = args.get(1).copied().unwrap_or(80) as usize;
    let budget = args.get(2).copied().unwrap_or(20);
    let bound = [BoundKind::Knapsack, BoundKind::Lp, BoundKind::Both]
        [args.get(3).copied().unwrap_or(2).min(2) as usize];
    let settings = GeneratorSettings {
        n_optional,
        n_precedences: 8,
        with_drive: true,
        with_campaign: true,
        ..GeneratorSettings::default()
    };
    let inst = Instance::new(&generate(seed, &settings)).unwrap();
    let start = State::initial(&inst);
    let out = plan_from(
        &inst,
        &start,
        &SearchSettings {
            node_budget: Some(budget),
            bound,
            ..SearchSettings::default()
        },
    )
    .unwrap();
    println!("tasks {}  status {:?}", inst.tasks().len(), out.status);
    println!(
        "value {}  bound {}  gap {:?}",
        out.value,
        out.best_bound,
        out.gap_points()
    );
    println!("violations {:?}", validate_plan(&inst, &start, &out.plan));
    println!("{:?}", out.stats);
    for s in &out.plan.steps {
        println!(
            "  {:>6} {:>6}  {}",
            s.start_s,
            s.end_s,
            inst.task(s.task).name
        );
    }
}
