//! Paper 004 Table 1 with the EKF of `localization::ekf`: the four cases over the paper's 1000 s
//! drive, for the bias-estimating filter and the paper's 4-state filter, over many seeds.
//!
//! ```text
//! cargo run --release -p localization --example ekf_table1 -- --out DIR [--seeds 20] [--first-seed 1]
//! ```
//!
//! Writes, for the first seed, `DIR/ekf_case{1..4}.csv` (bias-estimating filter) and
//! `DIR/ekf_case{1..4}_paper.csv` (the paper's filter), one row per second:
//! `t_s,east_err_m,north_err_m,total_err_m,sigma_east_m,sigma_north_m` (error = estimate − truth;
//! σ = the filter's 1σ); and `DIR/ekf_table1_runs.csv` with every run's error summary. Prints,
//! per filter and case, the mean ± standard deviation over the seeds of the final, RMS and maximum
//! total error, over the whole run and over its last 500 s, beside the paper's figure.

use std::fmt::Write as _;
use std::path::PathBuf;

use localization::ekf::{CaseRun, CaseSettings, FilterModel, Table1Case, ix, run_with};

/// The command line: `--out DIR`, `--seeds N`, `--first-seed S`.
struct Args {
    out: PathBuf,
    seeds: u64,
    first_seed: u64,
}

fn parse_args() -> Result<Args, String> {
    let mut out = None;
    let (mut seeds, mut first_seed) = (20, 1);
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--out" => out = Some(PathBuf::from(value()?)),
            "--seeds" => seeds = value()?.parse().map_err(|e| format!("--seeds: {e}"))?,
            "--first-seed" => {
                first_seed = value()?.parse().map_err(|e| format!("--first-seed: {e}"))?;
            }
            other => return Err(format!("unknown argument {other:?}")),
        }
    }
    let out = out.ok_or("usage: ekf_table1 --out DIR [--seeds N] [--first-seed S]")?;
    if seeds == 0 {
        return Err("--seeds must be at least 1".into());
    }
    Ok(Args {
        out,
        seeds,
        first_seed,
    })
}

/// Mean and (sample) standard deviation.
fn mean_sd(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (mean, var.sqrt())
}

fn error_csv(run: &CaseRun) -> String {
    let mut csv =
        String::from("t_s,east_err_m,north_err_m,total_err_m,sigma_east_m,sigma_north_m\n");
    for s in &run.steps {
        let [se, sn] = s.sigma_enu_m();
        writeln!(
            csv,
            "{},{:.6},{:.6},{:.6},{:.6},{:.6}",
            s.truth.t_s, s.error_east_m, s.error_north_m, s.error_total_m, se, sn
        )
        .expect("writing to a String cannot fail");
    }
    csv
}

/// Per-run figures: final, RMS and max total error over the run and the last 500 s, the filter's
/// final 1σ radius, and the final accelerometer-bias estimate error.
struct RunFigures {
    final_m: f64,
    rms_m: f64,
    max_m: f64,
    rms_last_m: f64,
    max_last_m: f64,
    sigma_final_m: f64,
}

fn figures(run: &CaseRun) -> RunFigures {
    let half = run.settings.duration_s / 2;
    let all = run.error_summary(0).expect("a run has seconds");
    let last = run.error_summary(half).expect("a run has its second half");
    let end = run.steps.last().expect("a run has seconds");
    let [se, sn] = end.sigma_enu_m();
    RunFigures {
        final_m: all.final_m,
        rms_m: all.rms_m,
        max_m: all.max_m,
        rms_last_m: last.rms_m,
        max_last_m: last.max_m,
        sigma_final_m: se.hypot(sn),
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = parse_args()?;
    std::fs::create_dir_all(&args.out)?;
    let seeds: Vec<u64> = (args.first_seed..args.first_seed + args.seeds).collect();
    let mut runs_csv = String::from(
        "model,case,seed,final_m,rms_m,max_m,rms_last500_m,max_last500_m,sigma_final_m,\
         accel_bias_err_x_m_per_s2,accel_bias_err_y_m_per_s2,ranges\n",
    );
    println!(
        "Paper 004 Table 1 — {} seeds ({}..={}), 1000 s, mean ± sd over seeds (metres)",
        seeds.len(),
        seeds[0],
        seeds[seeds.len() - 1]
    );
    println!(
        "{:<16} {:>4} {:>14} {:>17} {:>17} {:>17} {:>17} {:>17} {:>9}",
        "filter",
        "case",
        "paper",
        "final",
        "RMS 0-1000 s",
        "max 0-1000 s",
        "RMS 500-1000 s",
        "max 500-1000 s",
        "1σ final"
    );
    for (model, name, suffix) in [
        (FilterModel::BiasEstimating, "bias-estimating", ""),
        (FilterModel::Paper, "paper 4-state", "_paper"),
    ] {
        for case in Table1Case::ALL {
            let settings = CaseSettings::table1(case).with_model(model);
            let mut figs = Vec::with_capacity(seeds.len());
            for &seed in &seeds {
                let run = run_with(&settings, seed)?;
                if seed == seeds[0] {
                    let path = args
                        .out
                        .join(format!("ekf_case{}{suffix}.csv", case.number()));
                    std::fs::write(path, error_csv(&run))?;
                }
                let f = figures(&run);
                let end = run.steps.last().expect("a run has seconds");
                let bias = settings.imu.accel_bias_m_per_s2;
                writeln!(
                    runs_csv,
                    "{name},{},{seed},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.3e},{:.3e},{}",
                    case.number(),
                    f.final_m,
                    f.rms_m,
                    f.max_m,
                    f.rms_last_m,
                    f.max_last_m,
                    f.sigma_final_m,
                    end.estimate[ix::ACCEL_BIAS_X] - bias[0],
                    end.estimate[ix::ACCEL_BIAS_Y] - bias[1],
                    run.streams.ranges.len()
                )?;
                figs.push(f);
            }
            let cell = |pick: fn(&RunFigures) -> f64| {
                let (m, s) = mean_sd(&figs.iter().map(pick).collect::<Vec<_>>());
                format!("{m:>7.3} ± {s:<7.3}")
            };
            println!(
                "{:<16} {:>4} {:>14} {:>17} {:>17} {:>17} {:>17} {:>17} {:>9.3}",
                name,
                case.number(),
                case.paper_error_m().1,
                cell(|f| f.final_m),
                cell(|f| f.rms_m),
                cell(|f| f.max_m),
                cell(|f| f.rms_last_m),
                cell(|f| f.max_last_m),
                mean_sd(&figs.iter().map(|f| f.sigma_final_m).collect::<Vec<_>>()).0,
            );
        }
    }
    std::fs::write(args.out.join("ekf_table1_runs.csv"), runs_csv)?;
    println!("wrote {}", args.out.display());
    Ok(())
}
