//! An independent plan checker: it re-simulates a plan from a [`State`] with its own code
//! (nothing from the search) and lists every rule the plan breaks.
//!
//! On two timelines (some task holds the HBS link, see [`Timeline`](crate::Timeline)) it also
//! checks that no two steps sharing a timeline overlap, that every precondition has *ended*
//! before its successor starts, and simulates the battery through overlapping steps piece by
//! piece.
//! [`step_resources`] reports the same re-simulation step by step (battery and data after
//! each step, metres driven when it starts).

use crate::instance::{Instance, Task, TaskId};
use crate::plan::{Plan, PlanStep};
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
    /// The step starts before the previous one (or the start state) ends — on two
    /// timelines: before the previous step on the main timeline ends.
    Overlap {
        /// Step index.
        step: usize,
    },
    /// Two steps on the HBS link overlap: `step` starts before `other` (a step, or a task
    /// still running in the start state) ends.
    LinkOverlap {
        /// Step index.
        step: usize,
        /// The link task it overlaps.
        other: TaskId,
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

impl std::fmt::Display for Violation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Violation::UnknownTask { step } => write!(f, "step {step} names an unknown task"),
            Violation::Repeated { step } => {
                write!(f, "step {step} repeats a task already done")
            }
            Violation::WrongDuration {
                step,
                expected_s,
                found_s,
            } => write!(
                f,
                "step {step} lasts {found_s} s where its task takes {expected_s} s"
            ),
            Violation::OutsideWindow { step, start_s } => {
                write!(f, "step {step} starts at {start_s} s, outside its window")
            }
            Violation::Overlap { step } => {
                write!(f, "step {step} starts before the one before it ends")
            }
            Violation::LinkOverlap { step, other } => write!(
                f,
                "step {step} starts on the HBS link before task #{} ends",
                other.0
            ),
            Violation::PastEndOfSol { step } => {
                write!(f, "step {step} ends after the sol window")
            }
            Violation::MissingPrecondition { step, precondition } => write!(
                f,
                "step {step} starts before its precondition, task #{}, has ended",
                precondition.0
            ),
            Violation::OutsideDrivenWindow { step, driven_m } => write!(
                f,
                "step {step} starts at {driven_m:.1} m driven, outside its window"
            ),
            Violation::BatteryEmpty { step, energy_wh } => write!(
                f,
                "step {step} empties the battery ({energy_wh:.1} Wh at its end)"
            ),
            Violation::DataFull { step, data_mb } => write!(
                f,
                "step {step} overflows the data volume ({data_mb:.1} MB after it)"
            ),
            Violation::MissingMandatory { task } => {
                write!(f, "mandatory task #{} is neither done nor planned", task.0)
            }
        }
    }
}

/// Every violation of `plan` run from `state` on `instance`; empty means the plan is valid.
///
/// The battery is simulated exactly: it charges at `recharge_w` while idle and at
/// `recharge_w − power_w` during a task, clipped at capacity; within a step it is linear, so
/// checking the ends of steps checks it "throughout". On two timelines the powers of
/// overlapping steps add, and the battery is checked at every step boundary.
#[must_use]
pub fn validate_plan(instance: &Instance, state: &State, plan: &Plan) -> Vec<Violation> {
    if instance.uses_link() {
        return validate_timelines(instance, state, plan);
    }
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
        let Some(task) = check_step_task(instance, s, i, |t| done[t.index()], &mut out) else {
            continue;
        };
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

/// The battery, data and odometer around one step, as the validator re-simulates them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepResources {
    /// Metres driven (all drives) when the step starts.
    pub driven_at_start_m: f64,
    /// Battery energy when the step ends, Wh (on two timelines counting every step that
    /// overlaps it).
    pub energy_wh_after: f64,
    /// Stored data after the step (after its downlink), MB.
    pub data_mb_after: f64,
}

/// The validator's re-simulation of `plan` from `state`, step by step (for reports). Steps
/// keep their given durations (`end_s − start_s`), so an executed timeline with late steps is
/// simulated as it ran. Unknown tasks get the previous values.
#[must_use]
pub fn step_resources(instance: &Instance, state: &State, plan: &Plan) -> Vec<StepResources> {
    let p = instance.problem();
    let n = instance.tasks().len();
    let mut energy = state.energy_wh;
    let mut data = state.data_mb;
    let mut driven = state.driven_m;
    let mut now = state.time_s;
    let ends = instance
        .uses_link()
        .then(|| energy_at_ends(instance, state, plan));
    let mut out = Vec::with_capacity(plan.steps.len());
    for (i, s) in plan.steps.iter().enumerate() {
        let at_start = driven;
        if s.task.index() < n {
            let task = instance.task(s.task);
            // Idle recharge clipped at capacity, then the step's net draw; data added at the
            // end, then downlinked (the validator's arithmetic).
            let idle_s = (s.start_s - now).max(0);
            energy = (energy + p.recharge_w * idle_s as f64 / 3600.0).min(p.battery_capacity_wh);
            energy += (p.recharge_w - task.power_w) * (s.end_s - s.start_s).max(0) as f64 / 3600.0;
            energy = energy.min(p.battery_capacity_wh);
            data += task.data_mb;
            data = (data - task.downlink_mb).max(0.0);
            driven += task.drive_m;
            now = now.max(s.end_s);
        }
        out.push(StepResources {
            driven_at_start_m: at_start,
            energy_wh_after: ends.as_ref().map_or(energy, |e| e[i]),
            data_mb_after: data,
        });
    }
    out
}

/// The steps of `plan` (valid task, positive duration) and the tasks running in `state`, as
/// `(start, end, power, step index or None)`.
fn drains(instance: &Instance, state: &State, plan: &Plan) -> Vec<(i64, i64, f64, Option<usize>)> {
    let n = instance.tasks().len();
    let mut out: Vec<(i64, i64, f64, Option<usize>)> = state
        .running
        .iter()
        .filter(|r| r.task.index() < n && r.end_s > state.time_s)
        .map(|r| {
            (
                r.start_s.max(state.time_s),
                r.end_s,
                instance.task(r.task).power_w,
                None,
            )
        })
        .collect();
    out.extend(
        plan.steps
            .iter()
            .enumerate()
            .filter(|(_, s)| s.task.index() < n && s.end_s > s.start_s)
            .map(|(i, s)| {
                (
                    s.start_s.max(state.time_s),
                    s.end_s,
                    instance.task(s.task).power_w,
                    Some(i),
                )
            }),
    );
    out
}

/// Sweep the battery from `state` through every step piece by piece: `on_piece(end of the
/// piece, energy before clipping, index of each step running during it)`.
fn sweep_steps(
    instance: &Instance,
    state: &State,
    plan: &Plan,
    mut on_piece: impl FnMut(i64, f64, &mut dyn Iterator<Item = usize>),
) {
    let p = instance.problem();
    let d = drains(instance, state, plan);
    let mut points: Vec<i64> = d.iter().flat_map(|x| [x.0, x.1]).collect();
    points.push(state.time_s);
    points.sort_unstable();
    points.dedup();
    let mut e = state.energy_wh;
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b <= state.time_s {
            continue;
        }
        let active = || d.iter().filter(move |x| x.0 <= a && x.1 >= b);
        let draw_w: f64 = active().map(|x| x.2).sum();
        e += (p.recharge_w - draw_w) * (b - a) as f64 / 3600.0;
        on_piece(b, e, &mut active().filter_map(|x| x.3));
        e = e.min(p.battery_capacity_wh);
    }
}

/// On two timelines: the battery when each step ends, Wh.
fn energy_at_ends(instance: &Instance, state: &State, plan: &Plan) -> Vec<f64> {
    let cap = instance.problem().battery_capacity_wh;
    let mut at: Vec<(i64, f64)> = Vec::new();
    sweep_steps(instance, state, plan, |t, e, _| at.push((t, e.min(cap))));
    plan.steps
        .iter()
        .map(|s| {
            at.iter()
                .rev()
                .find(|(t, _)| *t <= s.end_s)
                .map_or(state.energy_wh, |x| x.1)
        })
        .collect()
}

/// [`validate_plan`] on two timelines.
/// The checks of one step that need only its task: the task exists (`None` if not, after
/// pushing `UnknownTask`), is not done already (`already_done`), lasts its duration and starts
/// within its window.
fn check_step_task<'a>(
    instance: &'a Instance,
    s: &PlanStep,
    i: usize,
    already_done: impl Fn(TaskId) -> bool,
    out: &mut Vec<Violation>,
) -> Option<&'a Task> {
    if s.task.index() >= instance.tasks().len() {
        out.push(Violation::UnknownTask { step: i });
        return None;
    }
    let task = instance.task(s.task);
    if already_done(s.task) {
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
    Some(task)
}

fn validate_timelines(instance: &Instance, state: &State, plan: &Plan) -> Vec<Violation> {
    let p = instance.problem();
    let n = instance.tasks().len();
    let mut out = Vec::new();
    // End of each task done before or in the plan; `i64::MIN`: ended by the start state.
    let mut end_of: Vec<Option<i64>> = vec![None; n];
    for t in &state.done {
        if t.index() < n {
            end_of[t.index()] = Some(i64::MIN);
        }
    }
    let mut main_free = state.time_s;
    let mut link: Option<(i64, TaskId)> = None;
    for r in &state.running {
        if r.task.index() >= n {
            continue;
        }
        end_of[r.task.index()] = Some(r.end_s);
        let tl = instance.task(r.task).timeline;
        if tl.uses_main() {
            main_free = main_free.max(r.end_s);
        }
        if tl.uses_link() && link.is_none_or(|(e, _)| r.end_s > e) {
            link = Some((r.end_s, r.task));
        }
    }
    // Steps in start order (ties in plan order).
    let mut order: Vec<usize> = (0..plan.steps.len()).collect();
    order.sort_by_key(|&i| plan.steps[i].start_s);
    let mut data = state.data_mb;
    let mut driven = state.driven_m;
    for &i in &order {
        let s = plan.steps[i];
        let Some(task) =
            check_step_task(instance, &s, i, |t| end_of[t.index()].is_some(), &mut out)
        else {
            continue;
        };
        let tl = task.timeline;
        if s.start_s < state.time_s || (tl.uses_main() && s.start_s < main_free) {
            out.push(Violation::Overlap { step: i });
        }
        if tl.uses_link()
            && let Some((e, other)) = link
            && s.start_s < e
        {
            out.push(Violation::LinkOverlap { step: i, other });
        }
        if s.end_s > p.end_s {
            out.push(Violation::PastEndOfSol { step: i });
        }
        for &q in &task.preconditions {
            if end_of
                .get(q.index())
                .copied()
                .flatten()
                .is_none_or(|e| e > s.start_s)
            {
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
        data += task.data_mb;
        if data > p.data_capacity_mb + DATA_EPS_MB {
            out.push(Violation::DataFull {
                step: i,
                data_mb: data,
            });
        }
        data = (data - task.downlink_mb).max(0.0);
        driven += task.drive_m;
        if tl.uses_main() {
            main_free = main_free.max(s.end_s);
        }
        if tl.uses_link() && link.is_none_or(|(e, _)| s.end_s > e) {
            link = Some((s.end_s, s.task));
        }
        end_of[s.task.index()] = Some(s.end_s);
    }
    // The battery through every piece; each step reports the lowest level while it runs.
    let mut lowest: Vec<f64> = vec![f64::INFINITY; plan.steps.len()];
    sweep_steps(instance, state, plan, |_, e, running| {
        for i in running {
            lowest[i] = lowest[i].min(e);
        }
    });
    for (i, &e) in lowest.iter().enumerate() {
        if e < -ENERGY_EPS_WH {
            out.push(Violation::BatteryEmpty {
                step: i,
                energy_wh: e,
            });
        }
    }
    for &m in instance.mandatory_tasks() {
        if end_of[m.index()].is_none() {
            out.push(Violation::MissingMandatory { task: m });
        }
    }
    out
}
