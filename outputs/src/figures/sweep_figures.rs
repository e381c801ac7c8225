//! Figures of a sweep: the distribution of the sols each strategy took
//! ([`segment_sols_cdf_svg`]) and the rates with their 95 % intervals ([`rates_svg`]).

use plotters::prelude::*;
use sweep::rows::RunRow;
use sweep::summary::Rate;

use crate::figures::canvas::{
    FigureError, Legend, Mark, WIDTH, colour_of_name, plot_error, svg_with_legend,
};

/// A CDF's points, colour and line width.
type Curve = (Vec<(f64, f64)>, RGBColor, u32);

/// The empirical distribution of the sols each strategy took over the runs of a sweep (the
/// study segment's `segment_sols` when the sweep has a segment, else `sols_to_goal`), as step
/// CDFs. A run that never covered the segment or reached the goal within the calendar counts in
/// the denominator only, so its strategy's curve stays below 1 by that share. Earlier
/// strategies are drawn wider, so a curve another one coincides with stays visible.
///
/// # Errors
/// When plotters cannot draw.
pub fn segment_sols_cdf_svg(
    title: &str,
    strategies: &[String],
    rows: &[RunRow],
    segment: bool,
) -> Result<String, FigureError> {
    let value = |r: &RunRow| {
        if segment {
            r.segment_sols
        } else {
            r.sols_to_goal
        }
    };
    let all: Vec<u32> = rows.iter().filter_map(value).collect();
    let lo = all.iter().copied().min().unwrap_or(0).saturating_sub(1);
    let hi = all.iter().copied().max().unwrap_or(lo + 1) + 1;
    let what = if segment {
        "sols to cover the study segment"
    } else {
        "sols to reach the goal"
    };
    let k = strategies.len();
    let width_of = |i: usize| 2 + (k - 1 - i) as u32 * 6 / k.max(1) as u32;
    let mut legend: Legend = Vec::new();
    let mut curves: Vec<Curve> = Vec::new();
    for (i, name) in strategies.iter().enumerate() {
        let colour = colour_of_name(name);
        let mine: Vec<&RunRow> = rows.iter().filter(|r| r.strategy.name() == name).collect();
        if mine.is_empty() {
            continue;
        }
        let n = mine.len() as f64;
        let mut vals: Vec<u32> = mine.iter().filter_map(|r| value(r)).collect();
        vals.sort_unstable();
        let mut pts = vec![(f64::from(lo), 0.0)];
        let mut j = 0usize;
        for x in lo..=hi {
            let before = j as f64 / n;
            while j < vals.len() && vals[j] <= x {
                j += 1;
            }
            pts.push((f64::from(x), before));
            pts.push((f64::from(x), j as f64 / n));
        }
        let censored = mine.len() - vals.len();
        let label = if censored > 0 {
            format!(
                "{name}: {censored} of {} runs need more than the calendar",
                mine.len()
            )
        } else {
            format!("{name} ({} runs)", mine.len())
        };
        legend.push((label, Mark::Line(colour, width_of(i))));
        curves.push((pts, colour, width_of(i)));
    }
    svg_with_legend(WIDTH, 420, &legend, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(f64::from(lo)..f64::from(hi), 0.0..1.05)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .max_light_lines(1)
            .x_desc(what)
            .y_desc("share of runs (CDF)")
            .x_labels(((hi - lo) as usize + 1).min(32))
            .x_label_formatter(&|x| format!("{}", x.round() as i64))
            .draw()
            .map_err(plot_error)?;
        for (pts, colour, width) in curves {
            chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(width)))
                .map_err(plot_error)?;
        }
        Ok(())
    })
}

/// Rates over a sweep's runs with their 95 % Wilson intervals: one group per rate
/// (`no_path_rate`, `fault_rate`, …), one point with its interval per strategy.
///
/// # Errors
/// When plotters cannot draw.
pub fn rates_svg(title: &str, per_strategy: &[(String, Vec<Rate>)]) -> Result<String, FigureError> {
    let mut names: Vec<String> = Vec::new();
    for (_, rates) in per_strategy {
        for r in rates {
            if !names.contains(&r.name) {
                names.push(r.name.clone());
            }
        }
    }
    let groups = names.len().max(1);
    let k = per_strategy.len().max(1) as f64;
    let legend: Legend = per_strategy
        .iter()
        .map(|(s, _)| (s.clone(), Mark::Line(colour_of_name(s), 2)))
        .collect();
    svg_with_legend(WIDTH, 420, &legend, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(0.0..groups as f64, -0.08..1.05)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .max_light_lines(1)
            .y_desc("share of runs, with 95 % Wilson interval")
            .x_labels(0)
            .y_label_formatter(&|y| {
                if *y < 0.0 {
                    String::new()
                } else {
                    format!("{y:.1}")
                }
            })
            .draw()
            .map_err(plot_error)?;
        // The rate names under their groups, as text in the plot (not tick labels).
        chart
            .draw_series(names.iter().enumerate().map(|(g, name)| {
                EmptyElement::at((g as f64 + 0.5, -0.04))
                    + Text::new(
                        name.clone(),
                        (-40, -6),
                        ("sans-serif", 13).into_font().color(&BLACK),
                    )
            }))
            .map_err(plot_error)?;
        for (i, (strategy, rates)) in per_strategy.iter().enumerate() {
            let colour = colour_of_name(strategy);
            let x_of = |name: &str| {
                let g = names.iter().position(|n| n == name).unwrap_or(0) as f64;
                g + 0.15 + 0.7 * (i as f64 + 0.5) / k
            };
            chart
                .draw_series(rates.iter().map(|r| {
                    ErrorBar::new_vertical(
                        x_of(&r.name),
                        r.interval.lo,
                        r.rate,
                        r.interval.hi,
                        colour.stroke_width(2),
                        8,
                    )
                }))
                .map_err(plot_error)?;
            chart
                .draw_series(
                    rates
                        .iter()
                        .map(|r| Circle::new((x_of(&r.name), r.rate), 4, colour.filled())),
                )
                .map_err(plot_error)?;
        }
        Ok(())
    })
}
