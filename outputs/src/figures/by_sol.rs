//! Figures of one run against sol, one series per strategy: the uncertainty radius
//! ([`uncertainty_by_sol_svg`], paper 000 Fig. 2 and 5) and the metres driven
//! ([`metres_by_sol_svg`]).

use plotters::prelude::*;
use sim::{CampaignOutcome, SolRecord};

use crate::figures::canvas::{
    FigureError, Legend, Mark, marker_svg, plot_error, sols_width, splice, strategy_colour,
    strategy_marker, styled_line_svg, svg_with_legend,
};

/// The sols any outcome covers, as `first..last + 1`.
fn sol_range(outcomes: &[CampaignOutcome]) -> (u32, u32) {
    let sols = || outcomes.iter().flat_map(|o| o.sols.iter());
    let first = sols().map(|s| s.sol).min().unwrap_or(0);
    let last = sols().map(|s| s.sol).max().unwrap_or(first) + 1;
    (first, last)
}

/// Sol `s` spans `s..s + 1` on the x axis; its label sits at the middle.
fn sol_label(x: &f64) -> String {
    if (x.fract() - 0.5).abs() < 1e-6 {
        format!("{}", x.floor() as i64)
    } else {
        String::new()
    }
}

/// Ticks at every half sol (labelled at the middles), at most about 64.
fn sol_ticks(first: u32, last: u32) -> usize {
    (2 * (last - first) as usize + 1).min(65)
}

fn strategy_legend(outcomes: &[CampaignOutcome], bar: bool) -> Legend {
    let mut entries: Legend = outcomes
        .iter()
        .map(|o| {
            let c = strategy_colour(o.strategy);
            let mark = if bar {
                Mark::Fill(c.to_rgba())
            } else {
                Mark::Styled(o.strategy)
            };
            (o.strategy.name().to_string(), mark)
        })
        .collect();
    if outcomes
        .iter()
        .any(|o| o.sols.iter().any(|s| s.fault.is_some()))
    {
        entries.push(("fault (end of the drive)".into(), Mark::Cross));
    }
    entries
}

/// The uncertainty radius r (metres) against sol for each outcome, as an SVG document: each
/// sol is drawn from its start radius at the sol's left edge to its end radius at its right
/// edge, so growth while driving and resets by localization both show; a drive that ended in
/// a fault is marked with a red cross at its end.
///
/// Strategies often share a line (the same drive, the same r), so each has its own dash
/// pattern ([`strategy_dash`](crate::figures::strategy_dash)) and a marker at the end of each drive ([`strategy_marker`]),
/// and each line is shifted by 2 px down and right per strategy (centred: from −4 to +4 px
/// with five), so coinciding lines lie side by side instead of hiding each other; 2 px is
/// under 2 % of the axes' spans.
///
/// # Errors
/// When plotters cannot draw (it does not fail on finite data).
pub fn uncertainty_by_sol_svg(
    title: &str,
    outcomes: &[CampaignOutcome],
) -> Result<String, FigureError> {
    let (first, last) = sol_range(outcomes);
    let max_r = outcomes
        .iter()
        .flat_map(|o| o.sols.iter())
        .map(|s| s.start_uncertainty_m.max(s.end_uncertainty_m))
        .filter(|r| r.is_finite())
        .fold(1.0_f64, f64::max);
    let legend = strategy_legend(outcomes, false);
    let mut lines = String::new();
    let svg = svg_with_legend(sols_width(first, last), 440, &legend, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(f64::from(first)..f64::from(last), 0.0..max_r * 1.08)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .max_light_lines(1)
            .x_desc("sol")
            .y_desc("uncertainty radius r (m)")
            .x_labels(sol_ticks(first, last))
            .x_label_formatter(&sol_label)
            .draw()
            .map_err(plot_error)?;
        let n = outcomes.len();
        for (i, o) in outcomes.iter().enumerate() {
            let shift = 2.0 * (i as f64 - (n as f64 - 1.0) / 2.0);
            let px = |x: f64, y: f64| {
                let (a, b) = chart.backend_coord(&(x, y));
                (f64::from(a) + shift, f64::from(b) + shift)
            };
            let mut points: Vec<(f64, f64)> = Vec::new();
            let mut marks: Vec<(f64, f64)> = Vec::new();
            for s in &o.sols {
                if !(s.start_uncertainty_m.is_finite() && s.end_uncertainty_m.is_finite()) {
                    continue;
                }
                points.push(px(f64::from(s.sol), s.start_uncertainty_m));
                let end = px(f64::from(s.sol + 1), s.end_uncertainty_m);
                points.push(end);
                if s.drove {
                    marks.push(end);
                }
            }
            lines.push_str(&styled_line_svg(&points, o.strategy));
            for m in marks {
                lines.push_str(&marker_svg(
                    strategy_marker(o.strategy),
                    m,
                    strategy_colour(o.strategy),
                ));
            }
        }
        // Fault crosses over every line (red, two strokes, 12 px across).
        for o in outcomes {
            for s in &o.sols {
                if s.fault.is_none() || !s.end_uncertainty_m.is_finite() {
                    continue;
                }
                let (a, b) = chart.backend_coord(&(f64::from(s.sol + 1), s.end_uncertainty_m));
                let (x, y) = (f64::from(a), f64::from(b));
                for (dx, dy) in [(6.0, 6.0), (6.0, -6.0)] {
                    lines.push_str(&format!(
                        "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" \
                         stroke=\"#FF0000\" stroke-width=\"2\"/>\n",
                        x - dx,
                        y - dy,
                        x + dx,
                        y + dy
                    ));
                }
            }
        }
        Ok(())
    })?;
    Ok(splice(svg, &lines))
}

/// Metres driven on each sol, one bar per strategy side by side (a sol without a drive has
/// no bar); a drive that ended in a fault has a red cross on its bar.
///
/// # Errors
/// When plotters cannot draw.
pub fn metres_by_sol_svg(title: &str, outcomes: &[CampaignOutcome]) -> Result<String, FigureError> {
    let (first, last) = sol_range(outcomes);
    let max_m = outcomes
        .iter()
        .flat_map(|o| o.sols.iter())
        .map(|s| s.distance_m)
        .filter(|d| d.is_finite())
        .fold(1.0_f64, f64::max);
    let n = outcomes.len().max(1) as f64;
    let width = 0.8 / n;
    let legend = strategy_legend(outcomes, true);
    svg_with_legend(sols_width(first, last), 400, &legend, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(f64::from(first)..f64::from(last), 0.0..max_m * 1.1)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .max_light_lines(1)
            .x_desc("sol")
            .y_desc("metres driven")
            .x_labels(sol_ticks(first, last))
            .x_label_formatter(&sol_label)
            .draw()
            .map_err(plot_error)?;
        let left = |i: usize, s: &SolRecord| f64::from(s.sol) + 0.1 + width * i as f64;
        for (i, o) in outcomes.iter().enumerate() {
            let colour = strategy_colour(o.strategy);
            let bars = o
                .sols
                .iter()
                .filter(|s| s.drove && s.distance_m.is_finite())
                .map(|s| {
                    Rectangle::new(
                        [(left(i, s), 0.0), (left(i, s) + width, s.distance_m)],
                        colour.filled(),
                    )
                });
            chart.draw_series(bars).map_err(plot_error)?;
        }
        for (i, o) in outcomes.iter().enumerate() {
            let faults = o
                .sols
                .iter()
                .filter(|s| s.fault.is_some() && s.distance_m.is_finite())
                .map(|s| {
                    Cross::new(
                        (left(i, s) + width / 2.0, s.distance_m),
                        5,
                        RED.stroke_width(2),
                    )
                });
            chart.draw_series(faults).map_err(plot_error)?;
        }
        Ok(())
    })
}
