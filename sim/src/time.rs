//! Mars time: sols and local mean solar time (LMST).
//!
//! A sol is 88,775 s; LMST divides it into 24 "Mars hours" of 3,698.96 s. Times inside a sol are
//! kept as integer seconds after local midnight ([`SolSeconds`]) so nothing accumulates in `f64`.

/// Length of a sol in SI seconds.
pub const SOL_S: u32 = 88_775;

/// Seconds after local midnight within one sol (0 ..= 88,775).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct SolSeconds(pub u32);

impl SolSeconds {
    /// The time of day for an LMST clock reading `hours:minutes` (a Mars hour is 1/24 sol).
    /// `None` if the reading is outside 00:00 ..= 24:00.
    #[must_use]
    pub fn from_lmst(hours: u32, minutes: u32) -> Option<Self> {
        if minutes >= 60 || hours > 24 || (hours == 24 && minutes > 0) {
            return None;
        }
        let fraction = (hours * 60 + minutes) as u64;
        Some(SolSeconds(((fraction * SOL_S as u64 + 720) / 1440) as u32))
    }

    /// Parse `"HH:MM"` LMST.
    #[must_use]
    pub fn parse_lmst(text: &str) -> Option<Self> {
        let (h, m) = text.trim().split_once(':')?;
        if h.is_empty() || m.len() != 2 {
            return None;
        }
        Self::from_lmst(h.parse().ok()?, m.parse().ok()?)
    }

    /// The LMST clock reading `HH:MM` of this time (rounded to the nearest Mars minute).
    #[must_use]
    pub fn lmst(self) -> String {
        let minutes = (self.0 as u64 * 1440 + SOL_S as u64 / 2) / SOL_S as u64;
        format!("{:02}:{:02}", minutes / 60, minutes % 60)
    }
}

/// The LMST clock reading `HH:MM` of `s` seconds after local midnight (clamped to the sol's
/// range of [`SolSeconds`]): the one formatter of plan, sol-log and message times.
#[must_use]
pub fn lmst_of(s: i64) -> String {
    SolSeconds(s.clamp(0, i64::from(u32::MAX)) as u32).lmst()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lmst_round_trips() {
        assert_eq!(SolSeconds::parse_lmst("00:00"), Some(SolSeconds(0)));
        assert_eq!(SolSeconds::parse_lmst("24:00"), Some(SolSeconds(SOL_S)));
        let noon = SolSeconds::parse_lmst("12:00").expect("valid");
        assert_eq!(noon.0, SOL_S / 2 + 1); // 44,387.5 s rounds up
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
    }
}
