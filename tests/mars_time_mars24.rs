//! `sim::time::mars_time` and `sim::time::earth_time` against an independent implementation:
//! `peers/mars24_reference.py`, the `marstime` package's Mars24 (Allison & McEwen 2000: MSD, MTC,
//! LMST) fed Terrestrial Time from ERFA (`pyerfa`: UTC → TAI → TT, and TAI − UTC), which also
//! turns Mars 2020 SCLK readings (TT seconds since J2000) back into UTC.
//!
//! Instants: 1200 spread over the Mars 2020 mission from sol 0 to sol 1900 (2021-02-18 to
//! 2026-06), their local times following a golden-ratio sequence so every hour of the sol is
//! visited; local midnight of every 19th sol and 0.001 s, 0.5 s and 2 s either side; both sides
//! of every leap second of `earth_time::LEAP_SECONDS` (1972-01-01 only after it), and fractions
//! of a second around the last (2016-12-31T23:59:59Z .. 2017-01-01T00:00:01Z, sent as ISO
//! strings). 1969 in all. Each must agree:
//!
//! - TT − UTC exactly (it is a whole number of seconds plus 32.184 s on both sides);
//! - MSD within 1 s (|ΔMSD| × 88 775.244 s), MTC and LMST at the mission's longitude within 1 s
//!   (differences taken across the 24 h wrap-around, converted to SI seconds);
//! - `Mission::lmst` (whole seconds) within 1 s of the peer's LMST;
//! - the mission sol, except within 1 s of a sol boundary (by the peer's local MSD), where it
//!   may be one off; 2 s from a boundary both sides must name the sol before and the sol after.
//!
//! SCLK: 1000 readings generated across the mission (not the public record's: the test reads
//! nothing outside the repository) plus 8 around the 2017 leap second, each turned into UTC by
//! `utc_from_m20_sclk` and by ERFA: within 1 s. Of those 8, 3 fall inside the inserted second
//! (ERFA's 23:59:60.x), which POSIX time cannot name: `utc_from_m20_sclk` repeats 23:59:59.x
//! there, and is compared with that. The leap-second table: ERFA's (from 1972)
//! must have exactly `LEAP_SECONDS`' dates and values, and `erfa.dat` at each table date and the
//! day before must give the table's value and the previous one.
//!
//! The worst differences are printed on stderr (`--nocapture` shows them). The peer runs from
//! `peers/.venv`; without it the check is skipped with a message on stderr, unless `CI` is set
//! (`.ci/run` creates the venv), then it fails.

use crate::common;

use std::time::Duration;

use serde_json::{Value, json};
use sim::time::earth_time::{DAY_S, LEAP_SECONDS, Utc, civil_from_days, tt_minus_utc_s};
use sim::time::mars_time::{
    MARS_2020, SOL_IN_DAYS, coordinated_mars_time_h, j2000_tt_days, lmst_h, m20_sclk_from_utc,
    mars_sol_date, utc_from_m20_sclk,
};
use sim::time::{SOL_S, SolSeconds};

/// SI seconds in a sol (Allison & McEwen 2000: 88 775.244 s).
const SOL_SI_S: f64 = SOL_IN_DAYS * DAY_S;
/// Sols the spread covers from landing: the mission to mid-2026.
const MISSION_SOLS: f64 = 1900.0;
/// The golden ratio's fractional part: consecutive multiples fill [0, 1) evenly.
const GOLDEN: f64 = 0.618_033_988_749_894_9;
const SPREAD_INSTANTS: usize = 1200;
const SCLK_READINGS: usize = 1000;

/// An instant to check: where it came from (for messages), how it is sent to the peer, and the
/// `Utc` it is here.
struct Instant {
    label: String,
    sent: Value,
    utc: Utc,
}

fn instants() -> Vec<Instant> {
    let m = &MARS_2020;
    let sol_zero_start = m.utc_at(0, SolSeconds::MIDNIGHT);
    let mut out = Vec::new();
    for k in 0..SPREAD_INSTANTS {
        let sol = (MISSION_SOLS * k as f64 / SPREAD_INSTANTS as f64).floor();
        let phase = (k as f64 * GOLDEN).fract();
        let utc = sol_zero_start.plus_s((sol + phase) * SOL_SI_S);
        out.push(Instant {
            label: format!("spread {k} (sol {sol}, {:.3} of the sol)", phase),
            sent: json!(utc.0),
            utc,
        });
    }
    for sol in (0..=1900).step_by(19) {
        let midnight = m.utc_at(sol, SolSeconds::MIDNIGHT);
        for offset_s in [-2.0, -0.5, -0.001, 0.0, 0.001, 0.5, 2.0] {
            let utc = midnight.plus_s(offset_s);
            out.push(Instant {
                label: format!("sol {sol} midnight {offset_s:+} s"),
                sent: json!(utc.0),
                utc,
            });
        }
    }
    // The second before 1972-01-01 is left out: UTC had no whole-second offset then.
    for (i, &(day, _)) in LEAP_SECONDS.iter().enumerate() {
        for offset_s in [-1.0, 0.0].into_iter().skip(usize::from(i == 0)) {
            let midnight = Utc(day as f64 * DAY_S);
            out.push(Instant {
                label: format!("leap second of {midnight} {offset_s:+} s"),
                sent: json!(midnight.0 + offset_s),
                utc: midnight.plus_s(offset_s),
            });
        }
    }
    for iso in [
        "2016-12-31T23:59:59Z",
        "2016-12-31T23:59:59.5Z",
        "2016-12-31T23:59:59.999Z",
        "2017-01-01T00:00:00Z",
        "2017-01-01T00:00:00.001Z",
        "2017-01-01T00:00:00.5Z",
        "2017-01-01T00:00:01Z",
    ] {
        out.push(Instant {
            label: iso.to_string(),
            sent: json!(iso),
            utc: Utc::parse_iso(iso).expect("valid"),
        });
    }
    out
}

/// SCLK readings across the mission, and around the 2017-01-01 leap second (TT 536 500 869.184 s
/// after J2000 is 2017-01-01T00:00:00Z; the second before it is 23:59:60).
fn sclk_readings() -> Vec<f64> {
    let first = m20_sclk_from_utc(MARS_2020.landing);
    let span_s = MISSION_SOLS * SOL_SI_S;
    let mut out: Vec<f64> = (0..SCLK_READINGS)
        .map(|k| {
            let whole = (first + span_s * k as f64 / SCLK_READINGS as f64).floor();
            whole + (k as f64 * GOLDEN).fract()
        })
        .collect();
    let new_year = m20_sclk_from_utc(Utc::parse_iso("2017-01-01T00:00:00Z").expect("valid"));
    out.extend([-3.0, -1.5, -0.9, -0.5, -0.1, 0.1, 0.5, 3.0].map(|d| new_year + d));
    out
}

/// `a − b` in hours, taken across the 24 h wrap-around, into (−12, 12].
fn hours_apart(a: f64, b: f64) -> f64 {
    12.0 - (12.0 - (a - b)).rem_euclid(24.0)
}

/// Mars hours as SI seconds.
fn mars_h_as_s(h: f64) -> f64 {
    h / 24.0 * SOL_SI_S
}

fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

/// The largest difference of one quantity, and where.
#[derive(Default)]
struct Worst {
    s: f64,
    at: String,
}

impl Worst {
    fn see(&mut self, s: f64, at: &str) {
        if s.abs() > self.s.abs() || self.at.is_empty() {
            self.s = s;
            self.at = at.to_string();
        }
    }
}

#[test]
fn mars_time_matches_marstime_with_erfa_over_the_mission() {
    let instants = instants();
    let sclk = sclk_readings();
    let mut dates = Vec::new();
    for &(day, _) in &LEAP_SECONDS {
        for d in [day, day - 1] {
            let (y, m, dd) = civil_from_days(d);
            dates.push(json!([y, m, dd]));
        }
    }
    let m = &MARS_2020;
    let request = json!({
        "utc": instants.iter().map(|i| i.sent.clone()).collect::<Vec<_>>(),
        "longitude_east_deg": m.longitude_east_deg,
        "landing_utc_s": m.landing.0,
        "sclk_s": sclk,
        "dates": dates,
    });
    let Some(python) = common::peers_python(&format!(
        "the marstime/ERFA cross-check of sim::time::mars_time ({} instants, {} SCLK readings, {} \
         leap-second dates; only the unit tests of sim::time::mars_time and sim::time::earth_time ran)",
        instants.len(),
        sclk.len(),
        LEAP_SECONDS.len()
    )) else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let input = dir.path().join("request.json");
    let output = dir.path().join("mars24.json");
    std::fs::write(&input, request.to_string()).expect("write");
    let o = common::output_within(
        std::process::Command::new(&python)
            .arg(common::root().join("peers/mars24_reference.py"))
            .arg(&input)
            .arg(&output),
        Duration::from_secs(120),
    );
    assert!(
        o.status.success(),
        "{}\n(a venv made before marstime and pyerfa joined peers/requirements.txt lacks them: \
         peers/.venv/bin/pip install -r peers/requirements.txt)",
        common::stderr(&o)
    );
    let peer: Value =
        serde_json::from_slice(&std::fs::read(&output).expect("the peer wrote its output"))
            .expect("the peer writes JSON");

    // The leap-second tables: same dates, same values; erfa.dat either side of each date.
    let table: Vec<(i64, f64)> = peer["leap_table"]
        .as_array()
        .expect("leap_table")
        .iter()
        .map(|r| {
            let (y, mo) = (r[0].as_i64().expect("year"), r[1].as_u64().expect("month"));
            let day = sim::time::earth_time::days_from_civil(y, mo as u32, 1);
            (day, r[2].as_f64().expect("TAI - UTC"))
        })
        .collect();
    assert_eq!(
        table,
        LEAP_SECONDS.to_vec(),
        "ERFA's leap seconds from 1972 on (left) against earth_time::LEAP_SECONDS (right)"
    );
    let dat: Vec<f64> = serde_json::from_value(peer["dat"].clone()).expect("dat");
    assert_eq!(dat.len(), 2 * LEAP_SECONDS.len());
    for (i, &(day, tai_utc)) in LEAP_SECONDS.iter().enumerate() {
        let (on, before) = (dat[2 * i], dat[2 * i + 1]);
        let date = civil_from_days(day);
        assert_eq!(on, tai_utc, "erfa.dat on {date:?}");
        if i == 0 {
            // Before 1972 UTC ran on rubber seconds: TAI − UTC was 9.89 s, not a whole number.
            assert!(on - before > 0.0 && on - before < 1.0, "{before}");
        } else {
            assert_eq!(
                before,
                LEAP_SECONDS[i - 1].1,
                "erfa.dat the day before {date:?}"
            );
        }
    }

    // Every instant.
    let theirs = peer["instants"].as_array().expect("instants");
    assert_eq!(theirs.len(), instants.len(), "one peer result per instant");
    let mut worst_msd = Worst::default();
    let mut worst_mtc = Worst::default();
    let mut worst_lmst = Worst::default();
    let mut worst_mission_lmst = Worst::default();
    let mut worst_tt = 0.0_f64;
    let (mut sols_equal, mut sols_one_off_at_boundary) = (0, 0);
    for (i, p) in instants.iter().zip(theirs) {
        let at = &i.label;
        let t = i.utc;
        assert!(
            (f(p, "utc_s") - t.0).abs() < 1e-6,
            "{at}: the peer read {} s",
            f(p, "utc_s")
        );
        let d_tt = tt_minus_utc_s(t) - f(p, "tt_minus_utc_s");
        assert!(d_tt.abs() < 1e-9, "{at}: TT − UTC differs by {d_tt} s");
        worst_tt = worst_tt.max(d_tt.abs());
        let d_days = j2000_tt_days(t) - f(p, "j2000_tt_days");
        assert!(d_days.abs() * DAY_S < 1e-3, "{at}: Δt_J2000 {d_days} days");

        let d_msd_s = (mars_sol_date(t) - f(p, "msd")) * SOL_SI_S;
        assert!(d_msd_s.abs() <= 1.0, "{at}: MSD differs by {d_msd_s} s");
        worst_msd.see(d_msd_s, at);
        let d_mtc_s = mars_h_as_s(hours_apart(coordinated_mars_time_h(t), f(p, "mtc_h")));
        assert!(d_mtc_s.abs() <= 1.0, "{at}: MTC differs by {d_mtc_s} s");
        worst_mtc.see(d_mtc_s, at);
        let d_lmst_s = mars_h_as_s(hours_apart(lmst_h(t, m.longitude_east_deg), f(p, "lmst_h")));
        assert!(d_lmst_s.abs() <= 1.0, "{at}: LMST differs by {d_lmst_s} s");
        worst_lmst.see(d_lmst_s, at);
        // Mission::lmst counts whole seconds of a SOL_S-second sol.
        let peer_sol_s = f(p, "lmst_h") / 24.0 * f64::from(SOL_S);
        let d_mission_s = {
            let d = m.lmst(t).0 as f64 - peer_sol_s;
            let half = f64::from(SOL_S) / 2.0;
            half - (half - d).rem_euclid(f64::from(SOL_S))
        };
        assert!(
            d_mission_s.abs() <= 1.0,
            "{at}: Mission::lmst {:?} against the peer's {peer_sol_s} s",
            m.lmst(t)
        );
        worst_mission_lmst.see(d_mission_s, at);

        let ours = m.sol_of(t);
        let peer_sol = p["sol"].as_i64().expect("sol");
        let local = f(p, "local_msd");
        let from_boundary_s = (local - local.round()).abs() * SOL_SI_S;
        if ours == peer_sol {
            sols_equal += 1;
        } else {
            assert!(
                from_boundary_s <= 1.0 && (ours - peer_sol).abs() == 1,
                "{at}: sol {ours} here, {peer_sol} in the peer, {from_boundary_s} s from a sol \
                 boundary"
            );
            sols_one_off_at_boundary += 1;
        }
        if let Some(rest) = at.strip_prefix("sol ") {
            let sol: i64 = rest
                .split(' ')
                .next()
                .and_then(|s| s.parse().ok())
                .expect("sol");
            if at.ends_with(" -2 s") {
                assert_eq!((ours, peer_sol), (sol - 1, sol - 1), "{at}");
            } else if at.ends_with(" +2 s") {
                assert_eq!((ours, peer_sol), (sol, sol), "{at}");
            }
        }
    }

    // SCLK → UTC.
    let theirs = peer["sclk"].as_array().expect("sclk");
    assert_eq!(theirs.len(), sclk.len(), "one peer result per SCLK reading");
    let mut worst_sclk = Worst::default();
    let mut in_leap_second = 0;
    for (&s, p) in sclk.iter().zip(theirs) {
        assert_eq!(f(p, "sclk_s"), s);
        let ours = utc_from_m20_sclk(s);
        // Inside an inserted leap second (ERFA's 23:59:60.x) POSIX time has no name for the
        // instant; `utc_from_m20_sclk` repeats 23:59:59.x, the peer's utc_s runs on to 00:00:00.x.
        let repeat_s = if p["in_leap_second"].as_bool().expect("in_leap_second") {
            in_leap_second += 1;
            1.0
        } else {
            0.0
        };
        let d_s = ours.0 - (f(p, "utc_s") - repeat_s);
        let at = format!("SCLK {s} ({ours} here, {} in ERFA)", p["utc"]);
        assert!(d_s.abs() <= 1.0, "{at}: {d_s} s apart");
        worst_sclk.see(d_s, &at);
    }
    assert_eq!(in_leap_second, 3, "readings in 2016-12-31T23:59:60");

    eprintln!(
        "mars_time against marstime {} with ERFA {} (pyerfa {}): {} instants, {} SCLK \
         readings\n  max |ΔTT−UTC| {:.1e} s\n  worst ΔMSD {:+.2e} s ({})\n  worst ΔMTC {:+.2e} s \
         ({})\n  worst ΔLMST {:+.2e} s ({})\n  worst ΔMission::lmst {:+.3} s ({})\n  sols: {} \
         equal, {} one off within 1 s of a sol boundary\n  worst ΔSCLK→UTC {:+.2e} s ({}; {} \
         readings in a leap second)",
        peer["versions"]["marstime"].as_str().unwrap_or("?"),
        peer["versions"]["erfa"].as_str().unwrap_or("?"),
        peer["versions"]["pyerfa"].as_str().unwrap_or("?"),
        instants.len(),
        sclk.len(),
        worst_tt,
        worst_msd.s,
        worst_msd.at,
        worst_mtc.s,
        worst_mtc.at,
        worst_lmst.s,
        worst_lmst.at,
        worst_mission_lmst.s,
        worst_mission_lmst.at,
        sols_equal,
        sols_one_off_at_boundary,
        worst_sclk.s,
        worst_sclk.at,
        in_leap_second,
    );
}
