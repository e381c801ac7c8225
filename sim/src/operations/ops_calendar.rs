//! The operations calendar computed from Mars time and the planning team's working rules, not
//! typed in.
//!
//! Mars time slips about 40 minutes a day against Earth time, so when a sol's post-drive data
//! reaches Earth moves through the team's working day in Pasadena; for up to two weeks a month it
//! arrives too late for the next plan: those sols are **restricted** (paper 000 §8). The rules
//! ([`TeamRules`]), applied to every sol:
//!
//! 1. **The deadline.** Sol `s`'s plan must be on the ground's transmitter by `uplink_lmst` on
//!    sol `s` minus the one-way light time allowance.
//! 2. **The planning day.** Shifts are worked on weekdays that are not holidays, from
//!    `shift_earliest_start_pt` for `shift_hours`. Sol `s` is planned on the latest working day
//!    whose shift, started at the earliest, ends before the deadline. Sols that share a
//!    planning day share one plan, uplinked on the first of them: the weekend plan of a Friday
//!    covers the sols whose planning day would fall on Saturday and Sunday (three sols, paper
//!    000 §8's 404-406; a holiday adds one).
//! 3. **The data.** A sol's post-drive data goes down on the afternoon relay pass at
//!    `relay_pass_lmst` and is on Earth, processed, `relay_latency_h` plus the light time later.
//! 4. **Restricted.** A planning shift may start as late as `shift_latest_start_pt` (and no later
//!    than its deadline allows); the plan of sol `s` is restricted when the previous sol's data
//!    arrives after that.
//!
//! Which sols the data of a drive reaches in time for is then [`crate::operations::calendar::Calendar`]'s
//! business (`data_available`); which sols `ground` drives follows from it
//! ([`crate::operations::policy`]). What the rules cannot know stays a typed, historic input of the
//! scenario: a sol without a relay pass (paper 000 §8: none on sol 406), a science stop.
//!
//! The defaults and what they rest on are in [`TeamRules`]'s field docs ([`TeamRules::for_mission`]). Times of day in
//! Pasadena are US Pacific time with daylight saving ([`crate::time::earth_time::pacific_offset_h`]).

use std::ops::RangeInclusive;

use crate::settings::field_error::FieldError;
use crate::settings::physical_range::PhysicalRange;
use crate::time::SolSeconds;
use crate::time::earth_time::{DAY_S, Utc, Weekday, pacific_offset_h, us_federal_holidays};
use crate::time::mars_time::Mission;

/// The planning team's working rules. Times of day in Pasadena are hours after local midnight.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TeamRules {
    /// The mission: sols and LMST.
    pub mission: Mission,
    /// When a sol's plan must be aboard, LMST (default 09:00: the rover wakes for the day's plan
    /// in the morning; the record's drives start 11:30-12:55 LMST after the morning's activities).
    pub uplink_lmst: SolSeconds,
    /// One-way light time allowed for, minutes (default 22: the largest Earth-Mars light time,
    /// at superior conjunction; the rules do not follow the distance).
    pub light_time_min: f64,
    /// The afternoon relay pass that carries the post-drive data, LMST (default 17:00: after the
    /// latest drive end of the record's sols 379-409, 16:08 LMST on sol 382, and the 30-minute
    /// post-drive imaging).
    pub relay_pass_lmst: SolSeconds,
    /// From the pass to the data on the ground ready to plan with, hours, besides light time
    /// (default 1.0: the relay orbiter's next Deep Space Network contact and processing;
    /// calibrated with `shift_latest_start_pt`, see there).
    pub relay_latency_h: f64,
    /// Earliest start of a planning shift in Pasadena, hours (default 6.0).
    pub shift_earliest_start_pt_h: f64,
    /// Latest start of a planning shift in Pasadena, hours (default 17.15, 17:09). Calibrated,
    /// with `relay_latency_h`, to paper 000 §8's week of sols 402-409: the plan of 402 (built on
    /// Wednesday) started from 401's drive, the 404-406 weekend plan from 402's but not 403's,
    /// and the plans of 408 and 409 did not know where the previous drive ended. Those facts
    /// hold for any latest start from 16:49 to 17:28 (401's and 402's data on the ground) with
    /// this latency; 17:09 is in the middle (`tests::paper_week_emerges`).
    pub shift_latest_start_pt_h: f64,
    /// How long a planning shift takes, hours (default 10).
    pub shift_hours: f64,
    /// Days without a shift besides weekends, as days since 1970-01-01 in Pasadena (default: the
    /// US federal holidays as observed, 5 U.S.C. 6103, a stand-in for JPL's own schedule).
    pub holidays: Vec<i64>,
}

impl TeamRules {
    /// The default rules for `mission`, with the US federal holidays of `years`.
    #[must_use]
    pub fn for_mission(mission: Mission, years: RangeInclusive<i64>) -> Self {
        Self {
            mission,
            uplink_lmst: SolSeconds::from_lmst(9, 0).unwrap_or(SolSeconds(33_291)),
            light_time_min: 22.0,
            relay_pass_lmst: SolSeconds::from_lmst(17, 0).unwrap_or(SolSeconds(62_882)),
            relay_latency_h: 1.0,
            shift_earliest_start_pt_h: 6.0,
            shift_latest_start_pt_h: 17.15,
            shift_hours: 10.0,
            holidays: years.flat_map(us_federal_holidays).collect(),
        }
    }

    /// The delays and shift lengths within a day the rules may have, hours (`relay_latency_h`,
    /// `shift_hours`).
    pub const HOURS_RANGE: PhysicalRange = PhysicalRange::new(0.0, 24.0, "hours");
    /// The one-way light times the rules may allow for, minutes: Earth-Mars one-way light time
    /// is 3-22 minutes.
    pub const LIGHT_TIME_RANGE_MIN: PhysicalRange = PhysicalRange::new(0.0, 30.0, "minutes");

    /// Checks the delays and the shift length against their ranges, and that a shift's latest
    /// start is not before its earliest.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field at fault.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::HOURS_RANGE.check("relay_latency_h", self.relay_latency_h)?;
        Self::LIGHT_TIME_RANGE_MIN.check("light_time_min", self.light_time_min)?;
        Self::HOURS_RANGE.check("shift_hours", self.shift_hours)?;
        if self.shift_latest_start_pt_h < self.shift_earliest_start_pt_h {
            return Err(FieldError::new(
                "shift_latest_start_pt_h",
                "a time at or after shift_earliest_start_pt_h",
                format!("{:.2} h", self.shift_latest_start_pt_h),
            )
            .naming("shift_earliest_start_pt_h"));
        }
        Ok(())
    }
}

/// Why a sol has no plan of its own, or why its plan is restricted.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ComputedSol {
    /// Mission sol.
    pub sol: u32,
    /// The deadline for its plan (UTC).
    pub deadline: Utc,
    /// Its planning day in Pasadena, days since 1970-01-01.
    pub planning_day: i64,
    /// That day's weekday.
    pub planning_weekday: Weekday,
    /// A plan is uplinked for this sol (false: the plan of an earlier sol covers it).
    pub uplink: bool,
    /// When this sol's post-drive data is on the ground (UTC).
    pub data_on_ground: Utc,
    /// The latest start of the shift that plans this sol (UTC).
    pub shift_latest_start: Utc,
    /// The previous sol's data arrives after that start.
    pub restricted: bool,
}

impl ComputedSol {
    /// The planning day as `YYYY-MM-DD Www`.
    #[must_use]
    pub fn planning_day_text(&self) -> String {
        let (y, m, d) = crate::time::earth_time::civil_from_days(self.planning_day);
        format!("{y:04}-{m:02}-{d:02} {}", self.planning_weekday.short())
    }
}

fn pasadena_day(t: Utc) -> i64 {
    t.civil_day(pacific_offset_h(t))
}

/// The instant `hours` after midnight in Pasadena on `day`.
fn pasadena_time(day: i64, hours: f64) -> Utc {
    // Midnight's offset holds for the day but on the two switch days (02:00): good to an hour
    // there, exact on every other.
    let guess = Utc(day as f64 * DAY_S + hours * 3600.0 + 8.0 * 3600.0);
    Utc(day as f64 * DAY_S + hours * 3600.0 - pacific_offset_h(guess) * 3600.0)
}

impl TeamRules {
    fn is_working_day(&self, day: i64) -> bool {
        !Weekday::of_days(day).is_weekend() && !self.holidays.contains(&day)
    }

    fn light_time_s(&self) -> f64 {
        self.light_time_min * 60.0
    }

    /// The deadline of sol `sol`'s plan.
    #[must_use]
    pub fn deadline(&self, sol: u32) -> Utc {
        self.mission
            .utc_at(i64::from(sol), self.uplink_lmst)
            .plus_s(-self.light_time_s())
    }

    /// When sol `sol`'s post-drive data is on the ground.
    #[must_use]
    pub fn data_on_ground(&self, sol: u32) -> Utc {
        self.mission
            .utc_at(i64::from(sol), self.relay_pass_lmst)
            .plus_s(self.light_time_s() + self.relay_latency_h * 3600.0)
    }

    /// The planning day of sol `sol`: the latest working day whose shift, started at the
    /// earliest, ends before the deadline.
    #[must_use]
    pub fn planning_day(&self, sol: u32) -> i64 {
        let deadline = self.deadline(sol);
        let mut day = pasadena_day(deadline);
        // At most a fortnight of holidays and weekends back.
        for _ in 0..14 {
            let end = pasadena_time(day, self.shift_earliest_start_pt_h + self.shift_hours);
            if self.is_working_day(day) && end <= deadline {
                return day;
            }
            day -= 1;
        }
        day
    }

    /// The calendar of `sols` under these rules.
    #[must_use]
    pub fn compute(&self, sols: RangeInclusive<u32>) -> Vec<ComputedSol> {
        let mut out: Vec<ComputedSol> = Vec::new();
        for sol in sols {
            let deadline = self.deadline(sol);
            let planning_day = self.planning_day(sol);
            let shift_latest_start = Utc(pasadena_time(planning_day, self.shift_latest_start_pt_h)
                .0
                .min(deadline.0 - self.shift_hours * 3600.0));
            let uplink = out.last().is_none_or(|p| p.planning_day != planning_day);
            let restricted = sol > 0 && self.data_on_ground(sol - 1) > shift_latest_start;
            out.push(ComputedSol {
                sol,
                deadline,
                planning_day,
                planning_weekday: Weekday::of_days(planning_day),
                uplink,
                data_on_ground: self.data_on_ground(sol),
                shift_latest_start,
                restricted,
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::time::mars_time::MARS_2020;

    /// Paper 000 §8's week: a Wednesday plan for 402, a Friday weekend plan for 404-406, plans
    /// on 407, 408 and 409; 402's plan knows 401's drive, the weekend plan does not know 403's,
    /// 408's and 409's do not know the drive before.
    #[test]
    fn paper_week_emerges() {
        let rules = TeamRules::for_mission(MARS_2020, 2022..=2022);
        let cal = rules.compute(396..=410);
        let at = |sol: u32| &cal[(sol - 396) as usize];
        for c in &cal {
            eprintln!(
                "sol {} planned {} uplink {} restricted {} data {} shift latest {}",
                c.sol,
                c.planning_day_text(),
                c.uplink,
                c.restricted,
                c.data_on_ground,
                c.shift_latest_start
            );
        }
        assert_eq!(at(402).planning_weekday, Weekday::Wednesday);
        assert!(at(402).uplink && !at(402).restricted);
        assert_eq!(at(404).planning_weekday, Weekday::Friday);
        assert!(at(404).uplink && at(404).restricted);
        assert!(!at(405).uplink && !at(406).uplink);
        for sol in [407, 408, 409] {
            assert!(at(sol).uplink, "{sol}");
        }
        assert!(at(408).restricted && at(409).restricted);
        // The weekend before: a Friday plan for 397-399, Monday's for 400, which knows 399's.
        assert!(at(397).uplink && !at(398).uplink && !at(399).uplink);
        assert!(at(400).uplink && !at(400).restricted);
    }
}
