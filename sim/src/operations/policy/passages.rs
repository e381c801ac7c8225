//! The passage limit: how far the planners let the rover drive from the last fix they know of
//! before their predicted uncertainty closes a passage ahead ([`Policy::passage_budget`]).

use super::Policy;
use crate::run::outcome::{LegClearance, PassageLimit};

/// Where the rover was on the route, as the planners know it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoutePosition {
    /// Distance along the route from waypoint 0, metres.
    pub along_m: f64,
    /// The waypoint the rover drives to next.
    pub next_waypoint: usize,
}

/// The route's passages as the planners see them.
#[derive(Clone, Copy, Debug)]
pub struct PassagesAhead<'a> {
    /// Per leg: its clearance and where its narrowest point is.
    pub legs: &'a [LegClearance],
    /// Distance along the route of each waypoint, metres (waypoint 0 at 0).
    pub waypoint_along_m: &'a [f64],
    /// The predicted growth, metres of radius per metre driven (VO working).
    pub k_vo: f64,
    /// The rover takes a waypoint as reached this far before it, plus a step, metres.
    pub arrival_tolerance_m: f64,
}

impl Policy {
    /// How far the rover may drive, in odometry from the last localization the planners know
    /// of, before their predicted uncertainty closes a passage ahead (paper 000 §2: drives are
    /// "pre-emptively shortened"; §8: extension plans "fundamentally limited by position
    /// uncertainty growth"). `None` when no passage ahead binds, or the policy does not plan
    /// around passages.
    ///
    /// The prediction: r grows by `k_vo` (VO working) per metre of route from `fix` — the
    /// route position of that localization, `fix_r_m` its radius. A passage of clearance `c`
    /// at route position `s` is passable if `r(s) < c − passage_margin_m`. Otherwise the rover
    /// must stop while `r < c − margin`, or before it enters the passage's leg (AutoNav plans
    /// to the next waypoint, so a closed passage anywhere on the leg ahead is a `NO_PATH`),
    /// whichever is further. Because the radius depends only on odometry since the fix, the
    /// limit holds wherever along its commanded path the rover ended a sol the planners have
    /// not seen: the plan is robust to where the rover is (paper 000 §8).
    #[must_use]
    pub fn passage_budget(
        &self,
        fix: RoutePosition,
        fix_r_m: f64,
        ahead: &PassagesAhead<'_>,
    ) -> Option<PassageLimit> {
        if !self.plans_around_passages {
            return None;
        }
        let margin = self.rules.passage_margin_m;
        let mut best: Option<PassageLimit> = None;
        for leg in ahead
            .legs
            .iter()
            .filter(|l| l.to_waypoint >= fix.next_waypoint)
        {
            let leg_start = ahead.waypoint_along_m[leg.to_waypoint - 1];
            // Entering this leg's waypoint target comes after the budget already found.
            let enter_budget = leg_start - fix.along_m - ahead.arrival_tolerance_m;
            if best.is_some_and(|b| enter_budget >= b.budget_since_fix_m) {
                break;
            }
            let (c, s) = match (leg.clearance_m, leg.narrowest_along_route_m) {
                (Some(c), Some(s)) => (c, s),
                // No path at all: stop before the leg.
                _ => (0.0, leg_start),
            };
            if s < fix.along_m {
                continue;
            }
            let predicted_r_m = fix_r_m + ahead.k_vo * (s - fix.along_m);
            if predicted_r_m < c - margin {
                continue;
            }
            let inside = if leg.to_waypoint > fix.next_waypoint {
                enter_budget
            } else {
                f64::NEG_INFINITY
            };
            let within_r = (c - margin - fix_r_m) / ahead.k_vo;
            let budget = inside.max(within_r).max(0.0);
            if best.is_none_or(|b| budget < b.budget_since_fix_m) {
                best = Some(PassageLimit {
                    to_waypoint: leg.to_waypoint,
                    clearance_m: c,
                    predicted_r_m,
                    budget_since_fix_m: budget,
                });
            }
        }
        best
    }
}
