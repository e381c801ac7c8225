//! The comparison for people and programs: the accuracy table of each matcher, the
//! side-by-side table (aligned text or Markdown), the whole printed report and its JSON.

use std::fmt::Write as _;

use localization::benchmark_set::{BenchmarkReport, ErrorStats};
use localization::matcher::Method;

use super::run::{BenchmarkRun, Comparison, ComparisonRow};

fn row(name: &str, e: &ErrorStats) -> String {
    format!(
        "  {name:<14} {:>5} {:>8.3} {:>9.3} {:>7.3} {:>7.3} {:>6} {:>6}\n",
        e.count, e.mean_m, e.median_m, e.p99_m, e.max_m, e.over_1m, e.over_2m
    )
}

/// The accuracy table of one matcher.
#[must_use]
pub fn accuracy_table(method: Method, r: &BenchmarkReport) -> String {
    let mut s = format!("method: {}\n", method.name());
    s.push_str("  cases              n   mean_m  median_m   p99_m   max_m  >1_m  >2_m\n");
    s.push_str(&row("all", &r.all));
    s.push_str(&row("accepted", &r.accepted));
    for (kind, e) in &r.by_terrain {
        s.push_str(&row(kind.name(), e));
    }
    let rejected: usize = r.rejections.iter().map(|(_, n)| n).sum();
    let reasons = if r.rejections.is_empty() {
        String::new()
    } else {
        let each: Vec<String> = r
            .rejections
            .iter()
            .map(|(name, n)| format!("{} {n}", name.replace('_', " ")))
            .collect();
        format!(" ({})", each.join(", "))
    };
    let _ = writeln!(
        s,
        "  rejected by validity checks: {rejected}{reasons}; could not run: {}",
        r.failures
    );
    s
}

/// The side-by-side table, as Markdown (`markdown`) or aligned text.
#[must_use]
pub fn table(rows: &[ComparisonRow], markdown: bool) -> String {
    let mut s = String::new();
    if markdown {
        s.push_str(
            "| localizer | accepted | mean m | p99 m | max m | within own radius | rejected | could not run | ms per case (mean / max) | needs |\n\
             |---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
        );
    } else {
        s.push_str(
            "localizer     accepted   mean_m    p99_m    max_m  in_radius  rejected  not_run  ms/case(mean)  ms/case(max)  needs\n",
        );
    }
    for r in rows {
        let a = &r.accepted;
        if markdown {
            let _ = writeln!(
                s,
                "| {} | {}/{} | {:.3} | {:.3} | {:.3} | {}/{} | {} | {} | {:.2} / {:.2} | {} |",
                r.localizer,
                a.count,
                r.cases,
                a.mean_m,
                a.p99_m,
                a.max_m,
                r.within_own_radius,
                a.count,
                r.rejected,
                r.could_not_run,
                r.mean_ms_per_case,
                r.max_ms_per_case,
                r.needs
            );
        } else {
            let _ = writeln!(
                s,
                "{:<12} {:>5}/{:<4} {:>7.3}  {:>7.3}  {:>7.3}  {:>9}  {:>8}  {:>7}  {:>13.2}  {:>12.2}  {}",
                r.localizer,
                a.count,
                r.cases,
                a.mean_m,
                a.p99_m,
                a.max_m,
                r.within_own_radius,
                r.rejected,
                r.could_not_run,
                r.mean_ms_per_case,
                r.max_ms_per_case,
                r.needs
            );
        }
    }
    s
}

impl BenchmarkRun {
    /// The printed report of `comparison`, which took `elapsed_s` seconds: each matcher's
    /// accuracy table, then with several localizers (or none of them a matcher) the
    /// side-by-side table, then the run's size and seeds.
    #[must_use]
    pub fn text(&self, comparison: &Comparison, elapsed_s: f64) -> String {
        let mut s = String::new();
        for (method, report) in &comparison.matcher_reports {
            let _ = writeln!(s, "{}", accuracy_table(*method, report));
        }
        if comparison.rows.len() > 1 || comparison.matcher_reports.is_empty() {
            s.push_str(
                "side by side (accuracy of the accepted results, metres; the localizer's own time per case):\n",
            );
            s.push_str(&table(&comparison.rows, false));
        }
        let _ = writeln!(
            s,
            "({} cases, seed {}, map seed {}, in {elapsed_s:.1} s)",
            self.cases, self.seed, self.map_seed
        );
        s
    }

    /// `comparison` as JSON: the run's size and seeds, the matchers' full reports and the
    /// side-by-side rows.
    #[must_use]
    pub fn json(&self, comparison: &Comparison) -> serde_json::Value {
        let reports: Vec<_> = comparison
            .matcher_reports
            .iter()
            .map(
                |(method, report)| serde_json::json!({ "method": method.name(), "report": report }),
            )
            .collect();
        serde_json::json!({
            "cases": self.cases,
            "seed": self.seed,
            "map_seed": self.map_seed,
            "matchers": reports,
            "comparison": comparison.rows,
        })
    }
}
