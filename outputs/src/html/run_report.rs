//! The report of one compare run ([`run_report`]): the scenario, the compare table, the verdict
//! against `ground` as a table, the statistics over runs when there are any, the figures and
//! each strategy's sol log.

use std::fmt::Write as _;

use sim::CampaignOutcome;
use study::Scenario;
use sweep::engine::Summary;

use crate::figures::run_figures::RunFigure;
use crate::html::markup::{escape, figure_html, meta_table, page, table};
use crate::html::run_tables::{against_ground_table, sol_log_table};
use crate::html::statistics::statistics_tables;
use crate::over_runs::against_ground_over_runs;
use crate::tables::metres_per_drive_sol;

/// The HTML report of one compare run: `outcomes` of `scenario` on its seed, `over_runs` when
/// the run also went over seeded worlds (`compare --runs`), `figures` from
/// [`crate::figures::run_figures()`], shown inline in their order.
#[must_use]
pub fn run_report(
    scenario: &Scenario,
    outcomes: &[CampaignOutcome],
    over_runs: Option<&Summary>,
    figures: &[RunFigure],
) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<h1>{}</h1>\n<p>{}</p>",
        escape(&scenario.name),
        escape(scenario.description.trim())
    );
    let seed = outcomes.first().map_or(scenario.seed, |o| o.seed);
    let cal = &scenario.settings.calendar;
    let sols = outcomes.iter().flat_map(|o| o.sols.iter());
    let first = sols.clone().map(|r| r.sol).min().unwrap_or(0);
    let last = sols.map(|r| r.sol).max().unwrap_or(first);
    meta_table(
        &mut s,
        &[
            ["scenario file".into(), scenario.path.display().to_string()],
            ["scenario SHA-256".into(), scenario.sha256.clone()],
            ["seed".into(), seed.to_string()],
            [
                "sols".into(),
                format!("{first}-{last} ({} in the calendar)", cal.sols_from(first)),
            ],
            ["solsim".into(), env!("CARGO_PKG_VERSION").into()],
        ],
    );
    s.push_str("<h2 id=\"compare\">Strategies side by side (one seeded run each)</h2>\n");
    let mut rows = vec![
        [
            "strategy",
            "sols to goal",
            "drive sols",
            "distance (m)",
            "m per drive sol",
            "NO_PATH faults",
            "faults",
            "max r (m)",
            "onboard localizations applied / rejected",
            "ground localizations",
        ]
        .map(String::from)
        .to_vec(),
    ];
    for o in outcomes {
        let t = &o.totals;
        let per = metres_per_drive_sol(t);
        rows.push(vec![
            o.strategy.name().into(),
            t.sols_to_goal
                .map_or("not reached".into(), |n| n.to_string()),
            t.drive_sols.to_string(),
            format!("{:.1}", t.distance_m),
            format!("{per:.1}"),
            t.no_path_faults.to_string(),
            t.faults.to_string(),
            format!("{:.2}", t.max_uncertainty_m),
            format!(
                "{} / {}",
                t.onboard_localizations_applied, t.onboard_localizations_rejected
            ),
            t.ground_localizations.to_string(),
        ]);
    }
    table(&mut s, "compare", &rows);
    science_table(&mut s, outcomes);
    against_ground_table(&mut s, scenario, outcomes);
    if let Some(summary) = over_runs {
        let left = scenario.study_segment.map(|g| cal.sols_from(g.from_sol));
        let _ = writeln!(
            s,
            "<h2 id=\"over-runs\">Over {} seeded worlds</h2>\n<pre>{}</pre>",
            summary.runs,
            escape(against_ground_over_runs(summary, left).trim_end())
        );
        statistics_tables(&mut s, summary);
    }
    s.push_str("<h2 id=\"figures\">Figures</h2>\n");
    for f in figures {
        figure_html(&mut s, &f.file, &f.caption, &f.svg);
    }
    s.push_str(
        "<h2 id=\"sol-logs\">Sol logs</h2>\n<p>Each strategy's sols; every column, under its \
         machine name, is in <code>&lt;scenario&gt;.&lt;strategy&gt;.sols.csv</code> beside the \
         run.</p>\n",
    );
    for o in outcomes {
        let _ = writeln!(s, "<h3 id=\"sols-{0}\">{0}</h3>", escape(o.strategy.name()));
        sol_log_table(&mut s, o);
        let changes: Vec<String> = o
            .sols
            .iter()
            .filter_map(|r| r.activity_plan.as_ref().map(|p| (r.sol, p)))
            .flat_map(|(sol, p)| p.changes.iter().map(move |c| format!("sol {sol} {c}")))
            .collect();
        if !changes.is_empty() {
            let _ = writeln!(
                s,
                "<p>Plan changes during execution:</p>\n<pre>{}</pre>",
                escape(&changes.join("\n"))
            );
        }
    }
    page(&format!("solsim report: {}", scenario.name), &s)
}

/// Science campaigns side by side (`done / failed` per campaign and strategy), when the
/// scenario has any (as under the terminal's compare table).
fn science_table(s: &mut String, outcomes: &[CampaignOutcome]) {
    let Some(first) = outcomes.iter().find(|o| !o.totals.science.is_empty()) else {
        return;
    };
    let campaigns: Vec<&String> = first.totals.science.keys().collect();
    let mut rows = vec![
        std::iter::once("strategy".to_string())
            .chain(campaigns.iter().map(|c| format!("{c} done / failed")))
            .collect::<Vec<_>>(),
    ];
    for o in outcomes {
        rows.push(
            std::iter::once(o.strategy.name().to_string())
                .chain(campaigns.iter().map(|c| {
                    o.totals
                        .science
                        .get(*c)
                        .map_or("-".into(), |t| format!("{} / {}", t.done, t.failed))
                }))
                .collect(),
        );
    }
    s.push_str("<h3 id=\"science\">Science campaigns</h3>\n");
    table(s, "science", &rows);
}
