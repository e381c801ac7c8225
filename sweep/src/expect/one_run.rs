//! `[[expect]]` entries of one run: each strategy they name run once on the scenario's seed
//! ([`check_one_run`]), each entry's checks against those runs ([`check_run`]).

use sim::{CampaignOutcome, FaultKind, Strategy};
use study::Scenario;
use study::expect::{Check, Expectation, Mismatch};

/// Runs the strategies the scenario's `[[expect]]` entries of one run need (in parallel, under
/// the scenario's seed) and checks every entry: one list of mismatches per entry, in file
/// order (empty = the entry holds).
#[must_use]
pub fn check_one_run(scenario: &Scenario) -> Vec<Vec<Mismatch>> {
    let mut needed: Vec<Strategy> = scenario
        .expectations
        .iter()
        .flat_map(Expectation::strategies)
        .collect();
    needed.sort_by_key(|s| s.stream_id());
    needed.dedup();
    let runs = scenario.compare(&needed, scenario.seeds());
    let outcome = |s: Strategy| {
        let i = needed.iter().position(|&n| n == s).unwrap_or_default();
        &runs[i]
    };
    scenario
        .expectations
        .iter()
        .map(|e| check_run(e, outcome))
        .collect()
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or_else(|| "nothing".into(), |v| format!("{v:.3}"))
}

/// Checks one entry against the runs (`outcome(strategy)` gives each strategy's run): one
/// [`Mismatch`] per failed check, none when the entry holds.
#[must_use]
pub fn check_run<'a>(
    e: &Expectation,
    outcome: impl Fn(Strategy) -> &'a CampaignOutcome,
) -> Vec<Mismatch> {
    let run = outcome(e.strategy);
    let rec = e.sol.and_then(|s| run.sol(s));
    let label = |q: &str| match e.sol {
        Some(s) => format!("{} sol {s} {q}", e.strategy.name()),
        None => format!("{} {q}", e.strategy.name()),
    };
    let mut out = Vec::new();
    for c in &e.checks {
        match c {
            Check::Fault(kind) => {
                let got = rec.and_then(|r| r.fault.as_ref()).map(|f| f.kind);
                if got != *kind {
                    let name = |k: Option<FaultKind>| k.map_or("none", FaultKind::name).into();
                    out.push(Mismatch {
                        check: label("fault"),
                        expected: name(*kind),
                        got: name(got),
                    });
                }
            }
            Check::Range { quantity, lo, hi } => {
                let got: Option<f64> = match *quantity {
                    "fault_after_m" => rec.and_then(|r| r.fault.as_ref()).map(|f| f.after_m),
                    "fault_uncertainty_m" => {
                        rec.and_then(|r| r.fault.as_ref()).map(|f| f.uncertainty_m)
                    }
                    "distance_m" => rec.map(|r| r.distance_m),
                    "end_uncertainty_m" => rec.map(|r| r.end_uncertainty_m),
                    "total_distance_m" => Some(run.totals.distance_m),
                    "max_uncertainty_m" => Some(run.totals.max_uncertainty_m),
                    "no_path_faults" => Some(f64::from(run.totals.no_path_faults)),
                    "faults" => Some(f64::from(run.totals.faults)),
                    "sols_to_goal" => run.totals.sols_to_goal.map(f64::from),
                    // The sol's plan with `sol`, every sol's otherwise.
                    "plan_violations" => Some(
                        run.sols
                            .iter()
                            .filter(|r| e.sol.is_none_or(|s| r.sol == s))
                            .filter_map(|r| r.activity_plan.as_ref())
                            .map(|p| p.violations.len() as f64)
                            .sum(),
                    ),
                    _ => None,
                };
                if !got.is_some_and(|g| g >= *lo - 1e-9 && g <= *hi + 1e-9) {
                    out.push(Mismatch {
                        check: label(quantity),
                        expected: format!("[{lo}, {hi}]"),
                        got: fmt_opt(got),
                    });
                }
            }
            Check::Drove(d) => {
                let got = rec.map(|r| r.drove);
                if got != Some(*d) {
                    out.push(Mismatch {
                        check: label("drove"),
                        expected: d.to_string(),
                        got: got.map_or("nothing".into(), |g| g.to_string()),
                    });
                }
            }
            Check::Sooner { than, by } => {
                let mine = run.totals.sols_to_goal;
                let theirs = outcome(*than).totals.sols_to_goal;
                let ok = match (mine, theirs) {
                    (Some(m), Some(t)) => m + by <= t,
                    (Some(_), None) => true,
                    _ => false,
                };
                if !ok {
                    out.push(Mismatch {
                        check: label(&format!("sols_to_goal vs {}", than.name())),
                        expected: format!(
                            "at least {by} fewer than {}",
                            theirs.map_or("never".into(), |t| t.to_string())
                        ),
                        got: mine.map_or("goal not reached".into(), |m| m.to_string()),
                    });
                }
            }
            Check::Science {
                campaign,
                failed,
                lo,
                hi,
            } => {
                let got = run
                    .totals
                    .science
                    .get(campaign)
                    .map(|t| if *failed { t.failed } else { t.done });
                let what = if *failed { "failed" } else { "done" };
                if !got.is_some_and(|g| g >= *lo && g <= *hi) {
                    out.push(Mismatch {
                        check: label(&format!("science {campaign} {what}")),
                        expected: format!("[{lo}, {hi}]"),
                        got: got.map_or("no such campaign".into(), |g| g.to_string()),
                    });
                }
            }
            Check::Covers {
                from_sol,
                distance_m,
                lo,
                hi,
            } => {
                let got = run.sols_to_cover(*from_sol, *distance_m);
                if !got.is_some_and(|g| g >= *lo && g <= *hi) {
                    out.push(Mismatch {
                        check: label(&format!("sols to cover {distance_m} m from sol {from_sol}")),
                        expected: format!("[{lo}, {hi}]"),
                        got: got.map_or("never".into(), |g| g.to_string()),
                    });
                }
            }
        }
    }
    out
}
