//! The rover's resource state between activities, and the one transition rule shared by the
//! search, the greedy completion and repair: start each appended task as early as possible.
//!
//! ## Time and waiting
//! A task starts at the earliest whole second `t ≥ max(previous end, earliest_start_s)` at
//! which the battery, recharging while idle at `recharge_w` (clipped at capacity), holds
//! enough energy to finish it without going below 0. Waiting is therefore allowed, but only
//! as long as it helps. This left-shifted, energy-aware schedule dominates every other
//! schedule of the same sequence: idling (`e ↦ min(C, e + R·Δ)`) and a draining task
//! (`e ↦ e − k`) satisfy `idle(drain(e)) ≥ drain(idle(e))`, and a charging task commutes with
//! idling, so starting a task earlier leaves at least as much energy at every later instant,
//! while data volume and metres driven depend only on the order. Windows are absolute (a
//! periodic campaign's instances are due at fixed times), so an earlier end never closes a
//! later window. Searching over orders with this rule is thus complete.
//!
//! ## Two timelines
//! When some task holds the HBS link ([`Timeline`](crate::Timeline)), a task starts at the earliest
//! second its window, the timelines it holds, the *ends* of its preconditions and the battery
//! allow. The timelines are exclusive; a task on the link alone overlaps main-timeline tasks, and
//! their powers add. The battery is then simulated piecewise: the cursor keeps the energy at the
//! earliest time any further task could start, and the tasks still running after it; every append
//! re-simulates them with the new task to the last end, so a drain that would empty the battery
//! while two tasks overlap is refused. Adding a task only lowers the energy later (powers are ≥ 0),
//! so a refusal is final. Appending the tasks of any schedule in start order reproduces it (a
//! left-shifted one exactly); where the battery makes a task wait while a task of the other
//! timeline runs, it waits for that task's end, then for recharge — a rule, not an exhaustive
//! search over waits. Data, distance and state-based windows stay on the main timeline (link-only
//! tasks have none), so they keep the order rule above.

use crate::error::PlanError;
use crate::instance::{Instance, Task, TaskId};
use crate::value::Value;
use serde::{Deserialize, Serialize};

mod timelines;

/// Energy slack, Wh: a battery at `-ENERGY_EPS_WH` still counts as empty, not overdrawn.
pub const ENERGY_EPS_WH: f64 = 1e-9;
/// Data slack, MB.
pub const DATA_EPS_MB: f64 = 1e-9;
/// Distance slack for state-based windows, m.
pub const DISTANCE_EPS_M: f64 = 1e-9;

/// What the rover has and has done at a moment: the start of a plan or of a replan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct State {
    /// Now, s after midnight.
    pub time_s: i64,
    /// Battery energy, Wh.
    pub energy_wh: f64,
    /// Stored data volume, MB.
    pub data_mb: f64,
    /// Metres driven so far this sol (for state-based windows).
    pub driven_m: f64,
    /// Tasks already done (they count towards preconditions, campaigns and value).
    pub done: Vec<TaskId>,
    /// Tasks of `done` still running after `time_s` — only where two timelines overlap (see
    /// [`Timeline`](crate::Timeline)): each holds its timelines and draws its power until its
    /// end. `energy_wh`, `data_mb` and `driven_m` already count them, except their draw after
    /// `time_s`. (default: none)
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub running: Vec<Running>,
}

/// A task started before a [`State`]'s `time_s` that ends after it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Running {
    /// The task (also in the state's `done`).
    pub task: TaskId,
    /// When it started, s after midnight.
    pub start_s: i64,
    /// When it ends, s after midnight.
    pub end_s: i64,
}

impl State {
    /// The same state at `t_s`, nothing started meanwhile: the battery recharges while idle
    /// and the [`running`](State::running) tasks draw until they end. On two timelines the
    /// state's time may come out later than `t_s`: the earliest time any task could start.
    ///
    /// # Errors
    /// [`PlanError::InvalidState`] if this state is malformed for `instance`, or `t_s` is
    /// before its time or after the end of the sol.
    pub fn advanced_to(&self, instance: &Instance, t_s: i64) -> Result<State, PlanError> {
        let mut cur = Cursor::new(instance, self)?;
        if t_s < self.time_s || t_s > instance.problem().end_s {
            return Err(PlanError::InvalidState {
                field: "time_s",
                value: t_s as f64,
                expected: "a time from the state's time to the end of the sol",
            });
        }
        if instance.uses_link() {
            cur.advance_to(instance, t_s);
        } else {
            cur.energy_wh = Cursor::idle(instance, cur.energy_wh, t_s - cur.time_s);
            cur.time_s = t_s;
            cur.energy_t_s = t_s;
        }
        Ok(cur.state(self.done.clone()))
    }

    /// The state at the start of `instance`'s window.
    #[must_use]
    pub fn initial(instance: &Instance) -> Self {
        let p = instance.problem();
        Self {
            time_s: p.start_s,
            energy_wh: p.initial_energy_wh,
            data_mb: p.initial_data_mb,
            driven_m: 0.0,
            done: Vec::new(),
            running: Vec::new(),
        }
    }
}

/// Why a task cannot be appended to a partial plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Blocker {
    /// The task is already done.
    AlreadyDone,
    /// A precondition has not run.
    PreconditionMissing,
    /// The metres driven are outside its state-based window.
    DrivenWindowMissed,
    /// Its latest start has passed.
    WindowMissed,
    /// The battery cannot supply it (even after recharging) before its latest start.
    Battery,
    /// It would end after the sol window.
    EndOfSol,
    /// Its data would overflow the data volume.
    DataVolume,
    /// Running it would make this mandatory task's window pass.
    MandatoryLost(TaskId),
}

impl std::fmt::Display for Blocker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Blocker::AlreadyDone => write!(f, "already done"),
            Blocker::PreconditionMissing => write!(f, "a precondition has not run"),
            Blocker::DrivenWindowMissed => {
                write!(f, "the metres driven are outside its window")
            }
            Blocker::WindowMissed => write!(f, "its latest start has passed"),
            Blocker::Battery => write!(f, "the battery cannot supply it in time"),
            Blocker::EndOfSol => write!(f, "it would end after the sol window"),
            Blocker::DataVolume => write!(f, "its data would overflow the data volume"),
            Blocker::MandatoryLost(t) => {
                write!(f, "it would make mandatory task #{} miss its window", t.0)
            }
        }
    }
}

/// A fixed-size set of task ids.
#[derive(Debug, PartialEq, Eq, Hash)]
pub(crate) struct TaskSet(Vec<u64>);

impl Clone for TaskSet {
    fn clone(&self) -> Self {
        Self(self.0.clone())
    }
    // Reuses the words (the search overwrites one scratch cursor per child).
    fn clone_from(&mut self, source: &Self) {
        self.0.clone_from(&source.0);
    }
}

impl TaskSet {
    pub(crate) fn new(n: usize) -> Self {
        Self(vec![0; n.div_ceil(64)])
    }
    pub(crate) fn contains(&self, t: TaskId) -> bool {
        self.0[t.index() / 64] >> (t.index() % 64) & 1 == 1
    }
    pub(crate) fn insert(&mut self, t: TaskId) {
        self.0[t.index() / 64] |= 1 << (t.index() % 64);
    }
}

/// The search's view of a [`State`]: the same quantities plus derived bookkeeping.
#[derive(Debug, PartialEq)]
pub(crate) struct Cursor {
    /// When the main timeline is free, s (on a single timeline: the end of the last task).
    pub time_s: i64,
    /// Battery energy at `energy_t_s`, Wh.
    pub energy_wh: f64,
    pub data_mb: f64,
    pub driven_m: f64,
    pub done: TaskSet,
    /// Members of each campaign done.
    pub counts: Vec<u32>,
    /// Mandatory tasks not yet done.
    pub mandatory_left: u32,
    pub value: Value,
    /// When the HBS link is free, s (two timelines only).
    pub link_free_s: i64,
    /// The time of `energy_wh`: no further task starts before it (`time_s` on one timeline).
    pub energy_t_s: i64,
    /// Tasks still running after `energy_t_s` (two timelines only).
    pub running: Vec<Running>,
    /// End of each task, s, `i64::MIN` until done or when done in the start state (two
    /// timelines only; empty otherwise).
    pub ends_s: Vec<i64>,
}

impl Clone for Cursor {
    fn clone(&self) -> Self {
        Self {
            time_s: self.time_s,
            energy_wh: self.energy_wh,
            data_mb: self.data_mb,
            driven_m: self.driven_m,
            done: self.done.clone(),
            counts: self.counts.clone(),
            mandatory_left: self.mandatory_left,
            value: self.value,
            link_free_s: self.link_free_s,
            energy_t_s: self.energy_t_s,
            running: self.running.clone(),
            ends_s: self.ends_s.clone(),
        }
    }
    // Field by field, reusing the vectors' buffers.
    fn clone_from(&mut self, source: &Self) {
        self.time_s = source.time_s;
        self.energy_wh = source.energy_wh;
        self.data_mb = source.data_mb;
        self.driven_m = source.driven_m;
        self.done.clone_from(&source.done);
        self.counts.clone_from(&source.counts);
        self.mandatory_left = source.mandatory_left;
        self.value = source.value;
        self.link_free_s = source.link_free_s;
        self.energy_t_s = source.energy_t_s;
        self.running.clone_from(&source.running);
        self.ends_s.clone_from(&source.ends_s);
    }
}

impl Cursor {
    /// The cursor of `state`, checked.
    pub(crate) fn new(inst: &Instance, state: &State) -> Result<Self, PlanError> {
        let p = inst.problem();
        let bad = |field, value: f64, expected| {
            Err(PlanError::InvalidState {
                field,
                value,
                expected,
            })
        };
        if state.time_s < p.start_s || state.time_s > p.end_s {
            return bad(
                "time_s",
                state.time_s as f64,
                "a time inside [start_s, end_s]",
            );
        }
        // Simulated states may sit a rounding error outside the range: accept and clamp.
        let energy_range = -ENERGY_EPS_WH..=p.battery_capacity_wh + ENERGY_EPS_WH;
        if !(state.energy_wh.is_finite() && energy_range.contains(&state.energy_wh)) {
            return bad("energy_wh", state.energy_wh, "0 ..= battery_capacity_wh");
        }
        let data_range = -DATA_EPS_MB..=p.data_capacity_mb + DATA_EPS_MB;
        if !(state.data_mb.is_finite() && data_range.contains(&state.data_mb)) {
            return bad("data_mb", state.data_mb, "0 ..= data_capacity_mb");
        }
        if !(state.driven_m.is_finite() && state.driven_m >= 0.0) {
            return bad("driven_m", state.driven_m, "a finite distance >= 0 m");
        }
        let n = inst.tasks().len();
        let mut c = Self {
            time_s: state.time_s,
            energy_wh: state.energy_wh.clamp(0.0, p.battery_capacity_wh),
            data_mb: state.data_mb.clamp(0.0, p.data_capacity_mb),
            driven_m: state.driven_m,
            done: TaskSet::new(n),
            counts: vec![0; inst.campaigns().len()],
            mandatory_left: inst.tasks().iter().filter(|t| t.mandatory).count() as u32,
            value: Value::ZERO,
            link_free_s: state.time_s,
            energy_t_s: state.time_s,
            running: Vec::new(),
            ends_s: if inst.uses_link() {
                vec![i64::MIN; n]
            } else {
                Vec::new()
            },
        };
        for &t in &state.done {
            if t.index() >= n {
                return bad("done", f64::from(t.0), "ids of tasks of this instance");
            }
            if c.done.contains(t) {
                return bad("done", f64::from(t.0), "each task at most once");
            }
            c.mark_done(inst, t);
        }
        if !inst.uses_link() {
            if let Some(r) = state.running.first() {
                return bad(
                    "running",
                    f64::from(r.task.0),
                    "no running task: only tasks on the hbs_link timeline overlap others",
                );
            }
            return Ok(c);
        }
        for r in &state.running {
            if r.task.index() >= n || !c.done.contains(r.task) {
                return bad("running", f64::from(r.task.0), "tasks of `done`");
            }
            if !(r.start_s <= state.time_s && r.end_s > r.start_s) {
                return bad(
                    "running",
                    r.end_s as f64,
                    "start_s <= time_s and end_s > start_s",
                );
            }
            c.hold(inst.task(r.task).timeline, r.task, r.end_s);
            if r.end_s > state.time_s {
                c.running.push(*r);
            }
        }
        c.settle(inst, state.time_s);
        Ok(c)
    }

    /// The state this cursor stands for, with `done` in the order the tasks were done.
    pub(crate) fn state(&self, done: Vec<TaskId>) -> State {
        State {
            time_s: self.energy_t_s,
            energy_wh: self.energy_wh,
            data_mb: self.data_mb,
            driven_m: self.driven_m,
            done,
            running: self.running.clone(),
        }
    }

    /// Energy after idling `dt_s` seconds from `energy_wh`.
    fn idle(inst: &Instance, energy_wh: f64, dt_s: i64) -> f64 {
        let p = inst.problem();
        (energy_wh + p.recharge_w * dt_s as f64 / 3600.0).min(p.battery_capacity_wh)
    }

    /// The earliest feasible start of `t` after this cursor, or `None` when `t` cannot be
    /// appended (done, precondition missing, window or resource violated, or a mandatory task
    /// would become impossible).
    pub(crate) fn earliest_start(&self, inst: &Instance, t: TaskId) -> Option<i64> {
        self.try_start(inst, t).ok()
    }

    /// [`Self::earliest_start`], saying why when `t` cannot be appended.
    pub(crate) fn try_start(&self, inst: &Instance, t: TaskId) -> Result<i64, Blocker> {
        let task = inst.task(t);
        let p = inst.problem();
        if self.done.contains(t) {
            return Err(Blocker::AlreadyDone);
        }
        if task.preconditions.iter().any(|&q| !self.done.contains(q)) {
            return Err(Blocker::PreconditionMissing);
        }
        if let Some([lo, hi]) = task.driven_window_m
            && (self.driven_m < lo - DISTANCE_EPS_M || self.driven_m > hi + DISTANCE_EPS_M)
        {
            return Err(Blocker::DrivenWindowMissed);
        }
        let d = task.duration_s;
        let start = if inst.uses_link() {
            self.battery_start_timelines(inst, task, t)?
        } else {
            self.battery_start(inst, task)?
        };
        let end = start + d;
        if end > p.end_s {
            return Err(Blocker::EndOfSol);
        }
        if self.data_mb + task.data_mb > p.data_capacity_mb + DATA_EPS_MB {
            return Err(Blocker::DataVolume);
        }
        // A mandatory task whose window closes before `end` could never be appended again
        // (on two timelines: if it shares one with `t`).
        if self.mandatory_left > u32::from(task.mandatory) {
            for &m in inst.mandatory_tasks() {
                let other = inst.task(m);
                if m != t
                    && other.latest_start_s < end
                    && !self.done.contains(m)
                    && (!inst.uses_link() || other.timeline.shares(task.timeline))
                {
                    return Err(Blocker::MandatoryLost(m));
                }
            }
        }
        Ok(start)
    }

    /// On one timeline: the earliest start after the previous task's end and the window's
    /// start at which the battery, recharging while idle, can carry `task`.
    fn battery_start(&self, inst: &Instance, task: &Task) -> Result<i64, Blocker> {
        let p = inst.problem();
        let d = task.duration_s;
        let mut start = self.time_s.max(task.earliest_start_s);
        if start > task.latest_start_s {
            return Err(Blocker::WindowMissed);
        }
        let net_wh = (p.recharge_w - task.power_w) * d as f64 / 3600.0;
        if net_wh < 0.0 {
            if -net_wh > p.battery_capacity_wh + ENERGY_EPS_WH {
                return Err(Blocker::Battery);
            }
            let mut e = Self::idle(inst, self.energy_wh, start - self.time_s);
            if e + net_wh < -ENERGY_EPS_WH {
                if p.recharge_w <= 0.0 {
                    return Err(Blocker::Battery);
                }
                let wait = ((-net_wh - ENERGY_EPS_WH - e) * 3600.0 / p.recharge_w).ceil();
                start += (wait.max(0.0) as i64).min(p.end_s);
                e = Self::idle(inst, self.energy_wh, start - self.time_s);
                // Rounding can leave the ceiling one second short.
                while e + net_wh < -ENERGY_EPS_WH && start <= task.latest_start_s {
                    start += 1;
                    e = Self::idle(inst, self.energy_wh, start - self.time_s);
                }
                if start > task.latest_start_s {
                    return Err(Blocker::Battery);
                }
            }
        }
        Ok(start)
    }

    /// Append `t` starting at `start_s` (from [`Self::earliest_start`]) and running
    /// `duration_s` (the model's when `None`).
    pub(crate) fn append(
        &mut self,
        inst: &Instance,
        t: TaskId,
        start_s: i64,
        duration_s: Option<i64>,
    ) {
        let task = inst.task(t);
        let p = inst.problem();
        let d = duration_s.unwrap_or(task.duration_s);
        if inst.uses_link() {
            self.hold(task.timeline, t, start_s + d);
            self.running.push(Running {
                task: t,
                start_s,
                end_s: start_s + d,
            });
        } else {
            let e = Self::idle(inst, self.energy_wh, start_s - self.time_s);
            self.energy_wh =
                (e + (p.recharge_w - task.power_w) * d as f64 / 3600.0).min(p.battery_capacity_wh);
            self.time_s = start_s + d;
            self.energy_t_s = self.time_s;
        }
        self.data_mb = (self.data_mb + task.data_mb - task.downlink_mb).max(0.0);
        self.driven_m += task.drive_m;
        self.mark_done(inst, t);
        if inst.uses_link() {
            self.settle(inst, i64::MIN);
        }
    }

    fn mark_done(&mut self, inst: &Instance, t: TaskId) {
        let task = inst.task(t);
        self.done.insert(t);
        self.value.tiers_micro[task.tier] += task.utility_micro;
        if let Some(c) = task.campaign {
            let curve = &inst.campaigns()[c];
            let n = self.counts[c];
            self.value.tiers_micro[curve.tier] += curve.utility(n + 1) - curve.utility(n);
            self.counts[c] = n + 1;
        }
        if task.mandatory {
            self.mandatory_left -= 1;
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::problem::{Activity, Problem};

    #[test]
    fn a_task_waits_for_the_battery_to_recharge() {
        // 10 Wh in the battery, 36 W recharge; the task needs a net 36 Wh.
        let p = Problem {
            start_s: 0,
            end_s: 20_000,
            battery_capacity_wh: 50.0,
            initial_energy_wh: 10.0,
            recharge_w: 36.0,
            data_capacity_mb: 10.0,
            initial_data_mb: 0.0,
            activities: vec![Activity::task("a", 3600, [0, 10_000], 72.0, 1.0)],
            campaigns: Vec::new(),
        };
        let inst = Instance::new(&p).unwrap();
        let cur = Cursor::new(&inst, &State::initial(&inst)).unwrap();
        // (36 − 10) Wh at 36 W is 2600 s.
        assert_eq!(cur.earliest_start(&inst, TaskId(0)), Some(2600));
        let mut after = cur.clone();
        after.append(&inst, TaskId(0), 2600, None);
        assert!(after.energy_wh.abs() < 1e-9);
        // A battery too small for the task never fits it.
        let mut small = p.clone();
        small.battery_capacity_wh = 30.0;
        let inst = Instance::new(&small).unwrap();
        let cur = Cursor::new(&inst, &State::initial(&inst)).unwrap();
        assert_eq!(cur.earliest_start(&inst, TaskId(0)), None);
    }

    #[test]
    fn recharge_is_clipped_at_capacity() {
        let p = Problem {
            start_s: 0,
            end_s: 20_000,
            battery_capacity_wh: 20.0,
            initial_energy_wh: 19.0,
            recharge_w: 36.0,
            data_capacity_mb: 10.0,
            initial_data_mb: 0.0,
            activities: vec![Activity::task("a", 100, [10_000, 10_000], 0.0, 1.0)],
            campaigns: Vec::new(),
        };
        let inst = Instance::new(&p).unwrap();
        let mut cur = Cursor::new(&inst, &State::initial(&inst)).unwrap();
        cur.append(&inst, TaskId(0), 10_000, None);
        assert_eq!(cur.energy_wh, 20.0);
    }
}
