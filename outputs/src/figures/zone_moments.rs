//! Where a run's keep-outs mattered: the moment its driven path came closest to each
//! ([`zone_moments`], with the r the rover had there), the zoomed panels those moments group
//! into ([`passage_panels`]) and the window of a fault's zoom ([`fault_window`]). The maps of
//! [`crate::figures::route_map`] and [`crate::figures::passages`] draw them.

use geo::BoundingRect as _;
use geo::{Distance as _, Euclidean};
use maps::zone::Zone;
use sim::CampaignOutcome;
use study::Scenario;

/// A keep-out farther than this from every point of the driven path never came into play: it
/// is drawn as given, not grown (metres).
pub const REACH_M: f64 = 150.0;
/// Keep-outs whose closest passes lie within this of each other share a panel (the two sides
/// of a passage), metres.
const GROUP_M: f64 = 100.0;

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

/// The panels of [`passages_svg`](crate::figures::passages_svg): the reached keep-outs grouped where their closest passes lie
/// within 100 m of each other (the two sides of a passage), in order along the traverse, each
/// window square around its passes and wide enough for the grown keep-outs and the disc.
#[must_use]
pub fn passage_panels(scenario: &Scenario, moments: &[Option<ZoneMoment>]) -> Vec<Panel> {
    let footprint_m = scenario.settings.grid.footprint_radius_m;
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
