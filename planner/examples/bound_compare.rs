//! Compares the knapsack and LP bounds on generated instances: the root bound's excess over
//! the best value found, nodes expanded, and time per expanded node.
//!
//! `cargo run -p planner --release --example bound_compare [instances] [n_optional] [budget]`

#![allow(clippy::unwrap_used)]

use planner::{
    BoundKind, GeneratorSettings, Instance, SearchSettings, State, generate, optimistic_bound,
    plan_from,
};
use std::time::Instant;

fn main() {
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let instances = args.first().copied().unwrap_or(20);
    let n_optional = args.get(1).copied().unwrap_or(12) as usize;
    let budget = args.get(2).copied().unwrap_or(20_000);
    let kinds = [BoundKind::Knapsack, BoundKind::Lp, BoundKind::Both];
    let mut root_excess = [0.0f64; 3];
    let mut root_time = [0.0f64; 3];
    let mut nodes = [0u64; 3];
    let mut time = [0.0f64; 3];
    let mut optimal = [0u32; 3];
    for seed in 0..instances {
        let settings = GeneratorSettings {
            n_optional,
            with_drive: seed % 2 == 0,
            with_campaign: seed % 3 == 0,
            ..GeneratorSettings::default()
        };
        let inst = Instance::new(&generate(seed, &settings)).unwrap();
        let start = State::initial(&inst);
        let mut best = None;
        for (k, &bound) in kinds.iter().enumerate() {
            let s = SearchSettings {
                node_budget: Some(budget),
                bound,
                ..SearchSettings::default()
            };
            let out = plan_from(&inst, &start, &s).unwrap();
            nodes[k] += out.stats.nodes_expanded;
            time[k] += out.stats.total_time.as_secs_f64();
            optimal[k] += u32::from(out.is_proven_optimal());
            best = best.max(Some(out.value));
        }
        let best = best.unwrap();
        for (k, &bound) in kinds.iter().enumerate() {
            let clock = Instant::now();
            let b = optimistic_bound(&inst, &start, bound).unwrap();
            root_time[k] += clock.elapsed().as_secs_f64();
            if let Some(b) = b {
                root_excess[k] +=
                    b.to_points().iter().sum::<f64>() - best.to_points().iter().sum::<f64>();
            }
        }
    }
    println!("{instances} instances, {n_optional} optional activities, node budget {budget}");
    println!("bound     root excess (pts)  root eval (us)  proven  nodes/instance  us/node");
    for (k, kind) in kinds.iter().enumerate() {
        println!(
            "{:<9} {:>17.2}  {:>14.1}  {:>6}  {:>14.0}  {:>7.1}",
            format!("{kind:?}"),
            root_excess[k] / instances as f64,
            1e6 * root_time[k] / instances as f64,
            optimal[k],
            nodes[k] as f64 / instances as f64,
            1e6 * time[k] / nodes[k].max(1) as f64
        );
    }
}
