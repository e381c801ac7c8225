//! What `solsim validate` reports of a scenario loaded without running it: what makes no
//! sense in it ([`crate::sanity`]'s findings), what was loaded, and each route leg's passage
//! clearance — as text or as a JSON document ([`Report`]).

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use crate::Scenario;
use crate::sanity::{Finding, Severity};

/// What was loaded, in figures.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Summary<'a> {
    /// The scenario's name.
    pub name: &'a str,
    /// Sols in the calendar.
    pub sols: usize,
    /// The first sol.
    pub first_sol: u32,
    /// The last sol.
    pub last_sol: u32,
    /// Route waypoints.
    pub waypoints: usize,
    /// Route length, metres.
    pub route_m: f64,
    /// Every `[[expect]]` entry, as `solsim regress` counts them.
    pub expectations: usize,
    /// Of which checked on one run per strategy.
    pub one_run_expectations: usize,
    /// Of which checked over a sweep (`runs = N`).
    pub statistical_expectations: usize,
    /// Planning grid, cells (width, height).
    pub grid_cells: [usize; 2],
    /// Planning grid cell size, metres.
    pub grid_resolution_m: f64,
    /// Science targets.
    pub science_targets: usize,
}

/// A route leg and the radius at which it closes.
#[derive(Debug, Serialize)]
pub struct Leg {
    /// The waypoint the leg leads to (index in the route).
    pub to_waypoint: usize,
    /// That waypoint, map metres.
    pub to_m: [f64; 2],
    /// Radius at which the leg closes (`null`: no path even at r = 0).
    pub closes_at_r_m: Option<f64>,
}

/// `solsim validate --json`.
#[derive(Debug, Serialize)]
pub struct Report<'a> {
    /// The scenario file.
    pub file: String,
    /// No error (warnings allowed).
    pub ok: bool,
    /// Findings that are errors.
    pub errors: usize,
    /// Findings that are warnings.
    pub warnings: usize,
    /// Every finding.
    pub findings: &'a [Finding],
    /// What was loaded.
    pub scenario: Summary<'a>,
    /// Each route leg's passage clearance.
    pub legs: Vec<Leg>,
}

/// A scenario's validation: the file, what was loaded and its findings.
#[derive(Debug)]
pub struct Validation<'a> {
    file: String,
    scenario: &'a Scenario,
    findings: &'a [Finding],
    summary: Summary<'a>,
}

impl<'a> Validation<'a> {
    /// The validation of `scenario`, loaded from `file` with `findings`.
    #[must_use]
    pub fn new(file: &Path, scenario: &'a Scenario, findings: &'a [Finding]) -> Self {
        let c = &scenario.settings;
        let s = scenario;
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
        Self {
            file: file.display().to_string(),
            scenario,
            findings,
            summary,
        }
    }

    /// Findings of [`Severity::Error`]: every other command refuses the scenario with the
    /// first.
    #[must_use]
    pub fn errors(&self) -> usize {
        self.findings
            .iter()
            .filter(|f| f.severity == Severity::Error)
            .count()
    }

    /// The JSON document (`solsim validate --json`).
    #[must_use]
    pub fn report(&self) -> Report<'_> {
        let errors = self.errors();
        let route = &self.scenario.settings.route;
        Report {
            file: self.file.clone(),
            ok: errors == 0,
            errors,
            warnings: self.findings.len() - errors,
            findings: self.findings,
            scenario: self.summary,
            legs: self
                .scenario
                .legs
                .iter()
                .map(|l| Leg {
                    to_waypoint: l.to_waypoint,
                    to_m: route[l.to_waypoint],
                    closes_at_r_m: l.clearance_m,
                })
                .collect(),
        }
    }

    /// The text: one line per finding, the verdict with what was loaded, the grid, the
    /// science, and each leg's passage clearance.
    #[must_use]
    pub fn text(&self) -> String {
        let (s, summary, file) = (self.scenario, &self.summary, &self.file);
        let c = &s.settings;
        let errors = self.errors();
        let warnings = self.findings.len() - errors;
        let mut t = String::new();
        for f in self.findings {
            let _ = writeln!(t, "{file}: {f}");
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
        let _ = writeln!(
            t,
            "{file}: {verdict} — {} ({} sols {}..{}, {} waypoints, {:.1} m of route, {})",
            s.name,
            summary.sols,
            summary.first_sol,
            summary.last_sol,
            summary.waypoints,
            summary.route_m,
            expectations_text(summary)
        );
        let _ = writeln!(
            t,
            "grid: {} × {} cells of {} m",
            c.grid.width, c.grid.height, c.grid.geo.resolution_m_per_px
        );
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
            let _ = writeln!(
                t,
                "science: {} targets ({later} revealed during the run); campaigns {}",
                sci.targets.len(),
                campaigns.join(", ")
            );
        }
        let _ = writeln!(
            t,
            "passage clearance per route leg (the uncertainty radius at which the leg closes):"
        );
        for l in &s.legs {
            let p = c.route[l.to_waypoint];
            let _ = match l.clearance_m {
                Some(r) => writeln!(
                    t,
                    "  leg to waypoint {:>2} ({:.1}, {:.1}): closes at r = {r:.2} m",
                    l.to_waypoint, p[0], p[1]
                ),
                None => writeln!(
                    t,
                    "  leg to waypoint {:>2} ({:.1}, {:.1}): no path even at r = 0",
                    l.to_waypoint, p[0], p[1]
                ),
            };
        }
        t
    }
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
