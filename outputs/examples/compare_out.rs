//! The output directory of `solsim compare SCENARIO --out DIR --report`, from the libraries
//! alone (no `solsim` binary, no clap): load the scenario, compare its strategies, write the
//! directory, and print what `solsim compare` prints.
//!
//! ```sh
//! cargo run -p outputs --example compare_out -- scenarios/sol383-386.toml /tmp/sol383-386
//! ```
//!
//! The files are byte for byte those of the command (the scenario's path is recorded in each
//! run's provenance as given, so give it as you would to `solsim compare`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use outputs::compare::{FileOptions, compare};

/// Writes the directory `solsim compare SCENARIO --out DIR --report` writes and returns what
/// the command prints.
///
/// # Errors
/// A scenario that cannot be loaded, a figure that cannot be drawn, a directory that cannot be
/// written.
pub fn compare_out(scenario: &Path, dir: &Path) -> Result<String, Box<dyn std::error::Error>> {
    let scenario = study::Scenario::load_within(scenario, maps::MemoryBudget::default())?;
    let comparison = compare(&scenario, None, &|_, _| {});
    let options = FileOptions {
        report: true,
        map_r_m: None,
    };
    let written = comparison.write(dir, &options)?;
    Ok(format!("{}{}\n", comparison.text(), written.summary_line()))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [scenario, dir] = args.as_slice() else {
        eprintln!("usage: compare_out SCENARIO.toml OUT_DIR");
        return ExitCode::from(2);
    };
    match compare_out(&PathBuf::from(scenario), &PathBuf::from(dir)) {
        Ok(printed) => {
            print!("{printed}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
