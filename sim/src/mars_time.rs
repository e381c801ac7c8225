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
//! every drive of the public record lands on its filed sol (`tests/record_import.rs`).

use crate::earth_time::{DAY_S, Utc, tt_minus_utc_s};
use crate::time::{SOL_S, SolSeconds};

/// Julian Date of 1970-01-01T00:00:00 (the Unix epoch).
const JD_UNIX_EPOCH: f64 = 2_440_587.5;
/// Julian Date of the J2000 epoch, 2000-01-01T12:00:00 TT.
const JD_J2000: f64 = 2_451_545.0;
/// Allison & McEwen (2000) eq. 32: the length of a mean solar day on Mars, Earth days.
pub const SOL_IN_DAYS: f64 = 1.027_491_252;

/// Days of Terrestrial Time since J2000 (Δt_J2000) at a UTC instant.
#[must_use]
pub fn j2000_tt_days(t: Utc) -> f64 {
    (t.0 + tt_minus_utc_s(t)) / DAY_S + JD_UNIX_EPOCH - JD_J2000
}

/// The UTC instant `days` of Terrestrial Time after J2000 (the inverse of [`j2000_tt_days`]).
#[must_use]
pub fn utc_from_j2000_tt_days(days: f64) -> Utc {
    let tt_unix = (days + JD_J2000 - JD_UNIX_EPOCH) * DAY_S;
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

    /// Allison & McEwen (2000) and the Mars24 worked example (NASA GISS, "Mars24 Sunclock —
    /// Algorithm and Worked Examples", example A: 2000-01-06 00:00:00 UTC): JD_TT 2451549.50074,
    /// Δt_J2000 4.50074, MSD 44795.99975, MTC 23:59:38.
    #[test]
    fn worked_example_a() {
        let t = Utc::from_civil(2000, 1, 6, 0, 0, 0.0);
        assert!((j2000_tt_days(t) - 4.500_743).abs() < 1e-6);
        let msd = mars_sol_date(t);
        assert!((msd - 44_795.999_76).abs() < 1e-5, "{msd}");
        let mtc_s = coordinated_mars_time_h(t) * 3600.0;
        assert!(
            (mtc_s - (23.0 * 3600.0 + 59.0 * 60.0 + 38.0)).abs() < 2.0,
            "{mtc_s}"
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
        let days = crate::earth_time::days_from_civil;
        let pasadena = |t: Utc| t.civil_day(crate::earth_time::pacific_offset_h(t));
        assert_eq!(pasadena(morning(402)), days(2022, 4, 7));
        assert_eq!(pasadena(morning(406)), days(2022, 4, 11));
    }
}
