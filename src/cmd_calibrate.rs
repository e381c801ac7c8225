//! `solsim calibrate`: re-derive a calibrated constant of the model from a scenario's record.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context as _;
use clap::{Args, Subcommand};
use maps::MemoryBudget;
use study::Scenario;
use study::calibrate::{calibrate_drive_rate, calibrate_vo};

/// `solsim calibrate`.
#[derive(Subcommand)]
pub enum CalibrateCommand {
    /// The VO failure probability on soil, from a record's distance without VO (the shipped
    /// value comes from `solsim calibrate vo scenarios/sol717-719.toml`: 0.289 m of 655.8 m).
    ///
    /// Re-simulates the ground strategy over run indices 0..RUNS to find the share of distance
    /// on each terrain class, then solves p_soil · Σ share · relative = novo / distance, the
    /// relative rates per class being judgement (sand 10, soil 1, bedrock 0.5). Prints the
    /// solved and the shipped value, and the distance without VO the shipped value gives on
    /// the same drives, against the record.
    Vo(VoArgs),
    /// The AutoNav drive rate at which the ground strategy, re-simulated, drives as many metres
    /// per drive sol as the record, over the sols both drove to their end (a faulted drive says
    /// nothing of the rate). For scenarios whose historic sols have no speed of their own (e.g.
    /// scenarios/crater-floor-passage.toml); one written by `solsim record import` drives each
    /// historic sol at its own speed, its distance over its window, and is refused.
    ///
    /// Bisects the rate; each step runs the ground strategy over run indices 0..RUNS. Prints
    /// the record's metres per drive sol, the scenario's rate and what ground drives at it, and
    /// the calibrated rate.
    DriveRate(VoArgs),
}

/// `solsim calibrate vo` and `solsim calibrate drive-rate`.
#[derive(Args)]
pub struct VoArgs {
    /// Scenario with a historic record (historic_distance_m, and for `vo` historic_novo_m, per
    /// sol).
    scenario: PathBuf,
    /// Ground re-simulations (run indices 0..RUNS).
    #[arg(long, value_name = "N", default_value_t = 200,
          value_parser = clap::value_parser!(u64).range(2..=100_000))]
    runs: u64,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
}

/// Run `solsim calibrate …`.
///
/// # Errors
/// A scenario that cannot be loaded or has no record to calibrate to.
pub fn run(
    cmd: &CalibrateCommand,
    budget: MemoryBudget,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    let (json, text) = match cmd {
        CalibrateCommand::Vo(a) => {
            let scenario = Scenario::load_within(&a.scenario, budget)?;
            let c = calibrate_vo(&scenario, a.runs)?;
            (a.json.then(|| serde_json::to_string_pretty(&c)), c.text())
        }
        CalibrateCommand::DriveRate(a) => {
            let scenario = Scenario::load_within(&a.scenario, budget)?;
            let c = calibrate_drive_rate(&scenario, a.runs)?;
            (a.json.then(|| serde_json::to_string_pretty(&c)), c.text())
        }
    };
    match json {
        Some(json) => writeln!(out, "{}", json.context("serialising the calibration")?)?,
        None => write!(out, "{text}")?,
    }
    Ok(())
}
