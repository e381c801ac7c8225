//! Figures as SVG (plotters, no fonts needed: the SVG carries its text as `<text>` elements).
//!
//! One run (written by `solsim compare` beside its other files, and shown by `solsim report`):
//! - [`uncertainty_by_sol_svg`]: the position-uncertainty radius against sol, one line per
//!   strategy (paper 000 Fig. 2 and 5);
//! - [`metres_by_sol_svg`]: metres driven per sol, one bar per strategy;
//! - [`route_map_svg`]: one strategy's traverse on the map — zones, keep-outs grown at a
//!   chosen r, the route, the driven path, sol-end discs and faults (paper 000 Fig. 3-4), over
//!   the whole traverse or zoomed on a window (a fault);
//! - [`sol_plans_gantt_svg`]: each sol's executed plan as a Gantt chart, the co-processor
//!   (HBS) chain on its own row.
//!
//! A sweep (shown by `solsim report`): [`segment_sols_cdf_svg`], the distribution of the sols
//! each strategy took, and [`rates_svg`], the fault rates with their 95 % intervals.
//!
//! The rover: [`slip_profile_svg`], slip against slope per terrain class and heading.
//!
//! Every strategy has one colour in every figure ([`strategy_colour`]); legends sit below the
//! plot, where they cover nothing.

use geo::{BooleanOps as _, Coord, LineString, MultiLineString, MultiPolygon};
use plotters::coord::Shift;
use plotters::prelude::*;
use sim::{CampaignOutcome, SolRecord, Strategy};
use study::Scenario;
use sweep::rows::RunRow;
use sweep::summary::Rate;

/// Width of every figure, pixels (a map of a long traverse is wider).
const WIDTH: u32 = 960;
/// Height of a legend row, pixels; three entries per row.
const LEGEND_ROW: u32 = 20;
/// Width of a legend column, pixels.
const LEGEND_COLUMN: i32 = 300;

/// The colour of a strategy, the same in every figure.
#[must_use]
pub fn strategy_colour(strategy: Strategy) -> RGBColor {
    match strategy {
        Strategy::Replay => RGBColor(140, 86, 75),
        Strategy::Ground => RGBColor(31, 119, 180),
        Strategy::Onboard => RGBColor(44, 160, 44),
        Strategy::Extension => RGBColor(255, 127, 14),
        Strategy::ExtensionOnboard => RGBColor(148, 103, 189),
    }
}

fn colour_of_name(name: &str) -> RGBColor {
    Strategy::from_name(name).map_or(RGBColor(90, 90, 90), strategy_colour)
}

/// A legend entry's symbol.
enum Mark {
    Fill(RGBAColor),
    Line(RGBColor, u32),
    Cross,
}

/// Legend entries: label and symbol.
type Legend = Vec<(String, Mark)>;

fn legend_height(entries: &Legend) -> u32 {
    let rows = entries.len().div_ceil(3) as u32;
    if rows == 0 { 0 } else { rows * LEGEND_ROW + 14 }
}

/// Draws `entries` in rows of three into `area` (the strip below a plot).
fn draw_legend(area: &DrawingArea<SVGBackend<'_>, Shift>, entries: &Legend) -> anyhow::Result<()> {
    let font = ("sans-serif", 13).into_font().color(&BLACK);
    for (k, (label, mark)) in entries.iter().enumerate() {
        let x = 72 + LEGEND_COLUMN * (k % 3) as i32;
        let y = 10 + LEGEND_ROW as i32 * (k / 3) as i32;
        match mark {
            Mark::Fill(c) => area.draw(&Rectangle::new([(x, y - 6), (x + 16, y + 6)], c.filled())),
            Mark::Line(c, w) => area.draw(&PathElement::new(
                vec![(x, y), (x + 16, y)],
                c.stroke_width(*w),
            )),
            Mark::Cross => area.draw(&Cross::new((x + 8, y), 5, RED.stroke_width(2))),
        }
        .map_err(plot_error)?;
        area.draw(&Text::new(label.clone(), (x + 24, y - 7), font.clone()))
            .map_err(plot_error)?;
    }
    Ok(())
}

/// An SVG of `width` × (`plot_height` + the legend's height): `draw` gets the upper area, the
/// legend goes below it.
fn svg_with_legend(
    width: u32,
    plot_height: u32,
    entries: &Legend,
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> anyhow::Result<()>,
) -> anyhow::Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, plot_height + legend_height(entries)))
            .into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let (upper, lower) = root.split_vertically(plot_height);
        draw(&upper)?;
        draw_legend(&lower, entries)?;
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}

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
                Mark::Line(c, 2)
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
/// # Errors
/// When plotters cannot draw (it does not fail on finite data).
pub fn uncertainty_by_sol_svg(title: &str, outcomes: &[CampaignOutcome]) -> anyhow::Result<String> {
    let (first, last) = sol_range(outcomes);
    let max_r = outcomes
        .iter()
        .flat_map(|o| o.sols.iter())
        .map(|s| s.start_uncertainty_m.max(s.end_uncertainty_m))
        .filter(|r| r.is_finite())
        .fold(1.0_f64, f64::max);
    let legend = strategy_legend(outcomes, false);
    svg_with_legend(WIDTH, 440, &legend, |root| {
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
        for o in outcomes {
            let colour = strategy_colour(o.strategy);
            let points: Vec<(f64, f64)> = o
                .sols
                .iter()
                .flat_map(|s| {
                    [
                        (f64::from(s.sol), s.start_uncertainty_m),
                        (f64::from(s.sol + 1), s.end_uncertainty_m),
                    ]
                })
                .filter(|p| p.1.is_finite())
                .collect();
            chart
                .draw_series(LineSeries::new(points, colour.stroke_width(2)))
                .map_err(plot_error)?;
        }
        for o in outcomes {
            let faults = o
                .sols
                .iter()
                .filter(|s| s.fault.is_some() && s.end_uncertainty_m.is_finite())
                .map(|s| {
                    Cross::new(
                        (f64::from(s.sol + 1), s.end_uncertainty_m),
                        6,
                        RED.stroke_width(2),
                    )
                });
            chart.draw_series(faults).map_err(plot_error)?;
        }
        Ok(())
    })
}

/// Metres driven on each sol, one bar per strategy side by side (a sol without a drive has
/// no bar); a drive that ended in a fault has a red cross on its bar.
///
/// # Errors
/// When plotters cannot draw.
pub fn metres_by_sol_svg(title: &str, outcomes: &[CampaignOutcome]) -> anyhow::Result<String> {
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
    svg_with_legend(WIDTH, 400, &legend, |root| {
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

/// The r at which [`route_map_svg`] grows the keep-outs by default: the uncertainty at the
/// run's first fault, or else the largest end-of-sol uncertainty of the run.
#[must_use]
pub fn default_map_r_m(outcome: &CampaignOutcome) -> f64 {
    outcome
        .sols
        .iter()
        .find_map(|s| s.fault.as_ref().map(|f| f.uncertainty_m))
        .unwrap_or_else(|| {
            outcome
                .sols
                .iter()
                .map(|s| s.end_uncertainty_m)
                .filter(|r| r.is_finite())
                .fold(0.0, f64::max)
        })
}

/// The window (x0, y0, x1, y1, map metres) a zoom on a fault at `at` with uncertainty `r_m`
/// shows: four grown radii around it, at least 60 m.
#[must_use]
pub fn fault_window(at: [f64; 2], r_m: f64, footprint_m: f64) -> [f64; 4] {
    let half = (4.0 * (r_m.max(0.0) + footprint_m)).max(60.0);
    [at[0] - half, at[1] - half, at[0] + half, at[1] + half]
}

/// Polygon vertices of a disc (for drawing in map metres, where a pixel-sized circle would not
/// scale).
fn disc(centre: [f64; 2], r: f64) -> Vec<(f64, f64)> {
    (0..48)
        .map(|k| {
            let a = f64::from(k) * std::f64::consts::TAU / 48.0;
            (centre[0] + r * a.cos(), centre[1] + r * a.sin())
        })
        .collect()
}

fn exterior(p: &geo::Polygon<f64>) -> Vec<(f64, f64)> {
    p.exterior().coords().map(|c| (c.x, c.y)).collect()
}

/// The plotting area (pixels) of a map chart of `size` with `caption`, as [`route_map_svg`]
/// builds it: measured on a throwaway drawing, so the axes can be given equal scale exactly.
fn map_plot_area(size: (u32, u32), caption: &str) -> anyhow::Result<(u32, u32)> {
    let mut scratch = String::new();
    let root = SVGBackend::with_string(&mut scratch, size).into_drawing_area();
    let chart = map_chart(&root, caption, [0.0, 0.0, 1.0, 1.0])?;
    Ok(chart.plotting_area().dim_in_pixel())
}

type MapChart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

fn map_chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    caption: &str,
    [x0, y0, x1, y1]: [f64; 4],
) -> anyhow::Result<MapChart<'a, 'b>> {
    ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(plot_error)
}

/// One strategy's traverse on the map, in map metres with equal scale on both axes:
/// - keep-out zones filled grey, and grown by `r_m` plus the rover footprint (the region the
///   rover's centre must avoid at that uncertainty) in orange;
/// - the keep-in union outlined, and shrunk by the same distance in a thin line;
/// - the route in black with its waypoints; the driven path in the strategy's colour, each
///   drive sol's end labelled with the sol (where there is room) and circled by its end-of-sol
///   uncertainty disc;
/// - faults as red crosses, named.
///
/// `window` (x0, y0, x1, y1, map metres) zooms on a part (a fault: [`fault_window`]); without
/// it the map shows the route and the driven paths with a margin.
///
/// # Errors
/// When plotters cannot draw.
pub fn route_map_svg(
    scenario: &Scenario,
    outcome: &CampaignOutcome,
    r_m: f64,
    window: Option<[f64; 4]>,
) -> anyhow::Result<String> {
    let colour = strategy_colour(outcome.strategy);
    let footprint_m = scenario.campaign.grid.footprint_radius_m;
    let grow_m = r_m.max(0.0) + footprint_m;
    let [mut x0, mut y0, mut x1, mut y1] = match window {
        Some(w) => w,
        None => {
            let mut pts: Vec<[f64; 2]> = scenario.campaign.route.clone();
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
    };
    // Size: a long traverse gets a wider figure; the plot is as tall as the extent needs at
    // that width (260-900 px), and the ranges are then widened so one metre is the same number
    // of pixels on both axes, measured on the plotting area itself.
    let aspect = (x1 - x0) / (y1 - y0);
    let width = if aspect > 4.0 { 1400 } else { WIDTH };
    let title = match window {
        None => format!(
            "{}: {} — keep-outs grown by r = {r_m:.2} m + {footprint_m:.2} m footprint",
            scenario.name,
            outcome.strategy.name()
        ),
        Some(_) => format!(
            "{}: {} near its fault — keep-outs grown by r = {r_m:.2} m + {footprint_m:.2} m footprint",
            scenario.name,
            outcome.strategy.name()
        ),
    };
    let (pw0, ph0) = map_plot_area((width, 600), &title)?;
    let want_h = (f64::from(pw0) / aspect).clamp(260.0, 900.0);
    let height = 600 - ph0 + want_h.round() as u32;
    let (pw, ph) = map_plot_area((width, height), &title)?;
    let scale = ((x1 - x0) / f64::from(pw)).max((y1 - y0) / f64::from(ph));
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    (x0, x1) = (
        cx - scale * f64::from(pw) / 2.0,
        cx + scale * f64::from(pw) / 2.0,
    );
    (y0, y1) = (
        cy - scale * f64::from(ph) / 2.0,
        cy + scale * f64::from(ph) / 2.0,
    );

    let frame: geo::Polygon<f64> =
        geo::Rect::new(Coord { x: x0, y: y0 }, Coord { x: x1, y: y1 }).to_polygon();
    let clip_area = |m: &MultiPolygon<f64>| m.intersection(&frame);
    // Outlines are cut as lines, so the frame's edge is never drawn as a zone's.
    let clip_rings = |m: &MultiPolygon<f64>| -> Vec<Vec<(f64, f64)>> {
        let rings: Vec<LineString<f64>> = m
            .iter()
            .flat_map(|p| {
                std::iter::once(p.exterior().clone()).chain(p.interiors().iter().cloned())
            })
            .collect();
        frame
            .clip(&MultiLineString::new(rings), false)
            .into_iter()
            .map(|l| l.coords().map(|c| (c.x, c.y)).collect())
            .collect()
    };
    let grey = RGBColor(120, 120, 120);
    let orange = RGBColor(255, 160, 60);
    let keep_in_colour = RGBColor(170, 120, 0);
    let mut legend: Legend = Vec::new();
    if scenario.zones.keep_outs().next().is_some() {
        legend.push((
            format!("keep-out grown by {grow_m:.2} m"),
            Mark::Fill(orange.mix(0.45)),
        ));
        legend.push(("keep-out".into(), Mark::Fill(grey.to_rgba())));
    }
    if scenario.zones.keep_ins().next().is_some() {
        legend.push((
            "keep-in edge; thin: shrunk by the same".into(),
            Mark::Line(keep_in_colour, 2),
        ));
    }
    legend.push(("route and waypoints".into(), Mark::Line(BLACK, 1)));
    legend.push((
        format!(
            "{} path, sol-end uncertainty discs",
            outcome.strategy.name()
        ),
        Mark::Line(colour, 2),
    ));
    if outcome.sols.iter().any(|s| s.fault.is_some()) {
        legend.push(("fault".into(), Mark::Cross));
    }
    svg_with_legend(width, height, &legend, |root| {
        let mut chart = map_chart(root, &title, [x0, y0, x1, y1])?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x, map metres east")
            .y_desc("y, map metres north")
            .draw()
            .map_err(plot_error)?;
        // The same offsets the GIS layers carry (maps::zone::offset).
        for (_, grown) in scenario.zones.keep_outs_grown(grow_m) {
            chart
                .draw_series(
                    clip_area(&grown)
                        .iter()
                        .map(|p| Polygon::new(exterior(p), orange.mix(0.45).filled())),
                )
                .map_err(plot_error)?;
        }
        for (_, z) in scenario.zones.keep_outs() {
            let inside = clip_area(z.geometry());
            chart
                .draw_series(
                    inside
                        .iter()
                        .map(|p| Polygon::new(exterior(p), grey.filled())),
                )
                .map_err(plot_error)?;
            // Holes (rare in a keep-out) are open ground again.
            for p in &inside {
                chart
                    .draw_series(p.interiors().iter().map(|ring| {
                        Polygon::new(
                            ring.coords().map(|c| (c.x, c.y)).collect::<Vec<_>>(),
                            WHITE.filled(),
                        )
                    }))
                    .map_err(plot_error)?;
            }
        }
        for (distance, width) in [(0.0, 2), (grow_m, 1)] {
            let Some(area) = scenario.zones.keep_in_shrunk(distance) else {
                continue;
            };
            chart
                .draw_series(
                    clip_rings(&area)
                        .into_iter()
                        .map(|r| PathElement::new(r, keep_in_colour.stroke_width(width))),
                )
                .map_err(plot_error)?;
        }
        let route: Vec<(f64, f64)> = scenario
            .campaign
            .route
            .iter()
            .map(|p| (p[0], p[1]))
            .collect();
        let inside = |p: (f64, f64)| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1;
        let route_lines = frame.clip(
            &MultiLineString::new(vec![LineString::from(route.clone())]),
            false,
        );
        chart
            .draw_series(route_lines.into_iter().map(|l| {
                PathElement::new(
                    l.coords().map(|c| (c.x, c.y)).collect::<Vec<_>>(),
                    BLACK.stroke_width(1),
                )
            }))
            .map_err(plot_error)?;
        chart
            .draw_series(
                route
                    .iter()
                    .filter(|p| inside(**p))
                    .map(|&p| Circle::new(p, 3, BLACK.filled())),
            )
            .map_err(plot_error)?;
        for s in &outcome.sols {
            let path: Vec<LineString<f64>> = vec![LineString::from(
                s.path_m
                    .iter()
                    .filter(|p| p[0].is_finite() && p[1].is_finite())
                    .map(|p| (p[0], p[1]))
                    .collect::<Vec<_>>(),
            )];
            if path[0].0.len() < 2 {
                continue;
            }
            chart
                .draw_series(
                    frame
                        .clip(&MultiLineString::new(path), false)
                        .into_iter()
                        .map(|l| {
                            PathElement::new(
                                l.coords().map(|c| (c.x, c.y)).collect::<Vec<_>>(),
                                colour.stroke_width(2),
                            )
                        }),
                )
                .map_err(plot_error)?;
        }
        // Sol labels only where they do not overlap one already placed (36 px apart).
        let mut labelled: Vec<(f64, f64)> = Vec::new();
        for s in outcome.sols.iter().filter(|s| s.drove) {
            let end = s.end_position_m;
            if !(end[0].is_finite() && end[1].is_finite() && s.end_uncertainty_m.is_finite()) {
                continue;
            }
            let mut ring = disc(end, s.end_uncertainty_m);
            ring.push(ring[0]);
            let ring = frame.clip(
                &MultiLineString::new(vec![LineString::from(ring.clone())]),
                false,
            );
            let at = (end[0], end[1]);
            if inside(at) {
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        disc(end, s.end_uncertainty_m),
                        colour.mix(0.10).filled(),
                    )))
                    .map_err(plot_error)?;
            }
            chart
                .draw_series(ring.into_iter().map(|l| {
                    PathElement::new(
                        l.coords().map(|c| (c.x, c.y)).collect::<Vec<_>>(),
                        colour.stroke_width(1),
                    )
                }))
                .map_err(plot_error)?;
            let far = |q: &(f64, f64)| (q.0 - at.0).hypot(q.1 - at.1) / scale > 36.0;
            if inside(at) && labelled.iter().all(far) {
                labelled.push(at);
                chart
                    .draw_series(std::iter::once(
                        EmptyElement::at(at)
                            + Text::new(
                                format!("{}", s.sol),
                                (3, 3),
                                ("sans-serif", 12).into_font().color(&BLACK),
                            ),
                    ))
                    .map_err(plot_error)?;
            }
        }
        for s in &outcome.sols {
            let Some(f) = &s.fault else { continue };
            let p = (f.position_m[0], f.position_m[1]);
            if !(p.0.is_finite() && p.1.is_finite() && inside(p)) {
                continue;
            }
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at(p)
                        + Cross::new((0, 0), 7, RED.stroke_width(3))
                        + Text::new(
                            format!("{} sol {}", f.kind.name(), s.sol),
                            (9, -16),
                            ("sans-serif", 13).into_font().color(&RED),
                        ),
                ))
                .map_err(plot_error)?;
        }
        Ok(())
    })
}

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
) -> anyhow::Result<Option<String>> {
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
) -> anyhow::Result<String> {
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
pub fn rates_svg(title: &str, per_strategy: &[(String, Vec<Rate>)]) -> anyhow::Result<String> {
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

/// The slip profile (`solsim slip-profile`): one panel per terrain class, slip (%) against
/// slope for up-, cross- and down-slope travel as measured by the rapier rover (lines), and the
/// closed-form steady slip of the same soil model for up and down (circles).
///
/// # Errors
/// When plotters cannot draw.
pub fn slip_profile_svg(profile: &sim::slip_profile::SlipProfile) -> anyhow::Result<String> {
    use maps::TerrainClass;
    use sim::slip_profile::ProfileHeading;
    let colour = |h: ProfileHeading| match h {
        ProfileHeading::Up => RGBColor(214, 39, 40),
        ProfileHeading::Cross => RGBColor(255, 127, 14),
        ProfileHeading::Down => RGBColor(31, 119, 180),
    };
    let mut legend: Legend = ProfileHeading::ALL
        .iter()
        .map(|&h| {
            (
                format!("{}-slope (rapier rover)", h.name()),
                Mark::Line(colour(h), 2),
            )
        })
        .collect();
    legend.push((
        "closed form, same soil (circles)".to_owned(),
        Mark::Fill(RGBColor(80, 80, 80).to_rgba()),
    ));
    let max_slope = profile.max_slope_deg().max(1.0);
    svg_with_legend(WIDTH, 380, &legend, |root| {
        let panels = root.split_evenly((1, 3));
        for (panel, terrain) in panels.iter().zip(TerrainClass::ALL) {
            let mut chart = ChartBuilder::on(panel)
                .caption(terrain.name(), ("sans-serif", 16))
                .margin(10)
                .x_label_area_size(36)
                .y_label_area_size(48)
                .build_cartesian_2d(0.0..max_slope, -20.0..105.0)
                .map_err(plot_error)?;
            chart
                .configure_mesh()
                .max_light_lines(1)
                .x_desc("slope (deg)")
                .y_desc("slip (%)")
                .draw()
                .map_err(plot_error)?;
            for h in ProfileHeading::ALL {
                let points: Vec<(f64, f64)> = profile
                    .curve(terrain, h)
                    .into_iter()
                    .map(|(x, s)| (x, 100.0 * s.clamp(-0.2, 1.05)))
                    .collect();
                chart
                    .draw_series(LineSeries::new(points, colour(h).stroke_width(2)))
                    .map_err(plot_error)?;
                let closed = profile
                    .rows
                    .iter()
                    .filter(|r| r.terrain == terrain && r.heading == h)
                    .filter_map(|r| r.closed_form_slip.map(|c| (r.slope_deg, 100.0 * c)))
                    .map(|p| Circle::new(p, 3, colour(h).filled()));
                chart.draw_series(closed).map_err(plot_error)?;
            }
        }
        Ok(())
    })
}

fn plot_error<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("drawing the figure failed: {e}")
}
