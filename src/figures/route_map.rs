//! Route maps: one strategy's traverse on the map ([`route_map_svg`]: the whole traverse, or a
//! window on a fault) and zoomed panels where its keep-outs mattered ([`passages_svg`]).
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

use geo::{BooleanOps as _, BoundingRect as _, Coord, LineString, MultiLineString, MultiPolygon};
use geo::{Distance as _, Euclidean};
use maps::zone::Zone;
use plotters::coord::Shift;
use plotters::prelude::*;
use sim::CampaignOutcome;
use study::Scenario;

use super::{Legend, Mark, WIDE, WIDTH, plot_error, strategy_colour, svg_with_legend};

/// A keep-out farther than this from every point of the driven path never came into play: it
/// is drawn as given, not grown (metres).
pub const REACH_M: f64 = 150.0;
/// Keep-outs whose closest passes lie within this of each other share a panel (the two sides
/// of a passage), metres.
const GROUP_M: f64 = 100.0;
/// Columns of panels in [`passages_svg`], and the size of each panel, pixels.
const PANEL_COLUMNS: u32 = 3;
const PANEL_SIZE: (u32, u32) = (466, 500);

/// How far a map grows the keep-outs (always plus the rover footprint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Growth {
    /// Every keep-out by this r, metres: `--map-r-m`, or a fault's r on its zoom.
    At(f64),
    /// Each keep-out by the r the rover had where its path came closest to it
    /// ([`zone_moments`]); a keep-out the path never came within [`REACH_M`] of is not grown.
    AtTheMoment,
}

/// Where a run's driven path came closest to one keep-out, and the rover's uncertainty there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZoneMoment {
    /// The sol of that pass.
    pub sol: u32,
    /// The closest point of the estimated path, map metres.
    pub at_m: [f64; 2],
    /// The uncertainty radius there, metres: the sol's start radius plus its growth over the
    /// sol in proportion to the path length driven so far (exact when the sol's share of
    /// driving without VO is even along it, as it is on a sol that kept VO throughout).
    pub r_m: f64,
    /// Distance from that point to the keep-out, metres (0 inside it).
    pub distance_m: f64,
    /// Index of the point along the run's whole path: orders the moments along the traverse.
    pub along: usize,
}

/// A point of the driven path: its sol, where, and the uncertainty radius there.
struct PathPoint {
    sol: u32,
    at: [f64; 2],
    r_m: f64,
}

/// Every point of the run's driven (estimated) path with the radius the rover had there.
fn path_points(outcome: &CampaignOutcome) -> Vec<PathPoint> {
    let mut out = Vec::new();
    for s in &outcome.sols {
        let pts: Vec<[f64; 2]> = s
            .path_m
            .iter()
            .copied()
            .filter(|p| p[0].is_finite() && p[1].is_finite())
            .collect();
        if pts.is_empty() || !(s.start_uncertainty_m.is_finite() && s.end_uncertainty_m.is_finite())
        {
            continue;
        }
        let step = |k: usize| (pts[k][0] - pts[k - 1][0]).hypot(pts[k][1] - pts[k - 1][1]);
        let total: f64 = (1..pts.len()).map(step).sum();
        let mut so_far = 0.0;
        for (k, &at) in pts.iter().enumerate() {
            if k > 0 {
                so_far += step(k);
            }
            let share = if total > 0.0 { so_far / total } else { 0.0 };
            out.push(PathPoint {
                sol: s.sol,
                at,
                r_m: s.start_uncertainty_m + (s.end_uncertainty_m - s.start_uncertainty_m) * share,
            });
        }
    }
    out
}

/// Distance from `p` to `zone`, metres (0 inside it).
fn distance_to_zone(p: [f64; 2], zone: &Zone) -> f64 {
    let point = geo::Point::new(p[0], p[1]);
    zone.geometry()
        .iter()
        .map(|poly| Euclidean.distance(&point, poly))
        .fold(f64::INFINITY, f64::min)
}

/// Path points this close to a zone's closest distance count as equally close (one step of
/// the planning grid), metres.
const TIE_M: f64 = 2.0;

/// For each keep-out of the scenario (in file order), the moment it mattered: where the run's
/// path came closest to it and the r then; `None` when the path never came within [`REACH_M`]
/// of it.
///
/// - Of points within 2 m of the closest distance (the rover went by the same place on two
///   sols, say stopping at the end of one and leaving on the next), the one with the largest r:
///   the tightest the keep-out was while the rover was there.
/// - A drive that ended in a fault within [`REACH_M`] of the keep-out did not pass it (its
///   moment is the fault's own, on the fault's zoom): its points count only when no other
///   drive came that near.
#[must_use]
pub fn zone_moments(scenario: &Scenario, outcome: &CampaignOutcome) -> Vec<Option<ZoneMoment>> {
    let path = path_points(outcome);
    let faults: Vec<(u32, [f64; 2])> = outcome
        .sols
        .iter()
        .filter_map(|s| s.fault.as_ref().map(|f| (s.sol, f.position_m)))
        .collect();
    scenario
        .zones
        .keep_outs()
        .map(|(_, zone)| {
            let bbox = zone.geometry().bounding_rect()?;
            let bbox_distance = |p: [f64; 2]| {
                let dx = (bbox.min().x - p[0]).max(p[0] - bbox.max().x).max(0.0);
                let dy = (bbox.min().y - p[1]).max(p[1] - bbox.max().y).max(0.0);
                dx.hypot(dy)
            };
            // Distance of every path point near the zone (the bounding box is a lower bound).
            let near: Vec<(usize, f64)> = path
                .iter()
                .enumerate()
                .filter(|(_, p)| bbox_distance(p.at) <= REACH_M)
                .map(|(k, p)| (k, distance_to_zone(p.at, zone)))
                .filter(|(_, d)| *d <= REACH_M)
                .collect();
            let stopped_here = |sol: u32| {
                faults
                    .iter()
                    .any(|(f, at)| *f == sol && distance_to_zone(*at, zone) <= REACH_M)
            };
            let passed: Vec<(usize, f64)> = near
                .iter()
                .copied()
                .filter(|(k, _)| !stopped_here(path[*k].sol))
                .collect();
            let candidates = if passed.is_empty() { near } else { passed };
            let closest = candidates
                .iter()
                .map(|(_, d)| *d)
                .fold(f64::INFINITY, f64::min);
            candidates
                .iter()
                .filter(|(_, d)| *d <= closest + TIE_M)
                .fold(None::<(usize, f64)>, |best, &(k, d)| match best {
                    Some((b, _)) if path[b].r_m >= path[k].r_m => best,
                    _ => Some((k, d)),
                })
                .map(|(k, d)| ZoneMoment {
                    sol: path[k].sol,
                    at_m: path[k].at,
                    r_m: path[k].r_m,
                    distance_m: d,
                    along: k,
                })
        })
        .collect()
}

/// One zoomed panel: the keep-outs (indices among the scenario's keep-outs) whose closest
/// passes lie together, and the window on them.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// `A`, `B`, … in order along the traverse (the overview marks the window with it).
    pub label: String,
    /// What the keep-outs are called: the first one's name, up to any parenthesis, without a
    /// trailing `left`/`right`.
    pub name: String,
    /// Indices of the keep-outs among [`maps::zone::ZoneSet::keep_outs`].
    pub keep_outs: Vec<usize>,
    /// The window shown, (x0, y0, x1, y1) map metres.
    pub window: [f64; 4],
}

/// `A`…`Z`, then `AA`, `AB`, … (spreadsheet columns).
fn panel_label(mut i: usize) -> String {
    let mut s = Vec::new();
    loop {
        s.push(b'A' + (i % 26) as u8);
        if i < 26 {
            break;
        }
        i = i / 26 - 1;
    }
    s.reverse();
    String::from_utf8(s).unwrap_or_default()
}

/// A keep-out's name as a panel title: up to any parenthesis, without `left`/`right`.
fn short_name(name: &str) -> String {
    let name = name.split(" (").next().unwrap_or(name).trim();
    let name = name
        .strip_suffix(" left")
        .or_else(|| name.strip_suffix(" right"))
        .unwrap_or(name);
    if name.is_empty() {
        "keep-out".to_owned()
    } else {
        name.to_owned()
    }
}

/// The panels of [`passages_svg`]: the reached keep-outs grouped where their closest passes lie
/// within 100 m of each other (the two sides of a passage), in order along the traverse, each
/// window square around its passes and wide enough for the grown keep-outs and the disc.
#[must_use]
pub fn passage_panels(scenario: &Scenario, moments: &[Option<ZoneMoment>]) -> Vec<Panel> {
    let footprint_m = scenario.campaign.grid.footprint_radius_m;
    let names: Vec<&str> = scenario.zones.keep_outs().map(|(_, z)| z.name()).collect();
    let mut order: Vec<(usize, ZoneMoment)> = moments
        .iter()
        .enumerate()
        .filter_map(|(i, m)| m.map(|m| (i, m)))
        .collect();
    order.sort_by_key(|(i, m)| (m.along, *i));
    let mut groups: Vec<Vec<(usize, ZoneMoment)>> = Vec::new();
    for (i, m) in order {
        let near = |g: &&mut Vec<(usize, ZoneMoment)>| {
            let a = g[0].1.at_m;
            (a[0] - m.at_m[0]).hypot(a[1] - m.at_m[1]) <= GROUP_M
        };
        match groups.iter_mut().find(|g| near(g)) {
            Some(g) => g.push((i, m)),
            None => groups.push(vec![(i, m)]),
        }
    }
    groups
        .iter()
        .enumerate()
        .map(|(k, g)| {
            let n = g.len() as f64;
            let cx = g.iter().map(|(_, m)| m.at_m[0]).sum::<f64>() / n;
            let cy = g.iter().map(|(_, m)| m.at_m[1]).sum::<f64>() / n;
            let r = g.iter().map(|(_, m)| m.r_m).fold(0.0, f64::max);
            let half = (1.6 * (r + footprint_m) + 25.0).max(75.0);
            Panel {
                label: panel_label(k),
                name: short_name(names.get(g[0].0).copied().unwrap_or("")),
                keep_outs: g.iter().map(|(i, _)| *i).collect(),
                window: [cx - half, cy - half, cx + half, cy + half],
            }
        })
        .collect()
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

/// The plotting area (pixels) of a map chart of `size` with `caption`, as [`map_chart`]
/// builds it: measured on a throwaway drawing, so the axes can be given equal scale exactly.
fn map_plot_area(size: (u32, u32), caption: &str, font: u32) -> anyhow::Result<(u32, u32)> {
    let mut scratch = String::new();
    let root = SVGBackend::with_string(&mut scratch, size).into_drawing_area();
    let chart = map_chart(&root, caption, font, [0.0, 0.0, 1.0, 1.0])?;
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
    font: u32,
    [x0, y0, x1, y1]: [f64; 4],
) -> anyhow::Result<MapChart<'a, 'b>> {
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
fn equal_scale(
    [x0, y0, x1, y1]: [f64; 4],
    size: (u32, u32),
    caption: &str,
    font: u32,
) -> anyhow::Result<([f64; 4], f64)> {
    let (pw, ph) = map_plot_area(size, caption, font)?;
    let scale = ((x1 - x0) / f64::from(pw)).max((y1 - y0) / f64::from(ph));
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (hw, hh) = (scale * f64::from(pw) / 2.0, scale * f64::from(ph) / 2.0);
    Ok(([cx - hw, cy - hh, cx + hw, cy + hh], scale))
}

const GREY: RGBColor = RGBColor(120, 120, 120);
const LIGHT_GREY: RGBColor = RGBColor(200, 200, 200);
const ORANGE: RGBColor = RGBColor(255, 160, 60);
const KEEP_IN: RGBColor = RGBColor(170, 120, 0);
const PANEL_BOX: RGBColor = RGBColor(0, 0, 0);

/// What one map drawing shows besides the zones, route and path.
struct Layers<'s> {
    /// The growth of each keep-out (`None`: drawn as given, never reached).
    grow_m: Vec<Option<f64>>,
    /// The keep-in shrunk by this (the thin line), if at all.
    keep_in_shrunk_m: Option<f64>,
    /// Sol-end discs and labels.
    sol_ends: bool,
    /// The closest passes to draw with their discs (panels).
    passes: Vec<ZoneMoment>,
    /// Panel windows to outline and letter (the overview).
    panels: &'s [Panel],
}

/// Draws the map of `outcome` into `chart`, over `frame` (x0, y0, x1, y1, map metres) at
/// `scale` metres per pixel.
fn draw_map(
    chart: &mut MapChart<'_, '_>,
    scenario: &Scenario,
    outcome: &CampaignOutcome,
    layers: &Layers<'_>,
    [x0, y0, x1, y1]: [f64; 4],
    scale: f64,
) -> anyhow::Result<()> {
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
        .campaign
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
        anyhow::Ok(())
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
/// - with [`Growth::AtTheMoment`] over the whole traverse, the windows of [`passages_svg`]'s
///   panels as lettered boxes;
/// - faults as red crosses, named.
///
/// `window` (x0, y0, x1, y1, map metres) zooms on a part (a fault: [`fault_window`]); without
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
) -> anyhow::Result<String> {
    let colour = strategy_colour(outcome.strategy);
    let footprint_m = scenario.campaign.grid.footprint_radius_m;
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
        window.unwrap_or_else(|| traverse_window(outcome, &scenario.campaign.route, largest_grow));
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
) -> anyhow::Result<Option<String>> {
    let moments = zone_moments(scenario, outcome);
    let panels = passage_panels(scenario, &moments);
    if panels.is_empty() {
        return Ok(None);
    }
    let colour = strategy_colour(outcome.strategy);
    let footprint_m = scenario.campaign.grid.footprint_radius_m;
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
