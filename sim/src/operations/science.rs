//! Science campaigns the rover plans for itself each drive sol (paper 003 §3, Fig. 2-3).
//!
//! A scenario may carry campaign intents that outlive any one sol:
//!
//! - **goal-set sampling** over [`Target`]s: observations of places on the map (a Mastcam
//!   outcrop across a long traverse, or a target autonomous science flags mid-campaign). A
//!   target is offered to a sol's planner only when the rover could be within
//!   [`Target::within_m`] of it: already there, or after this sol's drive (then the drive is a
//!   precondition). Whether it is *really* in reach is decided when the observation runs, from
//!   the rover's true position — a planned observation can fail;
//! - **temporally periodic** ([`Periodic`]): an instance due at `first_due + k × period` every
//!   sol, startable within ± tolerance (atmospheric opacity every 3 h ± 20 min);
//! - **state-based** ([`StateBased`]): an instance due every `every_m` metres of odometry since
//!   the campaign began, ± tolerance (a survey every 75 m). The sol's drive is split at those
//!   distances so the survey runs between segments.
//!
//! [`Science::for_sol`] turns the intents and what has been achieved so far
//! ([`ScienceProgress`]) into the sol's candidate activities and campaigns for
//! [`crate::operations::sol_plan`]. A goal set's count carries across sols: a campaign that has `n`
//! members already is offered with `min_count − n`, `max_count − n` and its utility scaled by
//! `decay^n`, so once `n ≥ min_count` the sol's plan earns exactly the mission-level curve's
//! increments (below `min_count` the members already taken are not credited again). A
//! periodic or state-based campaign counts per sol: it is offered with `min_count = 0` and
//! `max_count` = the sol's instances; each state-based instance is taken once
//! ([`ScienceProgress::next_instance`]).

use std::collections::BTreeMap;

use planner::{Activity, Campaign, CampaignIntent};

use crate::time::SolSeconds;

/// A goal-set observation of a place on the map.
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    /// The activity: id, name, duration, power, data volume, tier and utility (its campaign is
    /// the scenario's goal set; windows are set each sol).
    pub activity: Activity,
    /// Where the target is, map metres.
    pub position_m: [f64; 2],
    /// The rover must be this close to observe it, metres.
    pub within_m: f64,
    /// When autonomous science reveals it: `(sol, LMST)`; `None` if known from the start.
    pub revealed: Option<(u32, SolSeconds)>,
}

/// A temporally periodic intent.
#[derive(Clone, Debug, PartialEq)]
pub struct Periodic {
    /// The campaign (intent [`CampaignIntent::Periodic`]).
    pub campaign: Campaign,
    /// The first due time of every sol.
    pub first_due: SolSeconds,
    /// The instance activity (its id is the instances' prefix).
    pub template: Activity,
}

/// A state-based intent.
#[derive(Clone, Debug, PartialEq)]
pub struct StateBased {
    /// The campaign (intent [`CampaignIntent::StateBased`]).
    pub campaign: Campaign,
    /// The instance activity (its id is the instances' prefix).
    pub template: Activity,
}

/// A scenario's science campaigns.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Science {
    /// Goal-set targets.
    pub targets: Vec<Target>,
    /// The goal set the targets count towards (intent [`CampaignIntent::GoalSet`]).
    pub goal_set: Option<Campaign>,
    /// Periodic intents.
    pub periodic: Vec<Periodic>,
    /// State-based intents.
    pub state_based: Vec<StateBased>,
}

/// What the science campaigns have achieved so far, carried from sol to sol.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScienceProgress {
    /// Targets observed (ids).
    pub achieved: Vec<String>,
    /// Odometry since the campaign began, metres (the state-based cadence counts from 0).
    pub odometer_m: f64,
    /// Members done per campaign id.
    pub done: BTreeMap<String, u32>,
    /// Members that ran but failed per campaign id (a target out of reach).
    pub failed: BTreeMap<String, u32>,
    /// Per state-based campaign id: the first instance number not yet done (instance `k` is
    /// due at `k × every_m` of odometry; each is taken once).
    pub next_instance: BTreeMap<String, i64>,
}

impl ScienceProgress {
    /// Record a campaign member that ran: `observed` is false for a target out of reach.
    pub fn record(&mut self, science: &Science, activity_id: &str, observed: bool) {
        let Some(campaign) = science.campaign_of(activity_id) else {
            return;
        };
        if !observed {
            *self.failed.entry(campaign.to_string()).or_default() += 1;
            return;
        }
        *self.done.entry(campaign.to_string()).or_default() += 1;
        if science.target(activity_id).is_some() {
            self.achieved.push(activity_id.to_string());
        } else if let Some((c, k)) = science.state_based_instance(activity_id) {
            let next = self.next_instance.entry(c.to_string()).or_default();
            *next = (*next).max(k + 1);
        }
    }
}

/// One sol's science candidates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SolScience {
    /// Candidate activities (targets, periodic and state-based instances).
    pub activities: Vec<Activity>,
    /// The campaigns they count towards, as offered this sol.
    pub campaigns: Vec<Campaign>,
    /// Where to split the drive, metres from its start (state-based due distances).
    pub split_at_m: Vec<f64>,
}

/// The sol's view of the rover, for [`Science::for_sol`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolContext {
    /// The sol number.
    pub sol: u32,
    /// The planning window `[start, end]`.
    pub window: [SolSeconds; 2],
    /// The drive's first segment start.
    pub drive_start: SolSeconds,
    /// Metres the drive is planned to cover.
    pub drive_m: f64,
    /// When the activities before the drive (heating) begin.
    pub before_drive: SolSeconds,
}

/// How a target relates to the rover now: observable already, after the drive, or not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reach {
    /// Within reach now.
    Here,
    /// Within reach of where the drive is expected to end.
    AfterDrive,
    /// Neither.
    OutOfReach,
}

/// The point `d` metres along the polyline `path` (its last point if it is shorter).
#[must_use]
pub fn point_along(path: &[[f64; 2]], mut d: f64) -> [f64; 2] {
    for w in path.windows(2) {
        let len = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        if d <= len && len > 0.0 {
            let f = d / len;
            return [
                w[0][0] + f * (w[1][0] - w[0][0]),
                w[0][1] + f * (w[1][1] - w[0][1]),
            ];
        }
        d -= len;
    }
    path.last().copied().unwrap_or([f64::NAN; 2])
}

impl Target {
    /// The target's id.
    #[must_use]
    pub fn id(&self) -> &str {
        &self.activity.id
    }

    /// Whether it is revealed by `(sol, t)`.
    #[must_use]
    pub fn revealed_by(&self, sol: u32, t: SolSeconds) -> bool {
        self.revealed
            .is_none_or(|(s, at)| s < sol || (s == sol && at <= t))
    }

    /// Its reach along `route_ahead` (the rover's estimate, then the waypoints still to
    /// drive) with `drive_left_m` metres of driving still planned. The drive is expected to
    /// end `drive_left_m` along the route (at its end if that is nearer): the observation runs
    /// after the drive, so a target the drive passes by is not in reach.
    #[must_use]
    pub fn reach(&self, route_ahead: &[[f64; 2]], drive_left_m: f64) -> Reach {
        let dist = |p: [f64; 2]| (self.position_m[0] - p[0]).hypot(self.position_m[1] - p[1]);
        let Some(&here) = route_ahead.first() else {
            return Reach::OutOfReach;
        };
        if dist(here) <= self.within_m {
            Reach::Here
        } else if drive_left_m > 0.0
            && dist(point_along(route_ahead, drive_left_m)) <= self.within_m
        {
            Reach::AfterDrive
        } else {
            Reach::OutOfReach
        }
    }

    /// The sol's candidate activity for this target, startable in `window` (`None` if it
    /// is out of reach). In reach after the drive: the drive is its precondition. In reach
    /// now but not after the drive: it must end by `before_drive`, when the activities
    /// before the drive begin (`None`: no time before the drive is left, so no candidate).
    #[must_use]
    pub fn candidate(
        &self,
        goal_set: &str,
        window: [SolSeconds; 2],
        route_ahead: &[[f64; 2]],
        drive_left_m: f64,
        before_drive: Option<SolSeconds>,
    ) -> Option<Activity> {
        let mut a = self.activity.clone();
        a.campaign = Some(goal_set.to_string());
        a.earliest_start_s = window[0].planner_s();
        a.latest_start_s = window[1].planner_s() - a.duration_s();
        match self.reach(route_ahead, drive_left_m) {
            Reach::Here => {
                let end = point_along(route_ahead, drive_left_m);
                let stays = drive_left_m <= 0.0
                    || (self.position_m[0] - end[0]).hypot(self.position_m[1] - end[1])
                        <= self.within_m;
                if !stays {
                    a.latest_start_s = a
                        .latest_start_s
                        .min(before_drive?.planner_s() - a.duration_s());
                }
            }
            Reach::AfterDrive => a.preconditions.push("drive".into()),
            Reach::OutOfReach => return None,
        }
        (a.latest_start_s >= a.earliest_start_s).then_some(a)
    }
}

/// `k` of an instance id `{template_id}-{k}` (the ids [`planner::periodic_instances`] and
/// [`Science::for_sol`] give instances), `None` for any other id.
fn instance_number(template_id: &str, activity_id: &str) -> Option<i64> {
    let k = activity_id.strip_prefix(template_id)?.strip_prefix('-')?;
    if k.is_empty() || !k.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    k.parse().ok()
}

/// `c` as offered when `n` members are already done: the remaining counts, the utility of
/// the next member (`None` if the campaign is saturated).
fn remaining_campaign(c: &Campaign, n: u32) -> Option<Campaign> {
    (n < c.max_count).then(|| Campaign {
        min_count: c.min_count.saturating_sub(n),
        max_count: c.max_count - n,
        utility: c.utility * c.decay.powi(n.min(i32::MAX as u32) as i32),
        ..c.clone()
    })
}

impl Science {
    /// Whether there is nothing to plan.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.targets.is_empty() && self.periodic.is_empty() && self.state_based.is_empty()
    }

    /// The state-based campaign and instance number `k` of an instance id `{template}-{k}`.
    #[must_use]
    pub fn state_based_instance(&self, activity_id: &str) -> Option<(&str, i64)> {
        self.state_based.iter().find_map(|s| {
            instance_number(&s.template.id, activity_id).map(|k| (s.campaign.id.as_str(), k))
        })
    }

    /// Every campaign id, goal set first.
    pub fn campaign_ids(&self) -> impl Iterator<Item = &str> {
        self.goal_set
            .iter()
            .map(|c| c.id.as_str())
            .chain(self.periodic.iter().map(|p| p.campaign.id.as_str()))
            .chain(self.state_based.iter().map(|s| s.campaign.id.as_str()))
    }

    /// The target with activity id `id`.
    #[must_use]
    pub fn target(&self, id: &str) -> Option<&Target> {
        self.targets.iter().find(|t| t.id() == id)
    }

    /// The campaign a member activity id counts towards, and whether it is a target.
    #[must_use]
    pub fn campaign_of(&self, activity_id: &str) -> Option<&str> {
        if self.target(activity_id).is_some() {
            return self.goal_set.as_ref().map(|c| c.id.as_str());
        }
        self.periodic
            .iter()
            .map(|p| (&p.template.id, &p.campaign.id))
            .chain(
                self.state_based
                    .iter()
                    .map(|s| (&s.template.id, &s.campaign.id)),
            )
            .find(|(prefix, _)| instance_number(prefix, activity_id).is_some())
            .map(|(_, id)| id.as_str())
    }

    /// The goal set as offered given what `progress` has achieved (`None` if there is none
    /// or it is saturated).
    #[must_use]
    pub fn offered_goal_set(&self, progress: &ScienceProgress) -> Option<Campaign> {
        let gs = self.goal_set.as_ref()?;
        remaining_campaign(gs, progress.done.get(&gs.id).copied().unwrap_or(0))
    }

    /// The sol's candidates, given what `progress` has achieved; `route_ahead` is the rover's
    /// estimate followed by the waypoints still to drive.
    #[must_use]
    pub fn for_sol(
        &self,
        progress: &ScienceProgress,
        ctx: &SolContext,
        route_ahead: &[[f64; 2]],
    ) -> SolScience {
        let mut out = SolScience::default();
        let [start, end] = ctx.window;
        let (start_s, end_s) = (start.planner_s(), end.planner_s());
        if let Some(gs) = &self.goal_set
            && let Some(offered) = self.offered_goal_set(progress)
        {
            let before = out.activities.len();
            for t in &self.targets {
                if progress.achieved.iter().any(|a| a == t.id()) || !t.revealed_by(ctx.sol, start) {
                    continue;
                }
                out.activities.extend(t.candidate(
                    &gs.id,
                    ctx.window,
                    route_ahead,
                    ctx.drive_m,
                    Some(ctx.before_drive),
                ));
            }
            if out.activities.len() > before {
                out.campaigns.push(offered);
            }
        }

        for p in &self.periodic {
            let CampaignIntent::Periodic {
                period_s,
                tolerance_s,
            } = p.campaign.intent
            else {
                continue;
            };
            let instances = planner::clip_to_window(
                planner::periodic_instances(
                    &p.template,
                    &p.campaign.id,
                    p.first_due.planner_s(),
                    period_s,
                    tolerance_s,
                    end_s,
                ),
                start_s,
                end_s,
            );
            if !instances.is_empty() {
                out.campaigns.push(Campaign {
                    max_count: instances.len() as u32,
                    min_count: 0,
                    ..p.campaign.clone()
                });
                out.activities.extend(instances);
            }
        }

        for s in &self.state_based {
            let CampaignIntent::StateBased {
                every_m,
                tolerance_m,
            } = s.campaign.intent
            else {
                continue;
            };
            // Due distances k·every_m of odometry, relative to this sol's drive start: from
            // the first instance not yet done whose window has not been passed.
            let passed_k = ((progress.odometer_m - tolerance_m) / every_m)
                .ceil()
                .max(1.0) as i64;
            let first_k = passed_k.max(
                progress
                    .next_instance
                    .get(&s.campaign.id)
                    .copied()
                    .unwrap_or(1),
            );
            let mut instances = Vec::new();
            for k in first_k.. {
                let at_m = k as f64 * every_m - progress.odometer_m;
                if at_m - tolerance_m > ctx.drive_m || instances.len() >= 16 {
                    break;
                }
                let mut a = s.template.clone();
                a.id = format!("{}-{k}", s.template.id);
                a.campaign = Some(s.campaign.id.clone());
                a.earliest_start_s = ctx.drive_start.planner_s();
                a.latest_start_s = end_s - a.duration_s();
                a.driven_window_m = Some([(at_m - tolerance_m).max(0.0), at_m + tolerance_m]);
                if at_m > 1.0 && at_m < ctx.drive_m - 1.0 {
                    out.split_at_m.push(at_m);
                }
                instances.push(a);
            }
            if !instances.is_empty() {
                out.campaigns.push(Campaign {
                    max_count: instances.len() as u32,
                    min_count: 0,
                    ..s.campaign.clone()
                });
                out.activities.extend(instances);
            }
        }
        out.split_at_m.sort_by(f64::total_cmp);
        out.split_at_m.dedup_by(|a, b| (*a - *b).abs() < 1.0);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn template(id: &str, minutes: i64) -> Activity {
        Activity::task(id, minutes * 60, [0, 0], 25.0, 0.0)
    }

    fn science() -> Science {
        let campaign = |id: &str, intent, max_count| Campaign {
            id: id.into(),
            intent,
            tier: 2,
            min_count: 0,
            max_count,
            utility: 3.0,
            decay: 1.0,
        };
        let target = |id: &str, x: f64, revealed| Target {
            activity: template(id, 20),
            position_m: [x, 0.0],
            within_m: 10.0,
            revealed,
        };
        Science {
            targets: vec![
                target("near", 5.0, None),
                target("far", 200.0, None),
                target("later", 50.0, Some((2, SolSeconds(45_000)))),
            ],
            goal_set: Some(Campaign {
                decay: 0.5,
                utility: 10.0,
                tier: 1,
                ..campaign("outcrop", CampaignIntent::GoalSet, 3)
            }),
            periodic: vec![Periodic {
                campaign: campaign(
                    "tau",
                    CampaignIntent::Periodic {
                        period_s: 3 * 3600,
                        tolerance_s: 1200,
                    },
                    1,
                ),
                first_due: SolSeconds(37_000),
                template: template("tau", 5),
            }],
            state_based: vec![StateBased {
                campaign: campaign(
                    "survey",
                    CampaignIntent::StateBased {
                        every_m: 75.0,
                        tolerance_m: 10.0,
                    },
                    1,
                ),
                template: template("survey", 15),
            }],
        }
    }

    fn ctx(sol: u32, drive_m: f64) -> SolContext {
        SolContext {
            sol,
            window: [SolSeconds(36_000), SolSeconds(63_000)],
            drive_start: SolSeconds(40_000),
            drive_m,
            before_drive: SolSeconds(38_200),
        }
    }

    /// From the origin east along y = 0.
    const ROUTE: [[f64; 2]; 2] = [[0.0, 0.0], [500.0, 0.0]];

    #[test]
    fn targets_are_offered_by_reach_and_reveal_time() {
        let s = science();
        let out = s.for_sol(&ScienceProgress::default(), &ctx(1, 100.0), &ROUTE);
        let ids: Vec<&str> = out.activities.iter().map(|a| a.id.as_str()).collect();
        assert!(ids.contains(&"near") && !ids.contains(&"far") && !ids.contains(&"later"));
        let near = &out.activities[0];
        assert!(
            near.preconditions.is_empty(),
            "in reach now: no drive needed"
        );
        assert_eq!(
            near.latest_start_s + 1200,
            38_200,
            "observed before the drive leaves it"
        );
        // The drive ends 195 m along: 5 m short of "far", which is in reach then...
        let out = s.for_sol(&ScienceProgress::default(), &ctx(3, 195.0), &ROUTE);
        let far = out.activities.iter().find(|a| a.id == "far").expect("far");
        assert_eq!(far.preconditions, vec!["drive".to_string()]);
        assert!(
            !out.activities.iter().any(|a| a.id == "later"),
            "passed by: not in reach"
        );
        // "later" (50 m along) where a 45 m drive ends: offered only once revealed.
        let ids = |sol| {
            s.for_sol(&ScienceProgress::default(), &ctx(sol, 45.0), &ROUTE)
                .activities
                .iter()
                .any(|a| a.id == "later")
        };
        assert!(
            !ids(2) && ids(3),
            "revealed on sol 2 at 45 000 s, after the window opens"
        );
        // ...but not if the drive goes 30 m past it.
        let out = s.for_sol(&ScienceProgress::default(), &ctx(3, 230.0), &ROUTE);
        assert!(!out.activities.iter().any(|a| a.id == "far"));
        assert_eq!(point_along(&ROUTE, 900.0), [500.0, 0.0]);
    }

    #[test]
    fn a_goal_set_continues_its_curve_across_sols() {
        let s = science();
        let mut progress = ScienceProgress::default();
        progress.achieved.push("near".into());
        progress.done.insert("outcrop".into(), 1);
        let out = s.for_sol(&progress, &ctx(3, 195.0), &ROUTE);
        let gs = out
            .campaigns
            .iter()
            .find(|c| c.id == "outcrop")
            .expect("offered");
        assert_eq!((gs.min_count, gs.max_count), (0, 2));
        assert!(
            (gs.utility - 5.0).abs() < 1e-12,
            "second member worth decay × first"
        );
        assert!(!out.activities.iter().any(|a| a.id == "near"));
        progress.done.insert("outcrop".into(), 3);
        let out = s.for_sol(&progress, &ctx(3, 195.0), &ROUTE);
        assert!(out.campaigns.iter().all(|c| c.id != "outcrop"), "saturated");
    }

    #[test]
    fn survey_instances_follow_the_odometer_and_split_the_drive() {
        let s = science();
        let progress = ScienceProgress {
            odometer_m: 140.0,
            ..ScienceProgress::default()
        };
        let out = s.for_sol(&progress, &ctx(1, 200.0), &ROUTE);
        let surveys: Vec<&Activity> = out
            .activities
            .iter()
            .filter(|a| a.campaign.as_deref() == Some("survey"))
            .collect();
        // Due at 150, 225, 300 m of odometry: 10, 85, 160 m into this drive.
        assert_eq!(surveys.len(), 3);
        assert_eq!(surveys[0].id, "survey-2");
        assert_eq!(surveys[0].driven_window_m, Some([0.0, 20.0]));
        assert_eq!(out.split_at_m, vec![10.0, 85.0, 160.0]);
        assert_eq!(s.campaign_of("survey-2"), Some("survey"));
        // An instance is taken once: survey-5 (due at 375 m) ran early, within its tolerance,
        // at 368 m; the next sol starts at survey-6, not survey-5 again.
        let mut progress = ScienceProgress {
            odometer_m: 368.0,
            ..ScienceProgress::default()
        };
        progress.record(&s, "survey-5", true);
        let out = s.for_sol(&progress, &ctx(1, 100.0), &ROUTE);
        let first = out
            .activities
            .iter()
            .find(|a| a.campaign.as_deref() == Some("survey"));
        assert_eq!(first.map(|a| a.id.as_str()), Some("survey-6"));
        // Not done and passed by less than its tolerance: still offered, at the drive start.
        progress.next_instance.clear();
        progress.odometer_m = 380.0;
        let out = s.for_sol(&progress, &ctx(1, 100.0), &ROUTE);
        let first = out
            .activities
            .iter()
            .find(|a| a.campaign.as_deref() == Some("survey"));
        assert_eq!(
            first.map(|a| (a.id.as_str(), a.driven_window_m)),
            Some(("survey-5", Some([0.0, 5.0])))
        );
        assert_eq!(s.campaign_of("tau-0"), Some("tau"));
        assert_eq!(s.campaign_of("near"), Some("outcrop"));
        assert_eq!(s.campaign_of("survey"), None);
    }

    #[test]
    fn periodic_instances_are_clipped_to_the_window() {
        let out = science().for_sol(&ScienceProgress::default(), &ctx(1, 0.0), &ROUTE);
        let taus: Vec<&Activity> = out
            .activities
            .iter()
            .filter(|a| a.campaign.as_deref() == Some("tau"))
            .collect();
        assert_eq!(taus.len(), 3, "due at 37 000, 47 800 and 58 600 s");
        assert!(taus.iter().all(|a| a.earliest_start_s >= 36_000));
        assert!(taus.iter().all(|a| a.latest_start_s + 300 <= 63_000));
    }
}
