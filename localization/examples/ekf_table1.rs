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
//! σ = the filter's 1σ); `DIR/ekf_table1.svg` and `DIR/ekf_table1_paper.svg`, the total error
//! against time of the four cases (first seed) with the filter's 3σ radius and the paper's
//! figure (paper 004 Figs. 3, 5, 7, 9); and `DIR/ekf_table1_runs.csv` with every run's error
//! summary. Prints,
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

/// The four cases' total error (first seed) against time, one panel each, with the filter's 3σ
/// radius (3·√(σ_e² + σ_n²)) and the paper's figure as a dashed line.
fn error_figure(
    path: &std::path::Path,
    title: &str,
    runs: &[(Table1Case, CaseRun)],
) -> Result<(), Box<dyn std::error::Error>> {
    use plotters::prelude::*;
    let root = SVGBackend::new(path, (1100, 800)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 20))?;
    for ((case, run), area) in runs.iter().zip(root.split_evenly((2, 2))) {
        let three_sigma: Vec<(f64, f64)> = run
            .steps
            .iter()
            .map(|s| {
                let [se, sn] = s.sigma_enu_m();
                (f64::from(s.truth.t_s), 3.0 * se.hypot(sn))
            })
            .collect();
        let error: Vec<(f64, f64)> = run
            .steps
            .iter()
            .map(|s| (f64::from(s.truth.t_s), s.error_total_m))
            .collect();
        let (paper_m, paper_words) = case.paper_error_m();
        // The first seconds hold the prior's 10 m σ: scale to the run after 50 s.
        let top = error
            .iter()
            .chain(&three_sigma)
            .filter(|(t, _)| *t >= 50.0)
            .map(|(_, v)| *v)
            .fold(paper_m, f64::max)
            * 1.1;
        let mut chart = ChartBuilder::on(&area)
            .caption(
                format!(
                    "case {}: {} m image, {} m range (paper: {paper_words})",
                    case.number(),
                    case.image_resolution_m(),
                    case.range_sigma_m()
                ),
                ("sans-serif", 15),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(55)
            .build_cartesian_2d(0.0..1000.0, 0.0..top)?;
        chart
            .configure_mesh()
            .x_desc("time, s")
            .y_desc("total position error, m")
            .draw()?;
        chart
            .draw_series(LineSeries::new(error, BLUE.stroke_width(2)))?
            .label("|estimate - truth|")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
        chart
            .draw_series(LineSeries::new(three_sigma, RED.stroke_width(1)))?
            .label("filter 3-sigma radius")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
        chart
            .draw_series(DashedLineSeries::new(
                vec![(0.0, paper_m), (1000.0, paper_m)],
                6,
                4,
                BLACK.stroke_width(1),
            ))?
            .label("paper's figure")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
    }
    root.present()?;
    Ok(())
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
        let mut first_runs = Vec::new();
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
                    first_runs.push((case, run.clone()));
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
        error_figure(
            &args.out.join(format!("ekf_table1{suffix}.svg")),
            &format!("Paper 004 Table 1, {name} filter, seed {}", seeds[0]),
            &first_runs,
        )?;
    }
    std::fs::write(args.out.join("ekf_table1_runs.csv"), runs_csv)?;
    println!("wrote {}", args.out.display());
    Ok(())
}
