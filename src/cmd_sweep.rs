//! `solsim sweep`: Monte Carlo studies — run a scenario over run indices `0..N` under several
//! strategies, write `runs.parquet`, `sols.parquet`, `summary.json` and `manifest.json`, print
//! the rates, spreads and paired differences; `sweep merge` joins shard directories;
//! `sweep slurm` prints a Slurm job-array submit script.

use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::progress::Progress;
use anyhow::Context as _;
use clap::{Args, Subcommand};
use maps::MemoryBudget;
use maps::input_file::{first_unsafe_char, printable};
use sim::Strategy;
use study::Scenario;
use study::error::{MAX_EXCERPT_CHARS, excerpt};
use sweep::engine::{DEFAULT_CHUNK_RUNS, Shard, Summary, SweepResult, SweepSpec};
use sweep::summary::{Figure, RateKind, Statistics};

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
    /// derived from it (sim::seeds::run_seed), the same for every strategy.
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

/// Runs the sweep `spec` in memory, with progress on stderr as a sweep shows it (labelled
/// `compare`), and returns its summary: what `solsim compare --runs N` reports. Call
/// [`SweepSpec::validate`] first.
#[must_use]
pub fn summary_in_memory(scenario: &Scenario, spec: &SweepSpec) -> Summary {
    let progress = Progress::new(false, "compare", "runs", 0);
    let summary = sweep::engine::summary_in_memory(scenario, spec, &|done, total| {
        progress.update(done, total);
    });
    progress.finish();
    summary
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
            report(&result, &scenario, secs, pool.current_num_threads())
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
        writeln!(
            stdout,
            "merged {} into {}/ ({} × {})",
            plural(a.dirs.len() as u64, "shard directory").replace("directorys", "directories"),
            a.out.display(),
            plural(result.manifest.runs, "run"),
            plural(result.manifest.strategies.len() as u64, "strategy")
        )?;
    }
    Ok(())
}

/// A file a command wrote, as its `--json` describes it.
#[derive(serde::Serialize)]
pub struct WrittenFile {
    /// Name inside the output directory.
    pub file: String,
    /// Size, bytes.
    pub bytes: u64,
    /// SHA-256 of its bytes, hex, where the command records it (a sweep's manifest).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sha256: Option<String>,
}

impl WrittenFile {
    /// `dir/file`'s size as written, with `sha256` if known.
    ///
    /// # Errors
    /// The file cannot be read (it was just written: a race with something else).
    pub fn of(dir: &Path, file: &str, sha256: Option<String>) -> anyhow::Result<Self> {
        let path = dir.join(file);
        let bytes = std::fs::metadata(&path)
            .with_context(|| format!("{}: cannot read what was written", path.display()))?
            .len();
        Ok(WrittenFile {
            file: file.to_owned(),
            bytes,
            sha256,
        })
    }
}

/// `sweep --json` and `sweep merge --json`: what the command wrote and the statistics.
#[derive(serde::Serialize)]
struct SweepJson<'a> {
    /// The output directory.
    dir: String,
    /// `sweep merge`: the shard directories, as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    merged_from: Option<Vec<String>>,
    scenario: &'a sweep::manifest::ScenarioId,
    seed: u64,
    /// Run indices 0..runs of the whole sweep.
    runs: u64,
    /// The run indices this directory holds, [first, end).
    run_range: [u64; 2],
    shard: Option<sweep::manifest::ShardInfo>,
    strategies: &'a [String],
    baseline: Option<&'a str>,
    /// Run indices simulated by this command (`sweep`).
    #[serde(skip_serializing_if = "Option::is_none")]
    runs_run: Option<u64>,
    /// Run indices found committed by an interrupted sweep (`sweep --resume`).
    #[serde(skip_serializing_if = "Option::is_none")]
    runs_resumed: Option<u64>,
    /// The directory held the complete sweep already (`sweep --resume`).
    #[serde(skip_serializing_if = "Option::is_none")]
    already_complete: Option<bool>,
    /// Wall time, seconds (`sweep`).
    #[serde(skip_serializing_if = "Option::is_none")]
    seconds: Option<f64>,
    /// Worker threads (`sweep`).
    #[serde(skip_serializing_if = "Option::is_none")]
    threads: Option<usize>,
    /// Every file in the directory: the outputs with their SHA-256, then manifest.json.
    files: Vec<WrittenFile>,
    /// As in summary.json.
    statistics: &'a Statistics,
}

impl<'a> SweepJson<'a> {
    fn of(r: &'a SweepResult) -> anyhow::Result<Self> {
        let m = &r.manifest;
        let mut files = m
            .files
            .iter()
            .map(|(name, sha)| WrittenFile::of(&r.dir, name, Some(sha.clone())))
            .collect::<anyhow::Result<Vec<_>>>()?;
        files.push(WrittenFile::of(&r.dir, sweep::manifest::MANIFEST, None)?);
        let range = m.shard.map_or([0, m.runs], |sh| [sh.first_run, sh.end_run]);
        Ok(SweepJson {
            dir: r.dir.display().to_string(),
            merged_from: None,
            scenario: &m.scenario,
            seed: m.seed,
            runs: m.runs,
            run_range: range,
            shard: m.shard,
            strategies: &m.strategies,
            baseline: m.baseline.as_deref(),
            runs_run: Some(r.runs_run),
            runs_resumed: Some(r.runs_resumed),
            already_complete: Some(r.already_complete),
            seconds: None,
            threads: None,
            files,
            statistics: &r.summary.statistics,
        })
    }
}

/// Quotes `s` for bash (single quotes): every byte inside is data, none is code.
fn sh(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
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

/// What a Slurm submit script runs: every path absolute and checked by [`script_text`].
struct SlurmJob<'a> {
    /// Scenario name, for the script's opening comment.
    name: &'a str,
    /// The solsim binary the jobs run.
    solsim: &'a str,
    /// The scenario file.
    scenario: &'a str,
    /// The directory of the shards, the merged sweep and the logs.
    out: &'a str,
    spec: &'a SweepSpec,
    shards: u64,
    threads_per_task: u64,
    /// `sbatch` options beside the fixed ones (`--partition=…`, `--time=…`), each already
    /// checked to be letters, digits and `-_:.=`.
    sbatch_extra: String,
}

impl SlurmJob<'_> {
    /// The submit script. The two job scripts it writes are each one `printf '%s\n'` of
    /// single-quoted lines whose values are single-quoted again: no path can end a quote, a
    /// line or a here-document and become code.
    fn script(&self) -> String {
        let m = self.shards;
        let spec = self.spec;
        let strategies = spec
            .strategies
            .iter()
            .map(|s| s.name())
            .collect::<Vec<_>>()
            .join(",");
        let baseline = spec.baseline.map_or("none", Strategy::name);
        let (solsim, scen, outq) = (sh(self.solsim), sh(self.scenario), sh(self.out));
        let extra = &self.sbatch_extra;
        let shard_job = [
            "#!/usr/bin/env bash".to_string(),
            "set -euo pipefail".to_string(),
            format!(
                "exec {solsim} sweep {scen} --runs {} --strategies {strategies} --seed {} --baseline {baseline} \
                 --threads {} --shard \"$SLURM_ARRAY_TASK_ID/{m}\" --out {outq}/\"shard-$SLURM_ARRAY_TASK_ID-of-{m}\" --resume --quiet",
                spec.runs, spec.seed, self.threads_per_task
            ),
        ];
        let merge_job = [
            "#!/usr/bin/env bash".to_string(),
            "set -euo pipefail".to_string(),
            format!("exec {solsim} sweep merge {outq}/shard-*-of-{m} --out {outq}/merged --quiet"),
        ];
        let printf = |lines: &[String], file: &str| {
            let quoted: Vec<String> = lines.iter().map(|l| sh(l)).collect();
            format!(
                "printf '%s\\n' \\\n  {} \\\n  > \"$out/slurm/{file}\"",
                quoted.join(" \\\n  ")
            )
        };
        let mut s = String::new();
        let _ = writeln!(s, "#!/usr/bin/env bash");
        let _ = writeln!(
            s,
            "# solsim sweep of {} on Slurm: runs 0..{} of {strategies} (seed {}), in {m} shards —\n\
             # one array task per shard (`solsim sweep --shard K/{m}`), then a merge job that runs\n\
             # once every task has succeeded. Submit from a login node: bash THIS_FILE.\n\
             # Shards write {outq}/shard-K-of-{m}, the merge {outq}/merged, Slurm logs {outq}/slurm.\n\
             # A task that is requeued or re-run resumes its shard (--resume).",
            sh(self.name),
            spec.runs,
            spec.seed,
        );
        let _ = writeln!(s, "set -euo pipefail");
        let _ = writeln!(s, "out={outq}");
        let _ = writeln!(s, "mkdir -p \"$out/slurm\"");
        // sbatch reads `%` in an --output path as a filename pattern (`%j`: the job id);
        // `%%` is a literal one.
        let _ = writeln!(
            s,
            "logs={}/slurm  # $out/slurm for sbatch --output",
            sh(&self.out.replace('%', "%%"))
        );
        let _ = writeln!(s, "{}", printf(&shard_job, "shard.sh"));
        let _ = writeln!(s, "{}", printf(&merge_job, "merge.sh"));
        let _ = writeln!(
            s,
            "array=$(sbatch --parsable --job-name=solsim-sweep --array=0-{} --cpus-per-task={}{extra} \\\n  \
             --output=\"$logs/shard-%a.log\" \"$out/slurm/shard.sh\")",
            m - 1,
            self.threads_per_task
        );
        let _ = writeln!(s, "array=${{array%%;*}}");
        let _ = writeln!(
            s,
            "merge=$(sbatch --parsable --job-name=solsim-merge --dependency=afterok:\"$array\"{extra} \\\n  \
             --output=\"$logs/merge.log\" \"$out/slurm/merge.sh\")"
        );
        let _ = writeln!(s, "echo \"array job $array\"");
        let _ = writeln!(s, "echo \"merge job ${{merge%%;*}}\"");
        s
    }
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

fn plural(n: u64, what: &str) -> String {
    match (n, what) {
        (1, _) => format!("1 {what}"),
        (_, "strategy") => format!("{n} strategies"),
        _ => format!("{n} {what}s"),
    }
}

fn pct(x: f64) -> String {
    format!("{:.1}", 100.0 * x)
}

fn signed(x: f64, decimals: usize) -> String {
    let t = format!("{x:+.decimals$}");
    t.replace('-', "−")
}

/// The printed report of a sweep.
#[must_use]
pub fn report(r: &SweepResult, scenario: &Scenario, seconds: f64, threads: usize) -> String {
    let m = &r.manifest;
    let st: &Statistics = &r.summary.statistics;
    let mut s = String::new();
    let range = m.shard.map_or(0..m.runs, |sh| sh.first_run..sh.end_run);
    let _ = writeln!(
        s,
        "{} — {} × {} (runs {}..{} of {}, seed {}){}",
        scenario.name,
        plural(range.end - range.start, "run"),
        plural(m.strategies.len() as u64, "strategy"),
        range.start,
        range.end,
        m.runs,
        m.seed,
        m.shard.map_or(String::new(), |sh| format!(
            ", shard {}/{}",
            sh.index, sh.count
        ))
    );
    let how = if r.already_complete {
        "already complete".to_string()
    } else if r.runs_resumed > 0 {
        format!(
            "{} run indices resumed from committed chunks, {} run",
            r.runs_resumed, r.runs_run
        )
    } else {
        format!("{} run indices", r.runs_run)
    };
    let _ = writeln!(
        s,
        "{how} in {seconds:.1} s on {threads} threads; files in {}/ (runs.parquet, sols.parquet, summary.json, manifest.json)\n",
        r.dir.display()
    );
    let _ = writeln!(
        s,
        "Rates: % of runs [95 % Wilson interval]. Disc coverage: % of drive sols, pooled over the runs,\n\
         that ended with the truth inside the uncertainty disc [Wilson]. Figures: mean (p5–p95) over\n\
         the runs that have them (n = how many, when not all)."
    );
    let mut figs = vec![Figure::SolsToGoal];
    if m.segment.is_some() {
        figs.push(Figure::SegmentSols);
    }
    figs.extend([Figure::DistanceM, Figure::MaxUncertaintyM]);
    let rates = [
        RateKind::NoPath,
        RateKind::Fault,
        RateKind::TruthOutsideDisc,
        RateKind::GoalReached,
    ];
    let head_rate = |k: RateKind| match k {
        RateKind::NoPath => "NO_PATH",
        RateKind::Fault => "any fault",
        RateKind::TruthOutsideDisc => "truth outside r",
        RateKind::GoalReached => "goal reached",
    };
    let _ = write!(s, "{:<18}", "strategy");
    for k in rates {
        let _ = write!(s, " {:>19}", head_rate(k));
    }
    let _ = write!(s, " {:>22}", "disc coverage (sols)");
    for f in &figs {
        let _ = write!(s, " {:>19}", f.name());
    }
    let _ = writeln!(s);
    for ss in &st.strategies {
        let _ = write!(s, "{:<18}", ss.strategy);
        for k in rates {
            let cell = ss.rate(k.name()).map_or("-".into(), |r| {
                format!(
                    "{} [{}, {}]",
                    pct(r.rate),
                    pct(r.interval.lo),
                    pct(r.interval.hi)
                )
            });
            let _ = write!(s, " {cell:>19}");
        }
        let cell = ss.disc_coverage.as_ref().map_or("-".into(), |r| {
            format!(
                "{:.2} [{:.2}, {:.2}]",
                100.0 * r.rate,
                100.0 * r.interval.lo,
                100.0 * r.interval.hi
            )
        });
        let _ = write!(s, " {cell:>22}");
        for f in &figs {
            let cell = ss.figure(f.name()).map_or("-".into(), |sp| {
                let d = if sp.mean.abs() >= 100.0 { 0 } else { 2 };
                let n = if sp.n as u64 == ss.runs {
                    String::new()
                } else {
                    format!(" n={}", sp.n)
                };
                format!("{:.d$} ({:.d$}–{:.d$}){n}", sp.mean, sp.p5, sp.p95)
            });
            let _ = write!(s, " {cell:>19}");
        }
        let _ = writeln!(s);
    }
    if let Some(b) = &st.baseline {
        let mut paired = vec![Figure::SolsToGoal];
        if m.segment.is_some() {
            paired.extend([Figure::SegmentSols, Figure::SegmentDistanceM]);
        }
        paired.extend([Figure::NoPathFaults, Figure::DistanceM]);
        let _ = writeln!(
            s,
            "\nPaired difference from {b}: mean of (strategy − {b}) over the run indices where both have the\n\
             figure [95 % bootstrap interval, {} resamples].",
            st.bootstrap_resamples
        );
        for ss in st.strategies.iter().filter(|x| &x.strategy != b) {
            for (i, f) in paired.iter().enumerate() {
                let name = if i == 0 { ss.strategy.as_str() } else { "" };
                let cell = st
                    .paired(&ss.strategy, f.name())
                    .and_then(|p| p.difference)
                    .map_or("- (no run where both have it)".into(), |d| {
                        let dec = if f.name().ends_with("_m") { 1 } else { 2 };
                        format!(
                            "{:>8} [{}, {}]  {} pairs",
                            signed(d.mean, dec),
                            signed(d.interval.lo, dec),
                            signed(d.interval.hi, dec),
                            d.n
                        )
                    });
                let _ = writeln!(s, "{name:<18} {:<20} {cell}", f.name());
            }
        }
    }
    s
}
