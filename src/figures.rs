//! Figures as SVG (plotters, no fonts needed: the SVG carries its text as `<text>` elements).
//!
//! One run (written by `solsim compare` beside its other files, and shown by `solsim report`):
//! - [`uncertainty_by_sol_svg`]: the position-uncertainty radius against sol, one line per
//!   strategy (paper 000 Fig. 2 and 5);
//! - [`metres_by_sol_svg`]: metres driven per sol, one bar per strategy;
//! - [`route_map_svg`]: one strategy's traverse on the map — zones, keep-outs grown by the r
//!   the rover had where it passed each (or a chosen r), the route, the driven path, sol-end
//!   discs and faults (paper 000 Fig. 3-4), over the whole traverse or zoomed on a window (a
//!   fault); [`passages_svg`]: zoomed panels at each passage the path went through;
//! - [`sol_plans_gantt_svg`]: each sol's executed plan as a Gantt chart, the co-processor
//!   (HBS) chain on its own row.
//!
//! A sweep (shown by `solsim report`): [`segment_sols_cdf_svg`], the distribution of the sols
//! each strategy took, and [`rates_svg`], the fault rates with their 95 % intervals.
//!
//! The rover: [`slip_profile_svg`], slip against slope per terrain class and heading.
//!
//! Every strategy has one colour in every figure ([`strategy_colour`]), and where lines of
//! several strategies can coincide one dash pattern and marker ([`strategy_dash`],
//! [`strategy_marker`]); legends sit below the plot, where they cover nothing.

use plotters::coord::Shift;
use plotters::prelude::*;
use sim::{CampaignOutcome, SolRecord, Strategy};
use sweep::rows::RunRow;
use sweep::summary::Rate;

mod route_map;

pub use route_map::{
    Growth, Panel, REACH_M, ZoneMoment, fault_window, passage_panels, passages_svg, route_map_svg,
    zone_moments,
};

/// Width of every figure, pixels (a map of a long traverse is wider).
const WIDTH: u32 = 960;
/// Width of a figure of a long traverse (over a kilometre, or more than 16 sols), pixels: the
/// width of a laptop screen.
const WIDE: u32 = 1400;

/// The width of a figure with a sol axis from `first` to `last`.
fn sols_width(first: u32, last: u32) -> u32 {
    if last - first > 16 { WIDE } else { WIDTH }
}
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

/// The dash pattern of a strategy's line where lines of several strategies can coincide (the
/// uncertainty figure), as an SVG `stroke-dasharray` (empty: solid).
#[must_use]
pub fn strategy_dash(strategy: Strategy) -> &'static str {
    match strategy {
        Strategy::Replay => "10 5",
        Strategy::Ground => "",
        Strategy::Onboard => "6 3",
        Strategy::Extension => "2 3",
        Strategy::ExtensionOnboard => "12 4 2 4",
    }
}

/// The shape marking a strategy's points where lines can coincide.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    /// A filled circle.
    Circle,
    /// A filled square.
    Square,
    /// A filled triangle, point up.
    TriangleUp,
    /// A filled triangle, point down.
    TriangleDown,
    /// A filled diamond.
    Diamond,
}

/// The marker of a strategy, the same in every figure that uses markers.
#[must_use]
pub fn strategy_marker(strategy: Strategy) -> Marker {
    match strategy {
        Strategy::Replay => Marker::Square,
        Strategy::Ground => Marker::Circle,
        Strategy::Onboard => Marker::TriangleUp,
        Strategy::Extension => Marker::Diamond,
        Strategy::ExtensionOnboard => Marker::TriangleDown,
    }
}

fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// SVG of `marker` centred at (x, y) pixels, about 7 px across, white-edged so it stays
/// visible on a line of its own colour.
fn marker_svg(marker: Marker, (x, y): (f64, f64), colour: RGBColor) -> String {
    let paint = format!(
        "fill=\"{}\" stroke=\"#FFFFFF\" stroke-width=\"0.8\"",
        hex(colour)
    );
    let poly = |pts: &[(f64, f64)]| {
        let pts: Vec<String> = pts
            .iter()
            .map(|(dx, dy)| format!("{:.1},{:.1}", x + dx, y + dy))
            .collect();
        format!("<polygon points=\"{}\" {paint}/>\n", pts.join(" "))
    };
    match marker {
        Marker::Circle => format!("<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3.5\" {paint}/>\n"),
        Marker::Square => poly(&[(-3.2, -3.2), (3.2, -3.2), (3.2, 3.2), (-3.2, 3.2)]),
        Marker::TriangleUp => poly(&[(0.0, -4.5), (4.0, 3.0), (-4.0, 3.0)]),
        Marker::TriangleDown => poly(&[(0.0, 4.5), (4.0, -3.0), (-4.0, -3.0)]),
        Marker::Diamond => poly(&[(0.0, -4.5), (4.0, 0.0), (0.0, 4.5), (-4.0, 0.0)]),
    }
}

/// SVG of a strategy's styled line through `points` (pixels).
fn styled_line_svg(points: &[(f64, f64)], strategy: Strategy) -> String {
    let pts: Vec<String> = points
        .iter()
        .map(|(x, y)| format!("{x:.1},{y:.1}"))
        .collect();
    let dash = strategy_dash(strategy);
    let dash = if dash.is_empty() {
        String::new()
    } else {
        format!(" stroke-dasharray=\"{dash}\"")
    };
    format!(
        "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"2\"{dash} \
         stroke-linejoin=\"round\" points=\"{}\"/>\n",
        hex(strategy_colour(strategy)),
        pts.join(" ")
    )
}

/// `svg` with `extra` (SVG elements) inserted before its closing tag, so drawn on top.
fn splice(mut svg: String, extra: &str) -> String {
    if let Some(at) = svg.rfind("</svg>") {
        svg.insert_str(at, extra);
    }
    svg
}

fn colour_of_name(name: &str) -> RGBColor {
    Strategy::from_name(name).map_or(RGBColor(90, 90, 90), strategy_colour)
}

/// A legend entry's symbol.
enum Mark {
    Fill(RGBAColor),
    Line(RGBColor, u32),
    Cross,
    /// A strategy's dashed line and marker ([`strategy_dash`], [`strategy_marker`]): drawn
    /// into the SVG after plotters, which has no dashes.
    Styled(Strategy),
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
            Mark::Styled(_) => Ok(()),
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
    // The styled swatches, at the places draw_legend leaves them.
    let mut extra = String::new();
    for (k, (_, mark)) in entries.iter().enumerate() {
        let Mark::Styled(strategy) = mark else {
            continue;
        };
        let x = f64::from(72 + LEGEND_COLUMN * (k % 3) as i32);
        let y = f64::from(plot_height) + f64::from(10 + LEGEND_ROW as i32 * (k / 3) as i32);
        extra.push_str(&styled_line_svg(&[(x - 10.0, y), (x + 20.0, y)], *strategy));
        extra.push_str(&marker_svg(
            strategy_marker(*strategy),
            (x + 5.0, y),
            strategy_colour(*strategy),
        ));
    }
    Ok(splice(svg, &extra))
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
/// pattern ([`strategy_dash`]) and a marker at the end of each drive ([`strategy_marker`]),
/// and each line is shifted by 2 px down and right per strategy (centred: from −4 to +4 px
/// with five), so coinciding lines lie side by side instead of hiding each other; 2 px is
/// under 2 % of the axes' spans.
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
