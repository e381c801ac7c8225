//! The public record of Perseverance's drives: NASA's Mars 2020 MMGIS layers `M20_traverse.json`
//! (one LineString per drive: its filed sol, Rover Motion Counters, length, spacecraft clock at
//! start and end, path in lon/lat) and `M20_waypoints.json` (one Point per localized end of
//! drive). A snapshot is bundled in `data/m20/` with its source and date.
//!
//! [`TraverseLayer::read`] reads the traverse layer strictly (a file that is not such a layer is
//! one error naming the feature and the field); [`TraverseLayer::sols`] turns a sol range into
//! one [`RecordSol`] per sol, handling what the layer holds besides plain drives
//! ([`RecordFinding`]):
//!
//! - **re-filed drives**: an entry that starts at the same Rover Motion Counter as an earlier
//!   one is that drive filed again (sol 381's entry is sol 380's drive, 26.9 h long; sol 668's is
//!   sol 667's). The first filing is kept.
//! - **entries spanning idle sols**: an entry whose clock starts on an earlier sol than it ends
//!   (sol 394's starts at the end of sol 389's drive, 100 h before) gives the drive's end but not
//!   its start: the window's start is unknown ([`DriveWindow::start`] is `None`).
//! - **off-sol entries**: a drive whose clock ends on another sol than the one it is filed
//!   under (none in the bundled snapshot once re-filings are set aside).
//!
//! Mars time comes from [`sim::time::mars_time`]: the clock is read as Terrestrial Time seconds since
//! J2000 ([`sim::time::mars_time::utc_from_m20_sclk`]), sols and LMST at the landing site
//! ([`sim::time::mars_time::MARS_2020`]).

use std::collections::BTreeMap;
use std::ops::RangeInclusive;
use std::path::PathBuf;

use sim::time::mars_time::{MARS_2020, Mission, utc_from_m20_sclk};
use sim::time::{SOL_S, SolSeconds};

use crate::error::ScenarioError;

mod layer_file;

/// Largest layer file read, bytes (the bundled traverse through sol 1840 is 3.5 MB).
pub const MAX_LAYER_BYTES: u64 = 256 << 20;

/// An entry from the same start counter as an earlier one, at most this much longer, is that
/// drive filed again, metres (or [`REFILED_TOLERANCE_FRACTION`] of it, if more): the re-filings
/// of the bundled snapshot differ by 0.09-0.43 m (sols 359, 381, 668), the cumulative entries
/// by 82-314 m (351, 352).
pub const REFILED_TOLERANCE_M: f64 = 2.0;
/// See [`REFILED_TOLERANCE_M`]: 5 % of the earlier entry's length.
pub const REFILED_TOLERANCE_FRACTION: f64 = 0.05;

/// One entry of the traverse layer, as filed.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordEntry {
    /// Index of the feature in the layer.
    pub index: usize,
    /// The sol the drive is filed under.
    pub sol: u32,
    /// Rover Motion Counter at the start, `SITE_DRIVE`.
    pub from_rmc: String,
    /// Rover Motion Counter at the end.
    pub to_rmc: String,
    /// Localized path length, metres.
    pub length_m: f64,
    /// Spacecraft clock at the start, s.
    pub sclk_start_s: f64,
    /// Spacecraft clock at the end, s.
    pub sclk_end_s: f64,
    /// The path, `[lon, lat]` in planetocentric degrees, east-positive.
    pub path_lonlat_deg: Vec<[f64; 2]>,
}

/// The traverse layer.
#[derive(Clone, Debug, PartialEq)]
pub struct TraverseLayer {
    /// The file read.
    pub path: PathBuf,
    /// The layer's `name` (the MMGIS layer and its snapshot, e.g. `M20_Traverse_Path_tosol1840`).
    pub name: String,
    /// Its entries in file order.
    pub entries: Vec<RecordEntry>,
}

/// A drive's window of local mean solar time on its sol.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct DriveWindow {
    /// Start, LMST; `None` when the entry's clock starts on an earlier sol (an entry spanning
    /// idle sols: its start is not the drive's).
    pub start: Option<SolSeconds>,
    /// End, LMST.
    pub end: SolSeconds,
}

/// What the record says of one sol of a range.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordSol {
    /// Mission sol.
    pub sol: u32,
    /// The drives filed under it (after re-filings are set aside), in clock order.
    pub drives: Vec<RecordEntry>,
    /// The sol's drive window: from the first drive's start to the last's end.
    pub window: Option<DriveWindow>,
}

impl RecordSol {
    /// Metres the record drove on the sol (sum of its drives' lengths).
    #[must_use]
    pub fn length_m(&self) -> f64 {
        self.drives.iter().map(|d| d.length_m).sum()
    }

    /// The sol's path, `[lon, lat]` degrees, its drives' paths joined.
    #[must_use]
    pub fn path_lonlat_deg(&self) -> Vec<[f64; 2]> {
        self.drives
            .iter()
            .flat_map(|d| d.path_lonlat_deg.iter().copied())
            .collect()
    }
}

/// Something in the layer that is not a plain drive, and what was done with it.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum RecordFinding {
    /// An entry that starts at the same Rover Motion Counter as an earlier entry: that drive
    /// filed again. Set aside.
    Refiled {
        /// Sol it is filed under.
        sol: u32,
        /// Sol of the first filing, kept.
        first_sol: u32,
        /// The shared start counter.
        from_rmc: String,
        /// Its clock span, hours.
        span_h: f64,
    },
    /// An entry that starts at the same Rover Motion Counter as an earlier one and runs further:
    /// the earlier drive and this sol's, filed as one. The sol keeps what follows the earlier
    /// entry's end (length and path).
    Cumulative {
        /// Sol it is filed under.
        sol: u32,
        /// Sol of the earlier entry.
        first_sol: u32,
        /// The shared start counter.
        from_rmc: String,
        /// The entry's length, metres.
        total_m: f64,
        /// What the sol drove itself: the length beyond the earlier entry's, metres.
        own_m: f64,
    },
    /// An entry whose clock starts on an earlier sol than it ends: its end is the drive's, its
    /// start is not (the window's start is left unknown).
    SpansIdleSols {
        /// Sol it is filed under.
        sol: u32,
        /// Sol its clock starts on.
        clock_start_sol: i64,
        /// Its clock span, hours.
        span_h: f64,
    },
    /// A drive whose clock ends on another sol than it is filed under. Kept under its filed sol.
    OffSol {
        /// Sol it is filed under.
        sol: u32,
        /// Sol its clock ends on.
        clock_sol: i64,
    },
}

impl std::fmt::Display for RecordFinding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RecordFinding::Refiled {
                sol,
                first_sol,
                from_rmc,
                span_h,
            } => write!(
                f,
                "sol {sol}: its entry starts at RMC {from_rmc} like sol {first_sol}'s and spans {span_h:.1} h: sol {first_sol}'s drive filed again, set aside"
            ),
            RecordFinding::Cumulative {
                sol,
                first_sol,
                from_rmc,
                total_m,
                own_m,
            } => write!(
                f,
                "sol {sol}: its entry starts at RMC {from_rmc} like sol {first_sol}'s and runs {total_m:.2} m: both drives filed as one; sol {sol} drove the last {own_m:.2} m"
            ),
            RecordFinding::SpansIdleSols {
                sol,
                clock_start_sol,
                span_h,
            } => write!(
                f,
                "sol {sol}: its entry's clock starts on sol {clock_start_sol}, {span_h:.1} h before it ends: the end is the drive's, the start is not (window start unknown)"
            ),
            RecordFinding::OffSol { sol, clock_sol } => write!(
                f,
                "sol {sol}: the drive's clock ends on sol {clock_sol}; kept under sol {sol}"
            ),
        }
    }
}

/// A sol range of the record.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordRange {
    /// One entry per sol of the range, in order.
    pub sols: Vec<RecordSol>,
    /// What was set aside or left unknown, in sol order.
    pub findings: Vec<RecordFinding>,
}

impl TraverseLayer {
    /// The sols the layer files drives under, lowest and highest.
    #[must_use]
    pub fn sol_span(&self) -> (u32, u32) {
        let lo = self.entries.iter().map(|e| e.sol).min().unwrap_or(0);
        let hi = self.entries.iter().map(|e| e.sol).max().unwrap_or(0);
        (lo, hi)
    }

    /// Every entry classified: the drives kept (re-filings set aside) and the findings, over the
    /// whole layer. `mission` gives sols and LMST.
    #[must_use]
    pub fn classify(
        &self,
        mission: &Mission,
    ) -> (Vec<(RecordEntry, DriveWindow)>, Vec<RecordFinding>) {
        let mut order: Vec<&RecordEntry> = self.entries.iter().collect();
        order.sort_by(|a, b| {
            (a.sol, a.sclk_end_s, a.index)
                .partial_cmp(&(b.sol, b.sclk_end_s, b.index))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        // The latest kept entry from each start counter: its sol, length and end point.
        let mut by_rmc: BTreeMap<&str, (u32, f64, [f64; 2])> = BTreeMap::new();
        let mut kept = Vec::new();
        let mut findings = Vec::new();
        for e in order {
            let span_h = (e.sclk_end_s - e.sclk_start_s) / 3600.0;
            let mut e = e.clone();
            if let Some(&(first_sol, first_len, first_end)) = by_rmc.get(e.from_rmc.as_str()) {
                let own_m = e.length_m - first_len;
                if own_m <= REFILED_TOLERANCE_M.max(REFILED_TOLERANCE_FRACTION * first_len) {
                    findings.push(RecordFinding::Refiled {
                        sol: e.sol,
                        first_sol,
                        from_rmc: e.from_rmc.clone(),
                        span_h,
                    });
                    continue;
                }
                // A cumulative entry: the sol's own drive is what follows the earlier end.
                findings.push(RecordFinding::Cumulative {
                    sol: e.sol,
                    first_sol,
                    from_rmc: e.from_rmc.clone(),
                    total_m: e.length_m,
                    own_m,
                });
                let nearest = e
                    .path_lonlat_deg
                    .iter()
                    .enumerate()
                    .min_by(|a, b| {
                        let d = |p: &[f64; 2]| {
                            (p[0] - first_end[0]).powi(2) + (p[1] - first_end[1]).powi(2)
                        };
                        d(a.1).total_cmp(&d(b.1))
                    })
                    .map_or(0, |(k, _)| k);
                e.path_lonlat_deg.drain(..nearest);
                by_rmc.insert(
                    by_rmc
                        .get_key_value(e.from_rmc.as_str())
                        .map_or("", |(k, _)| k),
                    (
                        e.sol,
                        e.length_m,
                        *e.path_lonlat_deg.last().unwrap_or(&first_end),
                    ),
                );
                e.length_m = own_m;
            } else {
                by_rmc.insert(
                    self.entries[e.index].from_rmc.as_str(),
                    (
                        e.sol,
                        e.length_m,
                        *e.path_lonlat_deg.last().unwrap_or(&[0.0, 0.0]),
                    ),
                );
            }
            let e = &e;
            let start = utc_from_m20_sclk(e.sclk_start_s);
            let end = utc_from_m20_sclk(e.sclk_end_s);
            let (start_sol, end_sol) = (mission.sol_of(start), mission.sol_of(end));
            if end_sol != i64::from(e.sol) {
                findings.push(RecordFinding::OffSol {
                    sol: e.sol,
                    clock_sol: end_sol,
                });
            }
            let spans = start_sol < end_sol || e.sclk_end_s - e.sclk_start_s > f64::from(SOL_S);
            if spans {
                findings.push(RecordFinding::SpansIdleSols {
                    sol: e.sol,
                    clock_start_sol: start_sol,
                    span_h,
                });
            }
            kept.push((
                e.clone(),
                DriveWindow {
                    start: (!spans).then(|| mission.lmst(start)),
                    end: mission.lmst(end),
                },
            ));
        }
        (kept, findings)
    }

    /// One [`RecordSol`] per sol of `range`, with the findings that concern it.
    ///
    /// # Errors
    /// The range is empty or reversed, lies outside the sols the layer covers, or holds no drive.
    pub fn sols(&self, range: RangeInclusive<u32>) -> Result<RecordRange, ScenarioError> {
        let (lo, hi) = self.sol_span();
        let shown = format!("{}-{}", range.start(), range.end());
        if range.is_empty() {
            return Err(ScenarioError::Field {
                path: self.path.clone(),
                field: "sols".into(),
                expected: "a range FIRST-LAST with FIRST ≤ LAST".into(),
                got: shown,
            });
        }
        if *range.start() < lo || *range.end() > hi {
            return Err(ScenarioError::Field {
                path: self.path.clone(),
                field: "sols".into(),
                expected: format!("a range within the sols this record covers, {lo}-{hi}"),
                got: shown,
            });
        }
        let (kept, all_findings) = self.classify(&MARS_2020);
        let mut sols: Vec<RecordSol> = range
            .clone()
            .map(|sol| RecordSol {
                sol,
                drives: Vec::new(),
                window: None,
            })
            .collect();
        for (e, w) in kept.into_iter().filter(|(e, _)| range.contains(&e.sol)) {
            let s = &mut sols[(e.sol - range.start()) as usize];
            s.window = Some(match s.window {
                None => w,
                Some(prev) => DriveWindow {
                    start: prev.start,
                    end: w.end,
                },
            });
            s.drives.push(e);
        }
        if sols.iter().all(|s| s.drives.is_empty()) {
            return Err(ScenarioError::Field {
                path: self.path.clone(),
                field: "sols".into(),
                expected: "a range in which the rover drove at least once".into(),
                got: format!("{shown} (no drive filed under these sols)"),
            });
        }
        let findings = all_findings
            .into_iter()
            .filter(|f| {
                let sol = match f {
                    RecordFinding::Refiled { sol, .. }
                    | RecordFinding::Cumulative { sol, .. }
                    | RecordFinding::SpansIdleSols { sol, .. }
                    | RecordFinding::OffSol { sol, .. } => *sol,
                };
                range.contains(&sol)
            })
            .collect();
        Ok(RecordRange { sols, findings })
    }
}

/// Parse a sol range `FIRST-LAST` (or one sol `N`).
///
/// # Errors
/// A message saying what was expected.
pub fn parse_sol_range(text: &str) -> Result<RangeInclusive<u32>, String> {
    let expected = || {
        format!(
            "expected a sol range FIRST-LAST such as 379-409 (or one sol), got {:?}",
            maps::input_file::printable(text)
        )
    };
    let parse = |s: &str| -> Result<u32, String> {
        if s.is_empty() || s.len() > 6 || !s.bytes().all(|b| b.is_ascii_digit()) {
            return Err(expected());
        }
        s.parse().map_err(|_| expected())
    };
    let (a, b) = match text.split_once('-') {
        Some((a, b)) => (parse(a)?, parse(b)?),
        None => {
            let n = parse(text)?;
            (n, n)
        }
    };
    if a > b {
        return Err(expected());
    }
    Ok(a..=b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn layer(features: &str) -> Result<TraverseLayer, ScenarioError> {
        TraverseLayer::from_json_str(
            Path::new("t.json"),
            &format!(r#"{{"type":"FeatureCollection","name":"t","features":[{features}]}}"#),
        )
    }

    fn drive(sol: u32, from: &str, to: &str, start: f64, end: f64) -> String {
        format!(
            r#"{{"type":"Feature","properties":{{"sol":{sol},"fromRMC":"{from}","toRMC":"{to}","length":10.5,"SCLK_START":{start},"SCLK_END":{end}}},"geometry":{{"type":"LineString","coordinates":[[77.45,18.44,-2569.9],[77.451,18.441,-2569.8]]}}}}"#
        )
    }

    /// Sols 380 and 381 of the bundled record: the same drive filed twice.
    #[test]
    fn refiled_drive_is_set_aside() {
        let l = layer(
            &[
                drive(380, "11_1110", "11_2472", 700_671_634.0, 700_683_201.0),
                drive(381, "11_1110", "12_0", 700_671_634.0, 700_768_497.0),
            ]
            .join(","),
        )
        .expect("a layer");
        let r = l.sols(380..=381).expect("drives");
        assert_eq!(r.sols[0].drives.len(), 1);
        assert!(r.sols[1].drives.is_empty());
        assert!(matches!(
            r.findings[0],
            RecordFinding::Refiled {
                sol: 381,
                first_sol: 380,
                ..
            }
        ));
        let w = r.sols[0].window.expect("a window");
        // 11:33 to 14:41 LMST (the clock puts it on sol 380).
        assert_eq!(w.start.map(SolSeconds::lmst).as_deref(), Some("11:33"));
        assert_eq!(w.end.lmst(), "14:41");
    }

    #[test]
    fn not_a_layer_names_the_field() {
        let e = layer(
            &drive(380, "11_1110", "11_2472", 700_671_634.0, 700_683_201.0)
                .replace("\"length\":10.5", "\"length\":\"far\""),
        )
        .expect_err("an error");
        assert_eq!(
            e.to_string(),
            r#"t.json: features[0].properties.length: expected a path length, metres ≥ 0, got "far""#
        );
        let e = TraverseLayer::from_json_str(Path::new("z.json"), r#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"kind":"keep_out"},"geometry":null}]}"#).expect_err("an error");
        assert!(
            e.to_string()
                .starts_with("z.json: features[0].properties.sol: expected a sol number"),
            "{e}"
        );
        let l = layer(&drive(
            380,
            "11_1110",
            "11_2472",
            700_671_634.0,
            700_683_201.0,
        ))
        .expect("a layer");
        assert!(
            l.sols(500..=510)
                .expect_err("an error")
                .to_string()
                .contains("within the sols this record covers, 380-380")
        );
    }

    #[test]
    fn sol_ranges() {
        assert_eq!(parse_sol_range("379-409"), Ok(379..=409));
        assert_eq!(parse_sol_range("717"), Ok(717..=717));
        for bad in [
            "409-379",
            "",
            "-3",
            "3-",
            "a-b",
            "1-2-3",
            "+1-2",
            "9999999-1",
        ] {
            assert!(parse_sol_range(bad).is_err(), "{bad}");
        }
    }

    /// The bundled snapshot: every drive lands on its filed sol once the three re-filings (359,
    /// 381, 668) are set aside and the two cumulative entries (351, 352) cut; the entries spanning idle sols are listed.
    #[test]
    fn bundled_record_lands_on_its_sols() {
        let l = TraverseLayer::read(Path::new("../data/m20/M20_traverse.json")).expect("bundled");
        assert_eq!(l.entries.len(), 522);
        let (kept, findings) = l.classify(&MARS_2020);
        assert_eq!(kept.len(), 519);
        let refiled: Vec<u32> = findings
            .iter()
            .filter_map(|f| match f {
                RecordFinding::Refiled { sol, .. } => Some(*sol),
                _ => None,
            })
            .collect();
        assert_eq!(refiled, [359, 381, 668]);
        let cumulative: Vec<(u32, f64)> = findings
            .iter()
            .filter_map(|f| match f {
                RecordFinding::Cumulative { sol, own_m, .. } => {
                    Some((*sol, (own_m * 100.0).round() / 100.0))
                }
                _ => None,
            })
            .collect();
        assert_eq!(cumulative, [(351, 313.8), (352, 82.35)]);
        let off: Vec<&RecordFinding> = findings
            .iter()
            .filter(|f| matches!(f, RecordFinding::OffSol { .. }))
            .collect();
        assert!(off.is_empty(), "{off:?}");
        for f in &findings {
            eprintln!("{f}");
        }
        let r = l.sols(379..=409).expect("drives");
        let drove: Vec<u32> = r
            .sols
            .iter()
            .filter(|s| !s.drives.is_empty())
            .map(|s| s.sol)
            .collect();
        assert_eq!(drove.len(), 24);
        for idle in [381, 390, 391, 392, 393, 403, 406] {
            assert!(!drove.contains(&idle), "{idle}");
        }
    }
}
