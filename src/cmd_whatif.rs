//! `solsim whatif BASE VARIANT --runs N`: one strategy on two versions of a scenario that differ
//! in a setting, paired run by run ([`sweep::whatif`]).

use std::io::Write;
use std::path::PathBuf;

use maps::MemoryBudget;
use sim::Strategy;
use study::Scenario;
use sweep::whatif::{WhatifRun, table};

use crate::progress::Progress;

/// Arguments of `solsim whatif`.
#[derive(clap::Args, Debug)]
pub struct WhatifArgs {
    /// The scenario as it is.
    pub base: PathBuf,
    /// The scenario with the setting changed: the same seed (so the runs pair), the same
    /// sols and route.
    pub variant: PathBuf,
    /// Run indices 0..N (2 to 100000).
    #[arg(long, value_parser = clap::value_parser!(u64).range(2..=100_000))]
    pub runs: u64,
    /// The strategy both run under.
    #[arg(long, default_value = "ground")]
    pub strategy: String,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Run `solsim whatif`.
///
/// # Errors
/// A scenario that does not load, different seeds, a strategy that does not apply.
pub fn run(a: &WhatifArgs, budget: MemoryBudget, stdout: &mut dyn Write) -> anyhow::Result<()> {
    let strategy = Strategy::from_name(&a.strategy).ok_or_else(|| {
        anyhow::anyhow!(
            "--strategy {}: expected one of replay, ground, onboard, extension, extension+onboard",
            a.strategy
        )
    })?;
    let base = Scenario::load_within(&a.base, budget)?;
    let variant = Scenario::load_within(&a.variant, budget)?;
    let plan = WhatifRun::new(&base, &variant, strategy, a.runs, budget)?;
    let progress = Progress::new(false, "whatif", "runs", 2 * a.runs);
    let w = plan.run(&|done, total| progress.update(done, total));
    progress.finish();
    let w = w?;
    if a.json {
        writeln!(stdout, "{}", serde_json::to_string_pretty(&w)?)?;
    } else {
        write!(stdout, "{}", table(&w))?;
    }
    Ok(())
}
