//! Progress on standard error for the commands that can run for more than a couple of
//! seconds (`sweep`, `compare --runs`, `regress`, `localize-bench`, `seu-campaign`,
//! `map package`, `map generate`, and loading a scenario in `validate`, `run` and `compare`,
//! whose passage search runs leg by leg): a bar when standard error is a terminal, nothing when it is piped
//! or redirected, so logs and captured output hold only results.

use std::io::IsTerminal as _;

/// A progress bar labelled `label` counting `unit` (`sweep ▕████    ▏ 40/200 runs …`), or
/// nothing off a terminal or when quiet.
pub struct Progress {
    bar: Option<indicatif::ProgressBar>,
}

impl Progress {
    /// A bar over `total` items (it may change with [`Progress::update`]); hidden when `quiet`
    /// or when standard error is not a terminal.
    #[must_use]
    pub fn new(quiet: bool, label: &str, unit: &str, total: u64) -> Self {
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let bar = indicatif::ProgressBar::new(total);
            let template = format!(
                "{label} {{bar:40}} {{pos}}/{{len}} {unit}  {{per_sec}}  ETA {{eta}}  {{wide_msg}}"
            );
            bar.set_style(
                indicatif::ProgressStyle::with_template(&template)
                    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            bar
        });
        Self { bar }
    }

    /// `done` of `total` finished.
    pub fn update(&self, done: u64, total: u64) {
        if let Some(bar) = &self.bar {
            bar.set_length(total);
            bar.set_position(done);
        }
    }

    /// One more finished.
    pub fn inc(&self) {
        self.inc_by(1);
    }

    /// `n` more finished.
    pub fn inc_by(&self, n: u64) {
        if let Some(bar) = &self.bar {
            bar.inc(n);
        }
    }

    /// What is being done now, shown after the bar (`rapid-traverse-379-409: 6 checks over
    /// runs`).
    pub fn set_message(&self, message: String) {
        if let Some(bar) = &self.bar {
            bar.set_message(message);
        }
    }

    /// Clears the bar.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// Loads a scenario with a bar over its route's legs (the passage searches, the long part of
/// loading a long route) labelled `label`, cleared when done.
///
/// # Errors
/// As [`study::Scenario::load_within`].
pub fn load_scenario(
    label: &str,
    path: &std::path::Path,
    budget: maps::MemoryBudget,
) -> Result<study::Scenario, study::ScenarioError> {
    let progress = Progress::new(false, label, "legs", 0);
    let loaded = study::Scenario::load_observed(path, budget, &|done, total| {
        progress.update(done, total);
    });
    progress.finish();
    loaded
}
