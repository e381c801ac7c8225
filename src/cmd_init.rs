//! `solsim init SCENARIO.toml`: a commented starter scenario that runs as written.
//!
//! It is `solsim route import` ([`crate::cmd_route`]) of the bundled example track,
//! `scenarios/tracks/jezero-example.geojson` (compiled in, so `init` works anywhere), with one
//! example keep-out beside the route to show the zones format.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use maps::MemoryBudget;

use crate::cmd_route::StarterArgs;

/// The bundled example track, relative to the repository.
pub const EXAMPLE_TRACK: &str = "scenarios/tracks/jezero-example.geojson";

/// The example track's text.
const EXAMPLE_TRACK_TEXT: &str = include_str!("../scenarios/tracks/jezero-example.geojson");

/// `solsim init`.
#[derive(Args)]
pub struct InitArgs {
    /// The scenario file to write (*.toml); its map folder (GeoTIFFs, recipe.toml,
    /// zones.geojson) goes beside it with `.map` for `.toml`.
    pub scenario: PathBuf,
    /// Settings shared with `route import`.
    #[command(flatten)]
    pub starter: StarterArgs,
}

/// Run `solsim init`.
///
/// # Errors
/// An existing file without --force, a path that cannot be written, a bad option.
pub fn run(a: &InitArgs, budget: MemoryBudget, out: &mut impl Write) -> anyhow::Result<()> {
    let path = Path::new(EXAMPLE_TRACK);
    let track = crate::track_file::parse_geojson(EXAMPLE_TRACK_TEXT, path)?;
    let source = format!(
        "solsim's example track ({EXAMPLE_TRACK}: 1.46 km north-east from the Octavia E. Butler landing site)"
    );
    crate::cmd_route::write_starter(
        path,
        &track,
        &source,
        true,
        &a.scenario,
        &a.starter,
        budget,
        out,
    )
}
