//! `solsim sweep`: Monte Carlo studies — run a scenario over run indices `0..N` under several
//! strategies, write `runs.parquet`, `sols.parquet`, `summary.json` and `manifest.json`, print
//! the rates, spreads and paired differences; `sweep merge` joins shard directories;
//! `sweep slurm` prints a Slurm job-array submit script.
//!
//! This module holds the arguments and their checks; the engine is the [`sweep`] crate, what
//! is printed [`outputs::sweep_text`], the script [`outputs::slurm_script`].

use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::progress::Progress;
use anyhow::Context as _;
use clap::{Args, Subcommand};
use maps::MemoryBudget;
use maps::input_file::{first_unsafe_char, printable};
use outputs::slurm_script::SlurmJob;
use outputs::sweep_text::{SweepJson, merge_line, sweep_table};
use sim::Strategy;
use study::Scenario;
use study::error::{MAX_EXCERPT_CHARS, excerpt};
use sweep::engine::{DEFAULT_CHUNK_RUNS, Shard, SweepSpec};

/// `solsim sweep`.
#[derive(Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    #[command(subcommand)]
    command: Option<SweepCommand>,
    #[command(flatten)]
    run: SweepRunArgs,
}

#[derive(Subcommand)]
enum SweepCommand {
    /// Merge complete shard directories (`--shard K/N` sweeps) into the files one unsharded
    /// sweep writes, byte for byte.
    Merge(MergeArgs),
    /// Print a Slurm submit script: a job array with one shard per task, then a merge job
    /// that runs when every shard has succeeded. Run it with bash on the cluster's login node.
    /// Paths and names written into it must be UTF-8 without control characters, and --out
    /// without a backslash (Slurm cannot name log files in it).
    Slurm(SlurmArgs),
}

/// What is swept: shared by `sweep` and `sweep slurm`.
#[derive(Args, Clone)]
struct SweepWhat {
    /// Run indices 0..RUNS of every strategy. Run 0 uses the scenario's seed; run i ≥ 1 a seed
    /// derived from it (sim::seeds::RunSeeds::new), the same for every strategy.
    #[arg(long, value_name = "N", required = true)]
    runs: Option<u64>,
    /// Comma-separated strategies (replay, ground, onboard, extension, extension+onboard)
    /// [default: all that apply; replay only with historic drives]
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    strategies: Option<Vec<String>>,
    /// The sweep's seed [default: the scenario's seed]
    #[arg(long, value_name = "SEED")]
    seed: Option<u64>,
    /// Strategy the paired differences are taken against; `none` for none
    /// [default: ground when it is swept, else none]
    #[arg(long, value_name = "STRATEGY")]
    baseline: Option<String>,
}

#[derive(Args)]
struct SweepRunArgs {
    /// Scenario file (TOML).
    #[arg(required = true)]
    scenario: Option<PathBuf>,
    #[command(flatten)]
    what: SweepWhat,
    /// Worker threads [default: one per core]. The files do not depend on it.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1024))]
    threads: Option<u64>,
    /// Output directory: new, empty, or (with --resume) this sweep's
    /// [default: sweep-out/<scenario name>, or sweep-out/<name>-shard-K-of-N]
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Continue the sweep in --out after an interruption: committed chunks are kept, the rest
    /// is run; the files equal an uninterrupted sweep's.
    #[arg(long)]
    resume: bool,
    /// Run only slice K of N of the run indices (K = 0..N-1): runs K·RUNS/N .. (K+1)·RUNS/N.
    #[arg(long, value_name = "K/N")]
    shard: Option<String>,
    /// Runs per committed chunk (what a kill can lose).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_CHUNK_RUNS,
          value_parser = clap::value_parser!(u64).range(1..=100_000))]
    chunk_runs: u64,
    /// No progress and no table: only errors (and with --json, the JSON).
    #[arg(long, short)]
    quiet: bool,
    /// Print what the sweep did as one JSON document instead of the table: scenario, seed,
    /// runs (and this directory's run range and shard), strategies, baseline, run indices run
    /// and resumed, seconds, threads, the files in --out with their bytes and SHA-256, and the
    /// statistics of summary.json.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct MergeArgs {
    /// Shard directories (complete `solsim sweep --shard K/N` outputs), in any order.
    #[arg(required = true, value_name = "DIR")]
    dirs: Vec<PathBuf>,
    /// Output directory (new or empty).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Print nothing but errors (and with --json, the JSON).
    #[arg(long, short)]
    quiet: bool,
    /// Print what was merged as one JSON document instead of the line of text: the shard
    /// directories, scenario, seed, runs, strategies, baseline, the files in --out with their
    /// bytes and SHA-256, and the statistics of the merged summary.json.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct SlurmArgs {
    /// Scenario file (TOML).
    scenario: PathBuf,
    #[command(flatten)]
    what: SweepWhat,
    /// Shards: array tasks 0..SHARDS.
    #[arg(long, value_name = "M", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    shards: u64,
    /// Directory for the shards (OUT/shard-K-of-M), the merged sweep (OUT/merged) and the Slurm
    /// logs (OUT/slurm) [default: sweep-out/<scenario name>-slurm]
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Threads per array task (sbatch --cpus-per-task).
    #[arg(long, value_name = "N", default_value_t = 1,
          value_parser = clap::value_parser!(u64).range(1..=1024))]
    threads_per_task: u64,
    /// Slurm partition [default: the cluster's default].
    #[arg(long, value_name = "NAME")]
    partition: Option<String>,
    /// Time limit per array task (sbatch --time, e.g. 01:00:00) [default: the partition's].
    #[arg(long, value_name = "TIME")]
    time: Option<String>,
    /// The solsim binary the jobs run [default: this one].
    #[arg(long, value_name = "PATH")]
    solsim: Option<PathBuf>,
}

/// Runs `solsim sweep …`.
///
/// # Errors
/// Bad input (scenario, options, a directory that holds something else) or a write error.
pub fn run(args: &SweepArgs, budget: MemoryBudget, stdout: &mut dyn Write) -> anyhow::Result<()> {
    match &args.command {
        Some(SweepCommand::Merge(m)) => merge(m, stdout),
        Some(SweepCommand::Slurm(s)) => slurm(s, budget, stdout),
        None => sweep(&args.run, budget, stdout),
    }
}

fn strategy(option: &str, name: &str) -> anyhow::Result<Strategy> {
    Strategy::from_name(name.trim()).ok_or_else(|| {
        anyhow::anyhow!(
            "{option}: expected one of {}, got {name:?}",
            Strategy::ALL.map(Strategy::name).join(", ")
        )
    })
}

fn spec(what: &SweepWhat, scenario: &Scenario) -> anyhow::Result<SweepSpec> {
    let mut spec = SweepSpec::new(scenario, what.runs.unwrap_or(0));
    if let Some(list) = &what.strategies {
        spec.strategies = list
            .iter()
            .map(|s| strategy("--strategies", s))
            .collect::<anyhow::Result<_>>()?;
    }
    if let Some(seed) = what.seed {
        spec.seed = seed;
    }
    spec.baseline = match what.baseline.as_deref() {
        None => spec
            .strategies
            .contains(&Strategy::Ground)
            .then_some(Strategy::Ground),
        Some("none") => None,
        Some(name) => Some(strategy("--baseline", name)?),
    };
    Ok(spec)
}

fn sweep(a: &SweepRunArgs, budget: MemoryBudget, stdout: &mut dyn Write) -> anyhow::Result<()> {
    let path = a.scenario.as_deref().unwrap_or(Path::new(""));
    let started = Instant::now();
    let scenario = Scenario::load_within(path, budget)?;
    let mut spec = spec(&a.what, &scenario)?;
    spec.shard = a.shard.as_deref().map(Shard::parse).transpose()?;
    spec.chunk_runs = a.chunk_runs;
    spec.validate(&scenario, budget)?;
    let out = a.out.clone().unwrap_or_else(|| {
        let name = match spec.shard {
            Some(s) => format!("{}-shard-{}-of-{}", scenario.name, s.index, s.count),
            None => scenario.name.clone(),
        };
        Path::new("sweep-out").join(name)
    });
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads.map_or(0, |t| t as usize))
        .build()
        .context("cannot start the worker threads")?;
    let progress = Progress::new(a.quiet, "sweep", "runs", 0);
    let result = pool.install(|| {
        sweep::run(&scenario, &spec, &out, a.resume, &|done, total| {
            progress.update(done, total);
        })
    });
    progress.finish();
    let result = result?;
    if a.json {
        let doc = SweepJson {
            merged_from: None,
            seconds: Some(started.elapsed().as_secs_f64()),
            threads: Some(pool.current_num_threads()),
            ..SweepJson::of(&result)?
        };
        writeln!(stdout, "{}", serde_json::to_string_pretty(&doc)?)?;
    } else if !a.quiet {
        let secs = started.elapsed().as_secs_f64();
        write!(
            stdout,
            "{}",
            sweep_table(&result, &scenario, secs, pool.current_num_threads())
        )?;
    }
    Ok(())
}

fn merge(a: &MergeArgs, stdout: &mut dyn Write) -> anyhow::Result<()> {
    let result = sweep::merge(&a.dirs, &a.out)?;
    if a.json {
        let doc = SweepJson {
            merged_from: Some(a.dirs.iter().map(|d| d.display().to_string()).collect()),
            runs_run: None,
            runs_resumed: None,
            already_complete: None,
            ..SweepJson::of(&result)?
        };
        writeln!(stdout, "{}", serde_json::to_string_pretty(&doc)?)?;
    } else if !a.quiet {
        writeln!(stdout, "{}", merge_line(a.dirs.len(), &a.out, &result))?;
    }
    Ok(())
}

/// `path` as text that may enter the generated script: UTF-8 (a lossy conversion would run
/// another path than the one given) without control characters (a newline would end a
/// comment or a line of the script; an escape sequence would drive the terminal of whoever
/// reads it). `what` names the argument in the error.
fn script_text<'a>(what: &str, path: &'a Path) -> anyhow::Result<&'a str> {
    let Some(text) = path.to_str() else {
        anyhow::bail!(
            "{what}: expected a path of UTF-8 text (it is written into the script), got {:?}, which is not",
            printable(&path.to_string_lossy())
        );
    };
    if let Some((_, c)) = first_unsafe_char(text) {
        anyhow::bail!(
            "{what}: expected a path without control characters (it is written into the script), got \"{}\" (holds {})",
            excerpt(text, MAX_EXCERPT_CHARS),
            c.escape_default()
        );
    }
    Ok(text)
}

fn absolute(path: &Path, what: &str) -> anyhow::Result<PathBuf> {
    std::path::absolute(path).with_context(|| {
        format!(
            "{what}: cannot make {} absolute",
            printable(&path.to_string_lossy())
        )
    })
}

fn slurm(a: &SlurmArgs, budget: MemoryBudget, stdout: &mut dyn Write) -> anyhow::Result<()> {
    // Refused before anything is read: what the user typed, as typed.
    script_text("SCENARIO", &a.scenario)?;
    if let Some(out) = &a.out {
        script_text("--out", out)?;
    }
    if let Some(exe) = &a.solsim {
        script_text("--solsim", exe)?;
    }
    let scenario = Scenario::load_within(&a.scenario, budget)?;
    if let Some((_, c)) = first_unsafe_char(&scenario.name) {
        anyhow::bail!(
            "{}: name: expected text without control characters (it is written into the script), got \"{}\" (holds {})",
            printable(&a.scenario.to_string_lossy()),
            excerpt(&scenario.name, MAX_EXCERPT_CHARS),
            c.escape_default()
        );
    }
    let spec = spec(&a.what, &scenario)?;
    spec.validate(&scenario, budget)?;
    if a.shards > spec.runs {
        anyhow::bail!(
            "--shards: expected at most --runs ({}) shards, got {}",
            spec.runs,
            a.shards
        );
    }
    let mut sbatch_extra = String::new();
    for (opt, v) in [("--partition", &a.partition), ("--time", &a.time)] {
        if let Some(v) = v {
            if v.is_empty()
                || !v
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_:.".contains(c))
            {
                anyhow::bail!(
                    "{opt}: expected letters, digits, '-', '_', ':' or '.', got \"{}\"",
                    excerpt(v, MAX_EXCERPT_CHARS)
                );
            }
            let _ = write!(sbatch_extra, " {opt}={v}");
        }
    }
    // The paths as the script names them, absolute (it runs elsewhere): each checked again,
    // since the working directory, a symbolic link or this binary's location can add what
    // the argument did not hold.
    let exe = match &a.solsim {
        Some(p) => absolute(p, "--solsim")?,
        None => std::env::current_exe().context("cannot find this solsim binary")?,
    };
    let scenario_path = std::fs::canonicalize(&a.scenario).with_context(|| {
        format!(
            "SCENARIO: cannot resolve {}",
            printable(&a.scenario.to_string_lossy())
        )
    })?;
    let out = absolute(
        &a.out
            .clone()
            .unwrap_or_else(|| Path::new("sweep-out").join(format!("{}-slurm", scenario.name))),
        "--out",
    )?;
    let out = script_text("--out (made absolute)", &out)?;
    if out.contains('\\') {
        anyhow::bail!(
            "--out: expected a directory without a backslash (Slurm cannot name log files in it), got \"{}\"",
            excerpt(out, MAX_EXCERPT_CHARS)
        );
    }
    let job = SlurmJob {
        name: &scenario.name,
        solsim: script_text("--solsim (this solsim binary's path)", &exe)?,
        scenario: script_text("SCENARIO (resolved)", &scenario_path)?,
        out,
        spec: &spec,
        shards: a.shards,
        threads_per_task: a.threads_per_task,
        sbatch_extra,
    };
    write!(stdout, "{}", job.script())?;
    Ok(())
}
