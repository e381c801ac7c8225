//! `[calendar]`: uplinks, weekend plans and restricted sols computed from Mars time and the
//! team's rules ([`TeamRules`], checked by [`TeamRules::validate`]) over the scenario's
//! sols, with what `[[sols]]` types over them ([`ComputedCalendar`]).

use sim::operations::ops_calendar::{ComputedSol, TeamRules};

use super::raw::{RawCalendar, RawSol};
use crate::check::FieldCheck;
use crate::error::ScenarioError;

/// Largest sol a computed calendar covers (Mars time is good for any; this bounds the work).
const MAX_COMPUTED_SOL: u32 = 20_000;

/// A calendar computed from Mars time and the team's rules (`[calendar]`), and what the
/// scenario typed over it.
#[derive(Debug, Clone, PartialEq)]
pub struct ComputedCalendar {
    /// The rules.
    pub rules: TeamRules,
    /// What they give, per sol of the scenario.
    pub sols: Vec<ComputedSol>,
    /// Typed per-sol values that replace the computed ones (historic inputs): (sol, field,
    /// value).
    pub overrides: Vec<(u32, &'static str, bool)>,
}

/// The file's name of a [`TeamRules`] field: its key in `[calendar]` (a time in Pasadena
/// without the `_h` of the hours it holds).
fn toml_path(field: &str) -> String {
    let key = field
        .strip_suffix("_pt_h")
        .map_or_else(|| field.to_owned(), |shift| format!("{shift}_pt"));
    format!("calendar.{key}")
}

/// `"HH:MM"` in Pasadena as hours after midnight.
fn pasadena_clock(c: &FieldCheck<'_>, field: &str, v: &str) -> Result<f64, ScenarioError> {
    sim::time::SolSeconds::parse_lmst(v)
        .filter(|_| v < "24:00")
        .map(|_| {
            let (h, m) = v.split_at(2);
            f64::from(h.parse::<u32>().unwrap_or(0))
                + f64::from(m[1..].parse::<u32>().unwrap_or(0)) / 60.0
        })
        .ok_or_else(|| {
            c.err(
                field,
                "a time of day in Pasadena \"HH:MM\", 00:00 to 23:59",
                format!("{v:?}"),
            )
        })
}

/// The `[calendar]` table: the team's rules (defaults of [`TeamRules::for_mission`] where not
/// given), computed over the scenario's sols, with the typed `uplink` / `restricted` values
/// of `[[sols]]` recorded as overrides.
///
/// # Errors
/// A [`ScenarioError`] naming the first `calendar.…` field at fault, or a sol beyond
/// [`MAX_COMPUTED_SOL`].
pub(crate) fn computed_calendar(
    c: &FieldCheck<'_>,
    raw: &RawCalendar,
    sols: &[RawSol],
) -> Result<ComputedCalendar, ScenarioError> {
    if raw.mission != "mars2020" {
        return Err(c.err(
            "calendar.mission",
            "\"mars2020\" (the mission whose Mars time and landing sol solsim knows)",
            format!("{:?}", raw.mission),
        ));
    }
    let Some(first) = sols.first() else {
        return Err(c.err("sols", "at least one [[sols]] entry", "none"));
    };
    let mut rules = TeamRules::for_mission(sim::time::mars_time::MARS_2020, 2020..=2040);
    if let Some(t) = &raw.uplink_lmst {
        rules.uplink_lmst = c.lmst("calendar.uplink_lmst", t)?;
    }
    if let Some(t) = &raw.relay_pass_lmst {
        rules.relay_pass_lmst = c.lmst("calendar.relay_pass_lmst", t)?;
    }
    rules.relay_latency_h = raw.relay_latency_h.unwrap_or(rules.relay_latency_h);
    rules.light_time_min = raw.light_time_min.unwrap_or(rules.light_time_min);
    rules.shift_hours = raw.shift_hours.unwrap_or(rules.shift_hours);
    // The numbers are checked before the shift start times are parsed (the order the loader
    // has always reported two bad values in); the default start times pass, and the checks run
    // again once the file's start times are in.
    rules.validate().map_err(|e| c.setting(e, toml_path))?;
    if let Some(t) = &raw.shift_earliest_start_pt {
        rules.shift_earliest_start_pt_h = pasadena_clock(c, "calendar.shift_earliest_start_pt", t)?;
    }
    if let Some(t) = &raw.shift_latest_start_pt {
        rules.shift_latest_start_pt_h = pasadena_clock(c, "calendar.shift_latest_start_pt", t)?;
    }
    rules.validate().map_err(|e| c.setting(e, toml_path))?;
    for (i, d) in raw.holidays.iter().enumerate() {
        let day = sim::time::earth_time::Utc::parse_iso(&format!("{d}T12:00:00Z"))
            .filter(|_| d.len() == 10)
            .ok_or_else(|| {
                c.err(
                    &format!("calendar.holidays[{i}]"),
                    "a date \"YYYY-MM-DD\"",
                    format!("{d:?}"),
                )
            })?;
        rules.holidays.push(day.civil_day(0.0));
    }
    if let Some((i, s)) = sols
        .iter()
        .enumerate()
        .find(|(_, s)| s.sol > MAX_COMPUTED_SOL)
    {
        return Err(c.err(
            &format!("sols[{i}].sol"),
            format!("a sol within {MAX_COMPUTED_SOL} of landing for a computed calendar"),
            s.sol,
        ));
    }
    // One computed sol per entry from the first on: entries that are not consecutive are the
    // calendar's error, reported in order by the caller.
    let count = u32::try_from(sols.len()).unwrap_or(u32::MAX);
    let computed = rules.compute(first.sol..=first.sol.saturating_add(count - 1));
    let overrides = sols
        .iter()
        .flat_map(|s| {
            [
                s.uplink.map(|v| (s.sol, "uplink", v)),
                s.restricted.map(|v| (s.sol, "restricted", v)),
                s.downlink.map(|v| (s.sol, "downlink", v)),
                s.drive.map(|v| (s.sol, "drive", v)),
            ]
        })
        .flatten()
        .collect();
    Ok(ComputedCalendar {
        rules,
        sols: computed,
        overrides,
    })
}
