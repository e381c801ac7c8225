//! The map canvas of [`crate::figures::route_map`] and [`crate::figures::passages`]: a chart
//! in map metres at equal scale on both axes, and `draw_map`, which draws the zones (keep-outs
//! grown by their r), the route, the driven path, the sol-end discs, the closest passes and the
//! faults into it.

use geo::{BooleanOps as _, Coord, LineString, MultiLineString, MultiPolygon};
use maps::zone::Zone;
use plotters::coord::Shift;
use plotters::prelude::*;
use sim::CampaignOutcome;
use study::Scenario;

use crate::figures::canvas::{FigureError, plot_error, strategy_colour};
use crate::figures::zone_moments::{Panel, ZoneMoment};

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

/// The plotting area (pixels) of a map chart of `size` with `caption`, as [`map_chart`]
/// builds it: measured on a throwaway drawing, so the axes can be given equal scale exactly.
pub(crate) fn map_plot_area(
    size: (u32, u32),
    caption: &str,
    font: u32,
) -> Result<(u32, u32), FigureError> {
    let mut scratch = String::new();
    let root = SVGBackend::with_string(&mut scratch, size).into_drawing_area();
    let chart = map_chart(&root, caption, font, [0.0, 0.0, 1.0, 1.0])?;
    Ok(chart.plotting_area().dim_in_pixel())
}

pub(crate) type MapChart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

pub(crate) fn map_chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    caption: &str,
    font: u32,
    [x0, y0, x1, y1]: [f64; 4],
) -> Result<MapChart<'a, 'b>, FigureError> {
    ChartBuilder::on(area)
        .caption(caption, ("sans-serif", font))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(plot_error)
}

/// `window` widened so one metre is the same number of pixels on both axes of a chart of
/// `size` with `caption`; returns the widened window and the metres per pixel.
pub(crate) fn equal_scale(
    [x0, y0, x1, y1]: [f64; 4],
    size: (u32, u32),
    caption: &str,
    font: u32,
) -> Result<([f64; 4], f64), FigureError> {
    let (pw, ph) = map_plot_area(size, caption, font)?;
    let scale = ((x1 - x0) / f64::from(pw)).max((y1 - y0) / f64::from(ph));
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (hw, hh) = (scale * f64::from(pw) / 2.0, scale * f64::from(ph) / 2.0);
    Ok(([cx - hw, cy - hh, cx + hw, cy + hh], scale))
}

pub(crate) const GREY: RGBColor = RGBColor(120, 120, 120);
pub(crate) const LIGHT_GREY: RGBColor = RGBColor(200, 200, 200);
pub(crate) const ORANGE: RGBColor = RGBColor(255, 160, 60);
pub(crate) const KEEP_IN: RGBColor = RGBColor(170, 120, 0);
pub(crate) const PANEL_BOX: RGBColor = RGBColor(0, 0, 0);

/// What one map drawing shows besides the zones, route and path.
pub(crate) struct Layers<'s> {
    /// The growth of each keep-out (`None`: drawn as given, never reached).
    pub(crate) grow_m: Vec<Option<f64>>,
    /// The keep-in shrunk by this (the thin line), if at all.
    pub(crate) keep_in_shrunk_m: Option<f64>,
    /// Sol-end discs and labels.
    pub(crate) sol_ends: bool,
    /// The closest passes to draw with their discs (panels).
    pub(crate) passes: Vec<ZoneMoment>,
    /// Panel windows to outline and letter (the overview).
    pub(crate) panels: &'s [Panel],
}

/// Draws the map of `outcome` into `chart`, over `frame` (x0, y0, x1, y1, map metres) at
/// `scale` metres per pixel.
pub(crate) fn draw_map(
    chart: &mut MapChart<'_, '_>,
    scenario: &Scenario,
    outcome: &CampaignOutcome,
    layers: &Layers<'_>,
    [x0, y0, x1, y1]: [f64; 4],
    scale: f64,
) -> Result<(), FigureError> {
    let colour = strategy_colour(outcome.strategy);
    let frame: geo::Polygon<f64> =
        geo::Rect::new(Coord { x: x0, y: y0 }, Coord { x: x1, y: y1 }).to_polygon();
    let clip_area = |m: &MultiPolygon<f64>| m.intersection(&frame);
    // Outlines are cut as lines, so the frame's edge is never drawn as a zone's.
    let clip_lines = |rings: Vec<LineString<f64>>| -> Vec<Vec<(f64, f64)>> {
        frame
            .clip(&MultiLineString::new(rings), false)
            .into_iter()
            .map(|l| l.coords().map(|c| (c.x, c.y)).collect())
            .collect()
    };
    let rings_of = |m: &MultiPolygon<f64>| -> Vec<LineString<f64>> {
        m.iter()
            .flat_map(|p| {
                std::iter::once(p.exterior().clone()).chain(p.interiors().iter().cloned())
            })
            .collect()
    };
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x, map metres east")
        .y_desc("y, map metres north")
        .draw()
        .map_err(plot_error)?;
    let keep_outs: Vec<&Zone> = scenario.zones.keep_outs().map(|(_, z)| z).collect();
    // The same offsets the GIS layers carry (maps::zone::offset).
    for (zone, grow) in keep_outs.iter().zip(&layers.grow_m) {
        let Some(grow) = grow else { continue };
        chart
            .draw_series(
                clip_area(&zone.grown(*grow))
                    .iter()
                    .map(|p| Polygon::new(exterior(p), ORANGE.mix(0.45).filled())),
            )
            .map_err(plot_error)?;
    }
    for (zone, grow) in keep_outs.iter().zip(&layers.grow_m) {
        let fill = if grow.is_some() { GREY } else { LIGHT_GREY };
        let inside = clip_area(zone.geometry());
        chart
            .draw_series(
                inside
                    .iter()
                    .map(|p| Polygon::new(exterior(p), fill.filled())),
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
        // An outline two pixels wide, so a keep-out a few metres across still shows on a map
        // of kilometres.
        chart
            .draw_series(
                clip_lines(rings_of(zone.geometry()))
                    .into_iter()
                    .map(|r| PathElement::new(r, fill.stroke_width(2))),
            )
            .map_err(plot_error)?;
    }
    let shrinks = std::iter::once((0.0, 2)).chain(layers.keep_in_shrunk_m.map(|d| (d, 1)));
    for (distance, width) in shrinks {
        let Some(area) = scenario.zones.keep_in_shrunk(distance) else {
            continue;
        };
        chart
            .draw_series(
                clip_lines(rings_of(&area))
                    .into_iter()
                    .map(|r| PathElement::new(r, KEEP_IN.stroke_width(width))),
            )
            .map_err(plot_error)?;
    }
    let inside = |p: (f64, f64)| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1;
    let route: Vec<(f64, f64)> = scenario
        .settings
        .route
        .iter()
        .map(|p| (p[0], p[1]))
        .collect();
    chart
        .draw_series(
            clip_lines(vec![LineString::from(route.clone())])
                .into_iter()
                .map(|l| PathElement::new(l, BLACK.stroke_width(1))),
        )
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
        let path: Vec<(f64, f64)> = s
            .path_m
            .iter()
            .filter(|p| p[0].is_finite() && p[1].is_finite())
            .map(|p| (p[0], p[1]))
            .collect();
        if path.len() < 2 {
            continue;
        }
        chart
            .draw_series(
                clip_lines(vec![LineString::from(path)])
                    .into_iter()
                    .map(|l| PathElement::new(l, colour.stroke_width(2))),
            )
            .map_err(plot_error)?;
    }
    let disc_at = |chart: &mut MapChart<'_, '_>, centre: [f64; 2], r: f64, width: u32| {
        if inside((centre[0], centre[1])) {
            chart
                .draw_series(std::iter::once(Polygon::new(
                    disc(centre, r),
                    colour.mix(0.10).filled(),
                )))
                .map_err(plot_error)?;
        }
        let mut ring = disc(centre, r);
        ring.push(ring[0]);
        chart
            .draw_series(
                clip_lines(vec![LineString::from(ring)])
                    .into_iter()
                    .map(|l| PathElement::new(l, colour.stroke_width(width))),
            )
            .map_err(plot_error)?;
        Ok::<(), FigureError>(())
    };
    if layers.sol_ends {
        let mut labelled: Vec<(f64, f64)> = Vec::new();
        let mut labels = Vec::new();
        for s in outcome.sols.iter().filter(|s| s.drove) {
            let end = s.end_position_m;
            if !(end[0].is_finite() && end[1].is_finite() && s.end_uncertainty_m.is_finite()) {
                continue;
            }
            disc_at(chart, end, s.end_uncertainty_m, 1)?;
            let at = (end[0], end[1]);
            // Sol labels only where they do not overlap one already placed (36 px apart).
            let far = |q: &(f64, f64)| (q.0 - at.0).hypot(q.1 - at.1) / scale > 36.0;
            if inside(at) && labelled.iter().all(far) {
                labelled.push(at);
                labels.push((at, s.sol));
            }
        }
        chart
            .draw_series(labels.into_iter().map(|(at, sol)| {
                EmptyElement::at(at)
                    + Text::new(
                        format!("{sol}"),
                        (3, 3),
                        ("sans-serif", 12).into_font().color(&BLACK),
                    )
            }))
            .map_err(plot_error)?;
    }
    // The pass's disc as an outline only: a fill would hide how open the passage is.
    for m in &layers.passes {
        let mut ring = disc(m.at_m, m.r_m);
        ring.push(ring[0]);
        chart
            .draw_series(
                clip_lines(vec![LineString::from(ring)])
                    .into_iter()
                    .map(|l| PathElement::new(l, colour.stroke_width(2))),
            )
            .map_err(plot_error)?;
    }
    chart
        .draw_series(
            layers
                .passes
                .iter()
                .filter(|m| inside((m.at_m[0], m.at_m[1])))
                .map(|m| Circle::new((m.at_m[0], m.at_m[1]), 4, colour.filled())),
        )
        .map_err(plot_error)?;
    for p in layers.panels {
        let [a, b, c, d] = p.window;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(a, b), (c, b), (c, d), (a, d), (a, b)],
                PANEL_BOX.stroke_width(2),
            )))
            .map_err(plot_error)?;
        // The letter on a white tab above the box's left corner, readable over any zone.
        let tab = 10 * p.label.len() as i32 + 8;
        chart
            .draw_series(std::iter::once(
                EmptyElement::at((a, d))
                    + Rectangle::new([(-1, -20), (tab, 0)], WHITE.filled())
                    + Rectangle::new([(-1, -20), (tab, 0)], PANEL_BOX.stroke_width(1))
                    + Text::new(
                        p.label.clone(),
                        (3, -18),
                        ("sans-serif", 16).into_font().color(&PANEL_BOX),
                    ),
            ))
            .map_err(plot_error)?;
    }
    for s in &outcome.sols {
        let Some(f) = &s.fault else { continue };
        let p = (f.position_m[0], f.position_m[1]);
        if !(p.0.is_finite() && p.1.is_finite() && inside(p)) {
            continue;
        }
        let label = format!("{} sol {}", f.kind.name(), s.sol);
        // Left of the cross when the label would run past the right edge (about 7 px a letter).
        let dx = if (x1 - p.0) / scale < 9.0 + 7.5 * label.len() as f64 {
            -9 - (7.5 * label.len() as f64) as i32
        } else {
            9
        };
        // On a white tab, readable over a keep-out.
        let w = (7.5 * label.len() as f64) as i32;
        chart
            .draw_series(std::iter::once(
                EmptyElement::at(p)
                    + Rectangle::new([(dx - 2, -18), (dx + w, -1)], WHITE.mix(0.85).filled())
                    + Cross::new((0, 0), 7, RED.stroke_width(3))
                    + Text::new(label, (dx, -16), ("sans-serif", 13).into_font().color(&RED)),
            ))
            .map_err(plot_error)?;
    }
    Ok(())
}
