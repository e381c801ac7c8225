//! Route maps: one strategy's traverse on the map ([`route_map_svg`]: the whole traverse, or a
//! window on a fault); zoomed panels where its keep-outs mattered are [`crate::figures::passages`].
//!
//! A long traverse gets an overview plus zoomed panels, not a corridor view (the route
//! straightened into a strip). A passage is a gap of tens of metres in kilometres of route, so
//! at one scale it is a sliver and the uncertainty discs vanish; a corridor view would keep
//! one scale along the route, but it bends the keep-outs and the discs out of shape where the
//! route turns (the rapid traverse turns back on itself), and it would no longer be the map
//! the operators see in MMGIS. The overview keeps the map as it is, marks where each panel
//! lies (lettered boxes), and the panels show each passage at a scale where its gap, the path
//! through it and the disc are pixels wide.
//!
//! Keep-outs are grown by the radius of the moment they mattered ([`zone_moments`]): the r the
//! rover had where its driven path came closest to each one, not the run's largest r (at which
//! a passage the rover drove through can look closed).

use plotters::prelude::*;
use sim::CampaignOutcome;
use study::Scenario;

use crate::figures::canvas::{
    FigureError, Legend, Mark, WIDE, WIDTH, strategy_colour, svg_with_legend,
};
use crate::figures::map_canvas::{
    GREY, KEEP_IN, LIGHT_GREY, Layers, ORANGE, PANEL_BOX, draw_map, equal_scale, map_chart,
    map_plot_area,
};
use crate::figures::zone_moments::{REACH_M, passage_panels, zone_moments};

/// How far a map grows the keep-outs (always plus the rover footprint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Growth {
    /// Every keep-out by this r, metres: `--map-r-m`, or a fault's r on its zoom.
    At(f64),
    /// Each keep-out by the r the rover had where its path came closest to it
    /// ([`zone_moments`]); a keep-out the path never came within [`REACH_M`] of is not grown.
    AtTheMoment,
}

/// The extent of the route and the driven path, with a margin for the grown keep-outs and the
/// discs.
fn traverse_window(outcome: &CampaignOutcome, route: &[[f64; 2]], grow_m: f64) -> [f64; 4] {
    let mut pts: Vec<[f64; 2]> = route.to_vec();
    for s in &outcome.sols {
        pts.extend(s.path_m.iter().copied());
    }
    pts.retain(|p| p[0].is_finite() && p[1].is_finite());
    let (a, b, c, d) = pts.iter().fold(
        (f64::MAX, f64::MAX, f64::MIN, f64::MIN),
        |(a, b, c, d), p| (a.min(p[0]), b.min(p[1]), c.max(p[0]), d.max(p[1])),
    );
    let (a, b, c, d) = if a > c {
        (0.0, 0.0, 1.0, 1.0)
    } else {
        (a, b, c, d)
    };
    let max_disc = outcome
        .sols
        .iter()
        .map(|s| s.end_uncertainty_m)
        .filter(|r| r.is_finite())
        .fold(0.0, f64::max);
    let span: f64 = (c - a).max(d - b);
    let pad = (0.04 * span)
        .max(grow_m * 1.2)
        .max(max_disc.min(0.25 * span))
        .max(10.0);
    [a - pad, b - pad, c + pad, d + pad]
}

/// One strategy's traverse on the map, in map metres with equal scale on both axes:
/// - keep-out zones filled grey (outlined, so a narrow one still shows over kilometres), each
///   grown by its r plus the rover footprint (the region the rover's centre must avoid at that
///   uncertainty) in orange: with [`Growth::AtTheMoment`] the r the rover had where its path
///   came closest to that keep-out, and a keep-out it never came near in light grey, not
///   grown; with [`Growth::At`] one r for all, and the keep-in shrunk by the same in a thin
///   line;
/// - the keep-in union outlined;
/// - the route in black with its waypoints; the driven path in the strategy's colour, each
///   drive sol's end labelled with the sol (where there is room) and circled by its end-of-sol
///   uncertainty disc;
/// - with [`Growth::AtTheMoment`] over the whole traverse, the windows of [`passages_svg`](crate::figures::passages_svg)'s
///   panels as lettered boxes;
/// - faults as red crosses, named.
///
/// `window` (x0, y0, x1, y1, map metres) zooms on a part (a fault: [`fault_window`](crate::figures::fault_window)); without
/// it the map shows the route and the driven paths with a margin, 1400 px wide when they span
/// more than a kilometre or are more than four times as wide as tall.
///
/// # Errors
/// When plotters cannot draw.
pub fn route_map_svg(
    scenario: &Scenario,
    outcome: &CampaignOutcome,
    growth: Growth,
    window: Option<[f64; 4]>,
) -> Result<String, FigureError> {
    let colour = strategy_colour(outcome.strategy);
    let footprint_m = scenario.settings.grid.footprint_radius_m;
    let moments = zone_moments(scenario, outcome);
    let panels = match (growth, window) {
        (Growth::AtTheMoment, None) => passage_panels(scenario, &moments),
        _ => Vec::new(),
    };
    let grow_m: Vec<Option<f64>> = match growth {
        Growth::At(r) => vec![Some(r.max(0.0) + footprint_m); moments.len()],
        Growth::AtTheMoment => moments
            .iter()
            .map(|m| m.map(|m| m.r_m.max(0.0) + footprint_m))
            .collect(),
    };
    let largest_grow = grow_m.iter().flatten().copied().fold(footprint_m, f64::max);
    let zoomed = window.is_some();
    let window =
        window.unwrap_or_else(|| traverse_window(outcome, &scenario.settings.route, largest_grow));
    let [x0, y0, x1, y1] = window;
    let aspect = (x1 - x0) / (y1 - y0);
    let width = if aspect > 4.0 || (x1 - x0).max(y1 - y0) > 1000.0 {
        WIDE
    } else {
        WIDTH
    };
    let strategy = outcome.strategy.name();
    let title = match growth {
        Growth::At(r) if zoomed => format!(
            "{}: {strategy} near its fault — keep-outs grown by r = {r:.2} m + {footprint_m:.2} m footprint",
            scenario.name
        ),
        Growth::At(r) => format!(
            "{}: {strategy} — keep-outs grown by r = {r:.2} m + {footprint_m:.2} m footprint",
            scenario.name
        ),
        Growth::AtTheMoment => format!(
            "{}: {strategy} — each keep-out grown by the r at the closest pass + {footprint_m:.2} m footprint",
            scenario.name
        ),
    };
    // Size: the plot is as tall as the extent needs at that width (260-900 px), and the ranges
    // are then widened so one metre is the same number of pixels on both axes, measured on the
    // plotting area itself.
    let (pw0, ph0) = map_plot_area((width, 600), &title, 16)?;
    let want_h = (f64::from(pw0) / aspect).clamp(260.0, 900.0);
    let height = 600 - ph0 + want_h.round() as u32;
    let (frame, scale) = equal_scale(window, (width, height), &title, 16)?;

    let mut legend: Legend = Vec::new();
    let reached = grow_m.iter().any(Option::is_some);
    let unreached = grow_m.iter().any(Option::is_none);
    if reached {
        let what = match growth {
            Growth::At(r) => format!("keep-out grown by {:.2} m", r.max(0.0) + footprint_m),
            Growth::AtTheMoment => {
                format!("keep-out grown by r at the closest pass + {footprint_m:.2} m")
            }
        };
        legend.push((what, Mark::Fill(ORANGE.mix(0.45))));
        legend.push(("keep-out".into(), Mark::Fill(GREY.to_rgba())));
    }
    if unreached {
        legend.push((
            format!("keep-out never within {REACH_M:.0} m of the path"),
            Mark::Fill(LIGHT_GREY.to_rgba()),
        ));
    }
    if scenario.zones.keep_ins().next().is_some() {
        let what = match growth {
            Growth::At(_) => "keep-in edge; thin: shrunk by the same",
            Growth::AtTheMoment => "keep-in edge",
        };
        legend.push((what.into(), Mark::Line(KEEP_IN, 2)));
    }
    legend.push(("route and waypoints".into(), Mark::Line(BLACK, 1)));
    legend.push((
        format!("{strategy} path, sol-end uncertainty discs"),
        Mark::Line(colour, 2),
    ));
    if !panels.is_empty() {
        legend.push((
            "zoomed panel (next figure)".into(),
            Mark::Line(PANEL_BOX, 1),
        ));
    }
    if outcome.sols.iter().any(|s| s.fault.is_some()) {
        legend.push(("fault".into(), Mark::Cross));
    }
    let layers = Layers {
        grow_m,
        keep_in_shrunk_m: match growth {
            Growth::At(r) => Some(r.max(0.0) + footprint_m),
            Growth::AtTheMoment => None,
        },
        sol_ends: true,
        passes: Vec::new(),
        panels: &panels,
    };
    svg_with_legend(width, height, &legend, |root| {
        let mut chart = map_chart(root, &title, 16, frame)?;
        draw_map(&mut chart, scenario, outcome, &layers, frame, scale)
    })
}
