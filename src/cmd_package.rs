//! `solsim map package SCENARIO --out DIR`: the onboard map package of a scenario's route
//! ([`localization::map_package`], under the scenario's seeds: [`study::map_package`]), written
//! as an [`OutputSet`]: into a staging directory and swapped into place whole, so DIR holds an
//! earlier package or this one, never a mix, and no tile of an earlier package is left beside a
//! new manifest. DIR must be new, empty or an earlier solsim output.

use std::path::PathBuf;
use std::time::Instant;

use localization::map_package::{BLOCK_M, MANIFEST_FILE, PackageOptions, summary_text};
use study::Scenario;

use outputs::output_set::OutputSet;

/// Arguments of `solsim map package`.
#[derive(Debug, clap::Args)]
pub struct PackageArgs {
    /// Scenario file (TOML): its map and its route.
    pub scenario: PathBuf,
    /// Output directory for the tiles (PNG, each with a .pgw world file and a .png.aux.xml
    /// naming its CRS) and manifest.json.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Corridor half-width: pixels farther than this from the route are masked, metres.
    #[arg(long, default_value_t = 100.0, value_name = "M")]
    pub corridor_m: f64,
    /// Appearance pixel size, metres: 0.25 (the orthoimage), 0.5 or 1 (binned). The DEM is 1 m.
    #[arg(long, default_value_t = 0.25, value_name = "M")]
    pub resolution_m: f64,
    /// Side of the output tiles, metres (each tile is one appearance and one DEM PNG).
    #[arg(long, default_value_t = 1024, value_name = "M")]
    pub tile_m: usize,
    /// Side of the render blocks, metres (a check of seamlessness: the package must not change
    /// with it).
    #[arg(long, default_value_t = BLOCK_M, value_name = "M", hide = true)]
    pub block_m: usize,
    /// Print what was written as JSON (corridor area, pixels, tiles with their files, sizes
    /// and MD5s, total bytes, datum, seconds) instead of the text summary.
    #[arg(long)]
    pub json: bool,
}

/// Run `solsim map package`: render, mask, write, and print the sizes.
pub fn run(
    args: &PackageArgs,
    budget: maps::MemoryBudget,
    out: &mut dyn std::io::Write,
) -> anyhow::Result<()> {
    let start = Instant::now();
    let options = PackageOptions {
        corridor_m: args.corridor_m,
        resolution_m: args.resolution_m,
        tile_m: args.tile_m,
        block_m: args.block_m,
    };
    options.check(budget)?;
    let scenario = Scenario::load_within(&args.scenario, budget)?;
    // Fails before rendering if the directory cannot take the package.
    let set = OutputSet::begin(&args.out)?;
    let mut package = study::map_package::package_of(&scenario, &args.scenario, &options)?;
    let tiles = package.layout().tiles.clone();
    let progress =
        crate::progress::Progress::new(false, "map package", "tiles", tiles.len() as u64);
    for tile in &tiles {
        for (name, bytes) in package.render_tile(tile, &args.out)? {
            set.write(&name, &bytes)?;
        }
        progress.inc();
    }
    progress.finish();
    let manifest = package.manifest();
    set.write(MANIFEST_FILE, manifest.as_bytes())?;
    set.commit()?;
    let summary = package.summary(manifest.len() as u64, start.elapsed().as_secs_f64());
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&summary)?)?;
    } else {
        let text = summary_text(&scenario.name, &args.out, package.layout(), &summary);
        write!(out, "{text}")?;
    }
    Ok(())
}
