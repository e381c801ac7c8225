//! Solves one B6 instance ([`planner::b6_problem`]) and prints status, value, bound, stats.
//!
//! `cargo run -p planner --release --example b6_solve -- n seed [node_budget] [bound: 0 knapsack,
//! 1 lp, 2 both] [time_budget_ms]` (env `RESORT`: `resort_every`, default the settings' default)

#![allow(clippy::unwrap_used)]

use planner::{
    BoundKind, Instance, SearchSettings, State, b6_problem, optimistic_bound, plan, validate_plan,
};
use std::time::{Duration, Instant};

fn main() {
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let n = args.first().copied().unwrap_or(40) as usize;
    let seed = args.get(1).copied().unwrap_or(1);
    let budget = args.get(2).copied().unwrap_or(1_000_000);
    let bound = [BoundKind::Knapsack, BoundKind::Lp, BoundKind::Both]
        [args.get(3).copied().unwrap_or(2).min(2) as usize];
    let time_budget = args.get(4).map(|&ms| Duration::from_millis(ms));
    let p = b6_problem(n, seed);
    let clock = Instant::now();
    let out = plan(
        &p,
        &SearchSettings {
            node_budget: Some(budget),
            time_budget,
            bound,
            resort_every: std::env::var("RESORT")
                .map_or(SearchSettings::default().resort_every, |v| {
                    v.parse().unwrap()
                }),
            ..SearchSettings::default()
        },
    )
    .unwrap();
    let ms = clock.elapsed().as_secs_f64() * 1e3;
    let inst = Instance::new(&p).unwrap();
    let violations = validate_plan(&inst, &State::initial(&inst), &out.plan);
    println!(
        "n{n} seed{seed} {:?} {:.1} ms value {} bound {} gap {:?} violations {}",
        out.status,
        ms,
        out.value,
        out.best_bound,
        out.gap_points(),
        violations.len()
    );
    println!("{:?}", out.stats);
    // The root bounds, each tier on its own (`optimistic_bound`: the knapsack kind includes
    // the time-indexed bound, tuned without an incumbent).
    let root = State::initial(&inst);
    let show = |kind| match optimistic_bound(&inst, &root, kind).unwrap() {
        Some(v) => v.to_string(),
        None => "none (infeasible)".into(),
    };
    println!(
        "root bound: knapsack {} | lp {}",
        show(BoundKind::Knapsack),
        show(BoundKind::Lp)
    );
}
