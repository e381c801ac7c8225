//! `solsim calibrate`: re-derive a calibrated constant of the model from a scenario's record.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context as _;
use clap::{Args, Subcommand};
use maps::MemoryBudget;
use study::Scenario;
use study::calibrate::{VoCalibration, calibrate_drive_rate, calibrate_vo};

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
    match cmd {
        CalibrateCommand::Vo(a) => {
            let scenario = Scenario::load_within(&a.scenario, budget)?;
            let c = calibrate_vo(&scenario, a.runs)?;
            if a.json {
                print_json(&c, out)?;
            } else {
                print_vo(&c, out)?;
            }
            Ok(())
        }
        CalibrateCommand::DriveRate(a) => {
            let scenario = Scenario::load_within(&a.scenario, budget)?;
            let c = calibrate_drive_rate(&scenario, a.runs)?;
            if a.json {
                print_json(&c, out)?;
            } else {
                writeln!(
                    out,
                    "{} — drive rate calibration over {} ground re-simulations per step",
                    c.scenario, c.runs
                )?;
                writeln!(
                    out,
                    "record: {:.1} m per drive sol",
                    c.record_m_per_drive_sol
                )?;
                writeln!(
                    out,
                    "at the scenario's rate, {:.1} m/h: ground drives {:.1} m per drive sol",
                    c.scenario_rate_m_per_h, c.ground_m_per_drive_sol_at_scenario_rate
                )?;
                writeln!(
                    out,
                    "calibrated rate: {:.1} m/h (ground then drives {:.1} m per drive sol)",
                    c.calibrated_rate_m_per_h, c.ground_m_per_drive_sol_at_calibrated_rate
                )?;
            }
            Ok(())
        }
    }
}

fn print_json(c: &impl serde::Serialize, out: &mut impl Write) -> anyhow::Result<()> {
    let text = serde_json::to_string_pretty(c).context("serialising the calibration")?;
    writeln!(out, "{text}")?;
    Ok(())
}

fn print_vo(c: &VoCalibration, out: &mut impl Write) -> std::io::Result<()> {
    let pct = |x: f64| 100.0 * x;
    writeln!(
        out,
        "{} — VO failure calibration over {} ground re-simulations",
        c.scenario, c.runs
    )?;
    writeln!(
        out,
        "record: {:.3} m without VO in {:.1} m ({:.4} % of distance)",
        c.record_novo_m,
        c.record_distance_m,
        pct(c.record_novo_m / c.record_distance_m)
    )?;
    writeln!(
        out,
        "terrain under the re-simulated drives: sand {:.1} %, soil {:.1} %, bedrock {:.1} %",
        pct(c.terrain_share.sand),
        pct(c.terrain_share.soil),
        pct(c.terrain_share.bedrock)
    )?;
    writeln!(
        out,
        "relative failure rates (judgement): sand {}, soil {}, bedrock {}",
        c.relative.sand, c.relative.soil, c.relative.bedrock
    )?;
    writeln!(
        out,
        "solved VO failure probability per step on soil: {:.3e} (shipped: {:.3e}, sim::errors::VO_FAILURE_SOIL)",
        c.vo_failure_soil, c.shipped_vo_failure_soil
    )?;
    writeln!(
        out,
        "with the shipped value, metres without VO over the record's distance: {:.3} m [95 % interval {:.3}, {:.3}] (record {:.3} m)",
        c.simulated_novo_m,
        c.simulated_novo_interval_m[0],
        c.simulated_novo_interval_m[1],
        c.record_novo_m
    )
}
