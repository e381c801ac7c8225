//! The report of a complete sweep directory ([`sweep_report`]): its provenance, the CDF of the
//! sols each strategy took, the rates figure and the statistics tables.

use std::fmt::Write as _;

use sweep::engine::CompletedSweep;

use crate::figures::canvas::FigureError;
use crate::figures::sweep_figures::{rates_svg, segment_sols_cdf_svg};
use crate::html::markup::{escape, figure_html, meta_table, page};
use crate::html::statistics::statistics_tables;

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
pub fn sweep_report(sweep: &CompletedSweep) -> Result<String, FigureError> {
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
        &segment_sols_cdf_svg(
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
        &rates_svg(&format!("{name}: rates over {runs} runs"), &rates)?,
    );
    s.push_str("<h2 id=\"statistics\">Statistics</h2>\n");
    statistics_tables(&mut s, summary);
    Ok(page(&format!("solsim sweep report: {name}"), &s))
}
