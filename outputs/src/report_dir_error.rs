//! [`ReportDirError`]: why the report of a compare or sweep directory
//! ([`crate::report_dir`]) was refused — one line naming the file, the field and what was
//! expected.

use std::path::PathBuf;

use maps::input_file::InputFileError;

use crate::figures::canvas::FigureError;
use crate::output_set::OutputSetError;

/// Why `solsim report` could not write the report of a directory.
#[derive(Debug, thiserror::Error)]
pub enum ReportDirError {
    /// The directory reported on cannot be read.
    #[error("{}: cannot read the directory", dir.display())]
    ReadDir {
        /// The directory.
        dir: PathBuf,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// The directory reported on cannot be listed.
    #[error("{}: cannot list the directory", dir.display())]
    ListDir {
        /// The directory.
        dir: PathBuf,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// A file was given where a directory was expected.
    #[error(
        "{}: expected a compare output directory or a sweep directory, found a file",
        dir.display()
    )]
    NotADirectory {
        /// The path given.
        dir: PathBuf,
    },
    /// `--out` is the directory reported on, or holds it.
    #[error(
        "--out: expected a directory of its own for report.html, got {}, which holds the \
         directory reported on (it would be replaced)",
        out.display()
    )]
    OutHoldsDir {
        /// The output directory.
        out: PathBuf,
    },
    /// `--out` holds files other than an earlier report.
    #[error(
        "--out: expected a new or empty directory or an earlier report, got {}, which holds {} \
         other files ({}…); choose another --out",
        out.display(),
        count,
        first
    )]
    OutHoldsOthers {
        /// The output directory.
        out: PathBuf,
        /// How many other files it holds.
        count: usize,
        /// The first of them.
        first: String,
    },
    /// The directory holds neither run documents nor a sweep manifest.
    #[error(
        "{}: expected a compare output directory (<scenario>.<strategy>.json files) or a sweep \
         directory (manifest.json); found neither",
        dir.display()
    )]
    NeitherRunNorSweep {
        /// The directory.
        dir: PathBuf,
    },
    /// A file of the directory cannot be read.
    #[error("{}: cannot read", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: InputFileError,
    },
    /// A `.json` file is not JSON.
    #[error("{}: expected {expected}", path.display())]
    NotJson {
        /// The file.
        path: PathBuf,
        /// What it should hold (`a solsim run document (JSON)`).
        expected: &'static str,
        /// The parser's message.
        #[source]
        source: serde_json::Error,
    },
    /// A run document is JSON but not an object.
    #[error(
        "{}: expected a solsim run document (a JSON object with provenance, strategy and sols), \
         got another JSON value",
        path.display()
    )]
    NotARunDocument {
        /// The file.
        path: PathBuf,
    },
    /// A field of a run document or summary is missing, or not what it should be.
    #[error("{}: {field}: expected {expected}{}", path.display(), got.as_ref().map_or(String::new(), |g| format!(", got {g}")))]
    Field {
        /// The file.
        path: PathBuf,
        /// The field, dotted (`provenance.scenario_sha256`).
        field: String,
        /// What it should hold.
        expected: String,
        /// What it holds, when that is worth saying.
        got: Option<String>,
    },
    /// Two run documents of one strategy.
    #[error(
        "{}: expected one run document per strategy, got a second for {strategy} (the first is \
         {})",
        path.display(),
        first.display()
    )]
    SecondRun {
        /// The second document.
        path: PathBuf,
        /// Its strategy.
        strategy: &'static str,
        /// The first.
        first: PathBuf,
    },
    /// A run document of another scenario or seed than the first.
    #[error(
        "{}: expected a run of the scenario and seed of {} (one compare run per directory), got \
         another",
        path.display(),
        first.display()
    )]
    OtherRun {
        /// The document.
        path: PathBuf,
        /// The first document.
        first: PathBuf,
    },
    /// The scenario the provenance names is not there.
    #[error(
        "{}: provenance.scenario_file: the scenario {} is not there (paths are relative to where \
         compare ran); give it with --scenario FILE",
        path.display(),
        scenario.display()
    )]
    ScenarioMissing {
        /// The run document.
        path: PathBuf,
        /// The scenario file it names.
        scenario: PathBuf,
    },
    /// The scenario cannot be loaded.
    #[error(transparent)]
    Scenario(#[from] study::ScenarioError),
    /// The scenario file is not the one the run used.
    #[error(
        "{}: expected the scenario the run used (SHA-256 {recorded}), got one with SHA-256 \
         {found} (edited since the run?)",
        scenario.display()
    )]
    ScenarioEdited {
        /// The scenario file.
        scenario: PathBuf,
        /// The run's SHA-256 of it.
        recorded: String,
        /// Its SHA-256 now.
        found: String,
    },
    /// An input file of the scenario is not the one the run used.
    #[error(
        "{} ({field} of {}): expected the file the run used (SHA-256 {recorded}), got one with \
         SHA-256 {found} (edited since the run?)",
        file.display(),
        scenario.display()
    )]
    InputEdited {
        /// The input file.
        file: PathBuf,
        /// The scenario field naming it.
        field: String,
        /// The scenario file.
        scenario: PathBuf,
        /// The run's SHA-256 of it.
        recorded: String,
        /// Its SHA-256 now.
        found: String,
    },
    /// The scenario run again does not give back a run document of the directory.
    #[error(
        "{}: expected the run {} gives on seed {seed} with solsim {}, got another (written by \
         another solsim version, or edited)",
        path.display(),
        scenario.display(),
        env!("CARGO_PKG_VERSION")
    )]
    RunDiffers {
        /// The run document.
        path: PathBuf,
        /// The scenario file.
        scenario: PathBuf,
        /// The run's seed.
        seed: u64,
    },
    /// The runs recomputed do not give back the directory's statistics over runs.
    #[error(
        "{}: expected the statistics of {runs} runs of {} with solsim {}, got others (written by \
         another solsim version, or edited)",
        path.display(),
        scenario.display(),
        env!("CARGO_PKG_VERSION")
    )]
    OverRunsDiffer {
        /// The `.over-runs.json` file.
        path: PathBuf,
        /// The scenario file.
        scenario: PathBuf,
        /// Runs.
        runs: u64,
    },
    /// A sweep directory that cannot be read back, or a bad run count.
    #[error(transparent)]
    Sweep(#[from] sweep::SweepError),
    /// A figure could not be drawn.
    #[error(transparent)]
    Figure(#[from] FigureError),
    /// `--out` cannot be written.
    #[error(transparent)]
    OutputSet(#[from] OutputSetError),
}
