//! `solsim regress`: check the `[[expect]]` entries of every scenario in a directory
//! ([`outputs::regress`], which checks them with `sweep::expect`) and print the report as text
//! or JSON, with a JUnit file for CI. Exit code 1 on a mismatch.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context as _;
use clap::Args;
use maps::MemoryBudget;
use outputs::regress;
use outputs::run_files::write_atomic;

/// `solsim regress` arguments.
#[derive(Args)]
pub struct RegressArgs {
    /// Directory of scenario files (every *.toml in it).
    pub dir: PathBuf,
    /// Also write a JUnit XML report here (for CI).
    #[arg(long, value_name = "FILE")]
    pub junit: Option<PathBuf>,
    /// Print JSON instead of the text report: `{"passed", "failed", "cases": [{"scenario",
    /// "case", "what", "ok", "measured", "mismatches": [{"check", "expected", "got"}],
    /// "seconds"}]}`. The exit code is the same (1 on a mismatch).
    #[arg(long)]
    pub json: bool,
    /// No progress on standard error. Without it, a terminal shows a bar over every [[expect]]
    /// entry with the scenario and stage beside it; a piped or redirected standard error shows
    /// nothing either way.
    #[arg(long, short)]
    #[allow(rustdoc::broken_intra_doc_links)] // `[[expect]]` is the help's TOML, not a link
    pub quiet: bool,
}

/// Runs `solsim regress`: 0 when every entry holds, 1 on a mismatch.
///
/// # Errors
/// A directory that cannot be listed or holds no scenario, a scenario that cannot be loaded, a
/// JUnit file or standard output that cannot be written.
pub fn run(
    a: &RegressArgs,
    budget: MemoryBudget,
    stdout: &mut dyn std::io::Write,
) -> anyhow::Result<ExitCode> {
    let files = regress::scenario_files(&a.dir)
        .with_context(|| format!("{}: cannot list scenario files", a.dir.display()))?;
    if files.is_empty() {
        anyhow::bail!("{}: no scenario files (*.toml) found", a.dir.display());
    }
    // Progress over every [[expect]] entry, the scenario and stage beside the bar.
    let total: usize = files.iter().map(|f| regress::count_expectations(f)).sum();
    let progress = crate::progress::Progress::new(a.quiet, "regress", "checks", total as u64);
    let results = regress::check_scenarios(&files, budget, &|f, stage| match stage {
        regress::Stage::Loading => {
            progress.set_message(format!("{}: loading", f.display()));
        }
        regress::Stage::OneRun { name, checks } if checks > 0 => {
            progress.set_message(format!("{name}: {checks} checks on one run per strategy"))
        }
        regress::Stage::OverRuns { name, checks } if checks > 0 => {
            progress.set_message(format!("{name}: {checks} checks over runs (sweeps)"));
        }
        regress::Stage::Checked(n) => progress.inc_by(n as u64),
        _ => {}
    });
    progress.finish();
    let results = results?;
    if a.json {
        writeln!(stdout, "{}", regress::json_report(&results))?;
    } else {
        write!(stdout, "{}", regress::text_report(&results))?;
    }
    if let Some(path) = &a.junit {
        write_atomic(path, regress::junit(&results).as_bytes())
            .with_context(|| format!("{}: cannot write the JUnit report", path.display()))?;
    }
    let failed = results.iter().any(|r| !r.mismatches.is_empty());
    Ok(if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
