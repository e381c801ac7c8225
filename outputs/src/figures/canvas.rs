//! The canvas every figure draws on: the sizes, each strategy's colour, dash pattern and
//! marker (the same in every figure), the legend strip below a plot, and [`FigureError`].
//!
//! plotters draws into an SVG string; what it cannot draw (dashes, markers with a white edge)
//! is spliced into the SVG after it (`splice`).

use plotters::coord::Shift;
use plotters::prelude::*;
use sim::Strategy;

/// Why a figure could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// plotters refused a drawing step (it does not on finite data).
    #[error("drawing the figure failed: {detail}")]
    Draw {
        /// plotters' message.
        detail: String,
    },
}

/// Width of every figure, pixels (a map of a long traverse is wider).
pub(crate) const WIDTH: u32 = 960;
/// Width of a figure of a long traverse (over a kilometre, or more than 16 sols), pixels: the
/// width of a laptop screen.
pub(crate) const WIDE: u32 = 1400;

/// The width of a figure with a sol axis from `first` to `last`.
pub(crate) fn sols_width(first: u32, last: u32) -> u32 {
    if last - first > 16 { WIDE } else { WIDTH }
}
/// Height of a legend row, pixels; three entries per row.
pub(crate) const LEGEND_ROW: u32 = 20;
/// Width of a legend column, pixels.
pub(crate) const LEGEND_COLUMN: i32 = 300;

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

pub(crate) fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// SVG of `marker` centred at (x, y) pixels, about 7 px across, white-edged so it stays
/// visible on a line of its own colour.
pub(crate) fn marker_svg(marker: Marker, (x, y): (f64, f64), colour: RGBColor) -> String {
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
pub(crate) fn styled_line_svg(points: &[(f64, f64)], strategy: Strategy) -> String {
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
pub(crate) fn splice(mut svg: String, extra: &str) -> String {
    if let Some(at) = svg.rfind("</svg>") {
        svg.insert_str(at, extra);
    }
    svg
}

pub(crate) fn colour_of_name(name: &str) -> RGBColor {
    Strategy::from_name(name).map_or(RGBColor(90, 90, 90), strategy_colour)
}

/// A legend entry's symbol.
pub(crate) enum Mark {
    Fill(RGBAColor),
    Line(RGBColor, u32),
    Cross,
    /// A strategy's dashed line and marker ([`strategy_dash`], [`strategy_marker`]): drawn
    /// into the SVG after plotters, which has no dashes.
    Styled(Strategy),
}

/// Legend entries: label and symbol.
pub(crate) type Legend = Vec<(String, Mark)>;

pub(crate) fn legend_height(entries: &Legend) -> u32 {
    let rows = entries.len().div_ceil(3) as u32;
    if rows == 0 { 0 } else { rows * LEGEND_ROW + 14 }
}

/// Draws `entries` in rows of three into `area` (the strip below a plot).
pub(crate) fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    entries: &Legend,
) -> Result<(), FigureError> {
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
pub(crate) fn svg_with_legend(
    width: u32,
    plot_height: u32,
    entries: &Legend,
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), FigureError>,
) -> Result<String, FigureError> {
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

/// A plotters error as a [`FigureError`].
pub(crate) fn plot_error<E: std::fmt::Display>(e: E) -> FigureError {
    FigureError::Draw {
        detail: e.to_string(),
    }
}
