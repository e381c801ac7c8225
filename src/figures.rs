//! Figures as SVG (plotters, no fonts needed: the SVG carries its text as `<text>` elements).
//!
//! [`uncertainty_by_sol_svg`]: the position-uncertainty radius against sol, one line per
//! strategy (paper 000 Fig. 2 and 5), written by `solsim compare` beside its other files.

use plotters::prelude::*;
use sim::CampaignOutcome;

/// One colour per strategy, in `outcomes` order (cycled past five).
const COLOURS: [RGBColor; 5] = [
    RGBColor(90, 90, 90),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
];

/// The uncertainty radius r (metres) against sol for each outcome, as an SVG document: each
/// sol is drawn from its start radius at the sol's left edge to its end radius at its right
/// edge, so growth while driving and resets by localization both show; a drive that ended in
/// a fault is marked with a red cross at its end.
///
/// # Errors
/// When plotters cannot draw (it does not fail on finite data).
pub fn uncertainty_by_sol_svg(title: &str, outcomes: &[CampaignOutcome]) -> anyhow::Result<String> {
    let sols = || outcomes.iter().flat_map(|o| o.sols.iter());
    let first = sols().map(|s| s.sol).min().unwrap_or(0);
    let last = sols().map(|s| s.sol).max().unwrap_or(first) + 1;
    let max_r = sols()
        .map(|s| s.start_uncertainty_m.max(s.end_uncertainty_m))
        .filter(|r| r.is_finite())
        .fold(1.0_f64, f64::max);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 480)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(first..last, 0.0..max_r * 1.08)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .x_desc("sol")
            .y_desc("uncertainty radius r (m)")
            .x_labels(((last - first) as usize + 1).min(32))
            .draw()
            .map_err(plot_error)?;
        for (i, o) in outcomes.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let points: Vec<(u32, f64)> = o
                .sols
                .iter()
                .flat_map(|s| {
                    [
                        (s.sol, s.start_uncertainty_m),
                        (s.sol + 1, s.end_uncertainty_m),
                    ]
                })
                .filter(|p| p.1.is_finite())
                .collect();
            chart
                .draw_series(LineSeries::new(points, colour.stroke_width(2)))
                .map_err(plot_error)?
                .label(o.strategy.name())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                });
            let faults = o
                .sols
                .iter()
                .filter(|s| s.fault.is_some() && s.end_uncertainty_m.is_finite())
                .map(|s| Cross::new((s.sol + 1, s.end_uncertainty_m), 5, RED));
            chart.draw_series(faults).map_err(plot_error)?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(plot_error)?;
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}

fn plot_error<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow::anyhow!("drawing the figure failed: {e:?}")
}
