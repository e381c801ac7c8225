//! `[[sols]]`: one entry per consecutive sol — its plan, passes and whether it may drive,
//! typed or computed by `[calendar]` (`super::calendar`), and what the rover did historically
//! → the [`Calendar`] with the daily drive window of `[operations]`, checked by
//! [`Calendar::validate`]; the sols' notes and where their historic distances come from.

use sim::operations::calendar::{Calendar, HistoricSol, Planning, SolEntry};
use sim::time::SolSeconds;

use super::calendar::{ComputedCalendar, computed_calendar};
use super::operations;
use super::raw::{RawCalendar, RawSol};
use crate::check::FieldCheck;
use crate::error::ScenarioError;

/// What `[[sols]]` (and `[calendar]`) hold, checked.
pub(crate) struct Sols {
    /// The calendar.
    pub(crate) calendar: Calendar,
    /// The calendar computed from Mars time, with the typed overrides.
    pub(crate) computed_calendar: Option<ComputedCalendar>,
    /// Per-sol notes.
    pub(crate) notes: Vec<(u32, String)>,
    /// Per sol with a historic drive, where its distance comes from.
    pub(crate) historic_sources: Vec<(u32, String)>,
    /// Whether any sol has historic data.
    pub(crate) has_history: bool,
}

/// The file's name of a [`Calendar`] field: the drive window's in `[operations]`, a sol's in
/// its `[[sols]]` entry (the historic drive's as `historic_…` keys, its window by the end the
/// file gives).
fn toml_path(field: &str) -> String {
    operations::drive_window_path(field).unwrap_or_else(|| {
        field
            .replace(".historic.", ".historic_")
            .replace(".window", ".historic_drive_end_lmst")
    })
}

/// The calendar of `[[sols]]`, computed by `[calendar]` where it does not type a value, with
/// the daily drive window `drive_start`..`drive_end`.
///
/// # Errors
/// A [`ScenarioError`] naming the first `sols[i].…` (or `calendar.…`, `operations.…` drive
/// window) field at fault.
pub(crate) fn sols(
    c: &FieldCheck<'_>,
    raw_calendar: Option<&RawCalendar>,
    raw: &[RawSol],
    (drive_start, drive_end): (SolSeconds, SolSeconds),
) -> Result<Sols, ScenarioError> {
    // The entries are counted before they are read (a bound on the work).
    if raw.len() > Calendar::MAX_SOLS {
        return Err(c.err(
            "sols",
            format!("at most {} [[sols]] entries", Calendar::MAX_SOLS),
            raw.len(),
        ));
    }
    if raw.is_empty() {
        return Err(c.err("sols", "at least one [[sols]] entry", "none"));
    }
    let computed_calendar = raw_calendar
        .map(|cal| computed_calendar(c, cal, raw))
        .transpose()?;
    let mut sols = Vec::with_capacity(raw.len());
    let mut notes = Vec::new();
    let mut historic_sources = Vec::new();
    for (i, s) in raw.iter().enumerate() {
        let f = |name: &str| format!("sols[{i}].{name}");
        let computed = computed_calendar.as_ref().and_then(|cc| cc.sols.get(i));
        // The first sol's plan was uplinked before the range, if not on it.
        let uplink = s
            .uplink
            .unwrap_or_else(|| computed.is_none_or(|cs| cs.uplink || i == 0));
        let historic_planning = match s.historic_planning.as_deref() {
            None => None,
            Some("ground") => Some(Planning::Ground),
            Some("extension") => Some(Planning::Extension),
            Some(other) => {
                return Err(c.err(
                    &f("historic_planning"),
                    "\"ground\" or \"extension\"",
                    format!("{other:?}"),
                ));
            }
        };
        let historic = historic(c, s, &f)?;
        let downlink_lmst = s
            .downlink_lmst
            .as_deref()
            .map(|t| c.lmst(&f("downlink_lmst"), t))
            .transpose()?;
        if !s.note.is_empty() {
            notes.push((s.sol, s.note.clone()));
        }
        if let Some(source) = &s.historic_source {
            if historic.is_none() {
                return Err(c.err(
                    &f("historic_source"),
                    "only with historic_distance_m",
                    format!("{source:?}"),
                ));
            }
            historic_sources.push((s.sol, source.clone()));
        }
        let window = match (&s.historic_drive_start_lmst, &s.historic_drive_end_lmst) {
            (None, None) => None,
            (start, Some(end)) => {
                let end = c.lmst(&f("historic_drive_end_lmst"), end)?;
                let start = match start {
                    Some(t) => c.lmst(&f("historic_drive_start_lmst"), t)?,
                    None => drive_start,
                };
                Some((start, end))
            }
            (Some(_), None) => {
                return Err(c.err(
                    &f("historic_drive_end_lmst"),
                    "the end of the window whenever historic_drive_start_lmst is given",
                    "nothing",
                ));
            }
        };
        // The sol's own AutoNav rate: the record's distance over its whole window, for a
        // historic drive that ended without a fault (its terrain and plan set the pace). A
        // distance too small for a rate (5e-324 m underflows to 0 m/h) drives at the rover's.
        let drive_rate_m_per_h = match (historic, &s.historic_drive_start_lmst, window) {
            (Some(h), Some(_), Some((start, end))) if !h.ended_in_fault && end > start => {
                Some(h.distance_m / ((end - start) as f64 / 3600.0))
                    .filter(|rate| *rate > 0.0 && rate.is_finite())
            }
            _ => None,
        };
        let entry = SolEntry {
            sol: s.sol,
            uplink,
            restricted: s
                .restricted
                .unwrap_or_else(|| computed.is_some_and(|cs| cs.restricted && uplink)),
            downlink: s.downlink.unwrap_or(true),
            downlink_lmst,
            drive_allowed: s.drive.unwrap_or(true),
            window,
            drive_rate_m_per_h,
            historic_planning,
            historic,
        };
        // Each sol is checked as it is read, so the first sol at fault is the one named.
        Calendar::validate_sol(i, sols.last(), &entry).map_err(|e| c.setting(e, toml_path))?;
        sols.push(entry);
    }
    let calendar = Calendar {
        sols,
        drive_start,
        drive_end,
    };
    calendar.validate().map_err(|e| c.setting(e, toml_path))?;
    Ok(Sols {
        has_history: calendar.sols.iter().any(|s| s.historic.is_some()),
        calendar,
        computed_calendar,
        notes,
        historic_sources,
    })
}

/// What the rover did on sol `s` historically: a distance whenever its distance without VO
/// or its fault is given.
fn historic(
    c: &FieldCheck<'_>,
    s: &RawSol,
    f: &dyn Fn(&str) -> String,
) -> Result<Option<HistoricSol>, ScenarioError> {
    let distance_m = match (s.historic_distance_m, s.historic_novo_m) {
        (None, None) if s.historic_fault.is_none() => return Ok(None),
        (Some(distance_m), _) => distance_m,
        (None, _) => {
            return Err(c.err(
                &f("historic_distance_m"),
                "a distance whenever historic_novo_m or historic_fault is given",
                "nothing",
            ));
        }
    };
    let ended_in_fault = match s.historic_fault.as_deref() {
        None => false,
        Some("NO_PATH" | "KEEP_OUT" | "KEEP_IN") => true,
        Some(other) => {
            return Err(c.err(
                &f("historic_fault"),
                "\"NO_PATH\", \"KEEP_OUT\" or \"KEEP_IN\"",
                format!("{other:?}"),
            ));
        }
    };
    Ok(Some(HistoricSol {
        distance_m,
        novo_m: s.historic_novo_m.unwrap_or(0.0),
        ended_in_fault,
    }))
}
