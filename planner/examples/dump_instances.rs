//! Writes the B6 benchmark instances ([`planner::b6_problem`]) as `Problem` JSON, with the
//! planner's result under a node budget next to each, for `peers/planner_cpsat.py`.
//!
//! `cargo run -p planner --release --example dump_instances [out_dir] [node_budget] [sizes…]`
//! (defaults: `target/planner-instances`, 2 000 000 nodes, sizes 20 40 80, seeds 1–3; env
//! `SEEDS=1,2,…` and `BOUND=knapsack|lp|both`, default knapsack).
//! Writes `n{N}_seed{S}.json` (the problem) and `n{N}_seed{S}.planner.json` (status, value
//! per tier in micro-points, bound, nodes, wall ms).

#![allow(clippy::unwrap_used)]

use planner::{BoundKind, SearchSettings, b6_problem, plan};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args
        .first()
        .cloned()
        .unwrap_or_else(|| "target/planner-instances".into());
    let budget: u64 = args.get(1).map_or(2_000_000, |a| a.parse().unwrap());
    let sizes: Vec<usize> = if args.len() > 2 {
        args[2..].iter().map(|a| a.parse().unwrap()).collect()
    } else {
        vec![20, 40, 80]
    };
    let seeds: Vec<u64> = std::env::var("SEEDS")
        .map(|s| s.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or_else(|_| vec![1, 2, 3]);
    let bound = match std::env::var("BOUND").as_deref() {
        Ok("lp") => BoundKind::Lp,
        Ok("both") => BoundKind::Both,
        _ => BoundKind::Knapsack,
    };
    std::fs::create_dir_all(&out).unwrap();
    for &n in &sizes {
        for &seed in &seeds {
            let p = b6_problem(n, seed);
            let stem = format!("{out}/n{n}_seed{seed}");
            std::fs::write(
                format!("{stem}.json"),
                serde_json::to_string_pretty(&p).unwrap(),
            )
            .unwrap();
            if budget == 0 {
                continue;
            }
            let clock = Instant::now();
            let o = plan(
                &p,
                &SearchSettings {
                    node_budget: Some(budget),
                    bound,
                    ..SearchSettings::default()
                },
            )
            .unwrap();
            let ms = clock.elapsed().as_secs_f64() * 1e3;
            let summary = serde_json::json!({
                "status": format!("{:?}", o.status),
                "value_micro": o.value.tiers_micro,
                "bound_micro": o.best_bound.tiers_micro,
                "nodes": o.stats.nodes_expanded,
                "ms": ms,
            });
            println!("n{n} seed{seed}: {summary}");
            std::fs::write(format!("{stem}.planner.json"), summary.to_string()).unwrap();
        }
    }
}
