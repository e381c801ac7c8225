//! The HTML report of a compare output directory or a sweep directory, written afterwards
//! (`solsim report DIR --out OUT`, [`write_report`]; the page itself is [`crate::html`]).
//!
//! A compare directory holds each strategy's sol log as JSON but not the maps and zones a
//! figure draws, so the report loads the scenario the run names (or the one given), checks its
//! SHA-256 against the run's provenance, runs it again on the run's seed — deterministic, so
//! this gives the run back — and refuses to go on unless every JSON document it regenerates
//! equals the one in the directory. A report therefore never mixes a run with a scenario, map
//! or solsim version it did not come from. A sweep directory's rows are read back and its
//! summary recomputed and checked the same way ([`sweep::engine::read_complete`]).

use std::path::{Path, PathBuf};

use maps::MemoryBudget;
use maps::input_file::Follow;
use serde_json::Value;
use sim::{CampaignOutcome, Strategy};
use study::Scenario;
use sweep::engine::{Summary, SweepSpec};

use crate::figures::run_figures::run_figures;
use crate::html::run_report::run_report;
use crate::html::sweep_report::{sweep_report, sweep_title};
use crate::output_set::{MARKER_FILE, OutputSet};
use crate::over_runs::{MIN_RUNS, summary_json};
use crate::report_dir_error::ReportDirError;
use crate::run_files::run_json;

/// Largest run document read (a 1000-sol run's JSON is a few MB).
const MAX_RUN_JSON_BYTES: u64 = 1 << 30;

/// What to report on, and where.
#[derive(Debug, Clone, Copy)]
pub struct ReportRequest<'a> {
    /// A compare output directory or a complete sweep directory.
    pub dir: &'a Path,
    /// Directory for `report.html`, replaced whole (new, empty, or an earlier report).
    pub out: &'a Path,
    /// The scenario file of a compare directory, when it is no longer where its provenance
    /// says.
    pub scenario: Option<&'a Path>,
    /// Grow the keep-outs on the maps by this r, metres (see
    /// [`crate::compare::FileOptions::map_r_m`]).
    pub map_r_m: Option<f64>,
}

/// How far [`write_report`] is, for a progress display.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReportProgress {
    /// One more of a compare directory's three steps is done (the run again, the statistics
    /// over runs, the page).
    Step,
    /// Run indices recomputed of the statistics over runs.
    Runs {
        /// Done.
        done: u64,
        /// Of.
        total: u64,
    },
}

/// What kind of directory was reported on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReportKind {
    /// A `solsim compare` output directory.
    Compare,
    /// A `solsim sweep` directory.
    Sweep,
}

impl ReportKind {
    /// `compare` or `sweep`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            ReportKind::Compare => "compare",
            ReportKind::Sweep => "sweep",
        }
    }
}

/// A report written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WrittenReport {
    /// The path of `report.html`.
    pub path: PathBuf,
    /// What was reported on.
    pub kind: ReportKind,
    /// What it shows: `5 strategies on seed 383`, `sweep of 200 runs`, …
    pub title: String,
    /// Figures inline.
    pub figures: usize,
    /// Size of the page, bytes.
    pub bytes: usize,
}

/// `out` must be a directory of its own: not the directory reported on, nor one holding
/// anything but an earlier report (it is replaced whole, so a run or a sweep there would be
/// lost).
fn check_out(dir: &Path, out: &Path) -> Result<(), ReportDirError> {
    let Ok(entries) = std::fs::read_dir(out) else {
        return Ok(());
    };
    if let (Ok(a), Ok(b)) = (dir.canonicalize(), out.canonicalize())
        && (a == b || a.starts_with(&b))
    {
        return Err(ReportDirError::OutHoldsDir {
            out: out.to_path_buf(),
        });
    }
    let others: Vec<String> = entries
        .filter_map(|e| e.ok().map(|e| e.file_name().to_string_lossy().into_owned()))
        .filter(|n| n != MARKER_FILE && n != "report.html")
        .collect();
    if let Some(first) = others.first() {
        return Err(ReportDirError::OutHoldsOthers {
            out: out.to_path_buf(),
            count: others.len(),
            first: first.clone(),
        });
    }
    Ok(())
}

/// Writes `report.html` for `request.dir` into `request.out`, telling `progress` how far it
/// is.
///
/// # Errors
/// A directory that is neither a compare output nor a complete sweep; a run that the scenario
/// no longer gives; an unwritable `out`.
pub fn write_report(
    request: &ReportRequest<'_>,
    budget: MemoryBudget,
    progress: &(dyn Fn(ReportProgress) + Sync),
) -> Result<WrittenReport, ReportDirError> {
    let dir = request.dir;
    let meta = std::fs::metadata(dir).map_err(|source| ReportDirError::ReadDir {
        dir: dir.to_path_buf(),
        source,
    })?;
    if !meta.is_dir() {
        return Err(ReportDirError::NotADirectory {
            dir: dir.to_path_buf(),
        });
    }
    check_out(dir, request.out)?;
    OutputSet::check(request.out)?;
    let is_sweep = dir.join(sweep::manifest::MANIFEST).exists();
    let (html, title) = if is_sweep {
        let sweep = sweep::engine::read_complete(dir, budget)?;
        (sweep_report(&sweep)?, sweep_title(&sweep))
    } else {
        compare_dir_report(request, budget, progress)?
    };
    let set = OutputSet::begin(request.out)?;
    let path = set.write("report.html", html.as_bytes())?;
    set.commit()?;
    Ok(WrittenReport {
        path,
        kind: if is_sweep {
            ReportKind::Sweep
        } else {
            ReportKind::Compare
        },
        title,
        figures: html.matches("<figure").count(),
        bytes: html.len(),
    })
}

/// One run document of a compare directory.
struct RunDoc {
    path: PathBuf,
    value: Value,
    strategy: Strategy,
}

/// The value at `pointer` of a document, or the error naming the field.
fn field<'a>(
    path: &Path,
    v: &'a Value,
    pointer: &str,
    expected: &str,
) -> Result<&'a Value, ReportDirError> {
    v.pointer(pointer).ok_or_else(|| ReportDirError::Field {
        path: path.to_path_buf(),
        field: pointer.trim_start_matches('/').replace('/', "."),
        expected: expected.to_owned(),
        got: Some("nothing".into()),
    })
}

/// The field at `pointer` as text (a string as it is, any other value as JSON).
fn text_of(d: &RunDoc, pointer: &str, expected: &str) -> Result<String, ReportDirError> {
    let v = field(&d.path, &d.value, pointer, expected)?;
    Ok(v.as_str().map_or_else(|| v.to_string(), str::to_string))
}

/// A file of the directory, read as text.
fn read(path: &Path) -> Result<String, ReportDirError> {
    maps::input_file::read_text_input(path, MAX_RUN_JSON_BYTES, Follow::No).map_err(|source| {
        ReportDirError::Read {
            path: path.to_path_buf(),
            source,
        }
    })
}

/// The run documents of a compare directory, one per strategy, and its statistics over runs
/// file if any.
fn run_documents(dir: &Path) -> Result<(Vec<RunDoc>, Option<PathBuf>), ReportDirError> {
    let mut docs: Vec<RunDoc> = Vec::new();
    let mut over_runs: Option<PathBuf> = None;
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|source| ReportDirError::ListDir {
            dir: dir.to_path_buf(),
            source,
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    for path in entries {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if name.ends_with(".over-runs.json") {
            over_runs = Some(path);
            continue;
        }
        if !name.ends_with(".json") || !path.is_file() {
            continue;
        }
        let text = read(&path)?;
        let value: Value =
            serde_json::from_str(&text).map_err(|source| ReportDirError::NotJson {
                path: path.clone(),
                expected: "a solsim run document (JSON)",
                source,
            })?;
        if !value.is_object() {
            return Err(ReportDirError::NotARunDocument { path });
        }
        let name = field(&path, &value, "/strategy", "a strategy name")?;
        let strategy =
            name.as_str()
                .and_then(Strategy::from_name)
                .ok_or_else(|| ReportDirError::Field {
                    path: path.clone(),
                    field: "strategy".into(),
                    expected: "one of replay, ground, onboard, extension, extension+onboard".into(),
                    got: Some(name.to_string()),
                })?;
        if let Some(twin) = docs.iter().find(|d| d.strategy == strategy) {
            return Err(ReportDirError::SecondRun {
                path,
                strategy: strategy.name(),
                first: twin.path.clone(),
            });
        }
        docs.push(RunDoc {
            path,
            value,
            strategy,
        });
    }
    Ok((docs, over_runs))
}

/// The scenario the run documents name (or `given`), checked against their provenance: the
/// scenario file's and every input file's SHA-256. Returns it, its path and the run's seed.
fn run_scenario(
    docs: &[RunDoc],
    dir: &Path,
    given: Option<&Path>,
    budget: MemoryBudget,
) -> Result<(Scenario, PathBuf, u64), ReportDirError> {
    let Some(first) = docs.first() else {
        return Err(ReportDirError::NeitherRunNorSweep {
            dir: dir.to_path_buf(),
        });
    };
    let sha = text_of(
        first,
        "/provenance/scenario_sha256",
        "the scenario's SHA-256",
    )?;
    let seed = field(&first.path, &first.value, "/seed", "the run's seed")?
        .as_u64()
        .ok_or_else(|| ReportDirError::Field {
            path: first.path.clone(),
            field: "seed".into(),
            expected: "an unsigned integer".into(),
            got: None,
        })?;
    for d in &docs[1..] {
        let other = text_of(d, "/provenance/scenario_sha256", "the scenario's SHA-256")?;
        if other != sha || d.value.get("seed").and_then(Value::as_u64) != Some(seed) {
            return Err(ReportDirError::OtherRun {
                path: d.path.clone(),
                first: first.path.clone(),
            });
        }
    }
    let scenario_path = match given {
        Some(p) => p.to_path_buf(),
        None => PathBuf::from(text_of(
            first,
            "/provenance/scenario_file",
            "the scenario file's path",
        )?),
    };
    if given.is_none() && !scenario_path.exists() {
        return Err(ReportDirError::ScenarioMissing {
            path: first.path.clone(),
            scenario: scenario_path,
        });
    }
    let scenario = Scenario::load_within(&scenario_path, budget)?;
    if scenario.sha256 != sha {
        return Err(ReportDirError::ScenarioEdited {
            scenario: scenario_path,
            recorded: sha,
            found: scenario.sha256.clone(),
        });
    }
    for (field, file, sha) in &scenario.inputs_sha256 {
        let pointer = format!("/provenance/inputs_sha256/{field}");
        match first.value.pointer(&pointer).and_then(Value::as_str) {
            Some(recorded) if recorded == sha => {}
            Some(recorded) => {
                return Err(ReportDirError::InputEdited {
                    file: file.clone(),
                    field: field.to_string(),
                    scenario: scenario_path,
                    recorded: recorded.to_owned(),
                    found: sha.clone(),
                });
            }
            None => {
                return Err(ReportDirError::Field {
                    path: first.path.clone(),
                    field: format!("provenance.inputs_sha256.{field}"),
                    expected: "the SHA-256 of the run's input file".into(),
                    got: Some("nothing (written by an older solsim: run compare again)".into()),
                });
            }
        }
    }
    Ok((scenario, scenario_path, seed))
}

/// The directory's strategies run again on `seed`, each checked against its document.
fn run_again(
    scenario: &Scenario,
    scenario_path: &Path,
    docs: &[RunDoc],
    seed: u64,
) -> Result<Vec<CampaignOutcome>, ReportDirError> {
    let strategies: Vec<Strategy> = scenario
        .strategies()
        .into_iter()
        .chain(Strategy::ALL)
        .filter(|s| docs.iter().any(|d| d.strategy == *s))
        .fold(Vec::new(), |mut v, s| {
            if !v.contains(&s) {
                v.push(s);
            }
            v
        });
    let outcomes = scenario.compare(&strategies, sim::seeds::RunSeeds::from_master(seed));
    // The same documents, except where the scenario file is (a path, as given to compare).
    let comparable = |v: &Value| {
        let mut v = v.clone();
        if let Some(p) = v.get_mut("provenance").and_then(Value::as_object_mut) {
            p.remove("scenario_file");
        }
        v
    };
    for (o, doc) in outcomes.iter().zip(
        strategies
            .iter()
            .filter_map(|s| docs.iter().find(|d| d.strategy == *s)),
    ) {
        let again = run_json(scenario, o, &scenario.legs);
        if comparable(&again) != comparable(&doc.value) {
            return Err(ReportDirError::RunDiffers {
                path: doc.path.clone(),
                scenario: scenario_path.to_path_buf(),
                seed,
            });
        }
    }
    Ok(outcomes)
}

/// The statistics over runs of the `.over-runs.json` file at `path`, recomputed and checked
/// byte for byte against it.
fn over_runs_again(
    path: &Path,
    scenario: &Scenario,
    scenario_path: &Path,
    progress: &(dyn Fn(ReportProgress) + Sync),
) -> Result<Summary, ReportDirError> {
    let text = read(path)?;
    let value: Value = serde_json::from_str(&text).map_err(|source| ReportDirError::NotJson {
        path: path.to_path_buf(),
        expected: "a compare --runs summary",
        source,
    })?;
    let runs = value
        .get("runs")
        .and_then(Value::as_u64)
        .ok_or_else(|| ReportDirError::Field {
            path: path.to_path_buf(),
            field: "runs".into(),
            expected: "the number of runs".into(),
            got: None,
        })?;
    sweep::engine::check_runs(runs, MIN_RUNS)?;
    let summary = sweep::engine::summary_in_memory(
        scenario,
        &SweepSpec::new(scenario, runs),
        &|done, total| progress(ReportProgress::Runs { done, total }),
    );
    if summary_json(&summary) != text {
        return Err(ReportDirError::OverRunsDiffer {
            path: path.to_path_buf(),
            scenario: scenario_path.to_path_buf(),
            runs,
        });
    }
    Ok(summary)
}

/// The page of a compare directory and what it shows.
fn compare_dir_report(
    request: &ReportRequest<'_>,
    budget: MemoryBudget,
    progress: &(dyn Fn(ReportProgress) + Sync),
) -> Result<(String, String), ReportDirError> {
    let (docs, over_runs) = run_documents(request.dir)?;
    let (scenario, scenario_path, seed) =
        run_scenario(&docs, request.dir, request.scenario, budget)?;
    let outcomes = run_again(&scenario, &scenario_path, &docs, seed)?;
    progress(ReportProgress::Step);
    let summary = over_runs
        .map(|path| over_runs_again(&path, &scenario, &scenario_path, progress))
        .transpose()?;
    progress(ReportProgress::Step);
    let figures = run_figures(&scenario, &outcomes, request.map_r_m)?;
    let html = run_report(&scenario, &outcomes, summary.as_ref(), &figures);
    progress(ReportProgress::Step);
    let strategies = match outcomes.len() {
        1 => "1 strategy".to_string(),
        n => format!("{n} strategies"),
    };
    let title = match &summary {
        Some(s) => format!("{strategies} on seed {seed}, and over {} runs", s.runs),
        None => format!("{strategies} on seed {seed}"),
    };
    Ok((html, title))
}
