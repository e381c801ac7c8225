//! Plan repair after an activity ends late (or early), without search.
//!
//! The tasks after the slipped one keep their order and are re-timed by the same
//! earliest-start rule as the search (waiting for energy when needed). On two timelines the
//! state handed back is at the slipped task's start or later (the slipped task may still be
//! running: [`State::running`]), and the re-timed steps are sorted by start. If any of them no
//! longer fits — its window has passed, the battery or data volume would be violated, or a
//! mandatory task would be lost — repair gives up and hands back the state after the slipped
//! task, from which [`plan_from`](crate::plan_from) replans everything still undone.
//!
//! ## References
//! Paper 003 §3.1 ("time-efficient repair strategies (for example, to shift actions forward
//! after a small driving delay), while major disruptions … invoke a full replanning cycle")
//! and §5.

use crate::error::PlanError;
use crate::instance::{Instance, TaskId};
use crate::plan::{Plan, PlanStep};
use crate::state::{Blocker, Cursor, ENERGY_EPS_WH, State};

/// What repair achieved.
#[derive(Debug, Clone, PartialEq)]
pub enum RepairOutcome {
    /// Every later task still fits once shifted.
    Repaired {
        /// The state just after the slipped task ended.
        state: State,
        /// The re-timed remaining steps (after the slipped one), valid from `state`.
        plan: Plan,
        /// How many of them moved.
        shifted: usize,
    },
    /// A later task no longer fits: replan from `state`.
    ReplanNeeded {
        /// The state just after the slipped task ended.
        state: State,
        /// The first step (index into the original plan) that cannot be kept: the late step
        /// itself when the slip drained the modelled battery.
        step: usize,
        /// Its task.
        task: TaskId,
        /// Why it cannot be kept.
        reason: Blocker,
    },
}

/// Repair `plan` (run from `start`) after step `late_step` actually ended at `actual_end_s`.
///
/// Steps before `late_step` are assumed to have run as planned; the late step drew its power
/// for its actual duration.
///
/// # Errors
/// [`PlanError::InvalidState`] if `start` is malformed, `late_step` is out of range, or
/// `actual_end_s` is before the late step's start.
pub fn repair(
    instance: &Instance,
    start: &State,
    plan: &Plan,
    late_step: usize,
    actual_end_s: i64,
) -> Result<RepairOutcome, PlanError> {
    let mut cur = Cursor::new(instance, start)?;
    let Some(late) = plan.steps.get(late_step) else {
        return Err(PlanError::InvalidState {
            field: "late_step",
            value: late_step as f64,
            expected: "an index into the plan's steps",
        });
    };
    if actual_end_s <= late.start_s || actual_end_s > instance.problem().end_s {
        return Err(PlanError::InvalidState {
            field: "actual_end_s",
            value: actual_end_s as f64,
            expected: "a time after the late step's start and by the end of the sol",
        });
    }
    let mut done = start.done.clone();
    for s in &plan.steps[..late_step] {
        cur.append(instance, s.task, s.start_s, Some(s.end_s - s.start_s));
        done.push(s.task);
    }
    cur.append(
        instance,
        late.task,
        late.start_s,
        Some(actual_end_s - late.start_s),
    );
    done.push(late.task);
    // On two timelines the state is taken no earlier than the late step's start (it has
    // run): nothing is placed before it. On one, at its end.
    cur.advance_to(instance, late.start_s);
    // A slip long enough to drain the modelled battery: the executive must replan from
    // measured telemetry; hand back an empty (not negative) battery.
    let drained = cur.lowest_energy_wh(instance) < -ENERGY_EPS_WH;
    let mut state = cur.state(done);
    state.energy_wh = state.energy_wh.max(0.0);
    if drained {
        return Ok(RepairOutcome::ReplanNeeded {
            state,
            step: late_step,
            task: late.task,
            reason: Blocker::Battery,
        });
    }
    let mut steps = Vec::new();
    let mut shifted = 0;
    for (i, s) in plan.steps.iter().enumerate().skip(late_step + 1) {
        let new_start = match cur.try_start(instance, s.task) {
            Ok(t) => t,
            Err(reason) => {
                return Ok(RepairOutcome::ReplanNeeded {
                    state,
                    step: i,
                    task: s.task,
                    reason,
                });
            }
        };
        cur.append(instance, s.task, new_start, None);
        shifted += usize::from(new_start != s.start_s);
        steps.push(PlanStep {
            task: s.task,
            start_s: new_start,
            end_s: new_start + instance.task(s.task).duration_s,
        });
    }
    // Re-timed steps on two timelines may change their start order.
    steps.sort_by_key(|s| s.start_s);
    Ok(RepairOutcome::Repaired {
        state,
        plan: Plan { steps },
        shifted,
    })
}
