//! Each sol's executed plan as a Gantt chart ([`sol_plans_gantt_svg`]), the co-processor (HBS)
//! chain on its own row.

use plotters::prelude::*;
use sim::CampaignOutcome;

use crate::figures::canvas::{FigureError, Legend, Mark, WIDTH, plot_error, svg_with_legend};

/// What kind of activity a timeline row is, for its colour in [`sol_plans_gantt_svg`].
fn activity_class(activity: &str) -> (&'static str, RGBColor) {
    if activity.starts_with("drive") {
        ("drive", RGBColor(31, 119, 180))
    } else if activity == "hbs_transfer" {
        ("HBS: image transfer", RGBColor(148, 103, 189))
    } else if activity.starts_with("hbs_run") {
        ("HBS: localization run", RGBColor(197, 176, 213))
    } else if activity.starts_with("hbs_") {
        ("HBS: reboot", RGBColor(84, 39, 143))
    } else if activity.starts_with("heating") {
        ("heating", RGBColor(214, 39, 40))
    } else if activity.contains("imaging") || activity.contains("panorama") {
        ("post-drive imaging", RGBColor(255, 127, 14))
    } else if activity == "sunfind" || activity == "compare_apply" {
        (
            "localization: sunfind, compare and apply",
            RGBColor(44, 160, 44),
        )
    } else if activity.contains("comm") || activity.contains("downlink") {
        ("comm pass", RGBColor(23, 190, 207))
    } else {
        ("science", RGBColor(188, 189, 34))
    }
}

/// Whether a timeline row's outcome is a failure (a fault, a target out of reach).
fn failed(outcome: Option<&str>) -> bool {
    outcome.is_some_and(|o| {
        ["NO_PATH", "KEEP_OUT", "KEEP_IN", "out of reach", "failed"]
            .iter()
            .any(|w| o.contains(w))
    })
}

/// Each sol's executed plan of one run as a Gantt chart: one row per sol for the main
/// timeline and, where the sol ran the co-processor chain, one below it for the HBS link
/// (transfer, runs, reboot), against LMST (a Mars hour is 1/24 of the sol, 3698.96 s). A red
/// cross marks a row that failed (a drive's fault, a science target out of reach). `None` when
/// no sol of the run has a plan.
///
/// # Errors
/// When plotters cannot draw.
pub fn sol_plans_gantt_svg(
    title: &str,
    outcome: &CampaignOutcome,
) -> Result<Option<String>, FigureError> {
    let mars_hour_s = f64::from(sim::time::SOL_S) / 24.0;
    let lmst_h = |s: sim::time::SolSeconds| s.0 as f64 / mars_hour_s;
    // Rows: (label, sol, HBS link?).
    let mut rows: Vec<(String, u32, bool)> = Vec::new();
    for s in &outcome.sols {
        let Some(plan) = &s.activity_plan else {
            continue;
        };
        if plan.timeline.is_empty() {
            continue;
        }
        rows.push((format!("sol {}", s.sol), s.sol, false));
        if plan.timeline.iter().any(|t| !t.timeline.is_main()) {
            rows.push((format!("{} HBS", s.sol), s.sol, true));
        }
    }
    if rows.is_empty() {
        return Ok(None);
    }
    let steps = || {
        outcome
            .sols
            .iter()
            .filter_map(|s| s.activity_plan.as_ref())
            .flat_map(|p| p.timeline.iter())
    };
    let t0 = steps().map(|t| lmst_h(t.start_s)).fold(f64::MAX, f64::min);
    let t1 = steps().map(|t| lmst_h(t.end_s)).fold(f64::MIN, f64::max);
    let (h0, h1) = (t0.floor(), t1.ceil().max(t0.floor() + 1.0));
    let n = rows.len();
    let mut legend: Legend = Vec::new();
    for t in steps() {
        let (class, c) = activity_class(&t.activity);
        if !legend.iter().any(|(l, _)| l == class) {
            legend.push((class.to_string(), Mark::Fill(c.to_rgba())));
        }
    }
    legend.sort_by(|a, b| a.0.cmp(&b.0));
    if steps().any(|t| failed(t.outcome.as_deref())) {
        legend.push(("failed (fault, target out of reach)".into(), Mark::Cross));
    }
    let labels = rows.iter().map(|r| r.0.clone()).collect::<Vec<_>>();
    let height = (100 + 26 * n) as u32;
    let svg = svg_with_legend(WIDTH, height.max(200), &legend, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(80)
            .build_cartesian_2d(h0..h1, 0.0..n as f64)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_y_mesh()
            .max_light_lines(3)
            .x_desc("LMST")
            .x_labels(((h1 - h0) as usize + 1).min(25))
            .x_label_formatter(&|h| format!("{:02}:00", h.round() as i64))
            .y_labels(n * 2 + 1)
            .y_label_formatter(&|y| {
                // Labels at row centres only (row i spans n-i-1 .. n-i from the top).
                if (y.fract() - 0.5).abs() > 1e-6 {
                    return String::new();
                }
                let i = n as i64 - 1 - y.floor() as i64;
                usize::try_from(i)
                    .ok()
                    .and_then(|i| labels.get(i).cloned())
                    .unwrap_or_default()
            })
            .draw()
            .map_err(plot_error)?;
        let mut crosses: Vec<(f64, f64)> = Vec::new();
        for (i, (_, sol, hbs)) in rows.iter().enumerate() {
            let top = (n - i) as f64 - 0.15;
            let bottom = (n - i - 1) as f64 + 0.15;
            let Some(plan) = outcome
                .sols
                .iter()
                .find(|s| s.sol == *sol)
                .and_then(|s| s.activity_plan.as_ref())
            else {
                continue;
            };
            for t in plan
                .timeline
                .iter()
                .filter(|t| t.timeline.is_main() != *hbs)
            {
                let (_, c) = activity_class(&t.activity);
                let a = lmst_h(t.start_s);
                let b = lmst_h(t.end_s).max(a + 1.0 / 120.0);
                // A white edge keeps back-to-back rows (drive segments) apart.
                chart
                    .draw_series([
                        Rectangle::new([(a, bottom), (b, top)], c.filled()),
                        Rectangle::new([(a, bottom), (b, top)], WHITE.stroke_width(1)),
                    ])
                    .map_err(plot_error)?;
                if failed(t.outcome.as_deref()) {
                    crosses.push((b, (top + bottom) / 2.0));
                }
            }
        }
        chart
            .draw_series(
                crosses
                    .into_iter()
                    .map(|p| Cross::new(p, 6, RED.stroke_width(3))),
            )
            .map_err(plot_error)?;
        Ok(())
    })?;
    Ok(Some(svg))
}
