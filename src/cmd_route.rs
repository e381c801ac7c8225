//! `solsim route import TRACK --out SCENARIO.toml`: a scenario of your own from a track in Mars
//! longitude and latitude ([`study::track_file`]), on a procedural map placed around it
//! ([`study::starter`], [`study::starter_output`]). `solsim init` writes the same files for a
//! bundled example track.
//!
//! What is written, beside `SCENARIO.toml`: `SCENARIO.map/` with the map's GeoTIFFs
//! (appearance, DEM, terrain classes; the Jezero equirectangular CRS through the track's first
//! point), its `recipe.toml` and the zones file `zones.geojson`. The folder is one output set
//! ([`OutputSet`]: written aside and swapped into place whole); the scenario file is written
//! last, to a temporary file renamed into place ([`outputs::run_files::write_atomic`]), so a
//! scenario file never names a map that is not there, and a failure leaves nothing half
//! written.
//!
//! Before anything is put in place the scenario is loaded from the staged files and checked as
//! `solsim validate` checks it. A procedural crater can swallow a waypoint (a leg with no path
//! even at r = 0); the map is then generated again with the next seed, up to
//! [`study::starter_output::MAP_SEED_ATTEMPTS`] seeds, and the seed used is printed and written
//! in the recipe.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use clap::{Args, Subcommand};
use maps::MemoryBudget;
use study::starter::TrackPoint;
use study::starter_output::{StarterFiles, StarterRequest};

use outputs::output_set::OutputSet;

/// `solsim route`.
#[derive(Subcommand)]
pub enum RouteCommand {
    /// Write a scenario for your own traverse from a track in Mars longitude/latitude: the
    /// route, a procedural map around it and a computed calendar, ready for `solsim compare`.
    ///
    /// The track is GeoJSON — a LineString or MultiPoint (bare, as a Feature, or the one
    /// feature of a FeatureCollection), or a FeatureCollection of Point features in file order
    /// — or, for a file named *.csv, CSV with a header row (required) naming a lon and a lat
    /// column (also lon_deg/lat_deg or longitude/latitude; other columns are ignored).
    /// Coordinates are degrees, planetocentric, longitude east-positive (−180 to 360),
    /// latitude north (−90 to 90), on the IAU 2015 Mars sphere (IAU_2015:49900): the frame of
    /// MMGIS and of solsim's own longitude/latitude GIS outputs. A third GeoJSON number
    /// (elevation) is ignored; the map has its own DEM.
    ///
    /// Every point becomes a route waypoint, projected into map metres with the map's CRS, the
    /// Jezero equirectangular projection (true to scale at 18.4663° N; elsewhere map metres
    /// are ground metres × cos 18.4663° / cos latitude, printed) through the track's first
    /// point — the CRS of solsim's GIS outputs, so `compare`'s `gis/<scenario>.route.geojson` gives
    /// the track back within 1e-8° (waypoints are written to the millimetre).
    ///
    /// Written: SCENARIO.toml (every field commented; an AutoNav rate and drive window from
    /// the record of sols 379-409, a Mars 2020 calendar from sol 1100 with one sol per 100 m
    /// of route and 3 more, the other settings at solsim's defaults) and SCENARIO.map/ (the
    /// GeoTIFFs, recipe.toml, an empty zones.geojson for your keep-outs). Refused, exit 2,
    /// nothing written: malformed GeoJSON or CSV, a NaN, a latitude beyond ±90 (±89 for the
    /// map), fewer than 2 points, two consecutive points at the same millimetre, a map over
    /// the memory budget, an existing file without --force.
    ///
    /// Example, then the two commands it prints next:
    /// `solsim route import scenarios/tracks/jezero-example.geojson --out my-traverse.toml`,
    /// `solsim validate my-traverse.toml`, `solsim compare my-traverse.toml`.
    Import(ImportArgs),
}

/// `solsim route import`.
#[derive(Args)]
pub struct ImportArgs {
    /// Track file: GeoJSON, or CSV (*.csv) with a header row naming lon and lat, in degrees
    /// (planetocentric, east longitude).
    track: PathBuf,
    /// The scenario file to write (*.toml); its map and zones go to the folder beside it with
    /// the same name and `.map` for `.toml`.
    #[arg(long, value_name = "SCENARIO.toml")]
    out: PathBuf,
    #[command(flatten)]
    starter: StarterArgs,
}

/// Settings shared by `solsim init` and `solsim route import`.
#[derive(Args)]
pub struct StarterArgs {
    /// Replace an existing scenario file and map folder (the folder only if solsim wrote it).
    #[arg(long)]
    pub force: bool,
    /// Scenario name, the folder name of its outputs (default: the file name without .toml).
    #[arg(long)]
    pub name: Option<String>,
    /// Scenario seed, and the procedural map's (default: the first sol).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Map margin around the route's bounding box on every side, metres (50 to 100000).
    #[arg(long, value_name = "M", default_value_t = study::starter::DEFAULT_MAP_MARGIN_M)]
    pub map_margin_m: f64,
    /// First sol of the computed Mars 2020 calendar (1 to 19000).
    #[arg(long, value_name = "SOL", default_value_t = study::starter::DEFAULT_FIRST_SOL,
          value_parser = clap::value_parser!(u32).range(1..=19_000))]
    pub first_sol: u32,
}

/// Run `solsim route …`.
///
/// # Errors
/// A track that cannot be read or used, an --out that cannot be written.
pub fn run(cmd: &RouteCommand, budget: MemoryBudget, out: &mut impl Write) -> anyhow::Result<()> {
    match cmd {
        RouteCommand::Import(a) => {
            let track = study::track_file::read_track(&a.track)?;
            let source = format!("the track {}", a.track.display());
            write_starter(
                &a.track, &track, source, false, &a.out, &a.starter, budget, out,
            )
        }
    }
}

/// Place `track` (from `track_path`) on a map and write the scenario `scenario` and its map
/// folder, as the module docs say; print what was written and the next three commands.
///
/// # Errors
/// Any bad input, named; nothing is left half written.
#[allow(clippy::too_many_arguments)]
pub fn write_starter(
    track_path: &Path,
    track: &[TrackPoint],
    source: String,
    example_keep_out: bool,
    scenario: &Path,
    a: &StarterArgs,
    budget: MemoryBudget,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    let request = StarterRequest {
        force: a.force,
        name: a.name.clone(),
        seed: a.seed,
        map_margin_m: a.map_margin_m,
        first_sol: a.first_sol,
        source,
        example_keep_out,
    };
    let files = StarterFiles::plan(scenario, track_path, track, &request, budget)?;
    let (starter, map_dir) = (&files.starter, &files.map_dir);
    OutputSet::check(map_dir)?;
    let mut rejected: Vec<String> = Vec::new();
    let mut placed = None;
    for map_seed in files.map_seeds() {
        let recipe_text = starter.recipe_toml(map_seed);
        let recipe_path = map_dir.join("recipe.toml");
        let recipe = study::recipe::recipe_from_toml_str(&recipe_path, &recipe_text, budget)?;
        let set = OutputSet::begin(map_dir)?;
        let progress = crate::progress::Progress::new(
            false,
            "route import: map",
            "rows",
            maps::procedural::progress_rows(&recipe.terrain),
        );
        let layers = maps::procedural::generate_observed(&recipe.terrain, &|| progress.inc());
        progress.finish();
        // The set's own folder (an empty name inside it).
        let staging = set.staging_path("")?;
        layers
            .write_dir(&staging, recipe.dem_datum_m, &recipe.crs)
            .with_context(|| format!("{}: cannot write the map", map_dir.display()))?;
        set.write("recipe.toml", recipe_text.as_bytes())?;
        set.write("zones.geojson", starter.zones_geojson.as_bytes())?;
        // The scenario as `validate` sees it, from the staged files.
        let check_toml = starter.scenario_toml(".", "zones.geojson", map_seed);
        set.write(".check.toml", check_toml.as_bytes())?;
        let check = staging.join(".check.toml");
        let (_, findings) = study::Scenario::inspect_within(&check, budget)?;
        std::fs::remove_file(&check).with_context(|| format!("{}", check.display()))?;
        match findings
            .iter()
            .find(|f| f.severity == study::sanity::Severity::Error)
        {
            None => {
                set.commit()?;
                placed = Some(map_seed);
                break;
            }
            Some(f) => rejected.push(format!("seed {map_seed}: {}", f.field)),
        }
        // Dropped uncommitted: the staging folder goes, the target stays as it was.
    }
    let map_seed = placed.ok_or_else(|| files.blocked(track_path, &rejected))?;
    outputs::run_files::write_atomic(scenario, files.scenario_toml(map_seed).as_bytes())
        .with_context(|| format!("{}: cannot write the scenario", scenario.display()))?;
    write!(out, "{}", files.summary(map_seed, rejected.len()))?;
    Ok(())
}
