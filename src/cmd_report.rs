//! `solsim report DIR --out OUT`: the HTML report of a compare output directory or a sweep
//! directory. The arguments and the progress are here; what is checked and written is
//! [`outputs::report_dir`], the page [`outputs::html`].

use std::io::Write;
use std::path::PathBuf;

use anyhow::bail;
use clap::Args;
use maps::MemoryBudget;
use outputs::report_dir::{ReportProgress, ReportRequest, write_report};

use crate::progress::Progress;

/// `solsim report`'s arguments.
#[derive(Args)]
pub struct ReportArgs {
    /// A `solsim compare` output directory (with its `<scenario>.<strategy>.json` files) or a
    /// complete `solsim sweep` directory (with manifest.json).
    #[arg(value_name = "RUN_OR_SWEEP_DIR")]
    pub dir: PathBuf,
    /// Directory for report.html, replaced whole (it must be new, empty, or an earlier
    /// solsim output).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The scenario file of a compare directory, when it is no longer at the path its
    /// provenance names (relative paths are taken from the current directory).
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Grow the keep-outs on the whole-traverse maps and the fault zooms by this uncertainty r,
    /// metres [default: each keep-out by the r the rover had where its path came closest to
    /// it; each fault's zoom by the fault's r].
    #[arg(long, value_name = "R")]
    pub map_r_m: Option<f64>,
    /// Print what was written as one JSON document instead of the line of text: `{"report"
    /// (the path of report.html), "kind" ("compare" or "sweep"), "title", "figures" (inline),
    /// "bytes", "dir" (the directory reported on)}`.
    #[arg(long)]
    pub json: bool,
}

/// Checks `--map-r-m`.
///
/// # Errors
/// A negative, non-finite or absurd value.
pub fn check_map_r(r: Option<f64>) -> anyhow::Result<()> {
    match r {
        Some(r) if !(r.is_finite() && (0.0..=10_000.0).contains(&r)) => {
            let got = if r.abs() < 1e6 {
                format!("{r}")
            } else {
                format!("{r:e}")
            };
            bail!("--map-r-m: expected an uncertainty radius from 0 to 10000 metres, got {got}")
        }
        _ => Ok(()),
    }
}

/// Runs `solsim report`.
///
/// # Errors
/// A directory that is neither a compare output nor a complete sweep; a run that the scenario
/// no longer gives; an unwritable `--out`.
pub fn run(a: &ReportArgs, budget: MemoryBudget, stdout: &mut dyn Write) -> anyhow::Result<()> {
    check_map_r(a.map_r_m)?;
    let request = ReportRequest {
        dir: &a.dir,
        out: &a.out,
        scenario: a.scenario.as_deref(),
        map_r_m: a.map_r_m,
    };
    let steps = Progress::new(false, "report", "steps", 3);
    let runs = Progress::new(false, "compare", "runs", 0);
    let written = write_report(&request, budget, &|p| match p {
        ReportProgress::Step => steps.inc(),
        ReportProgress::Runs { done, total } => runs.update(done, total),
    });
    runs.finish();
    steps.finish();
    let written = written?;
    if a.json {
        let doc = serde_json::json!({
            "report": written.path.display().to_string(),
            "kind": written.kind.name(),
            "title": written.title,
            "figures": written.figures,
            "bytes": written.bytes,
            "dir": a.dir.display().to_string(),
        });
        writeln!(stdout, "{}", serde_json::to_string_pretty(&doc)?)?;
        return Ok(());
    }
    writeln!(
        stdout,
        "wrote {} ({}; {} figures inline, {:.0} KB, no network needed)",
        written.path.display(),
        written.title,
        written.figures,
        written.bytes as f64 / 1024.0
    )?;
    Ok(())
}
