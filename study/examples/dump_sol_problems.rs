//! Writes the planning problem of every drive sol the simulator builds, with the planner's
//! proven optimum next to each, for `peers/planner_cpsat.py` (issue 16: the peer on the sol
//! problems the simulator actually builds).
//!
//! ```text
//! cargo run --release -p study --example dump_sol_problems -- OUT_DIR [SCENARIO…]
//! ```
//!
//! Runs every strategy of each `SCENARIO` (default: `scenarios/rapid-traverse-379-409.toml` and
//! `scenarios/self-reliant-campaign.toml`; `replay` only where the scenario has a record) under
//! the scenario's own seed, capturing each drive sol's first planning problem
//! ([`sim::operations::sol_plan::capture_sol_problems`]). Every distinct problem (byte-identical JSON
//! counts once, under the first name that produced it) is written as
//! `<scenario>_<strategy>_sol<N>.json` (`+` in a strategy name becomes `-`), and
//! `planner::plan` with no node budget writes `<stem>.planner.json`: `{status, value_micro,
//! bound_micro, nodes, ms, ms_min_max, plan}` (the first five as
//! `planner/examples/dump_instances.rs` writes them, `ms` the median of 5 runs, `Instance::new`
//! included; `plan` is `[start_s, task]` per step). `index.json` lists every captured sol,
//! the file holding its problem and the problem's size; one line per distinct problem goes to
//! stdout.
//!
//! `dump_sol_problems --plan FILE.json…` only plans the given problem files and writes each
//! `FILE.planner.json` (for variants edited by hand, e.g. a tighter battery).

#![allow(clippy::unwrap_used, clippy::print_stdout)]

use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

use planner::{ActivityKind, Instance, SearchSettings, plan};
use study::Scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = args.next().unwrap_or_else(|| "target/sol-problems".into());
    if out == "--plan" {
        for file in args {
            let problem: planner::Problem = serde_json::from_str(&std::fs::read_to_string(&file)?)?;
            let path = Path::new(&file);
            let dir = path.parent().unwrap().to_string_lossy().to_string();
            let stem = path.file_stem().unwrap().to_string_lossy().to_string();
            solve(&dir, &stem, &problem);
        }
        return Ok(());
    }
    let mut scenarios: Vec<String> = args.collect();
    if scenarios.is_empty() {
        scenarios = vec![
            "scenarios/rapid-traverse-379-409.toml".into(),
            "scenarios/self-reliant-campaign.toml".into(),
        ];
    }
    std::fs::create_dir_all(&out)?;
    // JSON text -> stem of the file that holds it.
    let mut seen: BTreeMap<String, String> = BTreeMap::new();
    let mut index = Vec::new();
    for path in &scenarios {
        let scenario = Scenario::load(path.as_ref())?;
        let name = Path::new(path)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .to_string();
        for strategy in scenario.strategies() {
            let (_, problems) = sim::operations::sol_plan::capture_sol_problems(|| {
                scenario.run(strategy, scenario.seeds())
            });
            for (sol, problem) in problems {
                let json = serde_json::to_string_pretty(&problem)?;
                let stem = format!("{name}_{}_sol{sol}", strategy.name().replace('+', "-"));
                let file = match seen.get(&json) {
                    Some(first) => first.clone(),
                    None => {
                        seen.insert(json.clone(), stem.clone());
                        std::fs::write(format!("{out}/{stem}.json"), &json)?;
                        solve(&out, &stem, &problem);
                        stem.clone()
                    }
                };
                index.push(serde_json::json!({
                    "scenario": name, "strategy": strategy.name(), "sol": sol, "file": file,
                    "size": size(&problem),
                }));
            }
        }
    }
    std::fs::write(
        format!("{out}/index.json"),
        serde_json::to_string_pretty(&index)?,
    )?;
    println!(
        "{} sol problems, {} distinct, in {out}",
        index.len(),
        seen.len()
    );
    Ok(())
}

/// Activities, tasks after drive splitting, campaigns, whether the HBS link is used, and
/// whether the problem is accepted.
fn size(problem: &planner::Problem) -> serde_json::Value {
    let drives = problem
        .activities
        .iter()
        .filter(|a| matches!(a.kind, ActivityKind::Drive(_)))
        .count();
    match Instance::new(problem) {
        Ok(inst) => serde_json::json!({
            "activities": problem.activities.len(), "drives": drives,
            "tasks": inst.tasks().len(), "campaigns": problem.campaigns.len(),
            "mandatory": inst.mandatory_tasks().len(), "hbs_link": inst.uses_link(),
        }),
        Err(e) => serde_json::json!({ "error": e.to_string() }),
    }
}

fn solve(out: &str, stem: &str, problem: &planner::Problem) {
    let settings = SearchSettings {
        node_budget: None,
        ..SearchSettings::default()
    };
    // Median of RUNS wall times (the search is deterministic: every run gives the same plan).
    const RUNS: usize = 5;
    let mut times = Vec::with_capacity(RUNS);
    let mut outcome = None;
    for _ in 0..RUNS {
        let clock = Instant::now();
        let o = plan(problem, &settings);
        times.push(clock.elapsed().as_secs_f64() * 1e3);
        outcome = Some(o);
    }
    times.sort_by(f64::total_cmp);
    let summary = match outcome.unwrap() {
        Ok(o) => {
            let ms = times[RUNS / 2];
            let inst = Instance::new(problem).unwrap();
            let steps: Vec<_> = o
                .plan
                .steps
                .iter()
                .map(|s| serde_json::json!([s.start_s, inst.task(s.task).name]))
                .collect();
            serde_json::json!({
                "status": format!("{:?}", o.status),
                "value_micro": o.value.tiers_micro,
                "bound_micro": o.best_bound.tiers_micro,
                "nodes": o.stats.nodes_expanded,
                "ms": ms,
                "ms_min_max": [times[0], times[RUNS - 1]],
                "plan": steps,
            })
        }
        Err(e) => serde_json::json!({ "status": "Error", "error": e.to_string() }),
    };
    println!("{stem}: {} {}", size(problem), summary_line(&summary));
    std::fs::write(format!("{out}/{stem}.planner.json"), summary.to_string()).unwrap();
}

fn summary_line(s: &serde_json::Value) -> String {
    format!(
        "{} value {} nodes {} ms {:.2}",
        s["status"],
        s["value_micro"],
        s["nodes"],
        s["ms"].as_f64().unwrap_or(f64::NAN)
    )
}
