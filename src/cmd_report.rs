//! `solsim report DIR --out OUT`: the HTML report of a compare output directory or a sweep
//! directory (see [`crate::report_html`]).
//!
//! A compare directory holds each strategy's sol log as JSON but not the maps and zones a
//! figure draws, so the report loads the scenario the run names (or `--scenario`), checks its
//! SHA-256 against the run's provenance, runs it again on the run's seed — deterministic, so
//! this gives the run back — and refuses to go on unless every JSON document it regenerates
//! equals the one in the directory. A report therefore never mixes a run with a scenario, map
//! or solsim version it did not come from. A sweep directory's rows are read back and its
//! summary recomputed and checked the same way ([`sweep::engine::read_complete`]).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::Args;
use maps::MemoryBudget;
use maps::input_file::Follow;
use serde_json::Value;
use sim::Strategy;
use study::Scenario;
use sweep::engine::SweepSpec;

use crate::output_set::OutputSet;
use crate::progress::Progress;
use crate::{report, report_html, report_runs};

/// Largest run document read (a 1000-sol run's JSON is a few MB).
const MAX_RUN_JSON_BYTES: u64 = 1 << 30;

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

/// `--out` must be a directory of its own: not the directory reported on, nor one holding
/// anything but an earlier report (it is replaced whole, so a run or a sweep there would be
/// lost).
fn check_out(dir: &Path, out: &Path) -> anyhow::Result<()> {
    let Ok(entries) = std::fs::read_dir(out) else {
        return Ok(());
    };
    if let (Ok(a), Ok(b)) = (dir.canonicalize(), out.canonicalize())
        && (a == b || a.starts_with(&b))
    {
        bail!(
            "--out: expected a directory of its own for report.html, got {}, which holds the \
             directory reported on (it would be replaced)",
            out.display()
        );
    }
    let others: Vec<String> = entries
        .filter_map(|e| e.ok().map(|e| e.file_name().to_string_lossy().into_owned()))
        .filter(|n| n != crate::output_set::MARKER_FILE && n != "report.html")
        .collect();
    if !others.is_empty() {
        bail!(
            "--out: expected a new or empty directory or an earlier report, got {}, which \
             holds {} other files ({}…); choose another --out",
            out.display(),
            others.len(),
            others[0]
        );
    }
    Ok(())
}

/// Runs `solsim report`.
///
/// # Errors
/// A directory that is neither a compare output nor a complete sweep; a run that the scenario
/// no longer gives; an unwritable `--out`.
pub fn run(a: &ReportArgs, budget: MemoryBudget, stdout: &mut dyn Write) -> anyhow::Result<()> {
    check_map_r(a.map_r_m)?;
    let meta = std::fs::metadata(&a.dir)
        .with_context(|| format!("{}: cannot read the directory", a.dir.display()))?;
    if !meta.is_dir() {
        bail!(
            "{}: expected a compare output directory or a sweep directory, found a file",
            a.dir.display()
        );
    }
    check_out(&a.dir, &a.out)?;
    OutputSet::check(&a.out)?;
    let is_sweep = a.dir.join(sweep::manifest::MANIFEST).exists();
    let (html, what) = if is_sweep {
        let sweep = sweep::engine::read_complete(&a.dir, budget)?;
        let what = report_html::sweep_title(&sweep);
        (report_html::sweep_report(&sweep)?, what)
    } else {
        compare_dir_report(a, budget)?
    };
    let set = OutputSet::begin(&a.out)?;
    let path = set.write("report.html", html.as_bytes())?;
    set.commit()?;
    let figures = html.matches("<figure").count();
    if a.json {
        let doc = serde_json::json!({
            "report": path.display().to_string(),
            "kind": if is_sweep { "sweep" } else { "compare" },
            "title": what,
            "figures": figures,
            "bytes": html.len(),
            "dir": a.dir.display().to_string(),
        });
        writeln!(stdout, "{}", serde_json::to_string_pretty(&doc)?)?;
        return Ok(());
    }
    writeln!(
        stdout,
        "wrote {} ({what}; {figures} figures inline, {:.0} KB, no network needed)",
        path.display(),
        html.len() as f64 / 1024.0
    )?;
    Ok(())
}

/// One run document of a compare directory.
struct RunDoc {
    path: PathBuf,
    value: Value,
    strategy: Strategy,
}

fn field<'a>(
    path: &Path,
    v: &'a Value,
    pointer: &str,
    expected: &str,
) -> anyhow::Result<&'a Value> {
    v.pointer(pointer).ok_or_else(|| {
        anyhow::anyhow!(
            "{}: {}: expected {expected}, got nothing",
            path.display(),
            pointer.trim_start_matches('/').replace('/', ".")
        )
    })
}

fn compare_dir_report(a: &ReportArgs, budget: MemoryBudget) -> anyhow::Result<(String, String)> {
    let mut docs: Vec<RunDoc> = Vec::new();
    let mut over_runs: Option<PathBuf> = None;
    let mut entries: Vec<PathBuf> = std::fs::read_dir(&a.dir)
        .with_context(|| format!("{}: cannot list the directory", a.dir.display()))?
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
        let text = maps::input_file::read_text_input(&path, MAX_RUN_JSON_BYTES, Follow::No)
            .with_context(|| format!("{}: cannot read", path.display()))?;
        let value: Value = serde_json::from_str(&text).with_context(|| {
            format!("{}: expected a solsim run document (JSON)", path.display())
        })?;
        if !value.is_object() {
            bail!(
                "{}: expected a solsim run document (a JSON object with provenance, strategy \
                 and sols), got another JSON value",
                path.display()
            );
        }
        let name = field(&path, &value, "/strategy", "a strategy name")?;
        let strategy = name.as_str().and_then(Strategy::from_name).ok_or_else(|| {
            anyhow::anyhow!(
                "{}: strategy: expected one of replay, ground, onboard, extension, \
                     extension+onboard, got {name}",
                path.display()
            )
        })?;
        if let Some(twin) = docs.iter().find(|d| d.strategy == strategy) {
            bail!(
                "{}: expected one run document per strategy, got a second for {} (the first is \
                 {})",
                path.display(),
                strategy.name(),
                twin.path.display()
            );
        }
        docs.push(RunDoc {
            path,
            value,
            strategy,
        });
    }
    let Some(first) = docs.first() else {
        bail!(
            "{}: expected a compare output directory (<scenario>.<strategy>.json files) or a \
             sweep directory (manifest.json); found neither",
            a.dir.display()
        );
    };
    let text_of = |d: &RunDoc, pointer: &str, expected: &str| -> anyhow::Result<String> {
        let v = field(&d.path, &d.value, pointer, expected)?;
        Ok(v.as_str().map_or_else(|| v.to_string(), str::to_string))
    };
    let sha = text_of(
        first,
        "/provenance/scenario_sha256",
        "the scenario's SHA-256",
    )?;
    let seed = field(&first.path, &first.value, "/seed", "the run's seed")?
        .as_u64()
        .ok_or_else(|| {
            anyhow::anyhow!(
                "{}: seed: expected an unsigned integer",
                first.path.display()
            )
        })?;
    for d in &docs[1..] {
        let other = text_of(d, "/provenance/scenario_sha256", "the scenario's SHA-256")?;
        if other != sha || d.value.get("seed").and_then(Value::as_u64) != Some(seed) {
            bail!(
                "{}: expected a run of the scenario and seed of {} (one compare run per \
                 directory), got another",
                d.path.display(),
                first.path.display()
            );
        }
    }
    let scenario_path = match &a.scenario {
        Some(p) => p.clone(),
        None => PathBuf::from(text_of(
            first,
            "/provenance/scenario_file",
            "the scenario file's path",
        )?),
    };
    if a.scenario.is_none() && !scenario_path.exists() {
        bail!(
            "{}: provenance.scenario_file: the scenario {} is not there (paths are relative \
             to where compare ran); give it with --scenario FILE",
            first.path.display(),
            scenario_path.display()
        );
    }
    let scenario = Scenario::load_within(&scenario_path, budget)?;
    if scenario.sha256 != sha {
        bail!(
            "{}: expected the scenario the run used (SHA-256 {sha}), got one with SHA-256 {} \
             (edited since the run?)",
            scenario_path.display(),
            scenario.sha256
        );
    }
    for (field, file, sha) in &scenario.inputs_sha256 {
        let pointer = format!("/provenance/inputs_sha256/{field}");
        match first.value.pointer(&pointer).and_then(Value::as_str) {
            Some(recorded) if recorded == sha => {}
            Some(recorded) => bail!(
                "{} ({field} of {}): expected the file the run used (SHA-256 {recorded}), got \
                 one with SHA-256 {sha} (edited since the run?)",
                file.display(),
                scenario_path.display()
            ),
            None => bail!(
                "{}: provenance.inputs_sha256.{field}: expected the SHA-256 of the run's input \
                 file, got nothing (written by an older solsim: run compare again)",
                first.path.display()
            ),
        }
    }
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
    let progress = Progress::new(false, "report", "steps", 3);
    let outcomes = scenario.compare(&strategies, seed);
    progress.inc();
    // The same documents, except where the scenario file is (a path, as given to compare).
    let comparable = |v: &Value| {
        let mut v = v.clone();
        if let Some(p) = v.get_mut("provenance").and_then(Value::as_object_mut) {
            p.remove("scenario_file");
        }
        v
    };
    for o in &outcomes {
        let doc = docs
            .iter()
            .find(|d| d.strategy == o.strategy)
            .expect("a strategy of the directory");
        let again = report::run_json(&scenario, o, &scenario.legs);
        if comparable(&again) != comparable(&doc.value) {
            bail!(
                "{}: expected the run {} gives on seed {seed} with solsim {}, got another \
                 (written by another solsim version, or edited)",
                doc.path.display(),
                scenario_path.display(),
                env!("CARGO_PKG_VERSION")
            );
        }
    }
    let summary = match &over_runs {
        None => None,
        Some(path) => {
            let text = maps::input_file::read_text_input(path, MAX_RUN_JSON_BYTES, Follow::No)
                .with_context(|| format!("{}: cannot read", path.display()))?;
            let value: Value = serde_json::from_str(&text).with_context(|| {
                format!("{}: expected a compare --runs summary", path.display())
            })?;
            let runs = value.get("runs").and_then(Value::as_u64).ok_or_else(|| {
                anyhow::anyhow!("{}: runs: expected the number of runs", path.display())
            })?;
            sweep::engine::check_runs(runs, report_runs::MIN_RUNS)?;
            let summary =
                crate::cmd_sweep::summary_in_memory(&scenario, &SweepSpec::new(&scenario, runs));
            if report_runs::summary_json(&summary) != text {
                bail!(
                    "{}: expected the statistics of {runs} runs of {} with solsim {}, got \
                     others (written by another solsim version, or edited)",
                    path.display(),
                    scenario_path.display(),
                    env!("CARGO_PKG_VERSION")
                );
            }
            Some(summary)
        }
    };
    progress.inc();
    let figures = report_html::run_figures(&scenario, &outcomes, a.map_r_m)?;
    let html = report_html::run_report(&scenario, &outcomes, summary.as_ref(), &figures)?;
    progress.finish();
    let strategies = match outcomes.len() {
        1 => "1 strategy".to_string(),
        n => format!("{n} strategies"),
    };
    let what = match &summary {
        Some(s) => format!("{strategies} on seed {seed}, and over {} runs", s.runs),
        None => format!("{strategies} on seed {seed}"),
    };
    Ok((html, what))
}
