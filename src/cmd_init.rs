//! `solsim init SCENARIO.toml`: a commented starter scenario that runs as written.
//!
//! It is `solsim route import` ([`crate::cmd_route`]) of the bundled example track,
//! `scenarios/tracks/jezero-example.geojson` ([`study::track_file::example_track`], compiled
//! in, so `init` works anywhere), with one example keep-out beside the route to show the zones
//! format.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use maps::MemoryBudget;
use study::track_file::EXAMPLE_TRACK;

use crate::cmd_route::StarterArgs;

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
    let track = study::track_file::example_track()?;
    let source = format!(
        "solsim's example track ({EXAMPLE_TRACK}: 1.46 km north-east from the Octavia E. Butler landing site)"
    );
    crate::cmd_route::write_starter(
        Path::new(EXAMPLE_TRACK),
        &track,
        source,
        true,
        &a.scenario,
        &a.starter,
        budget,
        out,
    )
}
