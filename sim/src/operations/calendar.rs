//! The operations calendar: which sols get a new plan, which are restricted, when data reaches
//! Earth (paper 000 §8).
//!
//! A plan is uplinked on a sol with `uplink = true` and covers every sol up to the next uplink
//! (a weekend plan covers three sols). A sol's post-drive data (the panorama, the localization
//! result) goes down in the first downlink pass at or after that sol; it can be used to plan the
//! uplink of the *next* sol only if that sol is not **restricted**, and any later uplink otherwise.

use crate::settings::field_error::FieldError;
use crate::settings::physical_range::PhysicalRange;
use crate::time::SolSeconds;

/// How a plan was built (replays take it from the record; strategies fix it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Planning {
    /// Ground-in-the-loop: plan only from a ground-localized position, and drive only on sols
    /// whose post-drive data reaches Earth before the next plan is built.
    Ground,
    /// Opportunistic extension: breadcrumb waypoints appended at every uplink, planned without
    /// knowing where the rover ended; drive every sol the calendar allows.
    Extension,
}

/// What happened on a historic sol (replays only).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct HistoricSol {
    /// Odometry distance driven, metres (range [`HistoricSol::DISTANCE_RANGE_M`]).
    pub distance_m: f64,
    /// Of which without VO, metres (range [`HistoricSol::DISTANCE_RANGE_M`], at most
    /// `distance_m`).
    pub novo_m: f64,
    /// The drive ended in a fault historically: the distance is not a budget, the replay drives
    /// the sol's window and the fault must emerge from the zones and the uncertainty.
    pub ended_in_fault: bool,
}

/// One sol of the calendar.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SolEntry {
    /// Mission sol number.
    pub sol: u32,
    /// A new plan is uplinked this morning.
    pub uplink: bool,
    /// The previous sol's data arrives too late to plan this sol's uplink.
    pub restricted: bool,
    /// A downlink pass after the drive carries this sol's post-drive data.
    pub downlink: bool,
    /// Time of that pass, when it comes in the afternoon: a ground-planned drive that must get its
    /// panorama down on it ends early enough to take the panorama first.
    pub downlink_lmst: Option<SolSeconds>,
    /// Driving is allowed this sol (false: science sol, holiday, conjunction, …).
    pub drive_allowed: bool,
    /// This sol's own drive window (LMST start, end), instead of the calendar's: the record's
    /// window on a historic drive sol.
    pub window: Option<(SolSeconds, SolSeconds)>,
    /// This sol's own AutoNav rate, m/h, instead of the rover's: the record's speed on a
    /// historic drive sol (its distance over its window), the terrain and plan of that sol.
    pub drive_rate_m_per_h: Option<f64>,
    /// How the plan uplinked this sol was built historically (replays).
    pub historic_planning: Option<Planning>,
    /// What the rover did historically (replays).
    pub historic: Option<HistoricSol>,
}

impl HistoricSol {
    /// The distances a sol may have driven, metres: the longest Mars drives are well under
    /// 1 km a sol.
    pub const DISTANCE_RANGE_M: PhysicalRange = PhysicalRange::new(0.0, 10_000.0, "metres");

    /// Checks both distances against their range, and that no more was driven without VO
    /// than in all.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field at fault.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::DISTANCE_RANGE_M.check("distance_m", self.distance_m)?;
        Self::DISTANCE_RANGE_M.check("novo_m", self.novo_m)?;
        if self.novo_m > self.distance_m {
            return Err(FieldError::new(
                "novo_m",
                format!("at most distance_m ({} m)", self.distance_m),
                self.novo_m,
            )
            .naming("distance_m"));
        }
        Ok(())
    }
}

impl SolEntry {
    /// Checks the sol on its own: a historic plan only where a plan is uplinked, the historic
    /// drive ([`HistoricSol::validate`], as `historic.…`), a window inside the sol that ends
    /// after it starts, a positive rate.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field at fault.
    pub fn validate(&self) -> Result<(), FieldError> {
        if self.historic_planning.is_some() && !self.uplink {
            return Err(FieldError::new(
                "historic_planning",
                "only on a sol with an uplink",
                "a sol without one",
            ));
        }
        if let Some(historic) = &self.historic {
            historic.validate().map_err(|e| e.within("historic"))?;
        }
        if let Some((start, end)) = self.window {
            check_window(start, end, "window", "the drive's start", None)?;
        }
        if let Some(rate) = self
            .drive_rate_m_per_h
            .filter(|v| !(*v > 0.0 && v.is_finite()))
        {
            return Err(FieldError::new(
                "drive_rate_m_per_h",
                "a positive, finite rate, metres per hour",
                rate,
            ));
        }
        Ok(())
    }
}

/// A drive window from `start` to `end`: inside the sol, and `end` (the field `end_field`)
/// after the start (named `start_name` in the message; `sibling` if it is a field of the same
/// struct).
fn check_window(
    start: SolSeconds,
    end: SolSeconds,
    end_field: &str,
    start_name: &str,
    sibling: Option<&'static str>,
) -> Result<(), FieldError> {
    if start < SolSeconds::MIDNIGHT || end > SolSeconds::END_OF_SOL {
        return Err(FieldError::new(
            end_field,
            "a window inside the sol, 00:00 to 24:00 LMST",
            format!("{} s to {} s", start.0, end.0),
        ));
    }
    if end <= start {
        let e = FieldError::new(
            end_field,
            format!("a time after {start_name} ({})", start.lmst()),
            end.lmst(),
        );
        return Err(match sibling {
            Some(s) => e.naming(s),
            None => e,
        });
    }
    Ok(())
}

/// The calendar of a scenario: consecutive sols, the first with an uplink.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Calendar {
    /// The sols, consecutive and in order.
    pub sols: Vec<SolEntry>,
    /// Start of the daily drive window (LMST).
    pub drive_start: SolSeconds,
    /// End of the daily drive window (LMST).
    pub drive_end: SolSeconds,
}

impl Calendar {
    /// The most sols a calendar may hold (about 15 Mars years): a bound on a run's work and on
    /// what a loader reads.
    pub const MAX_SOLS: usize = 10_000;

    /// Checks that the calendar can be run: the daily drive window
    /// ([`Calendar::validate_drive_window`]), 1 ..= [`Calendar::MAX_SOLS`] sols, and each sol
    /// after the one before it ([`Calendar::validate_sol`]).
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field at fault.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::validate_drive_window(self.drive_start, self.drive_end)?;
        if self.sols.is_empty() {
            return Err(FieldError::new("sols", "at least one sol", "none"));
        }
        if self.sols.len() > Self::MAX_SOLS {
            return Err(FieldError::new(
                "sols",
                format!("at most {} sols", Self::MAX_SOLS),
                self.sols.len(),
            ));
        }
        for (i, entry) in self.sols.iter().enumerate() {
            Self::validate_sol(i, i.checked_sub(1).map(|p| &self.sols[p]), entry)?;
        }
        Ok(())
    }

    /// Checks the daily drive window, from `drive_start` to `drive_end`: inside the sol, and
    /// ending after it starts.
    ///
    /// # Errors
    /// A [`FieldError`] naming `drive_end`.
    pub fn validate_drive_window(
        drive_start: SolSeconds,
        drive_end: SolSeconds,
    ) -> Result<(), FieldError> {
        check_window(
            drive_start,
            drive_end,
            "drive_end",
            "drive_start",
            Some("drive_start"),
        )
    }

    /// Checks the sol at index `index` of the calendar, after `previous`: the sol after it
    /// (sols are consecutive), an uplink on the first, and the sol on its own
    /// ([`SolEntry::validate`]). A loader checks each sol as it reads it.
    ///
    /// # Errors
    /// A [`FieldError`] naming the field at fault as `sols[index].…`.
    pub fn validate_sol(
        index: usize,
        previous: Option<&SolEntry>,
        entry: &SolEntry,
    ) -> Result<(), FieldError> {
        let within = |e: FieldError| e.within(&format!("sols[{index}]"));
        // In u64: the sol before may be u32::MAX.
        let next = previous.map(|p| u64::from(p.sol) + 1);
        if let Some(next) = next.filter(|&n| n != u64::from(entry.sol)) {
            return Err(within(FieldError::new(
                "sol",
                format!("sol {next} (sols are consecutive)"),
                entry.sol,
            )));
        }
        if index == 0 && !entry.uplink {
            return Err(within(FieldError::new(
                "uplink",
                "true (the first sol starts a plan)",
                "false",
            )));
        }
        entry.validate().map_err(within)
    }

    /// Sols from `from_sol` (inclusive) to the end of the calendar. A run that did not cover a
    /// stretch counted from `from_sol` needs more than this many sols (a censored count).
    #[must_use]
    pub fn sols_from(&self, from_sol: u32) -> u32 {
        self.sols
            .last()
            .map_or(0, |last| (last.sol + 1).saturating_sub(from_sol))
    }

    /// Index of the next uplink strictly after index `i` (`None`: beyond the calendar).
    #[must_use]
    pub fn next_uplink_after(&self, i: usize) -> Option<usize> {
        (i + 1..self.sols.len()).find(|&j| self.sols[j].uplink)
    }

    /// Whether the post-drive data of sol index `s` is on Earth in time to plan the uplink at
    /// index `u`. An uplink beyond the calendar (`None`) is assumed to have everything.
    #[must_use]
    pub fn data_available(&self, s: usize, u: Option<usize>) -> bool {
        let Some(u) = u else { return true };
        let Some(pass) = (s..self.sols.len()).find(|&t| self.sols[t].downlink) else {
            return false;
        };
        u >= pass + 2 || (u == pass + 1 && !self.sols[u].restricted)
    }

    /// The drive window of the sol at index `i`: its own, else the calendar's.
    #[must_use]
    pub fn window_of(&self, i: usize) -> (SolSeconds, SolSeconds) {
        self.sols
            .get(i)
            .and_then(|e| e.window)
            .unwrap_or((self.drive_start, self.drive_end))
    }
}

/// A plain drive sol for unit tests (no pass time, no history).
#[cfg(test)]
pub(crate) fn test_sol(sol: u32, uplink: bool, restricted: bool, downlink: bool) -> SolEntry {
    SolEntry {
        sol,
        uplink,
        restricted,
        downlink,
        downlink_lmst: None,
        drive_allowed: true,
        window: None,
        drive_rate_m_per_h: None,
        historic_planning: None,
        historic: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use super::test_sol as sol;

    /// Sols 402-407 of paper 000 §8: a Wednesday plan (402-403) before a restricted Friday, a
    /// weekend plan (404-406) with no pass on 406.
    #[test]
    fn paper_week_data_availability() {
        let cal = Calendar {
            sols: vec![
                sol(402, true, false, true),
                sol(403, false, false, true),
                sol(404, true, true, true),
                sol(405, false, false, true),
                sol(406, false, false, false),
                sol(407, true, false, true),
            ],
            drive_start: SolSeconds(0),
            drive_end: SolSeconds(1),
        };
        assert!(
            cal.data_available(0, Some(2)),
            "402's panorama is in for the Friday plan"
        );
        assert!(
            !cal.data_available(1, Some(2)),
            "403's is not: Friday is restricted"
        );
        assert!(cal.data_available(3, Some(5)), "405's is in for Monday");
        assert!(!cal.data_available(4, Some(5)), "406 has no pass");
        assert!(cal.data_available(4, None));
        assert_eq!(cal.next_uplink_after(0), Some(2));
        assert_eq!(cal.next_uplink_after(5), None);
    }
}
