//! The statistics tables of a summary over runs: rates with their Wilson intervals, spreads,
//! paired differences from the baseline (a compare run with `--runs` and a sweep show them).

use std::fmt::Write as _;

use sweep::engine::Summary;

use crate::html::markup::{escape, table};

/// The rate, spread and paired-difference tables of a summary.
pub(crate) fn statistics_tables(s: &mut String, summary: &Summary) {
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
