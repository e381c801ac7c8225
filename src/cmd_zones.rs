//! `solsim zones check`: how far points are from a map's keep-in and keep-out zones — the
//! points CSV is [`study::point_files`]'s, the check, its table and JSON
//! [`maps::zone_check`]'s.

use anyhow::{Context, bail};
use maps::ZoneSet;
use std::io::Write;
use std::path::PathBuf;
use study::point_files::read_points;

/// Check points against a map's zones: distance to the nearest keep-out zone, distance to the
/// edge of the keep-in area, the largest position uncertainty each point tolerates, and where
/// the point is.
///
/// max_uncertainty_m = min of the two distances − footprint radius. Negative means the point is
/// not drivable at any uncertainty; it is not a depth: inside a keep-out (or outside the keep-in
/// area) the distance is 0, so the number is minus the footprint radius however deep the point
/// lies. The status column says where the point is: clear, footprint touches a zone (outside
/// every zone but nearer one than the footprint radius), inside keep-out (NAME, …; edges count
/// as inside), outside keep-in. --json gives the same with the flags inside_keep_out and
/// outside_keep_in.
#[derive(Debug, Clone, clap::Args)]
pub struct ZonesCheckArgs {
    /// Zones file: a GeoJSON FeatureCollection of Polygon/MultiPolygon features in map metres,
    /// with properties `kind` ("keep_in" or "keep_out") and optional `name`.
    #[arg(long, value_name = "FILE")]
    pub zones: PathBuf,

    /// Points CSV: a header row naming the columns x_m, y_m and optionally name (any order), then
    /// one point per row in map metres.
    #[arg(long, value_name = "FILE")]
    pub points: PathBuf,

    /// Rover footprint radius in metres, subtracted from the nearer zone distance to give
    /// max_uncertainty_m.
    #[arg(long, value_name = "METRES", default_value_t = 0.0)]
    pub footprint_radius_m: f64,

    /// Print a JSON array of objects (infinite distances as null) instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Run `solsim zones check`, writing the table (or JSON) to `out`.
///
/// # Errors
/// An unreadable or invalid zones file (a [`maps::ZoneError`]) or points file (naming the line and
/// column), a negative or non-finite footprint radius, or a failed write.
pub fn run(args: &ZonesCheckArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    let footprint = args.footprint_radius_m;
    let range = sim::grid::planning_grid::GridSettings::FOOTPRINT_RADIUS_RANGE_M;
    if !range.contains(footprint) {
        bail!(
            "--footprint-radius-m: expected {} ..= {} {}, got {footprint}",
            range.min,
            range.max,
            range.unit
        );
    }
    let zones = ZoneSet::load(&args.zones)?;
    let points = read_points(&args.points)?;
    let named: Vec<(&str, [f64; 2])> = points.iter().map(|p| (p.name.as_str(), p.xy)).collect();
    let rows = zones.check_points(&named, footprint);
    let written = if args.json {
        serde_json::to_string_pretty(&rows)
            .map_err(std::io::Error::from)
            .and_then(|text| writeln!(out, "{text}"))
    } else {
        write!(out, "{}", maps::zone_check::table(&rows))
    };
    match written {
        // A closed pipe (`| head`) means the reader has seen enough, not that the check failed.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        written => written.context("writing the zones check output"),
    }
}
