//! What each operations strategy decides, in one place (paper 000 §2, §8;
//! docs/design.md, "Operations strategies, precisely").
//!
//! | strategy | plans ([`PlanStyle`]) | skips or cuts a drive when | localizes |
//! |---|---|---|---|
//! | `replay` | the record's sols | the record did not drive | ground, when it has the data |
//! | `ground` | ground-in-the-loop, at most `max_drive_sols_per_plan` drive sols a plan | the ground does not know where the rover is; the sol's panorama would reach Earth after the next plan is built (skipped); the plan's last drive must end before its afternoon pass to downlink the panorama (cut); the predicted radius would close a passage ahead (shortened, paper 000 §2) | ground, at each uplink that has the data |
//! | `onboard` | self-localized: every sol the calendar allows, at most `max_drive_sols_per_plan` a plan, the previous plan's path continued when the ground has not seen the last drive | never for the panorama; the passage limit only binds after a rejected onboard localization | onboard after every drive sol; ground when it has the data |
//! | `extension` | opportunistic extension: breadcrumbs for `extension_plan_sols` sols, or over a gap without uplinks | the predicted radius from the last ground fix would close a passage ahead: the extension limit emerges; the optional `max_extension_sols` cap | ground, when it has the data |
//! | `extension+onboard` | opportunistic extension | never for localization (as `onboard` for the passage limit) | onboard after every drive sol; ground when it has the data |
//!
//! The passage limit ([`Policy::passage_budget`]) is one computation for all of them: the
//! odometry the rover may drive from the last localization before the radius, growing at the
//! VO rate along the route, reaches the clearance of a passage still ahead on its leg.
//!
//! Every strategy stops after the route's end, on the calendar's no-drive sols (the replay
//! follows its record instead), and after a fault until the ground has seen it.
//! [`crate::run::Simulation`] asks the policy at each uplink ([`Policy::plan`]) and each
//! sol ([`Policy::skip_reason`], [`Policy::drive_budget`]); it holds no `if strategy == …` of
//! its own.

use crate::operations::calendar::{Calendar, SolEntry};
use crate::operations::strategy::Strategy;
use crate::rover::autonav::{DriveLimits, VoSource};
use crate::run::outcome::{PassageLimit, SkipReason};
use crate::settings::field_error::FieldError;
use crate::settings::physical_range::{MARGIN_M, PhysicalRange};

mod passages;

pub use passages::{PassagesAhead, RoutePosition};

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

/// The operations rules every strategy plans under (the scenario's `[operations]`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct OperationsRules {
    /// An optional cap on extension drives without a localization, sols (`extension` only;
    /// default none: the limit emerges from the passages ahead; range
    /// [`OperationsRules::SOLS_RANGE`]).
    pub max_extension_sols: Option<u32>,
    /// Drive sols one ground or self-localized plan commands at most (default 3, historic
    /// practice: the longest plans of the record drive three sols, e.g. 383-385 and the
    /// weekend plans).
    pub max_drive_sols_per_plan: u32,
    /// Sols of breadcrumbs one extension plan lays (default 3: paper 000 §8, "if the operations
    /// team had planned the entire 407-409 drive in just the 407 uplink"); an uplink inside
    /// them needs no new drive plan.
    pub extension_plan_sols: u32,
    /// Planners shorten a drive when the predicted radius comes within this of a passage's
    /// clearance, metres (default 0: shortened when the prediction closes it; range
    /// [`crate::settings::physical_range::MARGIN_M`]).
    pub passage_margin_m: f64,
    /// Sols `ground` drives at most without the ground knowing where the rover is, by
    /// opportunistic extension in one-sol plans (default 3: today's practice, the longest such
    /// extension flown, sols 407-409, paper 000 §8: "we do not expect to be able to extend
    /// these plans for more than three sols").
    pub ground_extension_sols: u32,
    /// Plans `ground` looks ahead when it chooses a plan's drive sols (default 6, a week of
    /// plans): it drives the sols that give the most drive sols over them (paper 000 §8:
    /// "driving on sol 403 would thus have resulted in not being able to drive on sols 404 and
    /// 405").
    pub ground_lookahead_plans: u32,
    /// Whether plans stop short of a passage the predicted radius would close (default true:
    /// paper 000 §2's pre-emptive shortening, and the extension limit of §8). Off, every
    /// strategy drives into such passages and meets the `NO_PATH` faults that follow.
    pub preemptive_shortening: bool,
}

impl OperationsRules {
    /// The plan lengths and sol caps a rule may have, sols: one at least; at most the sols a
    /// calendar holds ([`Calendar::MAX_SOLS`]).
    pub const SOLS_RANGE: PhysicalRange =
        PhysicalRange::new(1.0, Calendar::MAX_SOLS as f64, "sols");
    /// The plans `ground` may look ahead: the next one at least; at most 12 (two weeks of
    /// plans), since the search over every plan's choices is exhaustive and its work
    /// multiplies with each plan looked ahead.
    pub const LOOKAHEAD_RANGE_PLANS: PhysicalRange = PhysicalRange::new(1.0, 12.0, "plans");

    /// Checks each rule against its range, in the order of the scenario file's
    /// `[operations]` (`ground_extension_sols` may be 0: no blind drives).
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        let sols = |field: &str, v: u32| Self::SOLS_RANGE.check(field, f64::from(v)).map(drop);
        if let Some(v) = self.max_extension_sols {
            sols("max_extension_sols", v)?;
        }
        sols("max_drive_sols_per_plan", self.max_drive_sols_per_plan)?;
        sols("extension_plan_sols", self.extension_plan_sols)?;
        MARGIN_M.check("passage_margin_m", self.passage_margin_m)?;
        if self.ground_extension_sols != 0 {
            sols("ground_extension_sols", self.ground_extension_sols)?;
        }
        Self::LOOKAHEAD_RANGE_PLANS.check(
            "ground_lookahead_plans",
            f64::from(self.ground_lookahead_plans),
        )?;
        Ok(())
    }
}

impl Default for OperationsRules {
    fn default() -> Self {
        Self {
            max_extension_sols: None,
            max_drive_sols_per_plan: 3,
            extension_plan_sols: 3,
            passage_margin_m: 0.0,
            preemptive_shortening: true,
            ground_extension_sols: 3,
            ground_lookahead_plans: 6,
        }
    }
}

/// The sols of the plan `first..end` the ground may command a drive on: driving is allowed and a
/// downlink pass at or after the sol, before the next plan, can carry its post-drive data (the
/// team does not drive a rover it cannot hear from: paper 000 §8's sol 406, "no communication
/// pass to send data to Earth on 406"; a conjunction).
fn ground_drivable(cal: &Calendar, first: usize, end: usize) -> Vec<usize> {
    (first..end)
        .filter(|&j| cal.sols[j].drive_allowed && (j..end).any(|t| cal.sols[t].downlink))
        .collect()
}

/// What the ground knows when it builds a plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct GroundKnowledge {
    /// The last drive's post-drive data is on Earth for this plan (or nothing drove yet).
    pub knows_position: bool,
    /// Calendar index of the last sol that drove.
    pub last_drive: Option<usize>,
    /// Sols driven since the last position the ground knew when it built a plan.
    pub drives_since_known: u32,
}

impl GroundKnowledge {
    /// What the ground knows at a plan uplinked with everything in hand.
    #[must_use]
    pub fn everything() -> Self {
        Self {
            knows_position: true,
            last_drive: None,
            drives_since_known: 0,
        }
    }
}

/// A strategy's decisions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Policy {
    /// The strategy.
    pub strategy: Strategy,
    /// How its plans choose their drive sols.
    pub style: PlanStyle,
    /// Whether the rover localizes itself after every drive sol.
    pub localizes_onboard: bool,
    /// Whether drives stop before a passage the predicted uncertainty would close (every
    /// strategy but the replay). For onboard strategies the rover checks the plan's passage
    /// limits against its own last applied localization, so a rejected localization stops it
    /// short instead of driving into a `NO_PATH`.
    pub plans_around_passages: bool,
    /// The rules it plans under.
    pub rules: OperationsRules,
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
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunSoFar {
    /// The end of the route was reached.
    pub goal_reached: bool,
    /// A fault halted driving and the ground has not yet seen it.
    pub halted_by_fault: bool,
    /// Sols driven since the last applied localization (ground or onboard).
    pub sols_since_localization: u32,
    /// The passage limit of the current plan ([`Policy::passage_budget`]), if one binds.
    pub passage: Option<PassageLimit>,
    /// Odometry since the last localization the planners know of, metres.
    pub driven_since_fix_m: f64,
}

/// A drive shorter than this is not worth commanding, metres (one AutoNav step of the
/// default 2 m).
const MIN_DRIVE_M: f64 = 2.0;

impl Policy {
    /// The policy of `strategy` under `rules`.
    #[must_use]
    pub fn new(strategy: Strategy, rules: OperationsRules) -> Self {
        let style = match strategy {
            Strategy::Replay => PlanStyle::Record,
            Strategy::Ground => PlanStyle::GroundInTheLoop,
            Strategy::Onboard => PlanStyle::SelfLocalized,
            Strategy::Extension | Strategy::ExtensionOnboard => PlanStyle::Extension,
        };
        let localizes_onboard = strategy.onboard_localization();
        Self {
            strategy,
            style,
            localizes_onboard,
            plans_around_passages: style != PlanStyle::Record && rules.preemptive_shortening,
            rules,
        }
    }

    /// Sols of the calendar one plan uplinked at `first` covers with commanded drives or
    /// breadcrumbs, up to the next uplink: extension plans lay `extension_plan_sols` sols of
    /// breadcrumbs, or enough to reach the next uplink (a conjunction plan covers the whole
    /// gap); other plans command at most `max_drive_sols_per_plan` drive sols.
    #[must_use]
    pub fn breadcrumb_sols(&self, first: usize, next_uplink: Option<usize>, len: usize) -> usize {
        let to_next = next_uplink.unwrap_or(len) - first;
        match self.style {
            PlanStyle::Extension => to_next.max(self.rules.extension_plan_sols as usize),
            _ => to_next,
        }
    }

    /// The drive sols of the plan uplinked at calendar index `first` (it runs up to the next
    /// uplink, `next_uplink`); `known`: what the ground knows of the rover for this plan.
    #[must_use]
    pub fn plan(
        &self,
        cal: &Calendar,
        first: usize,
        next_uplink: Option<usize>,
        known: GroundKnowledge,
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
            PlanStyle::Extension => PlanDrives {
                reasons: vec![
                    None;
                    self.breadcrumb_sols(first, next_uplink, cal.sols.len())
                        .min(cal.sols.len() - first)
                ],
                panorama_sol: None,
            },
            PlanStyle::SelfLocalized => PlanDrives {
                reasons: self.cap_drive_sols(cal, span.clone(), vec![None; span.len()]),
                panorama_sol: None,
            },
            PlanStyle::GroundInTheLoop => self.ground_plan(cal, first, next_uplink, known),
        }
    }

    /// Today's practice, one plan: with the rover's position known, a prefix of the plan's
    /// drive sols (at most `max_drive_sols_per_plan`); without it, an opportunistic extension
    /// drive in a one-sol plan while fewer than `ground_extension_sols` sols have been driven
    /// since the last known position, and nothing in a plan of several sols (a weekend plan
    /// starts from a localized position). Of those choices the planners take the one that
    /// drives the most sols over the next `ground_lookahead_plans` plans, the drives of this
    /// plan breaking ties; a drive left out for that reason is
    /// [`SkipReason::CostsLaterDrives`].
    fn ground_plan(
        &self,
        cal: &Calendar,
        first: usize,
        next_uplink: Option<usize>,
        known: GroundKnowledge,
    ) -> PlanDrives {
        let end = next_uplink.unwrap_or(cal.sols.len());
        let plans = self.plans_from(
            cal,
            first,
            self.rules.ground_lookahead_plans.max(1) as usize,
        );
        let options = self.ground_options(cal, first, end, known);
        // (drive sols over the plans looked at, the next plan knows where the rover is, drive
        // sols of this plan): the most drives; on a tie, a localized start for the next plan
        // (the panorama the ground-in-the-loop practice drives for), then driving now.
        let scored: Vec<(u32, bool, u32)> = options
            .iter()
            .map(|&(drives, after)| {
                let knows_next = after
                    .last_drive
                    .is_none_or(|d| cal.data_available(d, next_uplink));
                (
                    drives + self.best_ground(cal, &plans[1..], after),
                    knows_next,
                    drives,
                )
            })
            .collect();
        let best = scored.iter().copied().max().unwrap_or((0, true, 0));
        let chosen = scored.iter().position(|&s| s == best).unwrap_or(0);
        let driven = options.get(chosen).map_or(0, |o| o.0);
        let allowed = ground_drivable(cal, first, end);
        let max_option = options.iter().map(|o| o.0).max().unwrap_or(0);
        let mut reasons = Vec::with_capacity(end - first);
        for j in first..end {
            let rank = allowed.iter().position(|&a| a == j);
            let blind = !known.knows_position && options.len() == 1;
            let reason = match rank {
                _ if !cal.sols[j].drive_allowed => Some(SkipReason::NoDriveInCalendar),
                Some(r) if (r as u32) < driven => None,
                _ if blind => Some(if end - first > 1 {
                    SkipReason::AwaitingPostDriveData
                } else {
                    SkipReason::ExtensionLimit {
                        sols_without_localization: self.rules.ground_extension_sols,
                    }
                }),
                None => Some(SkipReason::DataTooLateForNextPlan),
                Some(r) if r as u32 >= max_option && known.knows_position => {
                    Some(SkipReason::PlanDriveSolsUsed {
                        drive_sols: self.rules.max_drive_sols_per_plan,
                    })
                }
                Some(r) => {
                    // The best choice that drives this sol too.
                    let if_driven = options
                        .iter()
                        .zip(&scored)
                        .filter(|(o, _)| o.0 > r as u32)
                        .map(|(_, s)| s.0)
                        .max()
                        .unwrap_or(0);
                    Some(if if_driven < best.0 {
                        SkipReason::CostsLaterDrives {
                            if_driven,
                            if_skipped: best.0,
                        }
                    } else {
                        SkipReason::DataTooLateForNextPlan
                    })
                }
            };
            reasons.push(reason);
        }
        let panorama_sol = (first..end)
            .zip(&reasons)
            .rev()
            .find(|(_, r)| r.is_none())
            .map(|(j, _)| j);
        PlanDrives {
            reasons,
            panorama_sol,
        }
    }

    /// The ground's drive sols over the whole calendar when every commanded drive happens (no
    /// fault, no route end, no passage): why each sol does not drive, or `None`. What the
    /// calendar alone decides for today's practice, as `solsim record baseline` reports it.
    #[must_use]
    pub fn calendar_schedule(&self, cal: &Calendar) -> Vec<Option<SkipReason>> {
        let mut out = vec![Some(SkipReason::NoPlanUplinked); cal.sols.len()];
        let mut known = GroundKnowledge::everything();
        let mut at = (!cal.sols.is_empty()).then_some(0);
        while let Some(u) = at {
            let next = cal.next_uplink_after(u);
            let knows = known
                .last_drive
                .is_none_or(|d| cal.data_available(d, Some(u)));
            if knows {
                known.knows_position = true;
                known.drives_since_known = 0;
            } else {
                known.knows_position = false;
            }
            let plan = self.plan(cal, u, next, known);
            for (k, reason) in plan.reasons.iter().enumerate() {
                out[u + k] = *reason;
                if reason.is_none() {
                    known.last_drive = Some(u + k);
                    known.drives_since_known += 1;
                }
            }
            at = next;
        }
        out
    }

    /// The plans from the one uplinked at `first` on, at most `count`: (first, end) indices.
    fn plans_from(&self, cal: &Calendar, first: usize, count: usize) -> Vec<(usize, usize)> {
        let mut plans = Vec::with_capacity(count);
        let mut at = Some(first);
        while let Some(u) = at {
            if plans.len() == count {
                break;
            }
            let next = cal.next_uplink_after(u);
            plans.push((u, next.unwrap_or(cal.sols.len())));
            at = next;
        }
        plans
    }

    /// The ground's choices for the plan `first..end`: (drive sols, what it knows after).
    fn ground_options(
        &self,
        cal: &Calendar,
        first: usize,
        end: usize,
        known: GroundKnowledge,
    ) -> Vec<(u32, GroundKnowledge)> {
        let allowed = ground_drivable(cal, first, end);
        let after = |drives: u32, since: u32| GroundKnowledge {
            knows_position: false,
            last_drive: if drives == 0 {
                known.last_drive
            } else {
                Some(allowed[drives as usize - 1])
            },
            drives_since_known: since + drives,
        };
        if known.knows_position {
            let most = (allowed.len() as u32).min(self.rules.max_drive_sols_per_plan);
            (0..=most).map(|d| (d, after(d, 0))).collect()
        } else if end - first == 1
            && !allowed.is_empty()
            && known.drives_since_known < self.rules.ground_extension_sols
        {
            (0..=1)
                .map(|d| (d, after(d, known.drives_since_known)))
                .collect()
        } else {
            vec![(0, after(0, known.drives_since_known))]
        }
    }

    /// The most drive sols over `plans` from what the ground knows before the first.
    fn best_ground(
        &self,
        cal: &Calendar,
        plans: &[(usize, usize)],
        before: GroundKnowledge,
    ) -> u32 {
        let Some(&(first, end)) = plans.first() else {
            return 0;
        };
        let knows = before
            .last_drive
            .is_none_or(|d| cal.data_available(d, Some(first)));
        let known = if knows {
            GroundKnowledge {
                knows_position: true,
                last_drive: before.last_drive,
                drives_since_known: 0,
            }
        } else {
            before
        };
        self.ground_options(cal, first, end, known)
            .into_iter()
            .map(|(drives, after)| drives + self.best_ground(cal, &plans[1..], after))
            .max()
            .unwrap_or(0)
    }

    /// Keep the first `max_drive_sols_per_plan` sols of `span` that may drive; later ones skip.
    fn cap_drive_sols(
        &self,
        cal: &Calendar,
        span: std::ops::Range<usize>,
        mut reasons: Vec<Option<SkipReason>>,
    ) -> Vec<Option<SkipReason>> {
        let cap = self.rules.max_drive_sols_per_plan;
        let mut commanded = 0u32;
        for (j, reason) in span.zip(reasons.iter_mut()) {
            if reason.is_some() || !cal.sols[j].drive_allowed {
                continue;
            }
            if commanded >= cap {
                *reason = Some(SkipReason::PlanDriveSolsUsed { drive_sols: cap });
            } else {
                commanded += 1;
            }
        }
        reasons
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
        } else if let Some(cap) = self.rules.max_extension_sols.filter(|&cap| {
            self.strategy == Strategy::Extension && run.sols_since_localization >= cap
        }) {
            Some(SkipReason::ExtensionLimit {
                sols_without_localization: cap,
            })
        } else {
            run.passage
                .filter(|p| p.budget_since_fix_m - run.driven_since_fix_m < MIN_DRIVE_M)
                .map(SkipReason::PassageAhead)
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
    use crate::run::outcome::LegClearance;
    use crate::time::SolSeconds;

    use crate::operations::calendar::test_sol as sol;

    /// The ground has not seen the last drive.
    fn blind() -> GroundKnowledge {
        GroundKnowledge {
            knows_position: false,
            last_drive: None,
            drives_since_known: 0,
        }
    }

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
        let capped = OperationsRules::default();
        let ground = Policy::new(Strategy::Ground, OperationsRules::default()).plan(
            &cal,
            0,
            next,
            GroundKnowledge::everything(),
        );
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
            let p = Policy::new(s, capped).plan(&cal, 0, next, blind());
            assert_eq!(p.reasons, vec![None; 3], "{s}");
            assert_eq!(p.panorama_sol, None, "{s}");
        }
        // Without the last drive's data the ground cannot plan at all.
        let blind =
            Policy::new(Strategy::Ground, OperationsRules::default()).plan(&cal, 0, next, blind());
        assert_eq!(
            blind.reasons,
            vec![Some(SkipReason::AwaitingPostDriveData); 3]
        );
    }

    /// Paper 000 §8's fortnight under the calendar computed from Mars time, with the one input
    /// the rules cannot know (no relay pass on sol 406): the ground drives every sol the record
    /// drove from 397 to 409 and skips 403 and 406 for the paper's reasons.
    #[test]
    fn ground_on_the_computed_calendar_skips_403_and_406_for_the_papers_reasons() {
        use crate::operations::ops_calendar::TeamRules;
        let rules = TeamRules::for_mission(crate::time::mars_time::MARS_2020, 2022..=2022);
        let sols = rules
            .compute(397..=409)
            .iter()
            .enumerate()
            .map(|(i, c)| SolEntry {
                uplink: c.uplink || i == 0,
                restricted: c.restricted && c.uplink,
                downlink: c.sol != 406,
                ..sol(c.sol, true, false, true)
            })
            .collect();
        let cal = Calendar {
            sols,
            drive_start: SolSeconds(0),
            drive_end: SolSeconds(1),
        };
        let got = Policy::new(Strategy::Ground, OperationsRules::default()).calendar_schedule(&cal);
        let drove: Vec<u32> = cal
            .sols
            .iter()
            .zip(&got)
            .filter(|(_, r)| r.is_none())
            .map(|(e, _)| e.sol)
            .collect();
        assert_eq!(
            drove,
            [397, 398, 399, 400, 401, 402, 404, 405, 407, 408, 409],
            "{got:?}"
        );
        assert!(
            matches!(got[6], Some(SkipReason::CostsLaterDrives { if_driven, if_skipped } ) if if_driven < if_skipped),
            "403: {:?}",
            got[6]
        );
        assert_eq!(got[9], Some(SkipReason::DataTooLateForNextPlan), "406");
    }

    #[test]
    fn only_extension_without_onboard_localization_is_capped() {
        let capped = OperationsRules {
            max_extension_sols: Some(3),
            ..OperationsRules::default()
        };
        let entry = sol(408, false, true, true);
        let run = RunSoFar {
            goal_reached: false,
            halted_by_fault: false,
            sols_since_localization: 3,
            passage: None,
            driven_since_fix_m: 0.0,
        };
        for s in Strategy::ALL {
            let got = Policy::new(s, capped).skip_reason(&entry, None, run);
            let capped = s == Strategy::Extension;
            assert_eq!(got.is_some(), capped, "{s}: {got:?}");
        }
    }

    /// A conjunction: one uplink, then 21 sols without one. Plans that are not extension plans
    /// command at most `max_drive_sols_per_plan` drives; extension breadcrumbs cover the gap.
    #[test]
    fn a_conjunction_is_driven_through_only_by_extension_plans() {
        let mut sols = vec![sol(500, true, true, true)];
        sols.extend((501..522).map(|s| sol(s, false, true, false)));
        sols.push(sol(522, true, true, true));
        let cal = Calendar {
            sols,
            drive_start: SolSeconds(0),
            drive_end: SolSeconds(1),
        };
        let next = cal.next_uplink_after(0);
        let rules = OperationsRules::default();
        // Onboard drives the plan's three sols; ground only the first, whose data reaches
        // Earth before the next plan (no pass in the gap).
        for (s, want) in [(Strategy::Onboard, 3), (Strategy::Ground, 1)] {
            let p = Policy::new(s, rules).plan(&cal, 0, next, GroundKnowledge::everything());
            let drives = p.reasons.iter().filter(|r| r.is_none()).count();
            assert_eq!(drives, want, "{s}: {:?}", p.reasons);
        }
        let p = Policy::new(Strategy::ExtensionOnboard, rules).plan(&cal, 0, next, blind());
        assert_eq!(p.reasons, vec![None; 22]);
    }

    /// Passage-aware planning on a straight route: waypoints every 100 m, one passage of
    /// clearance 12 m at 450 m (in the leg into waypoint 5). r grows 5 % per metre.
    #[test]
    fn the_passage_budget_stops_before_a_passage_the_prediction_closes() {
        let along: Vec<f64> = (0..8).map(|i| f64::from(i) * 100.0).collect();
        let legs: Vec<LegClearance> = (1..8)
            .map(|i| LegClearance {
                to_waypoint: i,
                clearance_m: Some(if i == 5 { 12.0 } else { 100.0 }),
                narrowest_along_route_m: Some(if i == 5 { 450.0 } else { along[i] - 50.0 }),
                narrowest_m: None,
            })
            .collect();
        let ahead = PassagesAhead {
            legs: &legs,
            waypoint_along_m: &along,
            k_vo: 0.05,
            arrival_tolerance_m: 4.0,
        };
        let ground = Policy::new(Strategy::Ground, OperationsRules::default());
        // From a fix at 0 m, r at the passage would be 22.5 m > 12 m: stop before entering the
        // leg into waypoint 5 (400 m − 4 m), which is further than where r reaches 12 m (240 m).
        let at0 = RoutePosition {
            along_m: 0.0,
            next_waypoint: 1,
        };
        let b = ground
            .passage_budget(at0, 0.0, &ahead)
            .expect("the passage binds");
        assert_eq!(b.to_waypoint, 5);
        assert!((b.budget_since_fix_m - 396.0).abs() < 1e-9, "{b:?}");
        assert!((b.predicted_r_m - 22.5).abs() < 1e-9);
        // From a fix at 300 m, r at the passage is 7.5 m: passable, nothing binds.
        let at300 = RoutePosition {
            along_m: 300.0,
            next_waypoint: 4,
        };
        assert_eq!(ground.passage_budget(at300, 0.0, &ahead), None);
        // From inside the passage's leg with r = 11 m (12.5 m predicted at the passage), only
        // 20 m more keep r below 12 m.
        let at420 = RoutePosition {
            along_m: 420.0,
            next_waypoint: 5,
        };
        let b = ground
            .passage_budget(at420, 11.0, &ahead)
            .expect("the passage binds");
        assert!((b.budget_since_fix_m - 20.0).abs() < 1e-9, "{b:?}");
        // A 5 m margin makes the 300 m fix bind too (7.5 m ≥ 12 − 5): the rover may drive on
        // while r < 7 m, 140 m, which is past the start of the passage's leg (96 m).
        let wary = Policy::new(
            Strategy::Ground,
            OperationsRules {
                passage_margin_m: 5.0,
                ..OperationsRules::default()
            },
        );
        let b = wary
            .passage_budget(at300, 0.0, &ahead)
            .expect("the passage binds");
        assert!((b.budget_since_fix_m - 140.0).abs() < 1e-9, "{b:?}");
        // The replay follows its record instead.
        let replay = Policy::new(Strategy::Replay, OperationsRules::default());
        assert_eq!(replay.passage_budget(at0, 0.0, &ahead), None);
        // The budget used up: the sol is skipped with the passage as the reason.
        let run = RunSoFar {
            goal_reached: false,
            halted_by_fault: false,
            sols_since_localization: 2,
            passage: ground.passage_budget(at0, 0.0, &ahead),
            driven_since_fix_m: 395.0,
        };
        let why = ground.skip_reason(&sol(410, true, true, true), None, run);
        assert!(
            matches!(why, Some(SkipReason::PassageAhead(p)) if p.to_waypoint == 5),
            "{why:?}"
        );
    }
}
