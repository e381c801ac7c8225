//! Zoomed panels of one strategy's map at each passage it drove through ([`passages_svg`]),
//! keep-outs grown by the r the rover had at its closest pass.

use plotters::prelude::*;
use sim::CampaignOutcome;
use study::Scenario;

use crate::figures::canvas::{
    FigureError, Legend, Mark, plot_error, strategy_colour, svg_with_legend,
};
use crate::figures::map_canvas::{GREY, KEEP_IN, Layers, ORANGE, draw_map, equal_scale, map_chart};
use crate::figures::zone_moments::{ZoneMoment, passage_panels, zone_moments};

/// Columns of panels in [`passages_svg`], and the size of each panel, pixels.
const PANEL_COLUMNS: u32 = 3;
const PANEL_SIZE: (u32, u32) = (466, 500);

/// Zoomed panels of one strategy's map at the places its keep-outs mattered
/// ([`passage_panels`]: the two sides of a passage share one), three to a row, each at equal
/// scale: the keep-outs grown by the r the rover had at its closest pass (plus the footprint),
/// the keep-in shrunk by the same, the route, the path, the closest pass as a dot with its
/// uncertainty disc, and any fault there. The caption names the passage, the sol of the pass
/// and its r. `None` when the path came near no keep-out.
///
/// # Errors
/// When plotters cannot draw.
pub fn passages_svg(
    scenario: &Scenario,
    outcome: &CampaignOutcome,
) -> Result<Option<String>, FigureError> {
    let moments = zone_moments(scenario, outcome);
    let panels = passage_panels(scenario, &moments);
    if panels.is_empty() {
        return Ok(None);
    }
    let colour = strategy_colour(outcome.strategy);
    let footprint_m = scenario.settings.grid.footprint_radius_m;
    let rows = (panels.len() as u32).div_ceil(PANEL_COLUMNS);
    let width = PANEL_SIZE.0 * PANEL_COLUMNS;
    let title_h = 34;
    let mut legend: Legend = vec![
        (
            format!("keep-out grown by r at the pass + {footprint_m:.2} m"),
            Mark::Fill(ORANGE.mix(0.45)),
        ),
        ("keep-out".into(), Mark::Fill(GREY.to_rgba())),
    ];
    if scenario.zones.keep_ins().next().is_some() {
        legend.push((
            "keep-in edge; thin: shrunk by the same".into(),
            Mark::Line(KEEP_IN, 2),
        ));
    }
    legend.push(("route and waypoints".into(), Mark::Line(BLACK, 1)));
    legend.push((
        format!("{} path", outcome.strategy.name()),
        Mark::Line(colour, 2),
    ));
    legend.push((
        "closest pass (dot) and its uncertainty disc".into(),
        Mark::Line(colour, 2),
    ));
    if outcome.sols.iter().any(|s| s.fault.is_some()) {
        legend.push(("fault".into(), Mark::Cross));
    }
    let height = title_h + rows * PANEL_SIZE.1;
    let title = format!(
        "{}: {} at each passage, keep-outs grown by the r of the pass",
        scenario.name,
        outcome.strategy.name()
    );
    let svg = svg_with_legend(width, height, &legend, |root| {
        let (head, body) = root.split_vertically(title_h);
        head.titled(&title, ("sans-serif", 18))
            .map_err(plot_error)?;
        for (k, panel) in panels.iter().enumerate() {
            let (col, row) = (k as u32 % PANEL_COLUMNS, k as u32 / PANEL_COLUMNS);
            let area = body
                .clone()
                .shrink((col * PANEL_SIZE.0, row * PANEL_SIZE.1), PANEL_SIZE);
            let passes: Vec<ZoneMoment> =
                panel.keep_outs.iter().filter_map(|&i| moments[i]).collect();
            let r_lo = passes.iter().map(|m| m.r_m).fold(f64::INFINITY, f64::min);
            let r_hi = passes.iter().map(|m| m.r_m).fold(0.0, f64::max);
            let sol = passes.iter().map(|m| m.sol).min().unwrap_or(0);
            // One disc: the pass with the largest r, the one that bound the passage most.
            let binding: Vec<ZoneMoment> = passes
                .iter()
                .copied()
                .reduce(|a, b| if b.r_m > a.r_m { b } else { a })
                .into_iter()
                .collect();
            let r_text = if r_hi - r_lo < 0.005 {
                format!("r = {r_hi:.2} m")
            } else {
                format!("r = {r_lo:.2}-{r_hi:.2} m")
            };
            let caption = format!(
                "{}: {}, passed sol {sol} at {r_text}",
                panel.label, panel.name
            );
            let (frame, scale) = equal_scale(panel.window, PANEL_SIZE, &caption, 14)?;
            // Each keep-out of the panel by its own r; the others near it by theirs (or as
            // given when never reached).
            let grow_m: Vec<Option<f64>> = moments
                .iter()
                .map(|m| m.map(|m| m.r_m.max(0.0) + footprint_m))
                .collect();
            let layers = Layers {
                grow_m,
                keep_in_shrunk_m: Some(r_hi + footprint_m),
                sol_ends: false,
                passes: binding,
                panels: &[],
            };
            let mut chart = map_chart(&area, &caption, 14, frame)?;
            draw_map(&mut chart, scenario, outcome, &layers, frame, scale)?;
        }
        Ok(())
    })?;
    Ok(Some(svg))
}
