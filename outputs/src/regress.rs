//! `solsim regress DIR`: every scenario's `[[expect]]` entries checked ([`check_scenarios`], by
//! [`sweep::expect`]), and the results as text with a diff under each failure
//! ([`text_report`]), as JSON ([`json_report`]) and as JUnit XML for CI ([`junit`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use maps::input_file::printable;
use study::expect::Mismatch;
use study::{Scenario, ScenarioError};

/// The result of one expectation.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// Scenario file.
    pub scenario: PathBuf,
    /// `name/expect[i]`.
    pub case: String,
    /// The expectation's description.
    pub what: String,
    /// Failed checks (empty = pass).
    pub mismatches: Vec<Mismatch>,
    /// What a statistical expectation measured (rates and paired differences with their
    /// 95 % intervals), printed beside it; empty for checks of one run.
    pub measured: Vec<String>,
    /// Wall-clock seconds this case cost: its share of the scenario's load and single runs
    /// (split equally among the checks of one run), or of the sweep it needed (split among
    /// the statistical entries sharing it).
    pub seconds: f64,
}

/// What [`check_scenario_observed`] is doing, for a progress display.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage<'a> {
    /// Loading the scenario file (maps, zones, the passage search).
    Loading,
    /// Running each strategy the checks of one run need, once, for this many checks of the
    /// scenario `name`.
    OneRun {
        /// The scenario's name.
        name: &'a str,
        /// Checks of one run.
        checks: usize,
    },
    /// Sweeping what this many checks over runs need.
    OverRuns {
        /// The scenario's name.
        name: &'a str,
        /// Checks over runs.
        checks: usize,
    },
    /// This many more checks are done.
    Checked(usize),
}

/// How many `[[expect]]` entries the scenario file at `path` holds, read from its TOML without
/// loading it (0 for a file that is not a regular text file of TOML: loading it reports why): the total of
/// `solsim regress`'s progress.
#[must_use]
pub fn count_expectations(path: &Path) -> usize {
    maps::input_file::read_text_file(path)
        .ok()
        .and_then(|text| toml::from_str::<toml::Table>(&text).ok())
        .and_then(|t| {
            t.get("expect")
                .and_then(toml::Value::as_array)
                .map(Vec::len)
        })
        .unwrap_or(0)
}

/// Check one scenario: load it, run what its expectations need, check each one.
///
/// # Errors
/// The [`ScenarioError`] of a scenario that cannot be loaded.
pub fn check_scenario(
    path: &Path,
    budget: maps::MemoryBudget,
) -> Result<Vec<CaseResult>, ScenarioError> {
    check_scenario_observed(path, budget, &|_| {})
}

/// [`check_scenario`], telling `observe` each [`Stage`] as it begins and the checks as they
/// are done.
///
/// # Errors
/// The [`ScenarioError`] of a scenario that cannot be loaded.
pub fn check_scenario_observed(
    path: &Path,
    budget: maps::MemoryBudget,
    observe: &dyn Fn(Stage<'_>),
) -> Result<Vec<CaseResult>, ScenarioError> {
    let start = std::time::Instant::now();
    observe(Stage::Loading);
    let scenario = Scenario::load_within(path, budget)?;
    observe(Stage::OneRun {
        name: &scenario.name,
        checks: scenario.expectations.len(),
    });
    let checked = sweep::expect::check_one_run(&scenario);
    observe(Stage::Checked(scenario.expectations.len()));
    let one_run_s = start.elapsed().as_secs_f64() / scenario.expectations.len().max(1) as f64;
    let mut results: Vec<(usize, CaseResult)> = scenario
        .expectations
        .iter()
        .zip(checked)
        .map(|(e, mismatches)| {
            let case = CaseResult {
                scenario: path.to_path_buf(),
                case: format!("{}/expect[{}]", scenario.name, e.index),
                what: e.what.clone(),
                mismatches,
                measured: Vec::new(),
                seconds: one_run_s,
            };
            (e.index, case)
        })
        .collect();
    observe(Stage::OverRuns {
        name: &scenario.name,
        checks: scenario.statistical_expectations.len(),
    });
    let swept = sweep::expect::check_statistical(&scenario);
    observe(Stage::Checked(scenario.statistical_expectations.len()));
    results.extend(
        scenario
            .statistical_expectations
            .iter()
            .zip(swept)
            .map(|(e, r)| {
                let case = CaseResult {
                    scenario: path.to_path_buf(),
                    case: format!("{}/expect[{}]", scenario.name, e.index),
                    what: format!("{} (over {} runs)", e.what, e.runs),
                    mismatches: r.mismatches,
                    measured: r.measured,
                    seconds: r.seconds,
                };
                (e.index, case)
            }),
    );
    results.sort_by_key(|(i, _)| *i);
    Ok(results.into_iter().map(|(_, c)| c).collect())
}

/// [`check_scenario_observed`] for each of `files` in turn, the results in file order; stops at
/// the first scenario that cannot be loaded. `observe` hears each file's stages.
///
/// # Errors
/// The [`ScenarioError`] of the first scenario that cannot be loaded.
pub fn check_scenarios(
    files: &[PathBuf],
    budget: maps::MemoryBudget,
    observe: &dyn Fn(&Path, Stage<'_>),
) -> Result<Vec<CaseResult>, ScenarioError> {
    let mut results = Vec::new();
    for f in files {
        results.extend(check_scenario_observed(f, budget, &|stage| {
            observe(f, stage)
        })?);
    }
    Ok(results)
}

/// The scenario files of a directory (`*.toml`, sorted).
///
/// # Errors
/// The directory cannot be read.
pub fn scenario_files(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    Ok(files)
}

/// Human-readable report: one line per case, and a diff under each failure.
#[must_use]
pub fn text_report(results: &[CaseResult]) -> String {
    let mut s = String::new();
    for r in results {
        let status = if r.mismatches.is_empty() {
            "ok  "
        } else {
            "FAIL"
        };
        // Loaders refuse control characters in names and `what`; escape again all the same,
        // so nothing from a file can drive the terminal.
        let _ = writeln!(s, "{status} {}  {}", printable(&r.case), printable(&r.what));
        for m in &r.measured {
            let _ = writeln!(s, "       {}", printable(m));
        }
        for m in &r.mismatches {
            let _ = writeln!(
                s,
                "       {}\n       - expected: {}\n       + got:      {}",
                printable(&m.check),
                printable(&m.expected),
                printable(&m.got)
            );
        }
    }
    let failed = results.iter().filter(|r| !r.mismatches.is_empty()).count();
    let _ = writeln!(s, "{} passed, {} failed", results.len() - failed, failed);
    s
}

/// The report as JSON (`solsim regress --json`).
#[must_use]
pub fn json_report(results: &[CaseResult]) -> String {
    let failed = results.iter().filter(|r| !r.mismatches.is_empty()).count();
    let cases: Vec<serde_json::Value> = results
        .iter()
        .map(|r| {
            serde_json::json!({
                "scenario": r.scenario.display().to_string(),
                "case": r.case,
                "what": r.what,
                "ok": r.mismatches.is_empty(),
                "measured": r.measured,
                "mismatches": r.mismatches.iter().map(|m| serde_json::json!({
                    "check": m.check,
                    "expected": m.expected,
                    "got": m.got,
                })).collect::<Vec<_>>(),
                "seconds": r.seconds,
            })
        })
        .collect();
    let doc = serde_json::json!({
        "passed": results.len() - failed,
        "failed": failed,
        "cases": cases,
    });
    serde_json::to_string_pretty(&doc).unwrap_or_default()
}

/// `s` as XML 1.0 character data or attribute value: markup characters as entities; tab, line
/// feed and carriage return as character references (kept through attribute normalisation);
/// every other control character — which XML 1.0 forbids (U+0001 …) or a reader's terminal
/// would obey — and U+FFFE / U+FFFF as its printable escape (`\u{1}`).
fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\t' => out.push_str("&#9;"),
            '\n' => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            c if maps::input_file::is_unsafe_char(c) || matches!(c, '\u{fffe}' | '\u{ffff}') => {
                out.extend(c.escape_default());
            }
            c => out.push(c),
        }
    }
    out
}

/// JUnit XML for CI.
#[must_use]
pub fn junit(results: &[CaseResult]) -> String {
    let failed = results.iter().filter(|r| !r.mismatches.is_empty()).count();
    let total_s: f64 = results.iter().map(|r| r.seconds).sum();
    let mut s = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"solsim-regress\" tests=\"{}\" failures=\"{failed}\" time=\"{total_s:.3}\">\n",
        results.len()
    );
    for r in results {
        let _ = write!(
            s,
            "  <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\"",
            xml_escape(&r.scenario.display().to_string()),
            xml_escape(&format!("{} {}", r.case, r.what)),
            r.seconds
        );
        if r.mismatches.is_empty() {
            s.push_str("/>\n");
        } else {
            let body: Vec<String> = r
                .mismatches
                .iter()
                .map(|m| format!("{}: expected {}, got {}", m.check, m.expected, m.got))
                .collect();
            let _ = writeln!(
                s,
                ">\n    <failure message=\"{}\">{}</failure>\n  </testcase>",
                xml_escape(&body[0]),
                xml_escape(&body.join("\n"))
            );
        }
    }
    s.push_str("</testsuite>\n");
    s
}
