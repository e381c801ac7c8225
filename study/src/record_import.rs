//! `solsim record import`: a replay scenario built from the public drive record for any sol range.
//!
//! What comes from where, written into the scenario's header and into each `[[sols]]` entry:
//!
//! - **historic input (the record, [`crate::record`])**: which sols drove; each drive's length
//!   (the record's localized path length) unless paper 000 gives the sol's odometry
//!   ([`PAPER_000_SOLS`]); each drive's window in LMST from the spacecraft clock; the route, the
//!   recorded path projected into map metres with the Jezero equirectangular CRS
//!   ([`maps::MarsEquirectangular::jezero`]), on past the range along the record's later drives.
//! - **historic input (paper 000)**: the odometry it quotes, the fault on sol 385, no relay pass
//!   on sol 406; the radius it gives on 385 (23.5 m at the passage, 26.91 m at the fault), from
//!   which the metres driven without Visual Odometry on 383-385 are derived.
//! - **computed**: the calendar (`[calendar]`, [`sim::operations::ops_calendar`]); which idle sols it
//!   explains for today's ground practice ([`sim::operations::policy::Policy::calendar_schedule`]). An idle
//!   sol it does not explain is a **historic science stop**, typed as `drive = false` and named.
//! - **measured**: each historic drive sol's AutoNav rate, its distance over its window (every
//!   strategy drives that sol at that pace); their mean, metres over hours of the range's drives
//!   with a whole window, for the other sols.
//! - **modelling choice** (the record has no zones): narrow passages across the recorded path,
//!   by the rule of [`ImportOptions`]: one `passage_into_sol_m` into every drive sol the ground
//!   planned from a known position, at least `passage_spacing_m` apart, of clearance
//!   `passage_clearance_m`; and at a historic `NO_PATH`, a passage at the point the record
//!   stopped whose clearance is the radius paper 000 gives at the fault. A procedural map
//!   around the route.

use std::ops::RangeInclusive;

use maps::{MapAnchor, MarsEquirectangular};
use sim::Strategy;
use sim::operations::calendar::{Calendar, SolEntry};
use sim::operations::policy::{OperationsRules, Policy};
use sim::time::SolSeconds;

use crate::error::ScenarioError;
use crate::record::{RecordRange, RecordSol, TraverseLayer};

mod passages;
mod polyline;
mod scenario_file;

pub use passages::{CORRIDOR_HALF_WIDTH_M, PASSAGE_REACH_M};
pub use polyline::{along, project_onto};
use polyline::{point_at, round1};
use scenario_file::{ScenarioFile, recipe_toml};

/// What paper 000 says of a sol, where it says anything.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaperSol {
    /// Mission sol.
    pub sol: u32,
    /// The odometry it quotes for the sol, metres.
    pub odometry_m: Option<f64>,
    /// The drive ended in `NO_PATH` after that distance.
    pub no_path: bool,
    /// No relay pass carried data to Earth that sol.
    pub no_relay_pass: bool,
    /// Where in the paper.
    pub source: &'static str,
}

/// Paper 000's per-sol facts (`docs/references.md`).
pub const PAPER_000_SOLS: [PaperSol; 6] = [
    PaperSol {
        sol: 385,
        odometry_m: Some(14.0),
        no_path: true,
        no_relay_pass: false,
        source: "paper 000 Fig. 4: NO_PATH after 14 m",
    },
    PaperSol {
        sol: 386,
        odometry_m: Some(245.37),
        no_path: false,
        no_relay_pass: false,
        source: "paper 000 §8: 245.37 m on sol 386",
    },
    PaperSol {
        sol: 402,
        odometry_m: Some(183.0),
        no_path: false,
        no_relay_pass: false,
        source: "paper 000 §8: 183 m on sol 402",
    },
    PaperSol {
        sol: 404,
        odometry_m: Some(260.32),
        no_path: false,
        no_relay_pass: false,
        source: "paper 000 §8: 260.32 m on sol 404",
    },
    PaperSol {
        sol: 405,
        odometry_m: Some(268.353),
        no_path: false,
        no_relay_pass: false,
        source: "paper 000 §8: 268.353 m on sol 405",
    },
    PaperSol {
        sol: 406,
        odometry_m: None,
        no_path: false,
        no_relay_pass: true,
        source: "paper 000 §8: no communication pass to send data to Earth on 406",
    },
];

/// Paper 000 Fig. 2: sols 717-719 drove 655.8 m (the record's lengths sum to 631.89 m).
pub const PAPER_000_717_719_M: f64 = 655.8;
/// Paper 000 Fig. 2: the radius after sols 717-719, metres (0.289 m of the 655.8 m without VO).
pub const PAPER_000_717_719_NOVO_M: f64 = 0.289;
/// Paper 000 §8: the radius when sol 385 met the passage, metres.
pub const PAPER_000_385_PASSAGE_R_M: f64 = 23.5;
/// Paper 000 Fig. 4: the radius at sol 385's fault, metres.
pub const PAPER_000_385_FAULT_R_M: f64 = 26.91;

/// How a range is turned into a scenario.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportOptions {
    /// The sols.
    pub sols: RangeInclusive<u32>,
    /// Scenario name (file names).
    pub name: String,
    /// Scenario seed (also the procedural map's).
    pub seed: u64,
    /// Use paper 000's odometry where it gives one (default true); else the record's lengths.
    pub paper_odometry: bool,
    /// Route past the range's last drive, along the record's later drives, metres (default
    /// 2000: room for a faster strategy to drive on).
    pub route_beyond_m: f64,
    /// Spacing of route waypoints along the recorded path, metres (default 100).
    pub waypoint_spacing_m: f64,
    /// Map margin around the route, metres (default 300).
    pub map_margin_m: f64,
    /// A passage this far into a drive sol planned from a known position, metres (default 30:
    /// paper 000 §2, a narrow passage "had to occur early in the drive when the uncertainty
    /// remained small").
    pub passage_into_sol_m: f64,
    /// Least distance between two such passages along the route, metres (default 600, as the
    /// rapid traverse's rule).
    pub passage_spacing_m: f64,
    /// Clearance of those passages, metres (default 17: between one sol's growth at the
    /// record's ≈ 220 m per drive sol, ≈ 11 m at 5 %, and two sols', ≈ 22 m; the passages close
    /// on the second sol without a localization, as sol 385's did at 23.5 m).
    pub passage_clearance_m: f64,
    /// Rover footprint radius, metres (default 1.5).
    pub footprint_radius_m: f64,
}

impl ImportOptions {
    /// Defaults for `sols`, named `record-FIRST-LAST`, seeded with the first sol.
    #[must_use]
    pub fn new(sols: RangeInclusive<u32>) -> Self {
        Self {
            name: format!("record-{}-{}", sols.start(), sols.end()),
            seed: u64::from(*sols.start()),
            sols,
            paper_odometry: true,
            route_beyond_m: 2000.0,
            waypoint_spacing_m: 100.0,
            map_margin_m: 300.0,
            passage_into_sol_m: 30.0,
            passage_spacing_m: 600.0,
            passage_clearance_m: 17.0,
            footprint_radius_m: 1.5,
        }
    }
}

/// One sol of the imported scenario.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ImportedSol {
    /// Mission sol.
    pub sol: u32,
    /// The replay's distance, metres (0: no drive).
    pub distance_m: f64,
    /// Where it comes from.
    pub source: String,
    /// Window start and end, LMST.
    pub window: Option<(Option<String>, String)>,
    /// Metres without VO (historic input derived from paper 000's radii), if any.
    pub novo_m: Option<f64>,
    /// The drive ended in `NO_PATH`.
    pub no_path: bool,
    /// Typed `drive = false`: a historic science stop.
    pub science_stop: bool,
    /// Typed `downlink = false`: no relay pass (paper 000).
    pub no_relay_pass: bool,
    /// Why the sol has no drive (the record's idle sols), as the scenario's note says.
    pub note: String,
    /// A drive sol the ground planned from a known position (the passage rule's sols).
    pub from_fix: bool,
}

/// A scenario built from the record.
#[derive(Clone, Debug, PartialEq)]
pub struct Imported {
    /// The scenario file's text (TOML).
    pub scenario_toml: String,
    /// The zones file's text (GeoJSON, map metres).
    pub zones_geojson: String,
    /// The procedural map's recipe (TOML).
    pub recipe_toml: String,
    /// Per sol, what was imported.
    pub sols: Vec<ImportedSol>,
    /// What the record held besides plain drives, and what was done with it.
    pub findings: Vec<String>,
    /// The record's mean speed over the range's drives with a whole window, m/h: the AutoNav
    /// rate of sols without their own.
    pub drive_rate_m_per_h: f64,
    /// Route length, metres.
    pub route_length_m: f64,
    /// The route's waypoints, map metres.
    pub route_m: Vec<[f64; 2]>,
    /// The options it was imported with.
    pub options: ImportOptions,
}

/// File name of the scenario, zones and map folder for `name`.
#[must_use]
pub fn file_names(name: &str) -> (String, String, &'static str) {
    (
        format!("{name}.toml"),
        format!("{name}.zones.geojson"),
        "map",
    )
}

/// Build the scenario for `opts.sols` from `layer`.
///
/// # Errors
/// The range is outside the record or holds no drive ([`TraverseLayer::sols`]); an option is
/// out of range.
pub fn import(layer: &TraverseLayer, opts: &ImportOptions) -> Result<Imported, ScenarioError> {
    let range = layer.sols(opts.sols.clone())?;
    let first = *opts.sols.start();
    let last = *opts.sols.end();
    let findings: Vec<String> = range.findings.iter().map(ToString::to_string).collect();

    // Map placement: the range's first recorded point at a provisional map origin, then the
    // whole route shifted so the map starts `map_margin_m` west and south of it.
    let mut path_lonlat: Vec<[f64; 2]> = range
        .sols
        .iter()
        .flat_map(RecordSol::path_lonlat_deg)
        .collect();
    let first_lonlat = *path_lonlat.first().ok_or_else(|| ScenarioError::Field {
        path: layer.path.clone(),
        field: "sols".into(),
        expected: "drives with a recorded path".into(),
        got: format!("{first}-{last}"),
    })?;
    let range_len_points = path_lonlat.len();
    // The route beyond: the record's next drives.
    let (kept, _) = layer.classify(&sim::time::mars_time::MARS_2020);
    let mut beyond: Vec<[f64; 2]> = kept
        .iter()
        .filter(|(e, _)| e.sol > last)
        .flat_map(|(e, _)| e.path_lonlat_deg.iter().copied())
        .collect();
    let provisional = MarsEquirectangular::jezero(&MapAnchor {
        anchor_m: [0.0, 0.0],
        lon_deg: first_lonlat[0],
        lat_deg: first_lonlat[1],
    });
    let project = |crs: &MarsEquirectangular, pts: &[[f64; 2]]| -> Vec<[f64; 2]> {
        pts.iter().map(|p| crs.map_from_lonlat(*p)).collect()
    };
    // Cut the beyond path at route_beyond_m.
    {
        let b = project(&provisional, &beyond);
        let cum = along(&b);
        let keep = cum.partition_point(|&c| c <= opts.route_beyond_m);
        beyond.truncate(keep);
    }
    path_lonlat.extend(beyond.iter().copied());
    let raw = project(&provisional, &path_lonlat);
    let (min_x, min_y) = raw
        .iter()
        .fold((f64::MAX, f64::MAX), |(a, b), p| (a.min(p[0]), b.min(p[1])));
    let (max_x, max_y) = raw
        .iter()
        .fold((f64::MIN, f64::MIN), |(a, b), p| (a.max(p[0]), b.max(p[1])));
    let m = opts.map_margin_m;
    let anchor = MapAnchor {
        anchor_m: [round1(m - min_x), round1(m - min_y)],
        lon_deg: first_lonlat[0],
        lat_deg: first_lonlat[1],
    };
    let crs = MarsEquirectangular::jezero(&anchor);
    let path_m = project(&crs, &path_lonlat);
    let cum = along(&path_m);
    let total_m = *cum.last().unwrap_or(&0.0);
    let width_m = max_x - min_x + 2.0 * m;
    let height_m = max_y - min_y + 2.0 * m;
    let resolution = if width_m.max(height_m) <= 2000.0 {
        2.0
    } else {
        4.0
    };

    // Where each sol's recorded path starts along the route (metres).
    let mut sol_start_along = Vec::new();
    {
        let mut k = 0usize;
        for s in &range.sols {
            sol_start_along.push(cum[k.min(cum.len() - 1)]);
            k += s.path_lonlat_deg().len();
        }
        debug_assert!(k == range_len_points);
    }

    // Route waypoints every waypoint_spacing_m along the path, and its end.
    let mut waypoints: Vec<[f64; 2]> = Vec::new();
    let mut s = 0.0;
    while s < total_m {
        waypoints.push(point_at(&path_m, &cum, s).0);
        s += opts.waypoint_spacing_m;
    }
    waypoints.push(*path_m.last().unwrap_or(&[m, m]));
    let waypoints: Vec<[f64; 2]> = waypoints
        .iter()
        .map(|p| [round1(p[0]), round1(p[1])])
        .collect();

    // Per sol: distance, source, window.
    let paper = |sol: u32| {
        PAPER_000_SOLS
            .iter()
            .find(|p| p.sol == sol && opts.paper_odometry)
    };
    let in_717 = |sol: u32| (717..=719).contains(&sol) && opts.paper_odometry;
    let record_717: f64 = {
        let all = layer.sols(717..=719).ok();
        all.map_or(0.0, |r: RecordRange| {
            r.sols.iter().map(RecordSol::length_m).sum()
        })
    };
    let mut sols: Vec<ImportedSol> = Vec::new();
    for s in &range.sols {
        let rec_m = s.length_m();
        let p = paper(s.sol);
        let (distance_m, source) = match (p.and_then(|p| p.odometry_m), rec_m > 0.0) {
            (Some(d), true) => (
                d,
                format!("{} (the record: {rec_m:.2} m)", p.map_or("", |p| p.source)),
            ),
            (None, true) if in_717(s.sol) && record_717 > 0.0 => (
                (rec_m * PAPER_000_717_719_M / record_717 * 100.0).round() / 100.0,
                format!(
                    "the record's {rec_m:.2} m scaled to paper 000 Fig. 2's {PAPER_000_717_719_M} m over 717-719 (the record: {record_717:.2} m)"
                ),
            ),
            (_, true) => (
                (rec_m * 100.0).round() / 100.0,
                format!("the record ({}, M20_traverse.json length)", layer.name),
            ),
            (_, false) => (0.0, String::new()),
        };
        sols.push(ImportedSol {
            sol: s.sol,
            distance_m,
            source,
            window: s
                .window
                .map(|w| (w.start.map(SolSeconds::lmst), w.end.lmst())),
            novo_m: None,
            no_path: p.is_some_and(|p| p.no_path) && rec_m > 0.0,
            science_stop: false,
            no_relay_pass: p.is_some_and(|p| p.no_relay_pass),
            note: String::new(),
            from_fix: false,
        });
    }
    // Metres without VO: from paper 000's radii on 383-385 (historic input), on 717-719 from
    // Fig. 2's 0.289 m.
    let distances: Vec<(u32, f64)> = sols.iter().map(|x| (x.sol, x.distance_m)).collect();
    let dist = |sol: u32| distances.iter().find(|x| x.0 == sol).map_or(0.0, |x| x.1);
    if opts.paper_odometry && opts.sols.contains(&383) && opts.sols.contains(&385) {
        let before = dist(383) + dist(384);
        let novo_before = ((PAPER_000_385_PASSAGE_R_M - 0.05 * before) / 0.45).max(0.0);
        let novo_385 = ((PAPER_000_385_FAULT_R_M - PAPER_000_385_PASSAGE_R_M - 0.05 * dist(385))
            / 0.45)
            .max(0.0);
        for x in &mut sols {
            match x.sol {
                383 | 384 if before > 0.0 => {
                    x.novo_m = Some((novo_before * x.distance_m / before * 1000.0).round() / 1000.0)
                }
                385 => x.novo_m = Some((novo_385.min(x.distance_m) * 1000.0).round() / 1000.0),
                _ => {}
            }
        }
    }
    if opts.paper_odometry && (717..=719).all(|s| opts.sols.contains(&s)) {
        let total: f64 = (717..=719).map(dist).sum();
        for x in sols.iter_mut().filter(|x| (717..=719).contains(&x.sol)) {
            x.novo_m =
                Some((PAPER_000_717_719_NOVO_M * x.distance_m / total * 1000.0).round() / 1000.0);
        }
    }

    // The calendar: which idle sols it explains for today's practice.
    let rules = sim::operations::ops_calendar::TeamRules::for_mission(
        sim::time::mars_time::MARS_2020,
        2020..=2040,
    );
    let computed = rules.compute(first..=last);
    let mut science_stop = vec![false; sols.len()];
    let no_pass: Vec<bool> = sols.iter().map(|x| x.no_relay_pass).collect();
    let calendar = |stops: &[bool]| Calendar {
        sols: computed
            .iter()
            .enumerate()
            .map(|(i, c)| SolEntry {
                sol: c.sol,
                uplink: c.uplink || i == 0,
                restricted: c.restricted && (c.uplink || i == 0),
                downlink: !no_pass[i],
                downlink_lmst: None,
                drive_allowed: !stops[i],
                window: None,
                drive_rate_m_per_h: None,
                historic_planning: None,
                historic: None,
            })
            .collect(),
        drive_start: SolSeconds(0),
        drive_end: SolSeconds(1),
    };
    let policy = Policy::new(Strategy::Ground, OperationsRules::default());
    let mut schedule = policy.calendar_schedule(&calendar(&science_stop));
    // An idle sol the ground would drive is a science stop; typing one changes the plans
    // around it, so settle.
    for _ in 0..sols.len() + 1 {
        let mut changed = false;
        for (i, x) in sols.iter().enumerate() {
            if x.distance_m == 0.0 && !science_stop[i] && schedule[i].is_none() {
                science_stop[i] = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
        schedule = policy.calendar_schedule(&calendar(&science_stop));
    }
    for (i, x) in sols.iter_mut().enumerate() {
        if x.distance_m > 0.0 {
            continue;
        }
        x.science_stop = science_stop[i];
        x.note = if x.science_stop {
            "historic science stop: the record did not drive and the computed calendar does not explain it".to_owned()
        } else {
            let why = schedule[i].map_or_else(String::new, |r| r.to_string());
            format!(
                "the record did not drive; the computed calendar explains it for the ground practice: {why}"
            )
        };
        if x.no_relay_pass {
            x.note.push_str(" (no relay pass: paper 000 §8)");
        }
    }

    // Which drive sols the ground planned from a known position (the passage rule's sols).
    let cal = calendar(&science_stop);
    let mut last_drive: Option<usize> = None;
    let mut from_fix = true;
    for (i, x) in sols.iter_mut().enumerate() {
        if cal.sols[i].uplink && last_drive.is_none_or(|d| cal.data_available(d, Some(i))) {
            from_fix = true;
        }
        if x.distance_m <= 0.0 {
            continue;
        }
        x.from_fix = from_fix;
        from_fix = false;
        last_drive = Some(i);
    }
    // First placement: each sol's start where its recorded path starts, on the route.
    let route_cum = along(&waypoints);
    let sol_starts_on_route: Vec<f64> = sol_start_along
        .iter()
        .map(|&s| {
            let (p, _) = point_at(&path_m, &cum, s);
            project_onto(&waypoints, &route_cum, p)
        })
        .collect();

    // Calibrated drive rate: the record's metres over hours, drives with a whole window.
    let (mut metres, mut hours, mut n) = (0.0, 0.0, 0usize);
    for s in &range.sols {
        if let (Some(w), [d]) = (s.window, s.drives.as_slice())
            && w.start.is_some()
        {
            metres += d.length_m;
            hours += (d.sclk_end_s - d.sclk_start_s) / 3600.0;
            n += 1;
        }
    }
    let drive_rate = if hours > 0.0 {
        (metres / hours * 10.0).round() / 10.0
    } else {
        100.0
    };
    // Default window: the median start and end of the range's windows.
    let median = |mut v: Vec<i64>| -> Option<SolSeconds> {
        v.sort_unstable();
        v.get(v.len() / 2).map(|&s| SolSeconds(s))
    };
    let starts: Vec<i64> = range
        .sols
        .iter()
        .filter_map(|s| s.window.and_then(|w| w.start))
        .map(|t| t.0)
        .collect();
    let ends: Vec<i64> = range
        .sols
        .iter()
        .filter_map(|s| s.window.map(|w| w.end.0))
        .collect();
    let default_start = median(starts).unwrap_or(SolSeconds(42_000)).lmst();
    let default_end = median(ends).unwrap_or(SolSeconds(52_000)).lmst();

    let recipe = recipe_toml(opts, [width_m, height_m], resolution, &anchor, first_lonlat);
    let t = ScenarioFile {
        layer_name: &layer.name,
        opts,
        sols: &sols,
        findings: &findings,
        drive_rate: (drive_rate, metres, hours, n),
        drive_window: (default_start, default_end),
        waypoints: &waypoints,
    }
    .toml();
    let mut imported = Imported {
        scenario_toml: t,
        zones_geojson: String::new(),
        recipe_toml: recipe,
        sols,
        findings,
        drive_rate_m_per_h: drive_rate,
        route_length_m: *along(&waypoints).last().unwrap_or(&0.0),
        route_m: waypoints,
        options: opts.clone(),
    };
    imported.zones_geojson = imported.place_passages(&sol_starts_on_route).0;
    Ok(imported)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn layer() -> TraverseLayer {
        TraverseLayer::read(Path::new("../data/m20/M20_traverse.json")).expect("bundled")
    }

    /// The rapid traverse: 24 drive sols; the idle sols the calendar explains (403, 406) are
    /// not science stops, the others (381, 390-393) are.
    #[test]
    fn rapid_traverse_import() {
        let got = import(&layer(), &ImportOptions::new(379..=409)).expect("imports");
        let drove: Vec<u32> = got
            .sols
            .iter()
            .filter(|x| x.distance_m > 0.0)
            .map(|x| x.sol)
            .collect();
        assert_eq!(drove.len(), 24);
        let stops: Vec<u32> = got
            .sols
            .iter()
            .filter(|x| x.science_stop)
            .map(|x| x.sol)
            .collect();
        for x in &got.sols {
            eprintln!("{} {:.2} {} {}", x.sol, x.distance_m, x.source, x.note);
        }
        for f in &got.findings {
            eprintln!("{f}");
        }
        eprintln!(
            "rate {} route {:.0}",
            got.drive_rate_m_per_h, got.route_length_m
        );
        assert_eq!(stops, [381, 390, 391, 392, 393]);
        let at = |sol: u32| &got.sols[(sol - 379) as usize];
        assert_eq!(at(402).distance_m, 183.0);
        assert!(at(406).no_relay_pass);
        assert!(
            crate::scenario::ScenarioSpec::from_toml_str(Path::new("x.toml"), &got.scenario_toml)
                .is_ok()
        );
    }
}
