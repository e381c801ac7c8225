//! `solsim compare`, `run` and `replay`: load a scenario, run its strategies through
//! [`outputs::compare`], print the table or JSON, write the output directory.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context as _;
use clap::Args;
use maps::MemoryBudget;
use outputs::output_set::OutputSet;
use outputs::run_files::{pretty, run_json};
use outputs::tables::sol_table;
use sim::Strategy;
use study::Scenario;
use sweep::engine::SweepSpec;

/// Where and how a run's outputs go.
// The doc comments are clap's help text (`<scenario name>` is a placeholder, not HTML).
#[allow(rustdoc::invalid_html_tags)]
#[derive(Args)]
pub struct OutputArgs {
    /// Print JSON on standard output instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Directory for the JSON, per-sol CSV and GeoJSON files (GIS layers in Mars
    /// longitude/latitude, and in the map's CRS with a .prj), replaced whole by each run (it
    /// must be new, empty, or an earlier solsim output) [default: solsim-out/<scenario name>]
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Do not write output files.
    #[arg(long)]
    pub no_files: bool,
}

/// `solsim compare`'s arguments.
#[derive(Args)]
pub struct CompareArgs {
    /// Scenario file (TOML).
    pub scenario: PathBuf,
    /// Also compare over N seeded worlds (2 to 10000000; run 0 is the scenario's seed): means,
    /// paired differences from ground with 95 % bootstrap intervals, fault rates with 95 %
    /// Wilson intervals (see above).
    #[arg(long, value_name = "N")]
    pub runs: Option<u64>,
    /// Worker threads [default: one per core]. The output does not depend on it.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1024))]
    pub threads: Option<u64>,
    /// Also write report.html (figures inline, the tables, the sol logs) beside the run's
    /// files; `solsim report DIR` writes it later from the directory.
    #[arg(long, conflicts_with = "no_files")]
    pub report: bool,
    /// Grow the keep-outs on the whole-traverse maps and the fault zooms by this uncertainty r,
    /// metres [default: each keep-out by the r the rover had where its path came closest to
    /// it; each fault's zoom by the fault's r].
    #[arg(long, value_name = "R")]
    pub map_r_m: Option<f64>,
    #[command(flatten)]
    #[allow(missing_docs)] // flattened: its fields are the options
    pub output: OutputArgs,
}

/// `solsim run`'s arguments.
#[derive(Args)]
pub struct RunArgs {
    /// Scenario file (TOML).
    pub scenario: PathBuf,
    /// Strategy: replay, ground, onboard, extension or extension+onboard.
    #[arg(long, short, default_value = "ground")]
    pub strategy: String,
    #[command(flatten)]
    #[allow(missing_docs)] // flattened: its fields are the options
    pub output: OutputArgs,
}

/// `solsim replay`'s arguments.
#[derive(Args)]
pub struct ReplayArgs {
    /// Scenario file (TOML) with historic per-sol distances.
    pub scenario: PathBuf,
    #[command(flatten)]
    #[allow(missing_docs)] // flattened: its fields are the options
    pub output: OutputArgs,
}

/// `solsim compare`.
pub fn compare(
    a: &CompareArgs,
    budget: MemoryBudget,
    stdout: &mut dyn std::io::Write,
) -> anyhow::Result<ExitCode> {
    // A bad --runs is refused before anything is loaded or run, as `sweep` refuses it.
    if let Some(runs) = a.runs {
        sweep::engine::check_runs(runs, outputs::over_runs::MIN_RUNS)?;
    }
    crate::cmd_report::check_map_r(a.map_r_m)?;
    let scenario = crate::progress::load_scenario("compare", &a.scenario, budget)?;
    let out = out_dir(&a.output, &scenario);
    let spec = match a.runs {
        None => None,
        Some(runs) => {
            let spec = SweepSpec::new(&scenario, runs);
            spec.validate(&scenario, budget)?;
            // The runs may take a while: an --out that cannot be written is refused first.
            if !a.output.no_files {
                OutputSet::check(&out)?;
            }
            Some(spec)
        }
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads.map_or(0, |t| t as usize))
        .build()
        .context("cannot start the worker threads")?;
    let progress = crate::progress::Progress::new(false, "compare", "runs", 0);
    let comparison = pool.install(|| {
        outputs::compare::compare(&scenario, spec.as_ref(), &|done, total| {
            progress.update(done, total);
        })
    });
    progress.finish();
    if a.output.json {
        write!(stdout, "{}", comparison.json())?;
    } else {
        write!(stdout, "{}", comparison.text())?;
    }
    if !a.output.no_files {
        let options = outputs::compare::FileOptions {
            report: a.report,
            map_r_m: a.map_r_m,
        };
        let written = comparison.write(&out, &options)?;
        if !a.output.json {
            writeln!(stdout, "{}", written.summary_line())?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// `solsim run` and `solsim replay`: one strategy.
pub fn run_one(
    path: &Path,
    strategy: &str,
    output: &OutputArgs,
    budget: MemoryBudget,
    stdout: &mut dyn std::io::Write,
) -> anyhow::Result<ExitCode> {
    let Some(strategy) = Strategy::from_name(strategy) else {
        let names: Vec<&str> = Strategy::ALL.iter().map(|s| s.name()).collect();
        anyhow::bail!(
            "--strategy: expected one of {}, got {strategy:?}",
            names.join(", ")
        );
    };
    let scenario = crate::progress::load_scenario("run", path, budget)?;
    if strategy == Strategy::Replay && !scenario.has_history {
        anyhow::bail!(
            "{}: sols[*].historic_distance_m: expected historic distances for a replay, got none",
            path.display()
        );
    }
    let outcome = scenario.run(strategy, scenario.seeds());
    if output.json {
        write!(
            stdout,
            "{}",
            pretty(&run_json(&scenario, &outcome, &scenario.legs))
        )?;
    } else {
        write!(stdout, "{}", sol_table(&outcome))?;
    }
    if !output.no_files {
        let dir = out_dir(output, &scenario);
        let written = outputs::compare::write_run_set(&dir, &scenario, &[outcome], &[])?;
        if !output.json {
            writeln!(stdout, "{}", written.summary_line())?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// `--out`, or its default `solsim-out/<scenario name>`.
fn out_dir(output: &OutputArgs, scenario: &Scenario) -> PathBuf {
    output
        .out
        .clone()
        .unwrap_or_else(|| outputs::compare::default_out_dir(scenario))
}
