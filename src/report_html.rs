//! `report.html`: one self-contained page an operator opens in a browser — the figures as
//! inline SVG, the tables as HTML, no script, no stylesheet or font from the network.
//!
//! - [`run_report`]: one seeded run per strategy (what `solsim compare` prints and writes):
//!   the scenario, the compare table and its verdict against `ground`, the statistics over
//!   runs when there are any, the figures of [`run_figures`], and each strategy's sol log.
//! - [`sweep_report`]: a sweep directory: the rates with their intervals, the spreads, the
//!   paired differences from the baseline, the CDF of sols and the rates figure.

use std::fmt::Write as _;

use sim::CampaignOutcome;
use study::Scenario;
use sweep::engine::{CompletedSweep, Summary};

use crate::{figures, report_runs};

mod run_tables;

use run_tables::{against_ground_table, sol_log_table};

/// Text for HTML: `&`, `<`, `>` and quotes escaped.
#[must_use]
pub fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&#39;"),
            c => s.push(c),
        }
    }
    s
}

/// The figures of one compare run, as (file name, caption, SVG): the uncertainty radius and
/// the metres per sol of every strategy, and per strategy its map (keep-outs grown at
/// `map_r_m`, or by default each at the r the rover had where it passed it), the zoomed panels
/// at its passages, a zoom on each fault and, where its sols were planned, the Gantt chart of
/// the plans.
///
/// # Errors
/// When a figure cannot be drawn.
pub fn run_figures(
    scenario: &Scenario,
    outcomes: &[CampaignOutcome],
    map_r_m: Option<f64>,
) -> anyhow::Result<Vec<(String, String, String)>> {
    let name = &scenario.name;
    let mut out = vec![
        (
            format!("{name}.uncertainty.svg"),
            "Position-uncertainty radius r per sol: growth while driving, drops where a \
             localization resets it, red crosses at faults (paper 000 Fig. 2 and 5). Each \
             strategy has its own dash pattern and a marker at the end of each drive, and the \
             lines are shifted 2 px apart, so where strategies share a line all stay visible."
                .to_string(),
            figures::uncertainty_by_sol_svg(
                &format!("{name}: uncertainty radius r per sol"),
                outcomes,
            )?,
        ),
        (
            format!("{name}.metres.svg"),
            "Metres driven per sol and strategy; red crosses where the drive ended in a fault."
                .to_string(),
            figures::metres_by_sol_svg(&format!("{name}: metres driven per sol"), outcomes)?,
        ),
    ];
    for o in outcomes {
        let strategy = o.strategy.name();
        let (growth, how) = match map_r_m {
            Some(r) => (
                figures::Growth::At(r),
                format!(
                    "keep-outs grown by r = {r:.1} m (as asked, --map-r-m) plus the rover footprint"
                ),
            ),
            None => (
                figures::Growth::AtTheMoment,
                format!(
                    "each keep-out grown by the r the rover had where its path came closest to it, \
                     plus the rover footprint (light grey: never within {:.0} m of the path, not \
                     grown)",
                    figures::REACH_M
                ),
            ),
        };
        let passages = figures::passages_svg(scenario, o)?;
        let boxes = if passages.is_some() && map_r_m.is_none() {
            "; the lettered boxes are the zoomed panels of the next figure"
        } else {
            ""
        };
        out.push((
            format!("{name}.{strategy}.map.svg"),
            format!(
                "{strategy} on the map: {how}; the route, the driven path, each sol's end with its \
                 uncertainty disc, faults in red{boxes} (paper 000 Fig. 3-4)."
            ),
            figures::route_map_svg(scenario, o, growth, None)?,
        ));
        if let Some(svg) = passages {
            out.push((
                format!("{name}.{strategy}.passages.svg"),
                format!(
                    "{strategy} at each passage it drove through, zoomed: the keep-outs grown by the \
                     r it had at its closest pass (the dot, with its uncertainty disc) plus the rover \
                     footprint, so a passage is drawn as open or closed as it was when the rover got \
                     there."
                ),
                svg,
            ));
        }
        // A zoom on each fault, at the fault's own r (paper 000 Fig. 4 shows sol 385's).
        let footprint_m = scenario.campaign.grid.footprint_radius_m;
        for s in &o.sols {
            let Some(f) = &s.fault else { continue };
            let r_fault = map_r_m.unwrap_or(f.uncertainty_m);
            out.push((
                format!("{name}.{strategy}.fault-sol{}.map.svg", s.sol),
                format!(
                    "{strategy}: the {} of sol {} after {:.1} m, at r = {:.2} m: the keep-outs \
                     grown by r = {r_fault:.2} m plus the footprint, the path and the disc at \
                     the end of the drive.",
                    f.kind.name(),
                    s.sol,
                    f.after_m,
                    f.uncertainty_m
                ),
                figures::route_map_svg(
                    scenario,
                    o,
                    figures::Growth::At(r_fault),
                    Some(figures::fault_window(f.position_m, r_fault, footprint_m)),
                )?,
            ));
        }
        if let Some(svg) =
            figures::sol_plans_gantt_svg(&format!("{name}: {strategy} sol plans (LMST)"), o)?
        {
            out.push((
                format!("{name}.{strategy}.plans.svg"),
                format!(
                    "{strategy}: each sol's plan as executed (LMST), the co-processor (HBS) \
                     chain on its own row below the sol it belongs to."
                ),
                svg,
            ));
        }
    }
    Ok(out)
}

/// The page: up to 1320 px of text and figures (a 1400 px figure is shown nearly at its size
/// on a 1400 px screen); tables wrap their header and text cells to fit, and sit in a
/// container that scrolls sideways rather than cut a column off if a table still does not fit.
const STYLE: &str = "body{font-family:sans-serif;margin:2em auto;max-width:1320px;color:#222;\
padding:0 1em}h1{font-size:1.6em}h2{margin-top:2em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}\
th,td{border:1px solid #ccc;padding:2px 6px;text-align:right}\
th{background:#f2f2f2;vertical-align:bottom}td{vertical-align:top}\
td:first-child,th:first-child,td.l,th.l{text-align:left}\
pre{background:#f7f7f7;padding:.8em;overflow-x:auto;font-size:.85em}\
figure{margin:1.5em 0}figure svg{max-width:100%;height:auto;border:1px solid #eee}\
figcaption{font-size:.9em;color:#555}.scroll{overflow-x:auto;max-width:100%}\
.meta td,.meta th{text-align:left}";

fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n{body}</body>\n</html>\n",
        escape(title)
    )
}

fn figure_html(s: &mut String, id: &str, caption: &str, svg: &str) {
    // The SVG document's XML declaration (if any) is not valid inside HTML.
    let svg = svg.find("<svg").map_or(svg, |at| &svg[at..]).trim_end();
    let _ = writeln!(
        s,
        "<figure id=\"{}\">\n{svg}\n<figcaption>{}</figcaption>\n</figure>",
        escape(id),
        escape(caption)
    );
}

/// A table from rows of cells (the first row is the header).
fn table(s: &mut String, class: &str, rows: &[Vec<String>]) {
    table_aligned(s, class, rows, &[]);
}

/// A table from rows of cells (the first row is the header), the columns `left` (text)
/// aligned left, the others (numbers) right.
fn table_aligned(s: &mut String, class: &str, rows: &[Vec<String>], left: &[usize]) {
    let _ = writeln!(s, "<div class=\"scroll\"><table class=\"{class}\">");
    for (i, row) in rows.iter().enumerate() {
        let tag = if i == 0 { "th" } else { "td" };
        s.push_str("<tr>");
        for (j, cell) in row.iter().enumerate() {
            let align = if j > 0 && left.contains(&j) {
                " class=\"l\""
            } else {
                ""
            };
            let _ = write!(s, "<{tag}{align}>{}</{tag}>", escape(cell));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</table></div>\n");
}

/// A two-column table of names and values (no header row).
fn meta_table(s: &mut String, rows: &[[String; 2]]) {
    s.push_str("<table class=\"meta\">\n");
    for [name, value] in rows {
        let _ = writeln!(
            s,
            "<tr><th scope=\"row\">{}</th><td>{}</td></tr>",
            escape(name),
            escape(value)
        );
    }
    s.push_str("</table>\n");
}

/// The HTML report of one compare run: `outcomes` of `scenario` on its seed, `over_runs` when
/// the run also went over seeded worlds (`compare --runs`), `figures` from [`run_figures`]
/// (file name, caption, SVG).
///
/// # Errors
/// When a figure cannot be drawn.
pub fn run_report(
    scenario: &Scenario,
    outcomes: &[CampaignOutcome],
    over_runs: Option<&Summary>,
    figures: &[(String, String, String)],
) -> anyhow::Result<String> {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<h1>{}</h1>\n<p>{}</p>",
        escape(&scenario.name),
        escape(scenario.description.trim())
    );
    let seed = outcomes.first().map_or(scenario.campaign.seed, |o| o.seed);
    let cal = &scenario.campaign.calendar;
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
        let per = if t.drive_sols > 0 {
            t.distance_m / f64::from(t.drive_sols)
        } else {
            0.0
        };
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
            escape(report_runs::against_ground_over_runs(summary, left).trim_end())
        );
        statistics_tables(&mut s, summary);
    }
    s.push_str("<h2 id=\"figures\">Figures</h2>\n");
    for (name, caption, svg) in figures {
        figure_html(&mut s, name, caption, svg);
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
    Ok(page(&format!("solsim report: {}", scenario.name), &s))
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

/// The rate, spread and paired-difference tables of a summary.
fn statistics_tables(s: &mut String, summary: &Summary) {
    let st = &summary.statistics;
    let pct = |x: f64| format!("{:.1}", 100.0 * x);
    let mut rows = vec![
        [
            "strategy",
            "rate",
            "runs counted",
            "of runs",
            "%",
            "95 % interval (%)",
        ]
        .map(String::from)
        .to_vec(),
    ];
    for strat in &st.strategies {
        for r in strat.rates.iter().chain(strat.disc_coverage.iter()) {
            rows.push(vec![
                strat.strategy.clone(),
                r.name.clone(),
                r.count.to_string(),
                r.runs.to_string(),
                pct(r.rate),
                format!("[{}, {}]", pct(r.interval.lo), pct(r.interval.hi)),
            ]);
        }
    }
    s.push_str("<h3>Rates (95 % Wilson intervals; disc_coverage counts drive sols)</h3>\n");
    table(s, "rates", &rows);
    let mut rows = vec![
        [
            "strategy",
            "figure",
            "runs with a value",
            "mean",
            "median",
            "p5",
            "p95",
        ]
        .map(String::from)
        .to_vec(),
    ];
    for strat in &st.strategies {
        for f in &strat.figures {
            let Some(sp) = f.spread else { continue };
            rows.push(vec![
                strat.strategy.clone(),
                f.name.clone(),
                sp.n.to_string(),
                format!("{:.2}", sp.mean),
                format!("{:.2}", sp.median),
                format!("{:.2}", sp.p5),
                format!("{:.2}", sp.p95),
            ]);
        }
    }
    s.push_str("<h3>Spreads over the runs</h3>\n");
    table(s, "spreads", &rows);
    if let Some(base) = &st.baseline {
        let mut rows = vec![
            [
                "strategy",
                "figure",
                "runs paired",
                "mean difference",
                "95 % bootstrap interval",
            ]
            .map(String::from)
            .to_vec(),
        ];
        for p in &st.paired {
            let Some(d) = p.difference else { continue };
            rows.push(vec![
                p.strategy.clone(),
                p.figure.clone(),
                d.n.to_string(),
                format!("{:+.3}", d.mean),
                format!("[{:+.3}, {:+.3}]", d.interval.lo, d.interval.hi),
            ]);
        }
        let _ = writeln!(
            s,
            "<h3>Paired differences from {} (same world per run)</h3>",
            escape(base)
        );
        table(s, "paired", &rows);
    }
}

/// `sweep of 200 runs`, or for a shard `shard 1 of 2 (runs 0..100 of a sweep of 200)`.
#[must_use]
pub fn sweep_title(sweep: &CompletedSweep) -> String {
    match &sweep.manifest.shard {
        None => format!("sweep of {} runs", sweep.manifest.runs),
        Some(sh) => format!(
            "shard {} of {} (runs {}..{} of a sweep of {})",
            sh.index, sh.count, sh.first_run, sh.end_run, sweep.manifest.runs
        ),
    }
}

/// The HTML report of a complete sweep directory.
///
/// # Errors
/// When a figure cannot be drawn.
pub fn sweep_report(sweep: &CompletedSweep) -> anyhow::Result<String> {
    let m = &sweep.manifest;
    let summary = &sweep.summary;
    let name = &m.scenario.name;
    let mut s = String::new();
    let runs = sweep.runs_here;
    let _ = writeln!(
        s,
        "<h1>{} — {}</h1>",
        escape(name),
        escape(&sweep_title(sweep))
    );
    let mut meta: Vec<[String; 2]> = vec![
        ["scenario SHA-256".into(), m.scenario.sha256.clone()],
        ["sweep seed".into(), m.seed.to_string()],
        ["strategies".into(), m.strategies.join(", ")],
        [
            "baseline".into(),
            m.baseline.clone().unwrap_or_else(|| "none".into()),
        ],
        ["written by solsim".into(), m.solsim_version.clone()],
    ];
    if let Some(seg) = &m.segment {
        meta.push([
            "study segment".into(),
            format!("{:.0} m from sol {}", seg.distance_m, seg.from_sol),
        ]);
    }
    if let Some(sh) = &m.shard {
        meta.push([
            "shard".into(),
            format!(
                "{} of {} (runs {}..{})",
                sh.index, sh.count, sh.first_run, sh.end_run
            ),
        ]);
    }
    meta_table(&mut s, &meta);
    s.push_str("<h2 id=\"figures\">Figures</h2>\n");
    let segment = m.segment.is_some();
    let what = if segment {
        "sols to cover the study segment"
    } else {
        "sols to reach the goal"
    };
    figure_html(
        &mut s,
        &format!("{name}.sols-cdf.svg"),
        &format!(
            "Empirical distribution of the {what} per strategy over {runs} runs; a run that did \
             not get there within the calendar counts only in the denominator (the curve stays \
             below 1)."
        ),
        &figures::segment_sols_cdf_svg(
            &format!("{name}: {what}"),
            &m.strategies,
            &sweep.rows,
            segment,
        )?,
    );
    let rates: Vec<(String, Vec<sweep::summary::Rate>)> = summary
        .statistics
        .strategies
        .iter()
        .map(|st| (st.strategy.clone(), st.rates.clone()))
        .collect();
    figure_html(
        &mut s,
        &format!("{name}.rates.svg"),
        "Share of runs with a NO_PATH fault, any fault, the truth outside the disc, and the \
         goal reached, per strategy, with 95 % Wilson intervals.",
        &figures::rates_svg(&format!("{name}: rates over {runs} runs"), &rates)?,
    );
    s.push_str("<h2 id=\"statistics\">Statistics</h2>\n");
    statistics_tables(&mut s, summary);
    Ok(page(&format!("solsim sweep report: {name}"), &s))
}
