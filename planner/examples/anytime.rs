//! Anytime quality on the B6 instances ([`planner::b6_problem`]): the value the planner reaches
//! within a wall-clock budget, against the proven (or best known) optimum.
//!
//! ```sh
//! cargo run -p planner --release --example anytime -- --out anytime.json --dump DIR
//!     [--sizes 80,160,320] [--seeds 1,2,3] [--budgets-ms 1,10,100,1000] [--repeats 3]
//!     [--proof-nodes 20000] [--proof-time-s 60]
//! ```
//!
//! For every instance and budget, `plan` runs `--repeats` times with `time_budget` = the budget,
//! no node budget and [`BoundKind::Knapsack`] (the settings of `benches/planner.rs`); each run
//! records status, value and best bound per tier (micro-points), nodes expanded, the search's own
//! `total_time` and the wall time of the whole `plan` call (instance building included, as the
//! budget is checked only inside the search). The value can change with timing, so the summary
//! gives the median and the min/max run, ordered lexicographically (tier 1 first) — the tiers of
//! one summary entry come from the same run. Every plan is checked with `validate_plan`.
//!
//! Once per instance, a proof attempt (`--proof-nodes` node budget, `--proof-time-s` safety
//! cap) gives the optimum, or the best value and bound found when the cap binds.
//!
//! `--dump DIR` writes each instance as `Problem` JSON (`n{N}_seed{S}.json`, as the bench's
//! `SOLSIM_PLANNER_DUMP` does) for `peers/planner_anytime.py`, which runs CP-SAT with the same
//! budgets and prints the table (`report`).

#![allow(clippy::unwrap_used)]

use std::path::PathBuf;
use std::time::{Duration, Instant};

use planner::{
    BoundKind, Instance, PlanOutcome, Problem, SearchSettings, State, b6_problem, plan,
    validate_plan,
};
use serde_json::{Value as Json, json};

struct Args {
    sizes: Vec<usize>,
    seeds: Vec<u64>,
    budgets_ms: Vec<u64>,
    repeats: usize,
    proof_nodes: u64,
    proof_time_s: u64,
    out: Option<PathBuf>,
    dump: Option<PathBuf>,
}

fn list<T: std::str::FromStr>(s: &str) -> Vec<T> {
    s.split(',')
        .map(|x| {
            x.trim()
                .parse()
                .ok()
                .expect("a comma-separated list of numbers")
        })
        .collect()
}

fn parse_args() -> Args {
    let mut a = Args {
        sizes: vec![80, 160, 320],
        seeds: vec![1, 2, 3],
        budgets_ms: vec![1, 10, 100, 1000],
        repeats: 3,
        proof_nodes: 20_000,
        proof_time_s: 60,
        out: None,
        dump: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut val = || it.next().unwrap_or_else(|| panic!("{flag} needs a value"));
        match flag.as_str() {
            "--sizes" => a.sizes = list(&val()),
            "--seeds" => a.seeds = list(&val()),
            "--budgets-ms" => a.budgets_ms = list(&val()),
            "--repeats" => a.repeats = val().parse().unwrap(),
            "--proof-nodes" => a.proof_nodes = val().parse().unwrap(),
            "--proof-time-s" => a.proof_time_s = val().parse().unwrap(),
            "--out" => a.out = Some(val().into()),
            "--dump" => a.dump = Some(val().into()),
            _ => panic!("unknown argument {flag} (see the doc comment of anytime.rs)"),
        }
    }
    a
}

/// One `plan` call: the outcome as JSON, and the wall time of the call in ms.
fn run(problem: &Problem, inst: &Instance, settings: &SearchSettings) -> (PlanOutcome, Json) {
    let clock = Instant::now();
    let out = plan(problem, settings).expect("valid problem");
    let wall_ms = clock.elapsed().as_secs_f64() * 1e3;
    let violations = validate_plan(inst, &State::initial(inst), &out.plan).len();
    assert_eq!(violations, 0, "the planner returned an invalid plan");
    let j = json!({
        "status": format!("{:?}", out.status),
        "value_micro": out.value.tiers_micro,
        "bound_micro": out.best_bound.tiers_micro,
        "nodes": out.stats.nodes_expanded,
        "search_ms": out.stats.total_time.as_secs_f64() * 1e3,
        "wall_ms": wall_ms,
    });
    (out, j)
}

fn main() {
    let args = parse_args();
    if let Some(d) = &args.dump {
        std::fs::create_dir_all(d).expect("dump dir");
    }
    let mut instances = Vec::new();
    for &n in &args.sizes {
        for &seed in &args.seeds {
            let problem = b6_problem(n, seed);
            let inst = Instance::new(&problem).expect("valid problem");
            if let Some(d) = &args.dump {
                let path = d.join(format!("n{n}_seed{seed}.json"));
                let text = serde_json::to_string_pretty(&problem).expect("serialise");
                std::fs::write(&path, text).expect("write problem");
            }
            // The proof attempt: deterministic while the node budget binds first.
            let proof_settings = SearchSettings {
                node_budget: Some(args.proof_nodes),
                time_budget: Some(Duration::from_secs(args.proof_time_s)),
                bound: BoundKind::Knapsack,
                ..SearchSettings::default()
            };
            let (p_out, proof) = run(&problem, &inst, &proof_settings);
            eprintln!(
                "n{n} seed{seed} proof attempt ({} nodes / {} s cap): {:?} value {} bound {} \
                 ({} nodes, {:.0} ms)",
                args.proof_nodes,
                args.proof_time_s,
                p_out.status,
                p_out.value,
                p_out.best_bound,
                p_out.stats.nodes_expanded,
                p_out.stats.total_time.as_secs_f64() * 1e3
            );
            let mut budgets = Vec::new();
            for &ms in &args.budgets_ms {
                let settings = SearchSettings {
                    node_budget: None,
                    time_budget: Some(Duration::from_millis(ms)),
                    bound: BoundKind::Knapsack,
                    ..SearchSettings::default()
                };
                let mut runs: Vec<(PlanOutcome, Json)> = (0..args.repeats.max(1))
                    .map(|_| run(&problem, &inst, &settings))
                    .collect();
                // Lexicographic order on the value (tier 1 first), then the bound.
                runs.sort_by_key(|(o, _)| (o.value, std::cmp::Reverse(o.best_bound)));
                let (lo, mid, hi) = (&runs[0], &runs[runs.len() / 2], &runs[runs.len() - 1]);
                eprintln!(
                    "  {ms:>5} ms: median {:?} value {} bound {} ({} nodes); min {} max {}",
                    mid.0.status,
                    mid.0.value,
                    mid.0.best_bound,
                    mid.0.stats.nodes_expanded,
                    lo.0.value,
                    hi.0.value
                );
                budgets.push(json!({
                    "budget_ms": ms,
                    "median": mid.1,
                    "min": lo.1,
                    "max": hi.1,
                    "runs": runs.iter().map(|r| r.1.clone()).collect::<Vec<_>>(),
                }));
            }
            instances.push(json!({
                "file": format!("n{n}_seed{seed}.json"),
                "n": n,
                "seed": seed,
                "proof": proof,
                "proof_node_budget": args.proof_nodes,
                "proof_time_cap_s": args.proof_time_s,
                "budgets": budgets,
            }));
        }
    }
    let doc = json!({
        "solver": "planner",
        "bound": "Knapsack",
        "repeats": args.repeats,
        "budgets_ms": args.budgets_ms,
        "instances": instances,
    });
    let text = serde_json::to_string_pretty(&doc).expect("serialise");
    match &args.out {
        Some(p) => std::fs::write(p, text).expect("write --out"),
        None => println!("{text}"),
    }
}
