//! `solsim route import TRACK --out SCENARIO.toml`: a scenario of your own from a track in Mars
//! longitude and latitude ([`crate::track_file`]), on a procedural map placed around it
//! ([`study::starter`]). `solsim init` writes the same files for a bundled example track.
//!
//! What is written, beside `SCENARIO.toml`: `SCENARIO.map/` with the map's GeoTIFFs
//! (appearance, DEM, terrain classes; the Jezero equirectangular CRS through the track's first
//! point), its `recipe.toml` and the zones file `zones.geojson`. The folder is one output set
//! ([`OutputSet`]: written aside and swapped into place whole); the scenario file is written
//! last, to a temporary file renamed into place ([`crate::report::write_atomic`]), so a
//! scenario file never names a map that is not there, and a failure leaves nothing half
//! written.
//!
//! Before anything is put in place the scenario is loaded from the staged files and checked as
//! `solsim validate` checks it. A procedural crater can swallow a waypoint (a leg with no path
//! even at r = 0); the map is then generated again with the next seed, up to
//! [`MAP_SEED_ATTEMPTS`] seeds, and the seed used is printed and written in the recipe.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::{Args, Subcommand};
use maps::MemoryBudget;
use study::starter::{Starter, StarterOptions, TrackPoint};

use crate::output_set::OutputSet;

/// Map seeds tried, from the scenario's seed on, before the route is reported as blocked.
pub const MAP_SEED_ATTEMPTS: u64 = 8;

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
            let track = crate::track_file::read_track(&a.track)?;
            let source = format!("the track {}", a.track.display());
            write_starter(
                &a.track, &track, &source, false, &a.out, &a.starter, budget, out,
            )
        }
    }
}

/// The companions of scenario file `scenario`: its map folder (`NAME.map/`).
///
/// # Errors
/// A path that does not end in `.toml`.
pub fn map_dir_of(scenario: &Path) -> anyhow::Result<PathBuf> {
    let is_toml = scenario
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let Some(stem) = scenario.file_stem().filter(|_| is_toml) else {
        bail!(
            "{}: expected a scenario file name ending in .toml",
            scenario.display()
        );
    };
    let mut name = stem.to_os_string();
    name.push(".map");
    Ok(scenario.with_file_name(name))
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
    source: &str,
    example_keep_out: bool,
    scenario: &Path,
    a: &StarterArgs,
    budget: MemoryBudget,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    let map_dir = map_dir_of(scenario)?;
    if !study::starter::MAP_MARGIN_RANGE_M.contains(&a.map_margin_m) {
        bail!(
            "--map-margin-m: expected {}, got {}",
            study::starter::MAP_MARGIN_EXPECTED,
            a.map_margin_m
        );
    }
    let name = match &a.name {
        Some(n) => {
            study::scenario::check_name(n).map_err(|e| anyhow::anyhow!("--name: expected {e}"))?;
            n.clone()
        }
        None => {
            let stem = scenario
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            study::scenario::check_name(&stem).map_err(|e| {
                anyhow::anyhow!(
                    "{}: the file name makes the scenario name: expected {e} (or give --name)",
                    scenario.display()
                )
            })?;
            stem
        }
    };
    let mut options = StarterOptions::new(&name, source);
    options.first_sol = a.first_sol;
    options.seed = a.seed.unwrap_or(u64::from(a.first_sol));
    options.map_margin_m = a.map_margin_m;
    options.example_keep_out = example_keep_out;
    let starter = Starter::new(track_path, track, &options, budget)?;

    // Nothing is replaced without --force; with it, the map folder only if solsim wrote it.
    for p in [scenario, map_dir.as_path()] {
        if p.symlink_metadata().is_ok() && !a.force {
            bail!(
                "{}: expected a new file, but it exists; pass --force to replace it",
                p.display()
            );
        }
    }
    if scenario.is_dir() {
        bail!("{}: expected a file, found a directory", scenario.display());
    }
    OutputSet::check(&map_dir)?;
    let map_name = map_dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();

    let mut rejected: Vec<String> = Vec::new();
    let mut placed = None;
    for attempt in 0..MAP_SEED_ATTEMPTS {
        let map_seed = options.seed.wrapping_add(attempt);
        let recipe_text = starter.recipe_toml(map_seed);
        let recipe = study::recipe::recipe_from_toml_str(
            &map_dir.join("recipe.toml"),
            &recipe_text,
            budget,
        )?;
        let set = OutputSet::begin(&map_dir)?;
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
        set.write(
            ".check.toml",
            starter
                .scenario_toml(".", "zones.geojson", map_seed)
                .as_bytes(),
        )?;
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
    let Some(map_seed) = placed else {
        bail!(
            "{}: the procedural maps of seeds {}..={} all block the route ({}); move the points, or try another --seed",
            track_path.display(),
            options.seed,
            options.seed.wrapping_add(MAP_SEED_ATTEMPTS - 1),
            rejected.join("; ")
        );
    };
    crate::report::write_atomic(
        scenario,
        starter
            .scenario_toml(&map_name, &format!("{map_name}/zones.geojson"), map_seed)
            .as_bytes(),
    )
    .with_context(|| format!("{}: cannot write the scenario", scenario.display()))?;

    let [w, h] = starter.map_px;
    let r = starter.resolution_m_per_px;
    writeln!(
        out,
        "wrote {} (+ {}/: map, recipe.toml, zones.geojson): {} waypoints, {:.0} m of route from {source}",
        scenario.display(),
        map_dir.display(),
        starter.route_m.len(),
        starter.route_length_m,
    )?;
    writeln!(
        out,
        "  map: {:.0} × {:.0} m at {r} m/px, {} m around the route, procedural (seed {map_seed}{}); CRS {}",
        w as f64 * r,
        h as f64 * r,
        options.map_margin_m,
        if rejected.is_empty() {
            String::new()
        } else {
            format!(
                "; seed{} {} put a waypoint where the map blocks it",
                if rejected.len() == 1 { "" } else { "s" },
                (options.seed..map_seed)
                    .map(|s| s.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        },
        starter.crs.name()
    )?;
    if (starter.easting_scale - 1.0).abs() > 0.01 {
        writeln!(
            out,
            "  note: the track lies far from 18.4663° N, where the projection is true to scale: east-west map metres are {:.3} ground metres",
            1.0 / starter.easting_scale
        )?;
    }
    writeln!(
        out,
        "  calendar: Mars 2020 sols {}-{}, computed (uplinks, weekends, restricted sols); zones: {}",
        starter.sols.start(),
        starter.sols.end(),
        if example_keep_out {
            "one example keep-out"
        } else {
            "none yet (add keep-outs to zones.geojson)"
        }
    )?;
    let s = scenario.display();
    writeln!(out, "next:")?;
    writeln!(out, "  solsim validate {s}")?;
    writeln!(out, "  solsim compare {s}")?;
    writeln!(out, "  solsim compare {s} --runs 100 --report")?;
    Ok(())
}
