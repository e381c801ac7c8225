//! Mars time: sols and local mean solar time (LMST).
//!
//! A sol is [`SOL_S`] = 88,775 s (the one seconds-per-sol constant); LMST divides it into 24
//! "Mars hours" of 3,698.96 s.
//!
//! # One instant type
//!
//! Every instant within a sol in `sim` is a [`SolSeconds`]: **integer** seconds after the sol's
//! local midnight, so nothing accumulates in `f64`. The calendar's drive window and downlink
//! pass, the plan's window and wake-up, every plan step's start and end, the sol log's timeline,
//! a science target's reveal and a periodic campaign's first due time are all `SolSeconds`.
//! It is signed: a planning window may open before midnight (the heating before a drive that
//! starts just after 00:00) or close past [`SOL_S`] (four hours after a late drive window), and
//! the arithmetic stays exact; the LMST reading ([`SolSeconds::lmst`]) clamps at 00:00.
//!
//! Durations are not instants: they stay plain integer seconds named `_s` (`heating_s: i64`).
//! An instant plus a duration is an instant (`t + d`), an instant minus an instant is a duration
//! (`b - a`), both exact.
//!
//! # The planner boundary
//!
//! The `planner` crate knows nothing of `sim`: its problems, plans and states carry `i64`
//! seconds after midnight. Values cross that boundary through one pair of exact conversions,
//! [`SolSeconds::from_planner_s`] (into `sim`) and [`SolSeconds::planner_s`] (out to the
//! planner); nothing else reads or builds the raw count. [`lmst_of`] formats a planner time
//! through the same formatter.
//!
//! # What stays `f64`
//!
//! Durations *measured* inside an activity are physical, not clock readings: AutoNav's driving
//! time (each step's commanded length over the drive rate, with the time budget trimming the last
//! step) and the co-processor model's log (`localization::hbs`: a transfer at a byte rate takes
//! fractional seconds). They become instants once, rounded to the nearest second, at the step
//! they end ([`SolSeconds::after_s`]). AutoNav's sum stays `f64` on purpose: summing it in
//! integer milliseconds moves the time budget's trim of the last step, and so every bundled
//! scenario's positions, distances and plan times (up to 18 s on a sol).

use std::ops::{Add, Sub};

pub mod earth_time;
pub mod mars_time;

/// Length of a sol in SI seconds.
pub const SOL_S: u32 = 88_775;

/// An instant within a sol: integer seconds after local midnight (negative before it, beyond
/// [`SOL_S`] after the sol's end; see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct SolSeconds(pub i64);

impl SolSeconds {
    /// Local midnight at the start of the sol (00:00 LMST).
    pub const MIDNIGHT: SolSeconds = SolSeconds(0);
    /// The end of the sol (24:00 LMST).
    pub const END_OF_SOL: SolSeconds = SolSeconds(SOL_S as i64);

    /// A time of the `planner` crate (`i64` seconds after midnight) as an instant.
    #[must_use]
    pub const fn from_planner_s(s: i64) -> Self {
        SolSeconds(s)
    }

    /// This instant as the `planner` crate's `i64` seconds after midnight.
    #[must_use]
    pub const fn planner_s(self) -> i64 {
        self.0
    }

    /// The instant a measured duration of `duration_s` (fractional seconds, e.g. AutoNav's
    /// driving time) after this one, rounded to the nearest second.
    #[must_use]
    pub fn after_s(self, duration_s: f64) -> Self {
        SolSeconds(self.0 + duration_s.round() as i64)
    }

    /// The time of day for an LMST clock reading `hours:minutes` (a Mars hour is 1/24 sol).
    /// `None` if the reading is outside 00:00 ..= 24:00.
    #[must_use]
    pub fn from_lmst(hours: u32, minutes: u32) -> Option<Self> {
        if minutes >= 60 || hours > 24 || (hours == 24 && minutes > 0) {
            return None;
        }
        let fraction = u64::from(hours * 60 + minutes);
        Some(SolSeconds(
            ((fraction * u64::from(SOL_S) + 720) / 1440) as i64,
        ))
    }

    /// Parse `"HH:MM"` LMST: exactly two ASCII digits, a colon and two ASCII digits, from
    /// 00:00 to 24:00. Nothing else is a clock reading: no sign (`"+11:30"`, `"11:+3"`, which
    /// integer parsing accepts), no spaces, no single-digit hour.
    #[must_use]
    pub fn parse_lmst(text: &str) -> Option<Self> {
        let &[h1, h0, b':', m1, m0] = text.as_bytes() else {
            return None;
        };
        if ![h1, h0, m1, m0].iter().all(u8::is_ascii_digit) {
            return None;
        }
        let digit = |d: u8| u32::from(d - b'0');
        Self::from_lmst(digit(h1) * 10 + digit(h0), digit(m1) * 10 + digit(m0))
    }

    /// The LMST clock reading `HH:MM` of this time (rounded to the nearest Mars minute; a time
    /// before midnight reads 00:00, one past the sol's end 24:MM and on): the one formatter of
    /// plan, sol-log and message times.
    #[must_use]
    pub fn lmst(self) -> String {
        let s = self.0.clamp(0, i64::from(u32::MAX)) as u64;
        let minutes = (s * 1440 + u64::from(SOL_S) / 2) / u64::from(SOL_S);
        format!("{:02}:{:02}", minutes / 60, minutes % 60)
    }
}

impl Add<i64> for SolSeconds {
    type Output = SolSeconds;
    /// The instant `duration_s` seconds later.
    fn add(self, duration_s: i64) -> SolSeconds {
        SolSeconds(self.0 + duration_s)
    }
}

impl Sub<i64> for SolSeconds {
    type Output = SolSeconds;
    /// The instant `duration_s` seconds earlier.
    fn sub(self, duration_s: i64) -> SolSeconds {
        SolSeconds(self.0 - duration_s)
    }
}

impl Sub for SolSeconds {
    type Output = i64;
    /// The duration from `earlier` to `self`, s (negative if `earlier` is later).
    fn sub(self, earlier: SolSeconds) -> i64 {
        self.0 - earlier.0
    }
}

/// The LMST clock reading `HH:MM` of a `planner` time (`i64` seconds after midnight):
/// `SolSeconds::from_planner_s(s).lmst()`.
#[must_use]
pub fn lmst_of(s: i64) -> String {
    SolSeconds::from_planner_s(s).lmst()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lmst_round_trips() {
        assert_eq!(SolSeconds::parse_lmst("00:00"), Some(SolSeconds(0)));
        assert_eq!(
            SolSeconds::parse_lmst("24:00"),
            Some(SolSeconds::END_OF_SOL)
        );
        let noon = SolSeconds::parse_lmst("12:00").expect("valid");
        assert_eq!(noon.planner_s(), i64::from(SOL_S / 2 + 1)); // 44,387.5 s rounds up
        assert_eq!(noon.lmst(), "12:00");
        assert_eq!(
            SolSeconds::parse_lmst("11:30")
                .map(SolSeconds::lmst)
                .as_deref(),
            Some("11:30")
        );
        assert_eq!(SolSeconds::parse_lmst("25:00"), None);
        assert_eq!(SolSeconds::parse_lmst("12:60"), None);
        assert_eq!(SolSeconds::parse_lmst("noon"), None);
        for loose in [
            "11:+3",
            "+11:30",
            " 11:30",
            "11:30 ",
            "9:30",
            "11:3",
            "-1:00",
            "١١:٣٠",
        ] {
            assert_eq!(SolSeconds::parse_lmst(loose), None, "{loose:?}");
        }
    }

    #[test]
    fn planner_times_cross_exactly_and_read_as_lmst() {
        for s in [
            -1_800,
            0,
            33_291,
            i64::from(SOL_S),
            i64::from(SOL_S) + 14_400,
        ] {
            assert_eq!(SolSeconds::from_planner_s(s).planner_s(), s);
            assert_eq!(lmst_of(s), SolSeconds::from_planner_s(s).lmst());
        }
        // Before midnight reads 00:00; past the sol's end the clock runs on.
        assert_eq!(SolSeconds(-1_800).lmst(), "00:00");
        assert_eq!(SolSeconds::END_OF_SOL.lmst(), "24:00");
        let start = SolSeconds::parse_lmst("11:30").expect("valid");
        let end = start + 600;
        assert_eq!(end - start, 600);
        assert_eq!(end - 600, start);
        assert_eq!(start.after_s(599.5), end);
        assert_eq!(start.after_s(0.4), start);
    }
}
