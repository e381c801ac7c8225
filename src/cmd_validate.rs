//! `solsim validate`: load a scenario without running it, list what makes no sense in it
//! ([`study::sanity`]) and describe what was loaded.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use maps::MemoryBudget;
use serde::Serialize;
use study::Scenario;
use study::sanity::{Finding, Severity};

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

#[derive(Serialize)]
struct Summary<'a> {
    name: &'a str,
    sols: usize,
    first_sol: u32,
    last_sol: u32,
    waypoints: usize,
    route_m: f64,
    /// Every `[[expect]]` entry, as `solsim regress` counts them.
    expectations: usize,
    /// Of which checked on one run per strategy.
    one_run_expectations: usize,
    /// Of which checked over a sweep (`runs = N`).
    statistical_expectations: usize,
    grid_cells: [usize; 2],
    grid_resolution_m: f64,
    science_targets: usize,
}

#[derive(Serialize)]
struct Leg {
    to_waypoint: usize,
    to_m: [f64; 2],
    /// Radius at which the leg closes (`null`: no path even at r = 0).
    closes_at_r_m: Option<f64>,
}

#[derive(Serialize)]
struct Report<'a> {
    file: String,
    ok: bool,
    errors: usize,
    warnings: usize,
    findings: &'a [Finding],
    scenario: Summary<'a>,
    legs: Vec<Leg>,
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
    let c = &s.campaign;
    let errors = findings
        .iter()
        .filter(|f| f.severity == Severity::Error)
        .count();
    let warnings = findings.len() - errors;
    let code = if errors > 0 {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    };
    let route_m: f64 = c
        .route
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum();
    let summary = Summary {
        name: &s.name,
        sols: c.calendar.sols.len(),
        first_sol: c.calendar.sols[0].sol,
        last_sol: c.calendar.sols[c.calendar.sols.len() - 1].sol,
        waypoints: c.route.len(),
        route_m,
        expectations: s.expectations.len() + s.statistical_expectations.len(),
        one_run_expectations: s.expectations.len(),
        statistical_expectations: s.statistical_expectations.len(),
        grid_cells: [c.grid.width, c.grid.height],
        grid_resolution_m: c.grid.geo.resolution_m_per_px,
        science_targets: c.science.targets.len(),
    };
    let file = a.scenario.display().to_string();
    if a.json {
        let report = Report {
            file,
            ok: errors == 0,
            errors,
            warnings,
            findings: &findings,
            scenario: summary,
            legs: s
                .legs
                .iter()
                .map(|l| Leg {
                    to_waypoint: l.to_waypoint,
                    to_m: c.route[l.to_waypoint],
                    closes_at_r_m: l.clearance_m,
                })
                .collect(),
        };
        writeln!(stdout, "{}", serde_json::to_string_pretty(&report)?)?;
        return Ok(code);
    }
    for f in &findings {
        writeln!(stdout, "{file}: {f}")?;
    }
    let verdict = match (errors, warnings) {
        (0, 0) => "ok".to_string(),
        (0, w) => format!("ok with {w} warning{}", plural(w)),
        (e, w) => format!(
            "{e} error{}, {w} warning{} — every other command refuses this scenario",
            plural(e),
            plural(w)
        ),
    };
    writeln!(
        stdout,
        "{file}: {verdict} — {} ({} sols {}..{}, {} waypoints, {:.1} m of route, {})",
        s.name,
        summary.sols,
        summary.first_sol,
        summary.last_sol,
        summary.waypoints,
        route_m,
        expectations_text(&summary)
    )?;
    writeln!(
        stdout,
        "grid: {} × {} cells of {} m",
        c.grid.width, c.grid.height, c.grid.geo.resolution_m_per_px
    )?;
    if !c.science.is_empty() {
        let sci = &c.science;
        let later = sci.targets.iter().filter(|t| t.revealed.is_some()).count();
        let campaigns: Vec<String> = sci
            .goal_set
            .iter()
            .map(|g| format!("{} (goal set)", g.id))
            .chain(
                sci.periodic
                    .iter()
                    .map(|p| format!("{} (periodic)", p.campaign.id)),
            )
            .chain(
                sci.state_based
                    .iter()
                    .map(|s| format!("{} (state-based)", s.campaign.id)),
            )
            .collect();
        writeln!(
            stdout,
            "science: {} targets ({later} revealed during the run); campaigns {}",
            sci.targets.len(),
            campaigns.join(", ")
        )?;
    }
    writeln!(
        stdout,
        "passage clearance per route leg (the uncertainty radius at which the leg closes):"
    )?;
    for l in &s.legs {
        let p = c.route[l.to_waypoint];
        match l.clearance_m {
            Some(r) => writeln!(
                stdout,
                "  leg to waypoint {:>2} ({:.1}, {:.1}): closes at r = {r:.2} m",
                l.to_waypoint, p[0], p[1]
            )?,
            None => writeln!(
                stdout,
                "  leg to waypoint {:>2} ({:.1}, {:.1}): no path even at r = 0",
                l.to_waypoint, p[0], p[1]
            )?,
        }
    }
    Ok(code)
}

/// `6 expectations (2 on one run, 4 over runs)`: every `[[expect]]` entry, as `solsim
/// regress` counts its cases.
fn expectations_text(summary: &Summary<'_>) -> String {
    let n = summary.expectations;
    let mut s = format!("{n} expectation{}", plural(n));
    if summary.one_run_expectations > 0 && summary.statistical_expectations > 0 {
        s.push_str(&format!(
            " ({} on one run, {} over runs)",
            summary.one_run_expectations, summary.statistical_expectations
        ));
    } else if summary.statistical_expectations > 0 {
        s.push_str(" (all over runs)");
    }
    s
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}
