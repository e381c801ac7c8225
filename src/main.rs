//! `solsim` — multi-sol Mars rover mission-operations simulator (command line).
//!
//! Exit codes: 0 success; 1 `regress` found a mismatch; 2 bad input (a scenario, map, zones or
//! points file that cannot be used — the message names the file and the field).

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context as _;
use clap::{Args, Parser, Subcommand};

use maps::MemoryBudget;
use outputs::run_files::write_atomic;
use solsim::{cmd_compare, cmd_localize, cmd_localize_rasters, cmd_map, cmd_package, cmd_zones};

/// Simulate multi-sol Mars rover drives: position uncertainty, grown keep-out zones, AutoNav
/// NO_PATH faults, and how operations strategies (ground-in-the-loop, onboard global
/// localization, opportunistic extension drives) change the outcome.
#[derive(Parser)]
#[command(
    name = "solsim",
    version,
    propagate_version = true,
    max_term_width = 100
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Memory the command may use for maps, rasters, the planning grid and zones, MiB. Sizes
    /// are computed from the inputs (raster headers, map extent ÷ grid.resolution_m, recipe
    /// sizes, zone vertices) and checked before anything is allocated; over it, the command
    /// stops with an error naming the field.
    #[arg(long, global = true, value_name = "MIB", default_value_t = MemoryBudget::DEFAULT_BYTES >> 20,
          value_parser = clap::value_parser!(u64).range(1..=(1 << 30)))]
    memory_budget_mib: u64,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scenario under every strategy and print them side by side (the main job).
    ///
    /// First a one-line verdict: what onboard localization, extension and the two together
    /// gain or lose against ground on the scenario's seed — drive sols by number, metres, the
    /// study segment's sols, a change in faults — and with --runs N the mean differences over
    /// the N runs with their 95 % intervals.
    ///
    /// Columns: sols to reach the end of the route, drive sols, metres driven, metres per drive
    /// sol, NO_PATH faults, all faults, largest uncertainty radius, onboard localizations
    /// applied/rejected, ground localizations. Under the table, each strategy against ground on
    /// the same seed: the drive sols it gained and lost, by number. Each gained sol is counted
    /// once, under the first kind that applies: no downlink pass, restricted, no uplink (weekend
    /// or multi-sol plan), ordinary sol. Per-strategy JSON, CSV and GeoJSON files go to --out
    /// (default solsim-out/<scenario name>/).
    ///
    /// With --runs N the scenario also runs over N seeded worlds (run indices 0..N; run 0 is
    /// the scenario's seed, the run of the table), in memory: the same sweep as `solsim sweep
    /// SCENARIO --runs N`, whose summary.json holds the same numbers. Under the one-run comparison
    /// it prints each strategy against ground over the N runs. For sols to cover the study
    /// segment, drive sols, metres, drive time, peak uncertainty r and uplinks that needed a
    /// drive plan: the strategy's mean against ground's, and the difference, the mean of
    /// (strategy − ground) run by run, with its 95 % bootstrap interval: the runs are resampled
    /// 10000 times (seeded, so the output repeats) and the interval holds the middle 95 % of
    /// the resampled means. An interval that excludes 0 says the difference is not an accident
    /// of these N worlds. NO_PATH and any-fault rates are % of runs with a 95 % Wilson
    /// interval, the true rates the count is consistent with (no fault in 200 runs: 0.0 %
    /// [0.0, 1.9]). Intervals narrow as 1/√N. The output does not depend on --threads; the
    /// summary also goes to --out as <scenario>.over-runs.json.
    Compare(cmd_compare::CompareArgs),
    /// Write report.html for a compare output directory or a sweep directory: one
    /// self-contained page (figures as inline SVG, no script, nothing from the network).
    ///
    /// For a compare directory: the scenario and provenance, the compare table, the verdict
    /// against ground (and the statistics over runs when compare ran with --runs), the figures
    /// (uncertainty radius per sol, metres per sol, each strategy's map with keep-outs grown
    /// at its fault's r, and its sol plans as a Gantt chart with the HBS chain) and every
    /// strategy's sol log. The scenario is loaded and run again on the run's seed; the report
    /// is refused unless that gives back every JSON file in the directory. For a sweep
    /// directory: rates with 95 % Wilson intervals, spreads, paired differences, the CDF of
    /// sols to cover the study segment (or to reach the goal) and the rates figure.
    /// `compare --report` writes the same page beside the run's files.
    Report(solsim::cmd_report::ReportArgs),
    /// Run a scenario under one strategy and print the sol-by-sol table (or JSON).
    ///
    /// The note column says why each drive ended — reached goal, fault: NO_PATH (or KEEP_OUT,
    /// KEEP_IN, SLIP), shortened for passage (the planners' predicted uncertainty would close
    /// the passage ahead), time limit (the drive window, or stopped so the panorama makes the
    /// afternoon pass), drove the record's distance — or why a sol did not drive, and the
    /// localizations. The JSON's sols[].drive_end holds the same words.
    Run(cmd_compare::RunArgs),
    /// Replay the historic record of a scenario (same as `run --strategy replay`).
    Replay(cmd_compare::ReplayArgs),
    /// Run every scenario's [[expect]] entries in a directory; exit 1 and print a diff on any
    /// mismatch.
    Regress(solsim::cmd_regress::RegressArgs),
    /// Write a commented starter scenario that runs as written: SCENARIO.toml and, beside it,
    /// SCENARIO.map/ (a procedural map, its recipe, zones.geojson with one example keep-out).
    ///
    /// The route is solsim's example track near Jezero (scenarios/tracks/jezero-example.geojson,
    /// 1.46 km from the Perseverance landing site); every field of the file is commented with
    /// its meaning, unit and default. `solsim route import` does the same for a track of your
    /// own. Refuses to replace an existing file unless --force.
    Init(solsim::cmd_init::InitArgs),
    /// Routes from outside solsim: `route import TRACK --out SCENARIO.toml` writes a scenario
    /// for a track in Mars longitude/latitude (GeoJSON or CSV).
    #[command(subcommand)]
    Route(solsim::cmd_route::RouteCommand),
    /// Check a scenario (file, maps, zones, route) without running it: list what makes no
    /// sense as errors (exit 2; every other command refuses the scenario) or warnings (exit 0),
    /// each with what to do, and print the route's passage clearance per leg.
    ///
    /// Errors: the route or the zones within one grid cell (coordinates in longitude/latitude
    /// degrees, not map metres), a zone entirely off the map, a waypoint inside a keep-out, a
    /// waypoint (the start included) outside the keep-in zones, a leg with no path even at
    /// r = 0 (also where the rover's footprint overlaps a zone at one of its waypoints).
    /// Warnings: a zone smaller than one grid cell.
    Validate(solsim::cmd_validate::ValidateArgs),
    /// Keep-in / keep-out zone queries.
    #[command(subcommand)]
    Zones(ZonesCommand),
    /// Map tools.
    #[command(subcommand)]
    Map(MapCommand),
    /// Onboard global localization accuracy on the synthetic benchmark set (264 post-drive
    /// panoramas over rocky, plain and dune terrain): mean, median, p99, max, counts over 1 m and
    /// 2 m, for census, NCC and mutual information.
    LocalizeBench(cmd_localize::LocalizeBenchArgs),
    /// Slip against slope, per terrain class (sand, soil, bedrock) and heading (up-, cross- and
    /// down-slope), measured by the six-wheel rover in rapier on terramechanics soils.
    ///
    /// Each run drives the rover on a plane slope (a heightfield collider) for --duration-s at
    /// 5 cm/s and measures slip = 1 − progress / commanded over the second half, the chassis
    /// tilt and the sideways drift; the wheels' traction comes from the Janosi–Hanamoto shear
    /// law and their rolling resistance from Bekker's sinkage (sim::rover::physics::soil cites the
    /// soil values). Writes slip_profile.csv (with the closed-form steady slip of the same
    /// soil model beside each up and down run), slip_profile.svg and slip_profile.json to
    /// --out. The simulator reads the bundled table sim/data/slip_profile.csv, which is this
    /// command's output at the defaults.
    SlipProfile(solsim::cmd_slip_profile::SlipProfileArgs),
    /// Inject radiation upsets (bit flips in storage, memory and results; stalls) into seeded
    /// onboard-localization runs on the co-processor model and count injected / caught / lost /
    /// corrupted-and-applied (which must be zero).
    SeuCampaign(cmd_localize::SeuArgs),
    /// Onboard global localization on your own rasters (orbital orthoimage and DEM, rover
    /// orthomosaic and DEM).
    ///
    /// Matches the rover's orthomosaic (and DEM), centred on the rover, against the orbital
    /// orthoimage (and DEM) around a prior position. Prints the position (E, N metres),
    /// correction, σ, best score, peak ratio, valid fraction and verdict (ACCEPTED, or
    /// REJECTED: reason — still exit 0); exit 2 on bad input.
    Localize(Box<cmd_localize_rasters::LocalizeArgs>),
    /// Plan one sol from a campaign file (paper 003): goal-set, periodic and state-based
    /// campaigns, drives split around them, mandatory comm passes, battery and data limits.
    ///
    /// Prints the timeline (LMST start/end, activity and drive segment, campaign, metres
    /// driven, energy and data after each step), the utility per campaign and per tier, the
    /// best bound and gap, the proof status (PROVEN OPTIMAL or FEASIBLE gap ...) and the plan
    /// validator's verdict. Deterministic under the node budget (default 100000 nodes); with
    /// --time-budget-ms the output may vary between runs. Exit 2 on a malformed file.
    Plan(solsim::cmd_plan::PlanArgs),
    /// Monte Carlo study: run a scenario over run indices 0..N under several strategies.
    ///
    /// Every strategy of run i sees the same world (common random numbers), so differences are
    /// paired. Prints per strategy the NO_PATH, any-fault, truth-outside-the-disc and
    /// goal-reached rates with 95 % Wilson intervals and the mean (p5–p95) of sols to goal,
    /// metres driven and the largest uncertainty; then each strategy's paired difference from
    /// the baseline (default ground) with a 95 % bootstrap interval. Writes runs.parquet (one
    /// row per run × strategy), sols.parquet (per sol), summary.json and manifest.json to
    /// --out. Parallel over runs; the files are identical whatever the thread count; --resume
    /// continues after a kill; --shard K/N, `sweep merge` and `sweep slurm` spread a sweep over
    /// machines.
    Sweep(Box<solsim::cmd_sweep::SweepArgs>),
    /// One strategy on two versions of a scenario that differ in a setting, over the same run
    /// indices: the variant against the base, paired run by run.
    ///
    /// Both files must carry the same seed: run i of both then sees the same world (the same
    /// heading errors, VO failures, slip draws), so a difference is the setting's, not luck's.
    /// First names every setting whose value differs between the two files, with both values
    /// (`rover.slip_aware_routing: true → false`), read from their TOML: map files compared by
    /// contents, not paths; name, description, notes and [[expect]] entries are not settings.
    /// Then prints, for each figure of `solsim sweep` (drive time, sols to goal, faults, ...), the
    /// base's and the variant's mean over the runs where both have it and their difference
    /// with a 95 % bootstrap interval; then the fault and goal rates of each with 95 % Wilson
    /// intervals. Example: scenarios/dune-crossing.toml against
    /// scenarios/dune-crossing-slip-unaware.toml asks what slip-aware routing buys.
    Whatif(solsim::cmd_whatif::WhatifArgs),
    /// The public record of Perseverance's drives (NASA's MMGIS layers, bundled in data/m20):
    /// import a sol range as a replay scenario; set the ground strategy beside the record.
    #[command(subcommand)]
    Record(solsim::cmd_record::RecordCommand),
    /// Re-derive a calibrated constant of the error model from a scenario's historic record
    /// (the command each calibrated default names).
    #[command(subcommand)]
    Calibrate(solsim::cmd_calibrate::CalibrateCommand),
    /// Print a shell completion script for solsim on standard output.
    ///
    /// bash: `solsim completions bash > ~/.local/share/bash-completion/completions/solsim`;
    /// zsh: `solsim completions zsh > ~/.zfunc/_solsim` (with `fpath+=~/.zfunc` before
    /// `compinit`); fish: `solsim completions fish > ~/.config/fish/completions/solsim.fish`.
    Completions(CompletionsArgs),
    /// Print the JSON Schema (draft 2020-12) of a file format: `scenario` or `campaign` (the
    /// `solsim plan` files).
    ///
    /// Generated from the structures the loaders parse, so it names every field they accept.
    /// It checks names and types; values, files and the whole are checked by `solsim validate`.
    /// For editors: `solsim schema scenario > scenario.schema.json`, then a first line
    /// `#:schema ./scenario.schema.json` in a scenario file (Taplo / Even Better TOML).
    Schema(SchemaArgs),
    /// Print solsim's manual page (roff) on standard output, or with --out write one page per
    /// command (solsim.1, solsim-compare.1, …) into a directory: `solsim man | man -l -`.
    Man(ManArgs),
}

#[derive(Args)]
struct CompletionsArgs {
    /// The shell.
    shell: clap_complete::Shell,
}

#[derive(Args)]
struct SchemaArgs {
    /// The file format.
    format: SchemaFormat,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum SchemaFormat {
    /// Scenario files (`solsim compare`, `run`, `sweep`, `validate`, …).
    Scenario,
    /// Campaign files of `solsim plan`.
    Campaign,
}

#[derive(Args)]
struct ManArgs {
    /// Directory for one page per command (created if missing); without it the top-level page
    /// goes to standard output.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

#[derive(Subcommand)]
enum ZonesCommand {
    /// For each point: distance to the nearest keep-out, distance to the keep-in edge, and
    /// max_uncertainty_m — the largest uncertainty radius at which the point stays drivable.
    Check(cmd_zones::ZonesCheckArgs),
}

#[derive(Subcommand)]
enum MapCommand {
    /// Generate a procedural map (appearance, DEM, terrain class GeoTIFFs) from a recipe TOML.
    Generate(cmd_map::GenerateArgs),
    /// Onboard map package of a scenario's route: the 25 cm orthoimage and 1 m DEM (16-bit cm)
    /// rendered along the route, masked to a corridor, as PNG tiles plus manifest.json; prints
    /// the corridor area, pixel counts, bytes per file, total MB and the time taken.
    Package(cmd_package::PackageArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(&e),
    };
    match dispatch(cli) {
        Ok(code) => code,
        Err(e) => {
            // Numbers readably whichever layer formatted them (`1e300`, not 301 digits), and
            // escaped as a whole: a path or a value quoted in a message can never drive the
            // terminal or break the one line.
            let line = study::error::readable_numbers(&one_line(&e));
            let _ = writeln!(
                std::io::stderr(),
                "error: {}",
                maps::input_file::printable(&line)
            );
            ExitCode::from(2)
        }
    }
}

/// Help and version go to stdout as clap prints them; a usage error is one `error:` line on
/// stderr (clap's message without its usage block and `--help` hint), exit 2.
fn usage_error(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(
        e.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        let _ = e.print();
        return if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
            ExitCode::from(2)
        } else {
            ExitCode::SUCCESS
        };
    }
    let text = e.render().to_string();
    let mut line = String::new();
    for l in text.lines() {
        let l = l.trim();
        if l.starts_with("Usage:") || l.starts_with("For more information") {
            break;
        }
        if !l.is_empty() {
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(l.strip_prefix("error: ").unwrap_or(l));
        }
    }
    let _ = writeln!(
        std::io::stderr(),
        "error: {}",
        maps::input_file::printable(&line)
    );
    ExitCode::from(2)
}

/// The message chain on one line, outermost first, each clause once: a cause whose text the
/// message before it already quotes is left out (`…: No such file or directory (os error 2)`
/// appears once, not twice).
fn one_line(e: &anyhow::Error) -> String {
    let mut line = String::new();
    for clause in e.chain().map(|c| c.to_string()) {
        if line.contains(&clause) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&clause);
    }
    line
}

/// Standard output that a closed pipe does not fail: once the reader has gone
/// (`solsim compare … | head -1`), the rest of the output is discarded and the command still
/// does its work — its files, its exit status — instead of dying with `error: Broken pipe`
/// (exit 2, and a panic in a writer that unwraps). Rust ignores SIGPIPE, so a closed pipe is an
/// `EPIPE` write error, caught here once for every command.
struct Stdout<W> {
    inner: W,
    /// The reader has gone: write nothing more.
    closed: bool,
}

impl<W: std::io::Write> Stdout<W> {
    fn absorb<T>(&mut self, result: std::io::Result<T>, ok: T) -> std::io::Result<T> {
        match result {
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
                self.closed = true;
                Ok(ok)
            }
            other => other,
        }
    }
}

impl<W: std::io::Write> std::io::Write for Stdout<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.closed {
            return Ok(buf.len());
        }
        let result = self.inner.write(buf);
        self.absorb(result, buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        if self.closed {
            return Ok(());
        }
        let result = self.inner.flush();
        self.absorb(result, ())
    }
}

fn dispatch(cli: Cli) -> anyhow::Result<ExitCode> {
    let stdout = &mut Stdout {
        inner: std::io::stdout().lock(),
        closed: false,
    };
    let budget = MemoryBudget::new(cli.memory_budget_mib << 20);
    match cli.command {
        Command::Compare(a) => cmd_compare::compare(&a, budget, stdout),
        Command::Report(a) => {
            solsim::cmd_report::run(&a, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Run(a) => {
            cmd_compare::run_one(&a.scenario, &a.strategy, &a.output, budget, stdout)
        }
        Command::Replay(a) => {
            cmd_compare::run_one(&a.scenario, "replay", &a.output, budget, stdout)
        }
        Command::Regress(a) => solsim::cmd_regress::run(&a, budget, stdout),
        Command::Validate(a) => solsim::cmd_validate::run(&a, budget, stdout),
        Command::Init(a) => {
            solsim::cmd_init::run(&a, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Route(c) => {
            solsim::cmd_route::run(&c, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Zones(ZonesCommand::Check(a)) => {
            cmd_zones::run(&a, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::SeuCampaign(a) => {
            cmd_localize::seu(&a, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Localize(a) => {
            cmd_localize_rasters::run(&a, budget, stdout, &mut std::io::stderr())?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Plan(a) => {
            solsim::cmd_plan::run(&a, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Sweep(a) => {
            solsim::cmd_sweep::run(&a, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Calibrate(c) => {
            solsim::cmd_calibrate::run(&c, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Record(c) => {
            solsim::cmd_record::run(&c, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Whatif(a) => {
            solsim::cmd_whatif::run(&a, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::SlipProfile(a) => {
            solsim::cmd_slip_profile::run(&a, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::LocalizeBench(a) => {
            cmd_localize::run(&a, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Map(MapCommand::Generate(a)) => {
            cmd_map::generate(&a, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Map(MapCommand::Package(a)) => {
            cmd_package::run(&a, budget, stdout)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Completions(a) => {
            use clap::CommandFactory as _;
            clap_complete::generate(a.shell, &mut Cli::command(), "solsim", stdout);
            Ok(ExitCode::SUCCESS)
        }
        Command::Schema(a) => {
            let schema = match a.format {
                SchemaFormat::Scenario => study::schema::scenario(),
                SchemaFormat::Campaign => study::schema::campaign(),
            };
            writeln!(stdout, "{}", serde_json::to_string_pretty(&schema)?)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Man(a) => {
            use clap::CommandFactory as _;
            man_pages(Cli::command(), a.out.as_deref(), stdout)?;
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// The top-level manual page on `stdout`, or with `out` one page per command and subcommand
/// (`solsim-sweep-merge.1`), each written to a temporary file and renamed into place.
fn man_pages(
    cmd: clap::Command,
    out: Option<&Path>,
    stdout: &mut dyn std::io::Write,
) -> anyhow::Result<()> {
    let Some(dir) = out else {
        clap_mangen::Man::new(cmd).render(stdout)?;
        return Ok(());
    };
    std::fs::create_dir_all(dir).with_context(|| format!("--out {}", dir.display()))?;
    fn write_all(cmd: clap::Command, name: String, dir: &Path) -> anyhow::Result<usize> {
        let mut pages = 1;
        for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
            pages += write_all(sub.clone(), format!("{name}-{}", sub.get_name()), dir)?;
        }
        let mut roff = Vec::new();
        let cmd = cmd
            .display_name(name.clone())
            .version(env!("CARGO_PKG_VERSION"));
        clap_mangen::Man::new(cmd).render(&mut roff)?;
        let path = dir.join(format!("{name}.1"));
        write_atomic(&path, &roff).with_context(|| format!("--out: {}", path.display()))?;
        Ok(pages)
    }
    let pages = write_all(cmd, "solsim".into(), dir)?;
    writeln!(stdout, "wrote {pages} manual pages to {}", dir.display())?;
    Ok(())
}
