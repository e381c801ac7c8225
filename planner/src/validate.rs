//! An independent plan checker: it re-simulates a plan from a [`State`] with its own code
//! (nothing from the search) and lists every rule the plan breaks.

use crate::instance::{Instance, TaskId};
use crate::plan::Plan;
use crate::state::{DATA_EPS_MB, DISTANCE_EPS_M, ENERGY_EPS_WH, State};
use serde::{Deserialize, Serialize};

/// One broken rule. `step` is the index into [`Plan::steps`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Violation {
    /// The step names a task the instance does not have.
    UnknownTask {
        /// Step index.
        step: usize,
    },
    /// The task is already done in the start state or appears twice.
    Repeated {
        /// Step index.
        step: usize,
    },
    /// `end_s − start_s` differs from the task's duration.
    WrongDuration {
        /// Step index.
        step: usize,
        /// The task's duration, s.
        expected_s: i64,
        /// `end_s − start_s`.
        found_s: i64,
    },
    /// The start lies outside `[earliest_start_s, latest_start_s]`.
    OutsideWindow {
        /// Step index.
        step: usize,
        /// The start, s.
        start_s: i64,
    },
    /// The step starts before the previous one (or the start state) ends.
    Overlap {
        /// Step index.
        step: usize,
    },
    /// The step ends after the sol window.
    PastEndOfSol {
        /// Step index.
        step: usize,
    },
    /// A precondition has not ended before the step starts.
    MissingPrecondition {
        /// Step index.
        step: usize,
        /// The missing task.
        precondition: TaskId,
    },
    /// Metres driven at the start lie outside the task's state-based window.
    OutsideDrivenWindow {
        /// Step index.
        step: usize,
        /// Metres driven at the start.
        driven_m: f64,
    },
    /// The battery would go below 0 during the step.
    BatteryEmpty {
        /// Step index.
        step: usize,
        /// Energy at the end of the step, Wh.
        energy_wh: f64,
    },
    /// Stored data would exceed the capacity at the end of the step.
    DataFull {
        /// Step index.
        step: usize,
        /// Data stored after the step's products, MB.
        data_mb: f64,
    },
    /// A mandatory task is neither done nor in the plan.
    MissingMandatory {
        /// The task.
        task: TaskId,
    },
}

/// Every violation of `plan` run from `state` on `instance`; empty means the plan is valid.
///
/// The battery is simulated exactly: it charges at `recharge_w` while idle and at
/// `recharge_w − power_w` during a task, clipped at capacity; within a step it is linear, so
/// checking the ends of steps checks it "throughout".
#[must_use]
pub fn validate_plan(instance: &Instance, state: &State, plan: &Plan) -> Vec<Violation> {
    let p = instance.problem();
    let n = instance.tasks().len();
    let mut out = Vec::new();
    let mut done = vec![false; n];
    for t in &state.done {
        if t.index() < n {
            done[t.index()] = true;
        }
    }
    let mut now = state.time_s;
    let mut energy = state.energy_wh;
    let mut data = state.data_mb;
    let mut driven = state.driven_m;
    let cap = p.battery_capacity_wh;
    for (i, s) in plan.steps.iter().enumerate() {
        if s.task.index() >= n {
            out.push(Violation::UnknownTask { step: i });
            continue;
        }
        let task = instance.task(s.task);
        if done[s.task.index()] {
            out.push(Violation::Repeated { step: i });
        }
        if s.end_s - s.start_s != task.duration_s {
            out.push(Violation::WrongDuration {
                step: i,
                expected_s: task.duration_s,
                found_s: s.end_s - s.start_s,
            });
        }
        if s.start_s < task.earliest_start_s || s.start_s > task.latest_start_s {
            out.push(Violation::OutsideWindow {
                step: i,
                start_s: s.start_s,
            });
        }
        if s.start_s < now {
            out.push(Violation::Overlap { step: i });
        }
        if s.end_s > p.end_s {
            out.push(Violation::PastEndOfSol { step: i });
        }
        for &q in &task.preconditions {
            if !done.get(q.index()).copied().unwrap_or(false) {
                out.push(Violation::MissingPrecondition {
                    step: i,
                    precondition: q,
                });
            }
        }
        if let Some([lo, hi]) = task.driven_window_m
            && (driven < lo - DISTANCE_EPS_M || driven > hi + DISTANCE_EPS_M)
        {
            out.push(Violation::OutsideDrivenWindow {
                step: i,
                driven_m: driven,
            });
        }
        let idle_s = (s.start_s - now).max(0);
        energy = (energy + p.recharge_w * idle_s as f64 / 3600.0).min(cap);
        let run_s = (s.end_s - s.start_s).max(0) as f64;
        energy += (p.recharge_w - task.power_w) * run_s / 3600.0;
        if energy < -ENERGY_EPS_WH {
            out.push(Violation::BatteryEmpty {
                step: i,
                energy_wh: energy,
            });
        }
        energy = energy.min(cap);
        data += task.data_mb;
        if data > p.data_capacity_mb + DATA_EPS_MB {
            out.push(Violation::DataFull {
                step: i,
                data_mb: data,
            });
        }
        data = (data - task.downlink_mb).max(0.0);
        driven += task.drive_m;
        now = now.max(s.end_s);
        done[s.task.index()] = true;
    }
    for &m in instance.mandatory_tasks() {
        if !done[m.index()] {
            out.push(Violation::MissingMandatory { task: m });
        }
    }
    out
}
