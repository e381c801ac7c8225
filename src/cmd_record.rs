//! `solsim record`: the public record of Perseverance's drives.
//!
//! - `record import --sols FIRST-LAST --out DIR`: a replay scenario for any sol range
//!   ([`study::record_import`]), its zones, and the procedural map around it, written as one
//!   output set.
//! - `record baseline SCENARIO`: `ground` beside the record ([`study::baseline`]).

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context as _;
use clap::{Args, Subcommand};
use maps::MemoryBudget;
use study::record::{TraverseLayer, parse_sol_range};
use study::record_import::{ImportOptions, file_names, import};

use outputs::output_set::OutputSet;

/// The bundled traverse layer, relative to the repository.
pub const BUNDLED_TRAVERSE: &str = "data/m20/M20_traverse.json";

/// The bundled traverse layer: under the working directory, else in the source tree solsim
/// was built from.
fn bundled_traverse() -> PathBuf {
    let here = PathBuf::from(BUNDLED_TRAVERSE);
    if here.exists() {
        here
    } else {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(BUNDLED_TRAVERSE)
    }
}

/// `solsim record`.
#[derive(Subcommand)]
pub enum RecordCommand {
    /// Write a replay scenario for a sol range of the record: scenario TOML, zones GeoJSON and a
    /// procedural map (GeoTIFFs with the Jezero CRS) in --out.
    ///
    /// Per sol: the historic distance (paper 000's odometry where it gives one, the record's
    /// length otherwise, each marked in `historic_source`), the drive's window in LMST from the
    /// spacecraft clock (Mars24), the route along the recorded path in map metres, the calendar
    /// computed from Mars time (`[calendar]`); idle sols the calendar does not explain become
    /// historic science stops. Re-filed drives, cumulative entries and entries spanning idle
    /// sols are handled and listed. Keep-out passages are placed by a written rule (a
    /// modelling choice: the record has no zones); the scenario's header says what comes from
    /// where.
    Import(ImportArgs),
    /// Set the ground strategy beside the record of a scenario: per sol, the planning day, the
    /// record's metres, what the calendar's rule decides for ground, what simulated ground
    /// drove (run 0) and how often (over --runs), and who drove: both, record only, model only.
    ///
    /// Every sol the team drove, ground must be able to drive: a baseline more cautious than
    /// reality inflates every gain credited to onboard localization. Disagreements are listed
    /// with the rule that decided them.
    Baseline(BaselineArgs),
}

/// `solsim record import`.
#[derive(Args)]
pub struct ImportArgs {
    /// The sols, `FIRST-LAST` (e.g. 379-409), within the record.
    #[arg(long, value_name = "FIRST-LAST")]
    sols: String,
    /// Output directory (a new or empty directory, or an earlier import): the scenario,
    /// zones, map/ and import-report.txt.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// The traverse layer (GeoJSON, NASA's MMGIS `M20_traverse.json`); default the bundled
    /// snapshot, data/m20/M20_traverse.json (of the working directory, else of the source tree
    /// solsim was built from).
    #[arg(long, value_name = "FILE")]
    record: Option<PathBuf>,
    /// Scenario name (default record-FIRST-LAST).
    #[arg(long)]
    name: Option<String>,
    /// Scenario and map seed (default the first sol).
    #[arg(long)]
    seed: Option<u64>,
    /// Use the record's lengths everywhere, not paper 000's odometry where it gives one.
    #[arg(long)]
    record_odometry: bool,
    /// Route past the range along the record's later drives, metres.
    #[arg(long, value_name = "M", default_value_t = 2000.0)]
    route_beyond_m: f64,
}

/// `solsim record baseline`.
#[derive(Args)]
pub struct BaselineArgs {
    /// Scenario with a record (e.g. one written by `record import`).
    scenario: PathBuf,
    /// Simulated ground runs (run indices 0..RUNS).
    #[arg(long, value_name = "N", default_value_t = 20,
          value_parser = clap::value_parser!(u64).range(1..=10_000))]
    runs: u64,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
}

/// Run `solsim record …`.
///
/// # Errors
/// A record or scenario that cannot be read, a range outside the record, an unusable --out.
pub fn run(cmd: &RecordCommand, budget: MemoryBudget, out: &mut impl Write) -> anyhow::Result<()> {
    match cmd {
        RecordCommand::Import(a) => import_cmd(a, budget, out),
        RecordCommand::Baseline(a) => baseline_cmd(a, budget, out),
    }
}

fn import_cmd(a: &ImportArgs, budget: MemoryBudget, out: &mut impl Write) -> anyhow::Result<()> {
    let sols = parse_sol_range(&a.sols).map_err(|e| anyhow::anyhow!("--sols: {e}"))?;
    if !(0.0..=100_000.0).contains(&a.route_beyond_m) {
        anyhow::bail!(
            "--route-beyond-m: expected 0 ..= 100000 metres, got {}",
            a.route_beyond_m
        );
    }
    let mut opts = ImportOptions::new(sols);
    if let Some(name) = &a.name {
        study::scenario::check_name(name).map_err(|e| anyhow::anyhow!("--name: {e}"))?;
        opts.name.clone_from(name);
    }
    if let Some(seed) = a.seed {
        opts.seed = seed;
    }
    opts.paper_odometry = !a.record_odometry;
    opts.route_beyond_m = a.route_beyond_m;
    OutputSet::check(&a.out)?;
    let record = a.record.clone().unwrap_or_else(bundled_traverse);
    let layer = TraverseLayer::read(&record)?;
    let imported = import(&layer, &opts)?;
    let (scenario_file, zones_file, map_dir) = file_names(&opts.name);

    // The map, from the recipe, checked against the budget like `map generate`.
    let recipe_path = a.out.join(map_dir).join("recipe.toml");
    let recipe = study::recipe::recipe_from_toml_str(&recipe_path, &imported.recipe_toml, budget)?;
    let set = OutputSet::begin(&a.out)?;
    let progress = crate::progress::Progress::new(
        false,
        "record import: map",
        "rows",
        maps::procedural::progress_rows(&recipe.terrain),
    );
    let layers = maps::procedural::generate_observed(&recipe.terrain, &|| progress.inc());
    progress.finish();
    let staging_map = set.staging_path(map_dir)?;
    layers
        .write_dir(&staging_map, recipe.dem_datum_m, &recipe.crs)
        .with_context(|| format!("{}: cannot write the map", a.out.join(map_dir).display()))?;
    set.write(
        &format!("{map_dir}/recipe.toml"),
        imported.recipe_toml.as_bytes(),
    )?;
    // Passages: placed where the replay, run without them, starts each sol.
    let scenario_path = set.write(&scenario_file, imported.scenario_toml.as_bytes())?;
    set.write(
        &zones_file,
        br#"{"type": "FeatureCollection", "features": []}"#,
    )?;
    let staged = staging_map
        .parent()
        .unwrap_or(&staging_map)
        .join(&scenario_file);
    let bare = study::Scenario::load_within(&staged, budget)?;
    let (zones, passages) = imported.place_passages(&imported.passage_starts(&bare));
    set.write(&zones_file, zones.as_bytes())?;
    set.write(
        "import-report.txt",
        imported.report_text(passages).as_bytes(),
    )?;
    set.commit()?;
    let summary = imported.summary(&layer.name, &scenario_path, &zones_file, map_dir, passages);
    write!(out, "{summary}")?;
    Ok(())
}

fn baseline_cmd(
    a: &BaselineArgs,
    budget: MemoryBudget,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    let scenario = study::Scenario::load_within(&a.scenario, budget)?;
    study::baseline::require_record(&scenario, &a.scenario)?;
    let b = study::baseline::ground_vs_record(&scenario, a.runs);
    if a.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&b)?)?;
    } else {
        write!(out, "{}", b.text())?;
    }
    Ok(())
}
