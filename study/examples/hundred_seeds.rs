//! Runs 100 seeds of a scenario with the map loaded once: the study API as a Monte Carlo study
//! would use it.
//!
//! ```text
//! cargo run --release -p study --example hundred_seeds [SCENARIO] [RUNS]
//! ```
//!
//! Loads `SCENARIO` (default `scenarios/sol383-386.toml`) once — maps, zones, planning grid and
//! leg clearances — then runs runs 0..RUNS (default 100) of the `ground` and `onboard`
//! strategies in parallel over runs (run 0 is the scenario's own seed; every strategy of one
//! run sees the same world, [`sim::seeds`]). Prints the load time, the time per run, and the
//! NO_PATH count per strategy. The per-run figures are in run order whatever the thread count.

use std::time::Instant;

use rayon::prelude::*;
use sim::Strategy;
use study::Scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .unwrap_or_else(|| "scenarios/sol383-386.toml".to_string());
    let runs: u64 = args.next().map_or(Ok(100), |r| r.parse())?;
    let strategies = [Strategy::Ground, Strategy::Onboard];

    let start = Instant::now();
    let scenario = Scenario::load(path.as_ref())?;
    let load_s = start.elapsed().as_secs_f64();

    let start = Instant::now();
    let outcomes: Vec<Vec<sim::CampaignOutcome>> = (0..runs)
        .into_par_iter()
        .map(|run| {
            strategies
                .iter()
                .map(|&s| scenario.run_index(s, run))
                .collect()
        })
        .collect();
    let run_s = start.elapsed().as_secs_f64();
    let n_runs = outcomes.len() * strategies.len();

    println!(
        "{}: loaded once in {:.3} s; {n_runs} runs ({runs} run indices × {} strategies) in {:.2} s on {} threads: {:.1} ms per run",
        scenario.name,
        load_s,
        strategies.len(),
        run_s,
        rayon::current_num_threads(),
        1e3 * run_s / n_runs as f64
    );
    for (k, s) in strategies.iter().enumerate() {
        let faulted = outcomes
            .iter()
            .filter(|o| o[k].totals.no_path_faults > 0)
            .count();
        let mean_m = outcomes.iter().map(|o| o[k].totals.distance_m).sum::<f64>() / runs as f64;
        println!(
            "  {:<8} runs with a NO_PATH: {faulted:>3} of {runs}; mean distance {mean_m:.1} m",
            s.name()
        );
    }
    Ok(())
}
