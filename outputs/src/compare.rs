//! The compare pipeline (`solsim compare`) as two calls: [`compare`] runs a loaded scenario's
//! strategies on its seed (and, given a sweep, over runs `0..N` in memory) and returns a
//! [`Comparison`]; [`Comparison::write`] writes it as an output directory — the same files
//! `solsim compare SCENARIO --out DIR [--report]` writes — and says what it wrote.
//!
//! What the command prints is here too: [`Comparison::text`] (the verdict, the table and each
//! strategy against ground) and [`Comparison::json`] (`--json`). [`write_run_set`] is the
//! writer both `compare` and `solsim run` use: every strategy's JSON, per-sol CSV and GIS
//! layers, and any further files, as one [`OutputSet`] swapped into place.
//!
//! ```no_run
//! use outputs::compare::{FileOptions, compare};
//!
//! let scenario = study::Scenario::load("scenarios/sol383-386.toml".as_ref())?;
//! let comparison = compare(&scenario, None, &|_, _| {});
//! print!("{}", comparison.text());
//! let options = FileOptions { report: true, map_r_m: None };
//! let written = comparison.write("solsim-out/sol383-386".as_ref(), &options)?;
//! println!("{}", written.summary_line());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::{Path, PathBuf};

use sim::CampaignOutcome;
use study::Scenario;
use sweep::engine::{Summary, SweepSpec};

use crate::against_ground::against_ground;
use crate::figures::canvas::FigureError;
use crate::figures::run_figures::run_figures;
use crate::html::run_report::run_report;
use crate::output_set::{OutputSet, OutputSetError};
use crate::over_runs::{CompareRunsJson, against_ground_over_runs, summary_json};
use crate::run_files::{pretty, run_json, write_run_files, write_scenario_files};
use crate::tables::compare_table;
use crate::verdict::verdict;

/// Why a comparison's files could not be written.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// A figure could not be drawn.
    #[error(transparent)]
    Figure(#[from] FigureError),
    /// The output directory could not be written; the earlier one is untouched.
    #[error(transparent)]
    OutputSet(#[from] OutputSetError),
}

/// One compare run: every strategy of a scenario on its seed, and the statistics over runs
/// when it also went over seeded worlds.
#[derive(Debug, Clone)]
pub struct Comparison<'s> {
    /// The scenario compared.
    pub scenario: &'s Scenario,
    /// One run per strategy on the scenario's seed, in the order of
    /// [`Scenario::strategies`].
    pub outcomes: Vec<CampaignOutcome>,
    /// The sweep's summary over run indices `0..N` (`compare --runs N`).
    pub over_runs: Option<Summary>,
}

/// What [`Comparison::write`] adds to the run files.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FileOptions {
    /// Also write `report.html` (`compare --report`).
    pub report: bool,
    /// Grow the keep-outs on the whole-traverse maps and the fault zooms by this uncertainty r,
    /// metres (`--map-r-m`); `None`: each keep-out by the r the rover had where its path came
    /// closest to it, each fault's zoom by the fault's r.
    pub map_r_m: Option<f64>,
}

/// What an output set holds once written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WrittenSet {
    /// The output directory.
    pub dir: PathBuf,
    /// Every file written, as its path in `dir` (the set's marker file aside).
    pub files: Vec<PathBuf>,
    /// SVG figures among them.
    pub svg_figures: usize,
    /// The statistics over runs file (`<scenario>.over-runs.json`), when written.
    pub over_runs: Option<String>,
    /// Whether `report.html` is among them.
    pub report: bool,
}

impl WrittenSet {
    /// The line `solsim compare` and `solsim run` print after writing (with a blank line
    /// before it, no newline after): how many files, where, and what they are.
    #[must_use]
    pub fn summary_line(&self) -> String {
        let mut also = String::new();
        if self.svg_figures > 0 {
            also.push_str(&format!("; {} SVG figures", self.svg_figures));
        }
        if let Some(name) = &self.over_runs {
            also.push_str(&format!("; {name}"));
        }
        if self.report {
            also.push_str("; report.html");
        }
        format!(
            "\nwrote {} files to {}/ (per strategy JSON, per-sol CSV and paths GeoJSON in Mars \
             lon/lat; more GIS layers in gis/, in the map's CRS in gis/projected/{also})",
            self.files.len(),
            self.dir.display()
        )
    }
}

/// Where `solsim compare` and `solsim run` write without `--out`: `solsim-out/<scenario name>`.
#[must_use]
pub fn default_out_dir(scenario: &Scenario) -> PathBuf {
    Path::new("solsim-out").join(&scenario.name)
}

/// Runs every strategy of `scenario` ([`Scenario::strategies`]) on its seed, in parallel, and
/// with `over_runs` the sweep it describes in memory (call [`SweepSpec::validate`] first),
/// telling `progress(done, total)` the run indices done. The result does not depend on the
/// thread count (run it in a rayon pool to choose it).
#[must_use]
pub fn compare<'s>(
    scenario: &'s Scenario,
    over_runs: Option<&SweepSpec>,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Comparison<'s> {
    let outcomes = scenario.compare(&scenario.strategies(), scenario.seeds());
    let over_runs =
        over_runs.map(|spec| sweep::engine::summary_in_memory(scenario, spec, progress));
    Comparison {
        scenario,
        outcomes,
        over_runs,
    }
}

impl Comparison<'_> {
    /// What `solsim compare --json` prints: the run documents as a JSON array, or with
    /// statistics over runs `{"one_run": [...], "over_runs": {...}}`; pretty, with a trailing
    /// newline.
    #[must_use]
    pub fn json(&self) -> String {
        let docs: Vec<serde_json::Value> = self
            .outcomes
            .iter()
            .map(|o| run_json(self.scenario, o, &self.scenario.legs))
            .collect();
        match &self.over_runs {
            None => pretty(&serde_json::Value::Array(docs)),
            Some(over_runs) => {
                let doc = CompareRunsJson {
                    one_run: docs,
                    over_runs,
                };
                let mut s = serde_json::to_string_pretty(&doc)
                    .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
                s.push('\n');
                s
            }
        }
    }

    /// What `solsim compare` prints: the scenario's name and description, the verdict, the
    /// table, each strategy against ground and, with statistics over runs, the same over the
    /// runs.
    #[must_use]
    pub fn text(&self) -> String {
        let scenario = self.scenario;
        let mut s = format!(
            "{} — {}\n\n{}\n",
            scenario.name,
            scenario.description.trim(),
            verdict(scenario, &self.outcomes, self.over_runs.as_ref())
        );
        s.push_str(&compare_table(&self.outcomes));
        s.push_str(&against_ground(scenario, &self.outcomes));
        if let Some(summary) = &self.over_runs {
            let left = scenario
                .study_segment
                .map(|g| scenario.settings.calendar.sols_from(g.from_sol));
            s.push_str(&against_ground_over_runs(summary, left));
        }
        s
    }

    /// The files beside the run files, as (name, text): the figures, `report.html` when
    /// asked, and the statistics over runs when there are any.
    ///
    /// # Errors
    /// A figure that cannot be drawn.
    pub fn extra_files(&self, options: &FileOptions) -> Result<Vec<(String, String)>, FigureError> {
        let mut extra: Vec<(String, String)> = Vec::new();
        let figures = run_figures(self.scenario, &self.outcomes, options.map_r_m)?;
        if options.report {
            extra.push((
                "report.html".into(),
                run_report(
                    self.scenario,
                    &self.outcomes,
                    self.over_runs.as_ref(),
                    &figures,
                ),
            ));
        }
        extra.extend(figures.into_iter().map(|f| (f.file, f.svg)));
        extra.extend(self.over_runs.iter().map(|s| {
            (
                format!("{}.over-runs.json", self.scenario.name),
                summary_json(s),
            )
        }));
        Ok(extra)
    }

    /// Writes the comparison into `dir` as one output set, replacing an earlier one whole:
    /// every strategy's JSON, per-sol CSV and GIS layers, the figures, `report.html` when
    /// asked, and the statistics over runs.
    ///
    /// # Errors
    /// A figure that cannot be drawn, or a directory that cannot be written (or is not one
    /// solsim may replace).
    pub fn write(&self, dir: &Path, options: &FileOptions) -> Result<WrittenSet, CompareError> {
        let extra = self.extra_files(options)?;
        Ok(write_run_set(dir, self.scenario, &self.outcomes, &extra)?)
    }
}

/// Writes the files of `outcomes` (each strategy's JSON, per-sol CSV and GIS layers, and the
/// layers they share) and the `extra` (name, text) files into `dir` as one output set: written
/// aside and swapped into place, so a kill leaves the earlier set or this one, never a mix.
///
/// # Errors
/// [`OutputSetError`]: a directory that cannot be written, or that is not one solsim may
/// replace.
pub fn write_run_set(
    dir: &Path,
    scenario: &Scenario,
    outcomes: &[CampaignOutcome],
    extra: &[(String, String)],
) -> Result<WrittenSet, OutputSetError> {
    let set = OutputSet::begin(dir)?;
    let mut files = write_scenario_files(&set, scenario)?;
    for o in outcomes {
        files.extend(write_run_files(&set, scenario, o, &scenario.legs)?);
    }
    for (name, text) in extra {
        files.push(set.write(name, text.as_bytes())?);
    }
    set.commit()?;
    let count = |suffix: &str| extra.iter().filter(|(n, _)| n.ends_with(suffix)).count();
    Ok(WrittenSet {
        dir: dir.to_path_buf(),
        files,
        svg_figures: count(".svg"),
        over_runs: (count("over-runs.json") > 0)
            .then(|| format!("{}.over-runs.json", scenario.name)),
        report: count("report.html") > 0,
    })
}
