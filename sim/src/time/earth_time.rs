//! Earth time: UTC instants, leap seconds, civil dates, and the clock of the planning team in
//! Pasadena (US Pacific time), for [`crate::time::mars_time`] and the computed operations calendar.
//!
//! An instant is a [`Utc`]: seconds since 1970-01-01 00:00:00 UTC not counting leap seconds
//! (POSIX time), as `f64` (a resolution of 0.2 µs in this century). Terrestrial Time, the uniform
//! scale the Mars24 algorithm needs, is UTC plus [`tt_minus_utc_s`]: 32.184 s plus the leap
//! seconds (TAI − UTC) of [`LEAP_SECONDS`].

use std::fmt;

/// An instant in UTC: seconds since 1970-01-01T00:00:00Z, leap seconds not counted.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, serde::Serialize)]
pub struct Utc(pub f64);

/// TAI − UTC from each leap second on: (the UTC day it takes effect, as days since 1970-01-01;
/// TAI − UTC from then on, s). IERS Bulletin C; the last was inserted at the end of 2016, and
/// IERS has announced none since. `tests/mars_time_mars24.rs` checks the table against ERFA's
/// (`erfa.dat`, an independent copy of the same bulletins).
pub const LEAP_SECONDS: [(i64, f64); 28] = [
    (days_from_civil(1972, 1, 1), 10.0),
    (days_from_civil(1972, 7, 1), 11.0),
    (days_from_civil(1973, 1, 1), 12.0),
    (days_from_civil(1974, 1, 1), 13.0),
    (days_from_civil(1975, 1, 1), 14.0),
    (days_from_civil(1976, 1, 1), 15.0),
    (days_from_civil(1977, 1, 1), 16.0),
    (days_from_civil(1978, 1, 1), 17.0),
    (days_from_civil(1979, 1, 1), 18.0),
    (days_from_civil(1980, 1, 1), 19.0),
    (days_from_civil(1981, 7, 1), 20.0),
    (days_from_civil(1982, 7, 1), 21.0),
    (days_from_civil(1983, 7, 1), 22.0),
    (days_from_civil(1985, 7, 1), 23.0),
    (days_from_civil(1988, 1, 1), 24.0),
    (days_from_civil(1990, 1, 1), 25.0),
    (days_from_civil(1991, 1, 1), 26.0),
    (days_from_civil(1992, 7, 1), 27.0),
    (days_from_civil(1993, 7, 1), 28.0),
    (days_from_civil(1994, 7, 1), 29.0),
    (days_from_civil(1996, 1, 1), 30.0),
    (days_from_civil(1997, 7, 1), 31.0),
    (days_from_civil(1999, 1, 1), 32.0),
    (days_from_civil(2006, 1, 1), 33.0),
    (days_from_civil(2009, 1, 1), 34.0),
    (days_from_civil(2012, 7, 1), 35.0),
    (days_from_civil(2015, 7, 1), 36.0),
    (days_from_civil(2017, 1, 1), 37.0),
];

/// Seconds in a civil (UTC) day.
pub const DAY_S: f64 = 86_400.0;

/// TAI − UTC at `t`, seconds (10 s before 1972, where UTC had no whole-second offset: outside
/// any mission this module serves).
#[must_use]
pub fn tai_minus_utc_s(t: Utc) -> f64 {
    let day = (t.0 / DAY_S).floor() as i64;
    LEAP_SECONDS
        .iter()
        .rev()
        .find(|&&(from, _)| day >= from)
        .map_or(10.0, |&(_, s)| s)
}

/// TT − UTC at `t`: 32.184 s plus TAI − UTC.
#[must_use]
pub fn tt_minus_utc_s(t: Utc) -> f64 {
    32.184 + tai_minus_utc_s(t)
}

/// Days since 1970-01-01 of a proleptic Gregorian date (Howard Hinnant's `days_from_civil`).
#[must_use]
pub const fn days_from_civil(year: i64, month: u32, day: u32) -> i64 {
    let y = if month <= 2 { year - 1 } else { year };
    let era = if y >= 0 { y } else { y - 399 } / 400;
    let yoe = y - era * 400;
    let m = month as i64;
    let doy = (153 * (if m > 2 { m - 3 } else { m + 9 }) + 2) / 5 + day as i64 - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The proleptic Gregorian date `(year, month, day)` of `days` since 1970-01-01.
#[must_use]
pub const fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = if z >= 0 { z } else { z - 146_096 } / 146_097;
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let year = yoe + era * 400 + if month <= 2 { 1 } else { 0 };
    (year, month, day)
}

/// Day of the week.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
pub enum Weekday {
    /// Monday.
    Monday,
    /// Tuesday.
    Tuesday,
    /// Wednesday.
    Wednesday,
    /// Thursday.
    Thursday,
    /// Friday.
    Friday,
    /// Saturday.
    Saturday,
    /// Sunday.
    Sunday,
}

impl Weekday {
    /// The weekday of `days` since 1970-01-01 (a Thursday).
    #[must_use]
    pub const fn of_days(days: i64) -> Self {
        match (days + 3).rem_euclid(7) {
            0 => Weekday::Monday,
            1 => Weekday::Tuesday,
            2 => Weekday::Wednesday,
            3 => Weekday::Thursday,
            4 => Weekday::Friday,
            5 => Weekday::Saturday,
            _ => Weekday::Sunday,
        }
    }

    /// Saturday or Sunday.
    #[must_use]
    pub const fn is_weekend(self) -> bool {
        matches!(self, Weekday::Saturday | Weekday::Sunday)
    }

    /// Three-letter English name.
    #[must_use]
    pub const fn short(self) -> &'static str {
        match self {
            Weekday::Monday => "Mon",
            Weekday::Tuesday => "Tue",
            Weekday::Wednesday => "Wed",
            Weekday::Thursday => "Thu",
            Weekday::Friday => "Fri",
            Weekday::Saturday => "Sat",
            Weekday::Sunday => "Sun",
        }
    }
}

impl Utc {
    /// The instant at a UTC civil date and time.
    #[must_use]
    pub fn from_civil(
        year: i64,
        month: u32,
        day: u32,
        hour: u32,
        minute: u32,
        second: f64,
    ) -> Self {
        Utc(days_from_civil(year, month, day) as f64 * DAY_S
            + f64::from(hour * 3600 + minute * 60)
            + second)
    }

    /// Parse `YYYY-MM-DDTHH:MM:SS[.fff]Z` (ISO 8601, UTC, nothing else). `None` if malformed
    /// or out of range.
    #[must_use]
    pub fn parse_iso(text: &str) -> Option<Self> {
        let b = text.as_bytes();
        if b.len() < 20
            || b[4] != b'-'
            || b[7] != b'-'
            || b[10] != b'T'
            || b[13] != b':'
            || b[16] != b':'
            || *b.last()? != b'Z'
        {
            return None;
        }
        let num = |r: std::ops::Range<usize>| -> Option<u32> {
            let s = text.get(r)?;
            s.bytes()
                .all(|c| c.is_ascii_digit())
                .then(|| s.parse().ok())?
        };
        let (year, month, day) = (num(0..4)?, num(5..7)?, num(8..10)?);
        let (hour, minute) = (num(11..13)?, num(14..16)?);
        let sec_text = text.get(17..text.len() - 1)?;
        let whole = sec_text.get(0..2)?;
        if !whole.bytes().all(|c| c.is_ascii_digit()) {
            return None;
        }
        let frac = &sec_text[2..];
        if !(frac.is_empty()
            || (frac.len() >= 2
                && frac.starts_with('.')
                && frac[1..].bytes().all(|c| c.is_ascii_digit())))
        {
            return None;
        }
        let second: f64 = sec_text.parse().ok()?;
        let days_in_month = days_from_civil(i64::from(year), month % 12 + 1, 1)
            - days_from_civil(i64::from(year), month, 1);
        let days_in_month = if month == 12 { 31 } else { days_in_month };
        if !(1..=12).contains(&month)
            || day == 0
            || i64::from(day) > days_in_month
            || hour > 23
            || minute > 59
            || second >= 60.0
        {
            return None;
        }
        Some(Self::from_civil(
            i64::from(year),
            month,
            day,
            hour,
            minute,
            second,
        ))
    }

    /// Days since 1970-01-01 of the UTC date of this instant, shifted by `offset_h` hours (a
    /// time zone's offset from UTC).
    #[must_use]
    pub fn civil_day(self, offset_h: f64) -> i64 {
        ((self.0 + offset_h * 3600.0) / DAY_S).floor() as i64
    }

    /// The civil time of day of this instant at `offset_h` hours from UTC, hours in [0, 24).
    #[must_use]
    pub fn hour_of_day(self, offset_h: f64) -> f64 {
        (self.0 + offset_h * 3600.0).rem_euclid(DAY_S) / 3600.0
    }

    /// This instant plus `s` seconds.
    #[must_use]
    pub fn plus_s(self, s: f64) -> Self {
        Utc(self.0 + s)
    }
}

impl fmt::Display for Utc {
    /// `YYYY-MM-DDTHH:MM:SSZ`, rounded to the nearest second.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = self.0.round() as i64;
        let (y, mo, d) = civil_from_days(t.div_euclid(86_400));
        let s = t.rem_euclid(86_400);
        write!(
            f,
            "{y:04}-{mo:02}-{d:02}T{:02}:{:02}:{:02}Z",
            s / 3600,
            s / 60 % 60,
            s % 60
        )
    }
}

/// The `n`-th (1-based) `weekday` of a month, as days since 1970-01-01.
fn nth_weekday(year: i64, month: u32, weekday: Weekday, n: i64) -> i64 {
    let first = days_from_civil(year, month, 1);
    let offset = (weekday as i64 - Weekday::of_days(first) as i64).rem_euclid(7);
    first + offset + 7 * (n - 1)
}

/// The last `weekday` of a month, as days since 1970-01-01.
fn last_weekday(year: i64, month: u32, weekday: Weekday) -> i64 {
    let next = if month == 12 {
        days_from_civil(year + 1, 1, 1)
    } else {
        days_from_civil(year, month + 1, 1)
    };
    let last = next - 1;
    last - (Weekday::of_days(last) as i64 - weekday as i64).rem_euclid(7)
}

/// US Pacific time's offset from UTC at `t`, hours: −7 in daylight time (second Sunday of March
/// 02:00 PST to first Sunday of November 02:00 PDT, the rule since 2007), −8 otherwise. The
/// planning team works in Pasadena.
#[must_use]
pub fn pacific_offset_h(t: Utc) -> f64 {
    let (year, _, _) = civil_from_days(t.civil_day(-8.0));
    let starts = Utc(nth_weekday(year, 3, Weekday::Sunday, 2) as f64 * DAY_S + 10.0 * 3600.0);
    let ends = Utc(nth_weekday(year, 11, Weekday::Sunday, 1) as f64 * DAY_S + 9.0 * 3600.0);
    if t >= starts && t < ends { -7.0 } else { -8.0 }
}

/// The US federal holidays of `year` as observed (a Saturday holiday on the Friday before, a
/// Sunday one on the Monday after), days since 1970-01-01: New Year's Day, Martin Luther King Jr.
/// Day, Presidents' Day, Memorial Day, Juneteenth (from 2021), Independence Day, Labor Day,
/// Columbus Day, Veterans Day, Thanksgiving and Christmas (5 U.S.C. 6103).
#[must_use]
pub fn us_federal_holidays(year: i64) -> Vec<i64> {
    let observed = |d: i64| match Weekday::of_days(d) {
        Weekday::Saturday => d - 1,
        Weekday::Sunday => d + 1,
        _ => d,
    };
    let mut days = vec![
        observed(days_from_civil(year, 1, 1)),
        nth_weekday(year, 1, Weekday::Monday, 3),
        nth_weekday(year, 2, Weekday::Monday, 3),
        last_weekday(year, 5, Weekday::Monday),
        observed(days_from_civil(year, 7, 4)),
        nth_weekday(year, 9, Weekday::Monday, 1),
        nth_weekday(year, 10, Weekday::Monday, 2),
        observed(days_from_civil(year, 11, 11)),
        nth_weekday(year, 11, Weekday::Thursday, 4),
        observed(days_from_civil(year, 12, 25)),
    ];
    if year >= 2021 {
        days.push(observed(days_from_civil(year, 6, 19)));
    }
    days.sort_unstable();
    days
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn civil_round_trip_and_weekdays() {
        for days in -800_000..800_000 {
            let (y, m, d) = civil_from_days(days);
            assert_eq!(days_from_civil(y, m, d), days);
        }
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(Weekday::of_days(0), Weekday::Thursday);
        // Paper 000 §8: sol 402's plan was uplinked on a Wednesday, 2022-04-06.
        assert_eq!(
            Weekday::of_days(days_from_civil(2022, 4, 6)),
            Weekday::Wednesday
        );
    }

    #[test]
    fn leap_seconds_and_iso() {
        let t = Utc::parse_iso("2016-12-31T23:59:59Z").expect("valid");
        assert_eq!(tai_minus_utc_s(t), 36.0);
        assert_eq!(tai_minus_utc_s(t.plus_s(1.0)), 37.0);
        assert_eq!(tt_minus_utc_s(t.plus_s(1.0)), 69.184);
        assert_eq!(t.to_string(), "2016-12-31T23:59:59Z");
        assert_eq!(
            Utc::parse_iso("2000-01-01T11:58:55.816Z").map(|t| t.0),
            Some(946_727_935.816)
        );
        for bad in [
            "2021-02-30T00:00:00Z",
            "2021-13-01T00:00:00Z",
            "2021-02-18 20:55:00Z",
            "2021-02-18T24:00:00Z",
            "2021-02-18T20:55:00",
            "2021-02-18T20:55:60Z",
            "2021-02-18T20:55:00.Z",
            "+021-02-18T20:55:00Z",
        ] {
            assert_eq!(Utc::parse_iso(bad), None, "{bad}");
        }
    }

    #[test]
    fn pacific_daylight_time_and_holidays() {
        // 2022: PDT from 13 March 10:00 UTC to 6 November 09:00 UTC.
        let at = |s: &str| pacific_offset_h(Utc::parse_iso(s).expect("valid"));
        assert_eq!(at("2022-03-13T09:59:59Z"), -8.0);
        assert_eq!(at("2022-03-13T10:00:00Z"), -7.0);
        assert_eq!(at("2022-11-06T08:59:59Z"), -7.0);
        assert_eq!(at("2022-11-06T09:00:00Z"), -8.0);
        let h = us_federal_holidays(2022);
        // Christmas 2022 fell on a Sunday: observed Monday the 26th; Juneteenth on Monday 20 June.
        assert!(h.contains(&days_from_civil(2022, 12, 26)));
        assert!(h.contains(&days_from_civil(2022, 6, 20)));
        assert!(h.contains(&days_from_civil(2022, 11, 24)));
        assert_eq!(h.len(), 11);
    }
}
