//! Mars time: UTC ↔ Mars Sol Date ↔ Coordinated Mars Time ↔ local mean solar time, mission sols,
//! and the Mars 2020 spacecraft clock.
//!
//! The Mars24 algorithm of Allison & McEwen (2000), "A post-Pathfinder evaluation of
//! areocentric solar coordinates with improved timing recipes for Mars seasonal/diurnal climate
//! studies", Planet. Space Sci. 48, 215-235, with that paper's constants:
//!
//! ```text
//! Δt_J2000 = JD_TT − 2451545.0                        (days of Terrestrial Time)
//! MSD      = (Δt_J2000 − 4.5) / 1.027491252 + 44796.0 − 0.00096
//! MTC      = 24 h × frac(MSD)                          (mean solar time at the prime meridian)
//! LMST     = MTC + λ_east × 24 h / 360°
//! ```
//!
//! A mission's sol `n` is the `n`-th local mean solar day since the one it landed in
//! ([`Mission::sol_of`]): sol 0 is the landing sol, sols start at local midnight at the mission's
//! reference longitude. Everything here is checked against an independent implementation (the
//! `marstime` package fed TT from ERFA) over 1000+ instants in `tests/mars_time_mars24.rs`, and
//! every drive of the public record lands on its filed sol (`study::record`'s unit test
//! `bundled_record_lands_on_its_sols`).
//!
//! The Mars24 page's worked examples (unit tests here) use Allison's later constants,
//! 1.0274912517 d and 0.0009626 sol; the paper's, kept here, give times 0.23 s later in 2000,
//! 0.19 s later in 2004, and within 0.04 s of them over the Mars 2020 mission (2021-2026).
//!
//! ## References
//!
//! - M. Allison and M. McEwen (2000), Planet. Space Sci. 48, 215-235, eq. 32 (above).
//! - NASA GISS, "Mars24 Sunclock — Algorithm and Worked Examples",
//!   <https://www.giss.nasa.gov/tools/mars24/help/algorithm.html>: examples A and B.

use crate::time::earth_time::{DAY_S, Utc, tt_minus_utc_s};
use crate::time::{SOL_S, SolSeconds};

/// J2000 (2000-01-01T12:00:00 TT) as seconds of TT on the POSIX count: JD 2451545.0 −
/// JD 2440587.5 (the Unix epoch) = 10957.5 days.
const J2000_TT_UNIX_S: f64 = (JD_J2000 - JD_UNIX_EPOCH) * DAY_S;
/// Julian Date of 1970-01-01T00:00:00 (the Unix epoch).
const JD_UNIX_EPOCH: f64 = 2_440_587.5;
/// Julian Date of the J2000 epoch, 2000-01-01T12:00:00 TT.
const JD_J2000: f64 = 2_451_545.0;
/// Allison & McEwen (2000) eq. 32: the length of a mean solar day on Mars, Earth days.
pub const SOL_IN_DAYS: f64 = 1.027_491_252;

/// Days of Terrestrial Time since J2000 (Δt_J2000) at a UTC instant.
#[must_use]
pub fn j2000_tt_days(t: Utc) -> f64 {
    // Seconds first, days last: through a Julian Date of 2.4e6 days the f64 keeps 4e-5 s.
    (t.0 + tt_minus_utc_s(t) - J2000_TT_UNIX_S) / DAY_S
}

/// The UTC instant `days` of Terrestrial Time after J2000 (the inverse of [`j2000_tt_days`]).
#[must_use]
pub fn utc_from_j2000_tt_days(days: f64) -> Utc {
    let tt_unix = days * DAY_S + J2000_TT_UNIX_S;
    // TT − UTC changes by a second at a leap second: two rounds settle it.
    let mut t = Utc(tt_unix - 69.184);
    for _ in 0..2 {
        t = Utc(tt_unix - tt_minus_utc_s(t));
    }
    t
}

/// The Mars Sol Date at a UTC instant (Allison & McEwen 2000, eq. 32).
#[must_use]
pub fn mars_sol_date(t: Utc) -> f64 {
    (j2000_tt_days(t) - 4.5) / SOL_IN_DAYS + 44_796.0 - 0.000_96
}

/// The UTC instant of a Mars Sol Date.
#[must_use]
pub fn utc_from_mars_sol_date(msd: f64) -> Utc {
    utc_from_j2000_tt_days((msd - 44_796.0 + 0.000_96) * SOL_IN_DAYS + 4.5)
}

/// Coordinated Mars Time (mean solar time at the prime meridian), hours in [0, 24).
#[must_use]
pub fn coordinated_mars_time_h(t: Utc) -> f64 {
    24.0 * mars_sol_date(t).rem_euclid(1.0)
}

/// Local mean solar time at east longitude `longitude_east_deg`, hours in [0, 24).
#[must_use]
pub fn lmst_h(t: Utc, longitude_east_deg: f64) -> f64 {
    24.0 * (mars_sol_date(t) + longitude_east_deg / 360.0).rem_euclid(1.0)
}

/// A rover mission on the surface: where its sols are counted from.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Mission {
    /// Mission name.
    pub name: &'static str,
    /// An instant in the landing sol (sol 0).
    pub landing: Utc,
    /// The longitude its local time is kept at, degrees east.
    pub longitude_east_deg: f64,
}

/// Mars 2020 (Perseverance). Touchdown at Jezero crater on 2021-02-18, 20:55 UTC as received on
/// Earth, 20:44 UTC at Mars (one-way light time 11 min): 15:53 LMST on sol 0. Local time is kept
/// at the landing site, 77.45089° E (the first point of the public traverse record,
/// `data/m20/M20_traverse.json`). Only the sol the landing falls in matters, hours from either
/// midnight.
pub const MARS_2020: Mission = Mission {
    name: "Mars 2020",
    landing: Utc(1_613_681_040.0), // 2021-02-18T20:44:00Z
    longitude_east_deg: 77.450_885_73,
};

impl Mission {
    /// Local Mars Sol Date: the MSD shifted to the mission's longitude, so that its integer part
    /// changes at local midnight.
    #[must_use]
    pub fn local_sol_date(&self, t: Utc) -> f64 {
        mars_sol_date(t) + self.longitude_east_deg / 360.0
    }

    /// The local Mars Sol Date at the start of sol 0.
    fn sol_zero(&self) -> f64 {
        self.local_sol_date(self.landing).floor()
    }

    /// Sols since landing at `t` with the fraction of the sol elapsed (sol 3.5 is noon of sol 3).
    #[must_use]
    pub fn sols_since_landing(&self, t: Utc) -> f64 {
        self.local_sol_date(t) - self.sol_zero()
    }

    /// The mission sol `t` falls in (negative before landing).
    #[must_use]
    pub fn sol_of(&self, t: Utc) -> i64 {
        self.sols_since_landing(t).floor() as i64
    }

    /// The local mean solar time of `t`, as seconds after local midnight of its sol (a sol of
    /// [`SOL_S`] s, as `sim::time`).
    #[must_use]
    pub fn lmst(&self, t: Utc) -> SolSeconds {
        let fraction = self.sols_since_landing(t).rem_euclid(1.0);
        SolSeconds((fraction * f64::from(SOL_S)).round() as i64)
    }

    /// The UTC instant of LMST `at` on mission sol `sol`.
    #[must_use]
    pub fn utc_at(&self, sol: i64, at: SolSeconds) -> Utc {
        let local = self.sol_zero() + sol as f64 + at.0 as f64 / f64::from(SOL_S);
        utc_from_mars_sol_date(local - self.longitude_east_deg / 360.0)
    }
}

/// The J2000 epoch, 2000-01-01T12:00:00 TT = 11:58:55.816 UTC, as a UTC instant.
pub const J2000_UTC: Utc = Utc(946_727_935.816);

/// The UTC instant of a Mars 2020 spacecraft clock reading (the `SCLK_START` / `SCLK_END` of the
/// public traverse record), read as seconds of Terrestrial Time since J2000. That reading puts
/// every drive of sols 379-409 and 717-719 on its filed sol, starting 11:30-12:55 LMST
/// (`data/m20/README.md`). The clock's drift against that reading is not modelled: the record
/// gives whole seconds, the windows are used to the Mars minute, and the sols are checked.
#[must_use]
pub fn utc_from_m20_sclk(sclk_s: f64) -> Utc {
    utc_from_j2000_tt_days(sclk_s / DAY_S)
}

/// The Mars 2020 spacecraft clock reading of a UTC instant (the inverse of
/// [`utc_from_m20_sclk`]).
#[must_use]
pub fn m20_sclk_from_utc(t: Utc) -> f64 {
    j2000_tt_days(t) * DAY_S
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The MSD of the Mars24 page below: its later constants (1.0274912517 d and 0.0009626 sol,
    /// Allison's revisions after the paper) where this module keeps the paper's (1.027491252 d,
    /// 0.00096 sol). The two differ by (Δt_J2000 − 4.5) × 2.84e-10 − 2.6e-6 sol: 0.23 s in 2000,
    /// 0.19 s in 2004, under 0.04 s over the Mars 2020 mission (2021-2026).
    fn msd_mars24_page(j2000_tt_days: f64) -> f64 {
        (j2000_tt_days - 4.5) / 1.027_491_251_7 + 44_796.0 - 0.000_962_6
    }

    /// SI seconds in a Mars hour.
    const MARS_HOUR_S: f64 = SOL_IN_DAYS * DAY_S / 24.0;

    /// Checks one worked example of NASA GISS, "Mars24 Sunclock — Algorithm and Worked
    /// Examples" (<https://www.giss.nasa.gov/tools/mars24/help/algorithm.html>, section III),
    /// published to 6 decimals of days (example A) or 5 (example B) and 5 decimals of hours:
    ///
    /// - our Δt_J2000 (steps A-1..A-6: UTC, TT − UTC = 64.184 s) is the published one to its
    ///   last digit;
    /// - the page's own constants ([`msd_mars24_page`]) applied to our Δt_J2000 give the
    ///   published MTC (C-2) and LMST (C-3) to their last digit: the page is reproduced;
    /// - our MTC and LMST (the paper's constants) are within 0.25 s of the published ones: the
    ///   difference the constants explain, `shift_s`, and the published rounding (0.02 s).
    fn check_worked_example(
        t: Utc,
        published_dt_days: f64,
        dt_decimals: i32,
        longitude_east_deg: f64,
        published_mtc_h: f64,
        published_lmst_h: f64,
        shift_s: f64,
    ) {
        let dt = j2000_tt_days(t);
        let half_unit = |decimals: i32| 0.5 * 10f64.powi(-decimals) + 1e-12;
        assert!(
            (dt - published_dt_days).abs() <= half_unit(dt_decimals),
            "Δt_J2000 {dt}"
        );
        let page_mtc_h = 24.0 * msd_mars24_page(dt).rem_euclid(1.0);
        let page_lmst_h = (page_mtc_h + longitude_east_deg / 15.0).rem_euclid(24.0);
        assert!(
            (page_mtc_h - published_mtc_h).abs() <= half_unit(5),
            "{page_mtc_h}"
        );
        assert!(
            (page_lmst_h - published_lmst_h).abs() <= half_unit(5),
            "{page_lmst_h}"
        );
        let explained_s = (mars_sol_date(t) - msd_mars24_page(dt)) * SOL_IN_DAYS * DAY_S;
        assert!((explained_s - shift_s).abs() < 0.01, "{explained_s}");
        let mtc_s = (coordinated_mars_time_h(t) - published_mtc_h) * MARS_HOUR_S;
        let lmst_s = (lmst_h(t, longitude_east_deg) - published_lmst_h) * MARS_HOUR_S;
        let rounding_s = half_unit(5) * MARS_HOUR_S;
        for d_s in [mtc_s, lmst_s] {
            assert!(
                (d_s - shift_s).abs() <= rounding_s,
                "{d_s} s, {shift_s} s explained"
            );
            assert!(d_s.abs() < 0.25, "{d_s} s");
        }
    }

    /// Mars24 worked example A, 2000-01-06 00:00:00 UTC at the prime meridian: JD_TT
    /// 2451549.500743, Δt_J2000 4.500743 days, MTC (the page's MST) = LMST = 23.99425 h =
    /// 23:59:39 (MSD 44795.99976). With the paper's constants MTC is 23.99431 h, 0.23 s later.
    #[test]
    fn worked_example_a() {
        let t = Utc::from_civil(2000, 1, 6, 0, 0, 0.0);
        assert_eq!(tt_minus_utc_s(t), 64.184);
        assert!((j2000_tt_days(t) + JD_J2000 - 2_451_549.500_743).abs() <= 5e-7);
        assert_eq!(mars_sol_date(t).floor(), 44_795.0);
        check_worked_example(t, 4.500_743, 6, 0.0, 23.994_25, 23.994_25, 0.231);
    }

    /// Mars24 worked example B, 2004-01-03 13:46:31 UTC (Spirit's landing) at 184.702° W
    /// (175.298° E): JD_UT 2453008.07397, JD_TT 2453008.07471, Δt_J2000 1463.07471 days, MTC
    /// 13.16537 h = 13:09:55, LMST 0.85190 h = 00:51:07 (MSD 46215.54856). With the paper's
    /// constants MTC is 13.16542 h, 0.19 s later.
    #[test]
    fn worked_example_b() {
        let t = Utc::from_civil(2004, 1, 3, 13, 46, 31.0);
        assert_eq!(t.0, 1_073_137_591.0);
        assert!((t.0 / DAY_S + JD_UNIX_EPOCH - 2_453_008.073_97).abs() <= 5e-6);
        assert_eq!(tt_minus_utc_s(t), 64.184);
        assert!((j2000_tt_days(t) + JD_J2000 - 2_453_008.074_71).abs() <= 5e-6);
        assert_eq!(mars_sol_date(t).floor(), 46_215.0);
        check_worked_example(
            t,
            1_463.074_71,
            5,
            360.0 - 184.702,
            13.165_37,
            0.851_90,
            0.194,
        );
    }

    #[test]
    fn round_trips() {
        for k in 0..2000 {
            let t = Utc(1.5e9 + f64::from(k) * 123_457.3);
            let back = utc_from_mars_sol_date(mars_sol_date(t));
            assert!((back.0 - t.0).abs() < 1e-3, "{k}");
            let sclk = m20_sclk_from_utc(t);
            assert!((utc_from_m20_sclk(sclk).0 - t.0).abs() < 1e-3);
        }
        let m = &MARS_2020;
        for sol in [0, 1, 379, 402, 1000] {
            for at in [SolSeconds(1), SolSeconds(40_000), SolSeconds(88_774)] {
                let t = m.utc_at(sol, at);
                assert_eq!(m.sol_of(t), sol);
                assert!((m.lmst(t) - at).abs() <= 1);
            }
        }
    }

    #[test]
    fn mars_2020_landing_sol() {
        let m = &MARS_2020;
        assert_eq!(m.sol_of(m.landing), 0);
        // Landing in the mid-afternoon, about 15:53 LMST.
        let at = m.lmst(m.landing);
        assert!(at.lmst().starts_with("15:5"), "{}", at.lmst());
        // Paper 000 §8 names sols by the day in Pasadena their plan is built, the day before
        // their morning: sol 402's plan on Wednesday 2022-04-06 (its 09:00 LMST is Thursday
        // morning there), sol 406 "Sunday" (its morning is Monday 2022-04-11).
        let morning = |sol| m.utc_at(sol, SolSeconds::from_lmst(9, 0).expect("valid"));
        let days = crate::time::earth_time::days_from_civil;
        let pasadena = |t: Utc| t.civil_day(crate::time::earth_time::pacific_offset_h(t));
        assert_eq!(pasadena(morning(402)), days(2022, 4, 7));
        assert_eq!(pasadena(morning(406)), days(2022, 4, 11));
    }
}
