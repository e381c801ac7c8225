//! What each operations strategy decides, in one place (paper 000 §2, §8; DESIGN.md,
//! "Operations strategies, precisely").
//!
//! | strategy | plans ([`PlanStyle`]) | skips or cuts a drive when | localizes |
//! |---|---|---|---|
//! | `replay` | the record's sols | the record did not drive | ground, when it has the data |
//! | `ground` | ground-in-the-loop | the ground does not know where the rover is; the sol's panorama would reach Earth after the next plan is built (skipped); the plan's last drive must end before its afternoon pass to downlink the panorama (cut) | ground, at each uplink that has the data |
//! | `onboard` | self-localized: every sol the calendar allows, the previous plan's path continued when the ground has not seen the last drive | never for the panorama | onboard after every drive sol; ground when it has the data |
//! | `extension` | opportunistic extension: breadcrumbs at every uplink | after `max_extension_sols` sols without a localization | ground, when it has the data |
//! | `extension+onboard` | opportunistic extension | never for localization | onboard after every drive sol; ground when it has the data |
//!
//! Every strategy stops after the route's end, on the calendar's no-drive sols (the replay
//! follows its record instead), and after a fault until the ground has seen it.
//! [`crate::campaign::run_campaign`] asks the policy at each uplink ([`Policy::plan`]) and each
//! sol ([`Policy::skip_reason`], [`Policy::drive_budget`]); it holds no `if strategy == …` of
//! its own.

use crate::autonav::{DriveLimits, VoSource};
use crate::calendar::{Calendar, SolEntry};
use crate::outcome::SkipReason;
use crate::strategy::Strategy;

/// How a strategy's plans choose their drive sols.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PlanStyle {
    /// The historic record: a sol drives if the record drove, as far as the record drove.
    Record,
    /// Ground-in-the-loop (today's practice): plan only from a ground-localized position; drive
    /// only sols whose post-drive data reaches Earth before the next plan is built; the plan's
    /// last drive ends in time for its panorama to go down on an afternoon pass.
    GroundInTheLoop,
    /// Onboard localization after every drive (paper 000 §8's initial deployment): no drive is
    /// skipped or cut to get a panorama down; where the ground has not seen the last drive the
    /// plan continues the previous plan's commanded path.
    SelfLocalized,
    /// Opportunistic extension (paper 000 §8): waypoint breadcrumbs appended at every uplink
    /// without knowing where the rover ended; every sol the calendar allows drives.
    Extension,
}

/// A strategy's decisions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Policy {
    /// The strategy.
    pub strategy: Strategy,
    /// How its plans choose their drive sols.
    pub style: PlanStyle,
    /// Whether the rover localizes itself after every drive sol.
    pub localizes_onboard: bool,
    /// Extension drives without a localization stop after this many sols (`extension` only).
    pub extension_cap_sols: Option<u32>,
}

/// The drive sols of one plan.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanDrives {
    /// Per sol of the plan (from its uplink up to the next): `None` if it may drive, else why
    /// not.
    pub reasons: Vec<Option<SkipReason>>,
    /// The calendar index of the sol whose drive must end before its afternoon pass so the
    /// panorama reaches the ground for the next plan.
    pub panorama_sol: Option<usize>,
}

/// What a sol's skip decision needs to know of the run so far.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunSoFar {
    /// The end of the route was reached.
    pub goal_reached: bool,
    /// A fault halted driving and the ground has not yet seen it.
    pub halted_by_fault: bool,
    /// Sols driven since the last applied localization (ground or onboard).
    pub sols_since_localization: u32,
}

impl Policy {
    /// The policy of `strategy`; `max_extension_sols` caps extension drives without
    /// localization.
    #[must_use]
    pub fn new(strategy: Strategy, max_extension_sols: u32) -> Self {
        let (style, cap) = match strategy {
            Strategy::Replay => (PlanStyle::Record, None),
            Strategy::Ground => (PlanStyle::GroundInTheLoop, None),
            Strategy::Onboard => (PlanStyle::SelfLocalized, None),
            Strategy::Extension => (PlanStyle::Extension, Some(max_extension_sols)),
            Strategy::ExtensionOnboard => (PlanStyle::Extension, None),
        };
        Self {
            strategy,
            style,
            localizes_onboard: strategy.onboard_localization(),
            extension_cap_sols: cap,
        }
    }

    /// The drive sols of the plan uplinked at calendar index `first` (it runs up to the next
    /// uplink, `next_uplink`); `ground_knows`: the last drive's post-drive data reached the
    /// ground in time for this plan.
    #[must_use]
    pub fn plan(
        &self,
        cal: &Calendar,
        first: usize,
        next_uplink: Option<usize>,
        ground_knows: bool,
    ) -> PlanDrives {
        let span = first..next_uplink.unwrap_or(cal.sols.len());
        match self.style {
            PlanStyle::Record => PlanDrives {
                reasons: cal.sols[span]
                    .iter()
                    .map(|e| match e.historic {
                        Some(h) if h.distance_m > 0.0 => None,
                        _ => Some(SkipReason::NoHistoricDrive),
                    })
                    .collect(),
                panorama_sol: None,
            },
            PlanStyle::SelfLocalized | PlanStyle::Extension => PlanDrives {
                reasons: vec![None; span.len()],
                panorama_sol: None,
            },
            PlanStyle::GroundInTheLoop if !ground_knows => PlanDrives {
                reasons: vec![Some(SkipReason::AwaitingPostDriveData); span.len()],
                panorama_sol: None,
            },
            PlanStyle::GroundInTheLoop => {
                // Drive up to the last sol whose post-drive data reaches Earth before the next
                // plan.
                let last = span
                    .clone()
                    .rev()
                    .find(|&j| cal.sols[j].drive_allowed && cal.data_available(j, next_uplink));
                PlanDrives {
                    reasons: span
                        .map(|j| {
                            if last.is_some_and(|l| j <= l) {
                                None
                            } else {
                                Some(SkipReason::DataTooLateForNextPlan)
                            }
                        })
                        .collect(),
                    panorama_sol: last,
                }
            }
        }
    }

    /// Why the rover does not drive on `entry` (`None`: it drives), given the plan's own
    /// reason for the sol and the run so far. In order: the route is complete, the calendar
    /// allows no drive (not for the replay, which follows its record), a fault halted driving,
    /// the plan skips the sol, the extension cap is reached.
    #[must_use]
    pub fn skip_reason(
        &self,
        entry: &SolEntry,
        plan_reason: Option<SkipReason>,
        run: RunSoFar,
    ) -> Option<SkipReason> {
        if run.goal_reached {
            Some(SkipReason::RouteComplete)
        } else if !entry.drive_allowed && self.style != PlanStyle::Record {
            Some(SkipReason::NoDriveInCalendar)
        } else if run.halted_by_fault {
            Some(SkipReason::HaltedAfterFault)
        } else if plan_reason.is_some() {
            plan_reason
        } else {
            self.extension_cap_sols
                .filter(|&cap| run.sols_since_localization >= cap)
                .map(|cap| SkipReason::ExtensionLimit {
                    sols_without_localization: cap,
                })
        }
    }

    /// The sol's drive budget and where VO comes from: the drive `window` and the terrain, or
    /// for the replay the record's distance and its fraction without VO. A historic fault must
    /// emerge from the geometry, so a replayed sol that faulted drives the window.
    #[must_use]
    pub fn drive_budget(&self, entry: &SolEntry, window: DriveLimits) -> (DriveLimits, VoSource) {
        match (self.style, entry.historic) {
            (PlanStyle::Record, Some(h)) => (
                if h.ended_in_fault {
                    window
                } else {
                    DriveLimits {
                        max_distance_m: Some(h.distance_m),
                        max_time_s: None,
                    }
                },
                VoSource::Historic {
                    novo_fraction: if h.distance_m > 0.0 {
                        h.novo_m / h.distance_m
                    } else {
                        0.0
                    },
                },
            ),
            _ => (window, VoSource::Terrain),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::time::SolSeconds;

    use crate::calendar::test_sol as sol;

    /// Paper 000 §8, sols 404-406: a weekend plan uplinked on 404, no pass on 406, restricted.
    fn weekend() -> Calendar {
        Calendar {
            sols: vec![
                sol(404, true, true, true),
                sol(405, false, true, true),
                sol(406, false, true, false),
                sol(407, true, true, true),
            ],
            drive_start: SolSeconds(0),
            drive_end: SolSeconds(1),
        }
    }

    #[test]
    fn ground_skips_the_sol_whose_panorama_cannot_reach_earth_and_onboard_does_not() {
        let cal = weekend();
        let next = cal.next_uplink_after(0);
        let ground = Policy::new(Strategy::Ground, 3).plan(&cal, 0, next, true);
        assert_eq!(
            ground.reasons,
            vec![None, None, Some(SkipReason::DataTooLateForNextPlan)]
        );
        assert_eq!(ground.panorama_sol, Some(1));
        for s in [
            Strategy::Onboard,
            Strategy::ExtensionOnboard,
            Strategy::Extension,
        ] {
            let p = Policy::new(s, 3).plan(&cal, 0, next, false);
            assert_eq!(p.reasons, vec![None; 3], "{s}");
            assert_eq!(p.panorama_sol, None, "{s}");
        }
        // Without the last drive's data the ground cannot plan at all.
        let blind = Policy::new(Strategy::Ground, 3).plan(&cal, 0, next, false);
        assert_eq!(
            blind.reasons,
            vec![Some(SkipReason::AwaitingPostDriveData); 3]
        );
    }

    #[test]
    fn only_extension_without_onboard_localization_is_capped() {
        let entry = sol(408, false, true, true);
        let run = RunSoFar {
            goal_reached: false,
            halted_by_fault: false,
            sols_since_localization: 3,
        };
        for s in Strategy::ALL {
            let got = Policy::new(s, 3).skip_reason(&entry, None, run);
            let capped = s == Strategy::Extension;
            assert_eq!(got.is_some(), capped, "{s}: {got:?}");
        }
    }
}
