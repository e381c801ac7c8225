//! Figures as SVG (plotters, no fonts needed: the SVG carries its text as `<text>` elements).
//!
//! One run (written by `solsim compare` beside its other files, and shown by `solsim report`):
//! - [`uncertainty_by_sol_svg`]: the position-uncertainty radius against sol, one line per
//!   strategy (paper 000 Fig. 2 and 5);
//! - [`metres_by_sol_svg`]: metres driven per sol, one bar per strategy;
//! - [`route_map_svg`]: one strategy's traverse on the map — zones, keep-outs grown at a
//!   chosen r, the route, the driven path, sol-end discs and faults (paper 000 Fig. 3-4);
//! - [`sol_plans_gantt_svg`]: each sol's executed plan as a Gantt chart, the co-processor
//!   (HBS) chain on its own row.
//!
//! A sweep (shown by `solsim report`): [`segment_sols_cdf_svg`], the distribution of the sols
//! each strategy took, and [`rates_svg`], the fault rates with their 95 % intervals.

use geo::{BooleanOps as _, Coord, LineString, MultiPolygon};
use plotters::coord::Shift;
use plotters::prelude::*;
use sim::{CampaignOutcome, SolRecord};
use study::Scenario;
use sweep::rows::RunRow;
use sweep::summary::Rate;

/// One colour per strategy, in `outcomes` order (cycled past five).
const COLOURS: [RGBColor; 5] = [
    RGBColor(90, 90, 90),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
];

/// The colour of the `i`-th strategy.
#[must_use]
pub fn colour(i: usize) -> RGBColor {
    COLOURS[i % COLOURS.len()]
}

/// Draws into an SVG string of `size` pixels.
fn svg_of(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> anyhow::Result<()>,
) -> anyhow::Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        draw(&root)?;
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
    svg_of((900, 480), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(first..last, 0.0..max_r * 1.08)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .max_light_lines(2)
            .x_desc("sol")
            .y_desc("uncertainty radius r (m)")
            .x_labels(((last - first) as usize + 1).min(32))
            .draw()
            .map_err(plot_error)?;
        for (i, o) in outcomes.iter().enumerate() {
            let colour = colour(i);
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
        legend(&mut chart, SeriesLabelPosition::UpperLeft)
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
    svg_of((900, 420), |root| {
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
            .max_light_lines(2)
            .x_desc("sol")
            .y_desc("metres driven")
            .x_labels(((last - first) as usize + 1).min(32))
            .x_label_formatter(&|x| format!("{}", x.floor() as u32))
            .draw()
            .map_err(plot_error)?;
        for (i, o) in outcomes.iter().enumerate() {
            let colour = colour(i);
            let left = |s: &SolRecord| f64::from(s.sol) + 0.1 + width * i as f64;
            let bars = o
                .sols
                .iter()
                .filter(|s| s.drove && s.distance_m.is_finite())
                .map(|s| {
                    Rectangle::new(
                        [(left(s), 0.0), (left(s) + width, s.distance_m)],
                        colour.filled(),
                    )
                });
            chart
                .draw_series(bars)
                .map_err(plot_error)?
                .label(o.strategy.name())
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 5), (x + 12, y + 5)], colour.filled())
                });
            let faults = o
                .sols
                .iter()
                .filter(|s| s.fault.is_some() && s.distance_m.is_finite())
                .map(|s| {
                    Cross::new(
                        (left(s) + width / 2.0, s.distance_m),
                        5,
                        RED.stroke_width(2),
                    )
                });
            chart.draw_series(faults).map_err(plot_error)?;
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight)
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

/// One strategy's traverse on the map, in map metres with equal scale on both axes, over the
/// route and the driven paths with a margin:
/// - keep-out zones filled grey, and grown by `r_m` plus the rover footprint (the region the
///   rover's centre must avoid at that uncertainty) in orange;
/// - keep-in zones outlined green, and shrunk by the same distance dashed;
/// - the route in black with its waypoints; the driven path in the strategy's colour, each
///   sol's end labelled with the sol and circled by its end-of-sol uncertainty disc;
/// - faults as red crosses.
///
/// # Errors
/// When plotters cannot draw.
pub fn route_map_svg(
    scenario: &Scenario,
    outcome: &CampaignOutcome,
    colour_index: usize,
    r_m: f64,
) -> anyhow::Result<String> {
    let colour = colour(colour_index);
    let footprint_m = scenario.campaign.grid.footprint_radius_m;
    let grow_m = r_m.max(0.0) + footprint_m;
    // Extent: the route and the driven paths, with room for the discs.
    let mut pts: Vec<[f64; 2]> = scenario.campaign.route.clone();
    for s in &outcome.sols {
        pts.extend(s.path_m.iter().copied());
        pts.push(s.end_position_m);
    }
    pts.retain(|p| p[0].is_finite() && p[1].is_finite());
    let (mut x0, mut y0, mut x1, mut y1) = pts.iter().fold(
        (f64::MAX, f64::MAX, f64::MIN, f64::MIN),
        |(a, b, c, d), p| (a.min(p[0]), b.min(p[1]), c.max(p[0]), d.max(p[1])),
    );
    if x0 > x1 {
        (x0, y0, x1, y1) = (0.0, 0.0, 1.0, 1.0);
    }
    let max_disc = outcome
        .sols
        .iter()
        .map(|s| s.end_uncertainty_m)
        .filter(|r| r.is_finite())
        .fold(0.0, f64::max);
    let span: f64 = (x1 - x0).max(y1 - y0);
    let pad = (0.06 * span)
        .max(grow_m * 1.2)
        .max(max_disc.min(0.25 * span))
        .max(10.0);
    (x0, y0, x1, y1) = (x0 - pad, y0 - pad, x1 + pad, y1 + pad);
    // Equal scale: the plot is 900 px wide and as tall as the extent needs (200-900 px); a
    // clamped height widens the other axis instead of distorting.
    let plot_w = 900.0;
    let mut plot_h = plot_w * (y1 - y0) / (x1 - x0);
    if plot_h > 900.0 {
        plot_h = 900.0;
        let want = (y1 - y0) * plot_w / plot_h;
        let grow = (want - (x1 - x0)) / 2.0;
        (x0, x1) = (x0 - grow, x1 + grow);
    } else if plot_h < 200.0 {
        plot_h = 200.0;
        let want = (x1 - x0) * plot_h / plot_w;
        let grow = (want - (y1 - y0)) / 2.0;
        (y0, y1) = (y0 - grow, y1 + grow);
    }
    let frame: geo::Polygon<f64> =
        geo::Rect::new(Coord { x: x0, y: y0 }, Coord { x: x1, y: y1 }).to_polygon();
    let clip = |m: &MultiPolygon<f64>| m.intersection(&frame);
    let title = format!(
        "{}: {} — keep-outs grown by r = {r_m:.1} m + {footprint_m:.1} m footprint",
        scenario.name,
        outcome.strategy.name()
    );
    // The legend goes below the map, where it covers nothing.
    let legend_h = 70.0;
    let size = ((plot_w + 100.0) as u32, (plot_h + 110.0 + legend_h) as u32);
    svg_of(size, |root| {
        let (upper, lower) = root.split_vertically((plot_h + 110.0) as u32);
        let mut chart = ChartBuilder::on(&upper)
            .caption(&title, ("sans-serif", 16))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x, map metres east")
            .y_desc("y, map metres north")
            .draw()
            .map_err(plot_error)?;
        let grey = RGBColor(120, 120, 120);
        let orange = RGBColor(255, 160, 60);
        let teal = RGBColor(0, 110, 120);
        let mut entries: Vec<(String, Mark)> = Vec::new();
        if scenario.zones.keep_outs().next().is_some() {
            entries.push((
                format!("keep-out grown by {grow_m:.1} m"),
                Mark::Fill(orange.mix(0.45)),
            ));
            entries.push(("keep-out".into(), Mark::Fill(grey.to_rgba())));
        }
        if scenario.zones.keep_ins().next().is_some() {
            entries.push((
                "keep-in; thin: shrunk by the same".into(),
                Mark::Line(teal, 2),
            ));
        }
        entries.push(("route and waypoints".into(), Mark::Line(BLACK, 1)));
        entries.push((
            format!(
                "{} path, sol-end uncertainty discs",
                outcome.strategy.name()
            ),
            Mark::Line(colour, 2),
        ));
        if outcome.sols.iter().any(|s| s.fault.is_some()) {
            entries.push(("fault".into(), Mark::Cross));
        }
        // The same offsets the GIS layers carry (maps::zone::offset).
        for (_, grown) in scenario.zones.keep_outs_grown(grow_m) {
            let grown = clip(&grown);
            chart
                .draw_series(
                    grown
                        .iter()
                        .map(|p| Polygon::new(exterior(p), orange.mix(0.45).filled())),
                )
                .map_err(plot_error)?;
        }
        for (_, z) in scenario.zones.keep_outs() {
            let inside = clip(z.geometry());
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
        let rings = |m: &MultiPolygon<f64>| -> Vec<Vec<(f64, f64)>> {
            clip(m)
                .iter()
                .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                .map(|r: &LineString<f64>| r.coords().map(|c| (c.x, c.y)).collect())
                .collect()
        };
        // The keep-in union as given, thick, and shrunk by r plus the footprint, thin.
        let keep_in = [
            (scenario.zones.keep_in_shrunk(0.0), 2),
            (scenario.zones.keep_in_shrunk(grow_m), 1),
        ];
        for (area, width) in keep_in {
            let Some(area) = area else { continue };
            chart
                .draw_series(
                    rings(&area)
                        .into_iter()
                        .map(|r| PathElement::new(r, teal.stroke_width(width))),
                )
                .map_err(plot_error)?;
        }
        let route: Vec<(f64, f64)> = scenario
            .campaign
            .route
            .iter()
            .map(|p| (p[0], p[1]))
            .collect();
        chart
            .draw_series(std::iter::once(PathElement::new(
                route.clone(),
                BLACK.stroke_width(1),
            )))
            .map_err(plot_error)?;
        chart
            .draw_series(route.iter().map(|&p| Circle::new(p, 3, BLACK.filled())))
            .map_err(plot_error)?;
        for s in &outcome.sols {
            let path: Vec<(f64, f64)> = s
                .path_m
                .iter()
                .filter(|p| p[0].is_finite() && p[1].is_finite())
                .map(|p| (p[0], p[1]))
                .collect();
            if path.len() >= 2 {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        path,
                        colour.stroke_width(2),
                    )))
                    .map_err(plot_error)?;
            }
        }
        for s in outcome.sols.iter().filter(|s| s.drove) {
            let end = s.end_position_m;
            if !(end[0].is_finite() && end[1].is_finite() && s.end_uncertainty_m.is_finite()) {
                continue;
            }
            let mut ring = disc(end, s.end_uncertainty_m);
            chart
                .draw_series(std::iter::once(Polygon::new(
                    ring.clone(),
                    colour.mix(0.12).filled(),
                )))
                .map_err(plot_error)?;
            ring.push(ring[0]);
            chart
                .draw_series([EmptyElement::at((end[0], end[1]))
                    + Text::new(
                        format!("{}", s.sol),
                        (3, 3),
                        ("sans-serif", 12).into_font().color(&BLACK),
                    )])
                .map_err(plot_error)?;
            chart
                .draw_series(std::iter::once(PathElement::new(
                    ring,
                    colour.stroke_width(1),
                )))
                .map_err(plot_error)?;
        }
        for s in &outcome.sols {
            let Some(f) = &s.fault else { continue };
            let p = (f.position_m[0], f.position_m[1]);
            if !(p.0.is_finite() && p.1.is_finite()) {
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
        legend_below(&lower, &entries)
    })
}

/// A legend entry's symbol in [`legend_below`].
enum Mark {
    Fill(RGBAColor),
    Line(RGBColor, u32),
    Cross,
}

/// A legend in rows of three entries, drawn in its own area (below a map, so it covers none
/// of it).
fn legend_below(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    entries: &[(String, Mark)],
) -> anyhow::Result<()> {
    let font = ("sans-serif", 13).into_font().color(&BLACK);
    for (k, (label, mark)) in entries.iter().enumerate() {
        let x = 72 + 300 * (k % 3) as i32;
        let y = 12 + 20 * (k / 3) as i32;
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

/// What kind of activity a timeline row is, for its colour in [`sol_plans_gantt_svg`].
fn activity_class(activity: &str) -> (&'static str, RGBColor) {
    if activity.starts_with("drive") {
        ("drive", RGBColor(31, 119, 180))
    } else if activity.starts_with("hbs_") {
        ("HBS co-processor chain", RGBColor(148, 103, 189))
    } else if activity.starts_with("heating") {
        ("heating", RGBColor(214, 39, 40))
    } else if activity.contains("imaging") || activity.contains("panorama") {
        ("imaging", RGBColor(255, 127, 14))
    } else if activity == "sunfind" || activity == "compare_apply" {
        (
            "localization (sunfind, compare and apply)",
            RGBColor(44, 160, 44),
        )
    } else if activity.contains("comm") || activity.contains("downlink") {
        ("communication", RGBColor(23, 190, 207))
    } else {
        ("science and other", RGBColor(140, 140, 140))
    }
}

/// Each sol's executed plan of one run as a Gantt chart: one row per sol for the main
/// timeline and, where the sol ran the co-processor chain, one below it for the HBS link
/// (transfer, runs, reboot), against LMST hours. `None` when no sol of the run has a plan.
///
/// # Errors
/// When plotters cannot draw.
pub fn sol_plans_gantt_svg(
    title: &str,
    outcome: &CampaignOutcome,
) -> anyhow::Result<Option<String>> {
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
    let t0 = steps().map(|t| t.start_s.0).min().unwrap_or(0) as f64 / 3600.0;
    let t1 = steps().map(|t| t.end_s.0).max().unwrap_or(0) as f64 / 3600.0;
    let (h0, h1) = (t0.floor(), t1.ceil().max(t0.floor() + 1.0));
    let n = rows.len();
    // Below the rows, room for the legend (up to seven classes) so it never covers a bar.
    let legend_rows = 5.0;
    let height = (90.0 + 26.0 * (n as f64 + legend_rows)) as u32;
    let labels = rows.iter().map(|r| r.0.clone()).collect::<Vec<_>>();
    let svg = svg_of((900, height.max(260)), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(80)
            .build_cartesian_2d(h0..h1, -legend_rows..n as f64)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_y_mesh()
            .max_light_lines(2)
            .x_desc("LMST (hours)")
            .x_labels(((h1 - h0) as usize + 1).min(25))
            .x_label_formatter(&|h| format!("{:02}:00", h.round() as i64))
            .y_labels((n + legend_rows as usize) * 2 + 1)
            .y_label_formatter(&|y| {
                // Labels at row centres only (row i spans n-i-1 .. n-i from the top).
                let f = y.fract();
                if *y < 0.0 || (f - 0.5).abs() > 1e-6 {
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
        let mut seen: Vec<&'static str> = Vec::new();
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
                let (class, c) = activity_class(&t.activity);
                let a = t.start_s.0 as f64 / 3600.0;
                let b = (t.end_s.0 as f64 / 3600.0).max(a + 1.0 / 120.0);
                let series = chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(a, bottom), (b, top)],
                        c.filled(),
                    )))
                    .map_err(plot_error)?;
                if !seen.contains(&class) {
                    seen.push(class);
                    series.label(class).legend(move |(x, y)| {
                        Rectangle::new([(x, y - 5), (x + 12, y + 5)], c.filled())
                    });
                }
                if t.outcome
                    .as_deref()
                    .is_some_and(|o| o.contains("NO_PATH") || o.contains("fault"))
                {
                    chart
                        .draw_series(std::iter::once(Cross::new(
                            (b, (top + bottom) / 2.0),
                            6,
                            RED.stroke_width(3),
                        )))
                        .map_err(plot_error)?;
                }
            }
        }
        legend(&mut chart, SeriesLabelPosition::LowerRight)
    })?;
    Ok(Some(svg))
}

/// The empirical distribution of the sols each strategy took over the runs of a sweep (the
/// study segment's `segment_sols` when the sweep has a segment, else `sols_to_goal`), as step
/// CDFs. A run that never covered the segment or reached the goal within the calendar counts in
/// the denominator only, so its strategy's curve stays below 1 by that share.
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
    svg_of((900, 440), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(f64::from(lo)..f64::from(hi), 0.0..1.05)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .max_light_lines(2)
            .x_desc(what)
            .y_desc("share of runs (CDF)")
            .x_labels(((hi - lo) as usize + 1).min(32))
            .x_label_formatter(&|x| format!("{}", x.round() as i64))
            .draw()
            .map_err(plot_error)?;
        for (i, name) in strategies.iter().enumerate() {
            let colour = colour(i);
            let mine: Vec<&RunRow> = rows.iter().filter(|r| r.strategy.name() == name).collect();
            if mine.is_empty() {
                continue;
            }
            let n = mine.len() as f64;
            let mut vals: Vec<u32> = mine.iter().filter_map(|r| value(r)).collect();
            vals.sort_unstable();
            let mut pts = vec![(f64::from(lo), 0.0)];
            let mut k = 0usize;
            for x in lo..=hi {
                let before = k as f64 / n;
                while k < vals.len() && vals[k] <= x {
                    k += 1;
                }
                pts.push((f64::from(x), before));
                pts.push((f64::from(x), k as f64 / n));
            }
            let censored = mine.len() - vals.len();
            let label = if censored > 0 {
                format!(
                    "{name} ({censored} of {} runs: more than the calendar)",
                    mine.len()
                )
            } else {
                format!("{name} ({} runs)", mine.len())
            };
            // Earlier strategies wider, so a curve another one coincides with stays visible.
            let width = 2 + 2 * (strategies.len() - 1 - i) as u32;
            chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(width)))
                .map_err(plot_error)?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                });
        }
        legend(&mut chart, SeriesLabelPosition::LowerRight)
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
    let label_names = names.clone();
    svg_of((900, 440), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            // A free column on the right for the legend.
            .build_cartesian_2d(0.0..groups as f64 + 0.9, 0.0..1.05)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .max_light_lines(2)
            .y_desc("share of runs, with 95 % Wilson interval")
            .x_labels(groups * 2 + 1)
            .x_label_formatter(&|x| {
                if (x.fract() - 0.5).abs() > 1e-6 {
                    return String::new();
                }
                label_names
                    .get(x.floor() as usize)
                    .cloned()
                    .unwrap_or_default()
            })
            .draw()
            .map_err(plot_error)?;
        for (i, (strategy, rates)) in per_strategy.iter().enumerate() {
            let colour = colour(i);
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
                .map_err(plot_error)?
                .label(strategy.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                });
            chart
                .draw_series(
                    rates
                        .iter()
                        .map(|r| Circle::new((x_of(&r.name), r.rate), 4, colour.filled())),
                )
                .map_err(plot_error)?;
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight)
    })
}

fn legend<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    at: SeriesLabelPosition,
) -> anyhow::Result<()> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(at)
        .draw()
        .map_err(plot_error)
}

fn plot_error<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("drawing the figure failed: {e}")
}
