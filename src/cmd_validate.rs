//! `solsim validate`: load a scenario without running it, list what makes no sense in it
//! ([`study::sanity`]) and describe what was loaded ([`study::validation`]).

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use maps::MemoryBudget;
use study::Scenario;
use study::validation::Validation;

/// `solsim validate` arguments.
#[derive(Args)]
pub struct ValidateArgs {
    /// Scenario file (TOML).
    pub scenario: PathBuf,
    /// Print JSON on standard output: `{"file", "ok", "errors", "warnings", "findings":
    /// [{"severity", "field", "expected", "got", "hint"}], "scenario": {...}, "legs": [...]}`;
    /// `scenario.expectations` counts every `[[expect]]` entry, as `solsim regress` does
    /// (`one_run_expectations` + `statistical_expectations`).
    /// A file that cannot be read or a malformed field is still one `error:` line on stderr.
    #[arg(long)]
    pub json: bool,
}

/// Runs `solsim validate`: exit 0 when the scenario has no error (warnings allowed), 2 when it
/// has one (each is printed; every other command refuses the scenario with the first).
///
/// # Errors
/// A file that cannot be read, or a malformed field ([`study::ScenarioError`]).
pub fn run(
    a: &ValidateArgs,
    budget: MemoryBudget,
    stdout: &mut dyn Write,
) -> anyhow::Result<ExitCode> {
    // A long route's passage searches take a while: a bar over the legs on a terminal.
    let progress = crate::progress::Progress::new(false, "validate", "legs", 0);
    let loaded = Scenario::inspect_observed(&a.scenario, budget, &|done, total| {
        progress.update(done, total);
    });
    progress.finish();
    let (s, findings) = loaded?;
    let validation = Validation::new(&a.scenario, &s, &findings);
    if a.json {
        writeln!(
            stdout,
            "{}",
            serde_json::to_string_pretty(&validation.report())?
        )?;
    } else {
        write!(stdout, "{}", validation.text())?;
    }
    Ok(if validation.errors() > 0 {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}
