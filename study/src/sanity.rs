//! Checks that a scenario means what its author meant: every field may be well formed and the
//! whole still be nonsense — a route written in longitude/latitude degrees lands on the map
//! within one grid cell of its origin, a waypoint inside a keep-out makes every leg "close" at a
//! negative radius, zones off the map are silently ignored. [`findings`] names each such
//! problem with what to do about it.
//!
//! A [`Severity::Error`] is refused by every command that loads the scenario
//! ([`crate::Scenario::load`]); a [`Severity::Warning`] is something an operator may mean, which
//! `solsim validate` prints and nothing refuses.

use serde::Serialize;

use crate::error::{ScenarioError, excerpt};

/// Most characters of a zone's name quoted in a finding (names come from the zones file).
const ZONE_NAME_CHARS: usize = 60;
use crate::scenario::Scenario;

/// How bad a [`Finding`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Severity {
    /// The scenario cannot mean what it says: every command refuses it.
    Error,
    /// Probably a mistake, possibly intended: `solsim validate` says so, nothing refuses it.
    Warning,
}

impl Severity {
    /// `error` or `warning`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
        }
    }
}

/// One problem with a scenario as a whole, worded like a [`ScenarioError::Field`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Finding {
    /// Error or warning.
    pub severity: Severity,
    /// Where: a TOML path (`route.waypoints[2]`) or a zone (`map.zones: "crater" (feature 3)`).
    pub field: String,
    /// What would make sense.
    pub expected: String,
    /// What the scenario holds.
    pub got: String,
    /// What to do about it.
    pub hint: String,
}

impl Finding {
    /// The finding as the one-line error a command refusing the scenario prints.
    #[must_use]
    pub fn to_error(&self, scenario: &std::path::Path) -> ScenarioError {
        // Built whole, not through `ScenarioError::field`: its excerpt would cut the hint, and
        // every part here is solsim's own text (zone names are excerpted where they enter).
        ScenarioError::Field {
            path: scenario.to_path_buf(),
            field: self.field.clone(),
            expected: self.expected.clone(),
            got: format!("{} — {}", self.got, self.hint),
        }
    }
}

impl std::fmt::Display for Finding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {}: expected {}, got {} — {}",
            self.severity.name(),
            self.field,
            self.expected,
            self.got,
            self.hint
        )
    }
}

/// Map coordinates that look like longitude/latitude degrees: every one within ±360 × ±90.
fn degree_like(points: &[[f64; 2]]) -> bool {
    !points.is_empty()
        && points
            .iter()
            .all(|p| p[0].abs() <= 360.0 && p[1].abs() <= 90.0)
}

/// Bounding box `[x0, y0, x1, y1]` of `points` (`None` when empty).
fn bbox(points: impl IntoIterator<Item = [f64; 2]>) -> Option<[f64; 4]> {
    points.into_iter().fold(None, |b, p| {
        Some(b.map_or([p[0], p[1], p[0], p[1]], |b: [f64; 4]| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        }))
    })
}

const COORDINATES_HINT: &str = "scenario and zone coordinates are map metres, x east and y north \
    of the map's origin; convert longitude/latitude degrees to map metres";

/// Every problem [`Scenario`] `s` has as a whole: errors first, then warnings, each in file
/// order. Empty for a scenario that makes sense.
#[must_use]
pub fn findings(s: &Scenario) -> Vec<Finding> {
    let mut out = Vec::new();
    let c = &s.settings;
    let cell_m = c.grid.geo.resolution_m_per_px;
    let (x0, y0, x1, y1) = s.layers.dem.extent_m();
    let extent = format!("x {x0:.1}..{x1:.1} m, y {y0:.1}..{y1:.1} m");

    // The route: longer than one grid cell, or it is probably in degrees.
    // Waypoints already reported: their legs are not reported again.
    let mut bad_waypoint = vec![false; c.route.len()];
    if let Some([bx0, by0, bx1, by1]) = bbox(c.route.iter().copied())
        && c.route.len() >= 2
        && (bx1 - bx0).max(by1 - by0) < cell_m
    {
        let degrees = if degree_like(&c.route) {
            "; these look like longitude/latitude degrees"
        } else {
            ""
        };
        out.push(Finding {
            severity: Severity::Error,
            field: "route.waypoints".into(),
            expected: format!(
                "a route spanning more than one {cell_m} m grid cell of the map ({extent})"
            ),
            got: format!(
                "{} waypoints within {:.3} × {:.3} m{degrees}",
                c.route.len(),
                bx1 - bx0,
                by1 - by0
            ),
            hint: COORDINATES_HINT.into(),
        });
        bad_waypoint.fill(true);
    }

    // Zones: on the map, larger than a cell, not all packed into one cell (degrees).
    let zone_points = |z: &maps::zone::Zone| -> Vec<[f64; 2]> {
        z.geometry()
            .0
            .iter()
            .flat_map(|p| p.exterior().0.iter().map(|c| [c.x, c.y]))
            .collect()
    };
    let all: Vec<[f64; 2]> = s.zones.iter().flat_map(|(_, z)| zone_points(z)).collect();
    let zones_in_one_cell =
        bbox(all.iter().copied()).is_some_and(|b| (b[2] - b[0]).max(b[3] - b[1]) < cell_m);
    if zones_in_one_cell {
        let degrees = if degree_like(&all) {
            "; these look like longitude/latitude degrees"
        } else {
            ""
        };
        out.push(Finding {
            severity: Severity::Error,
            field: format!("map.zones ({})", s.zones.source().display()),
            expected: format!(
                "zones spanning more than one {cell_m} m grid cell of the map ({extent})"
            ),
            got: format!("{} zones within one cell{degrees}", s.zones.len()),
            hint: COORDINATES_HINT.into(),
        });
    } else {
        for (_, z) in s.zones.iter() {
            let Some([zx0, zy0, zx1, zy1]) = bbox(zone_points(z)) else {
                continue;
            };
            let field = format!(
                "map.zones: {} \"{}\" (feature {})",
                z.kind().as_str(),
                excerpt(z.name(), ZONE_NAME_CHARS),
                z.feature_index()
            );
            if zx1 < x0 || zx0 > x1 || zy1 < y0 || zy0 > y1 {
                out.push(Finding {
                    severity: Severity::Error,
                    field,
                    expected: format!("a zone that overlaps the map ({extent})"),
                    got: format!(
                        "x {zx0:.1}..{zx1:.1} m, y {zy0:.1}..{zy1:.1} m, entirely off the map"
                    ),
                    hint: format!("the planner ignores it; {COORDINATES_HINT}"),
                });
            } else if (zx1 - zx0).max(zy1 - zy0) < cell_m {
                out.push(Finding {
                    severity: Severity::Warning,
                    field,
                    expected: format!("a zone larger than one {cell_m} m grid cell"),
                    got: format!("{:.2} × {:.2} m", zx1 - zx0, zy1 - zy0),
                    hint: "the planning grid marks the cells the zone touches, so it acts as a \
                           whole cell; draw it at its true size or set grid.resolution_m finer"
                        .into(),
                });
            }
        }
    }

    // Waypoints against the zones, when the zones are where the route is.
    if !zones_in_one_cell {
        let has_keep_in = s.zones.keep_ins().next().is_some();
        for (i, &w) in c.route.iter().enumerate() {
            if bad_waypoint[i] {
                continue;
            }
            let field = format!("route.waypoints[{i}]");
            let at = format!("[{}, {}]", w[0], w[1]);
            if let Some((_, z)) = s.zones.keep_outs().find(|(_, z)| z.covers(w)) {
                bad_waypoint[i] = true;
                out.push(Finding {
                    severity: Severity::Error,
                    field,
                    expected: "a waypoint outside every keep-out zone".into(),
                    got: format!(
                        "{at}, inside keep-out \"{}\" (feature {})",
                        excerpt(z.name(), ZONE_NAME_CHARS),
                        z.feature_index()
                    ),
                    hint: "AutoNav can never reach it; move the waypoint out of the zone, or \
                           change the zone"
                        .into(),
                });
            } else if has_keep_in && !s.zones.in_keep_in(w) {
                bad_waypoint[i] = true;
                let what = if i == 0 { "the start" } else { "a waypoint" };
                out.push(Finding {
                    severity: Severity::Error,
                    field,
                    expected: format!("{what} inside the keep-in zones"),
                    got: format!("{at}, outside every keep-in"),
                    hint: if i == 0 {
                        "the rover would begin the campaign in a KEEP_IN fault; move the start \
                         or widen the keep-in"
                            .into()
                    } else {
                        "AutoNav can never reach it; move the waypoint or widen the keep-in".into()
                    },
                });
            }
            // A waypoint where the footprint overlaps a zone is no finding of its own: AutoNav
            // plans to the waypoint's cell, closed there even at r = 0, so each leg to or from
            // it is closed at r = 0 and reported below with the overlap as its cause. (It was
            // a warning that also hid its legs: a keep-in sliver along the route passed.)
        }
    }

    // Legs closed with perfect knowledge (r = 0): no path, or one whose narrowest cell the
    // footprint does not fit (`clearance ≤ 0` closes a cell at r = 0, as AutoNav's A* has it).
    for leg in &s.legs {
        let (a, b) = (leg.to_waypoint - 1, leg.to_waypoint);
        if bad_waypoint[a] || bad_waypoint[b] {
            continue;
        }
        let closed = match leg.clearance_m {
            None => Some(
                "no path at all within 150 m of the leg (hazards, slopes and zones)".to_string(),
            ),
            Some(r) if r <= 0.0 => {
                // Name an end whose own cell is closed: moving it clears the leg.
                let overlap = [a, b].into_iter().find_map(|i| {
                    let w = c.route[i];
                    let cell = c.grid.cell_of(w)?;
                    let clearance = f64::from(c.grid.clearance_m[cell]);
                    (clearance <= 0.0).then(|| {
                        format!(
                            "; at waypoint {i} [{}, {}] the footprint overlaps a zone by {:.2} m",
                            w[0], w[1], -clearance
                        )
                    })
                });
                Some(format!(
                    "closes at r = {r:.2} m{}",
                    overlap.unwrap_or_default()
                ))
            }
            Some(_) => None,
        };
        if let Some(got) = closed {
            out.push(Finding {
                severity: Severity::Error,
                field: format!("route.waypoints[{a}..={b}]"),
                expected: "a leg AutoNav can drive with perfect position knowledge (r = 0)".into(),
                got,
                hint: "every drive on it faults NO_PATH at once; move its waypoints where the \
                       rover's footprint fits, add a waypoint around the obstacle or change the \
                       zones"
                    .into(),
            });
        }
    }

    out.sort_by_key(|f| f.severity == Severity::Warning);
    out
}
