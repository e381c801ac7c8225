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

use crate::error::PlanError;
use crate::instance::{Instance, TaskId};
use crate::value::Value;
use serde::{Deserialize, Serialize};

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
}

impl State {
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
    pub time_s: i64,
    pub energy_wh: f64,
    pub data_mb: f64,
    pub driven_m: f64,
    pub done: TaskSet,
    /// Members of each campaign done.
    pub counts: Vec<u32>,
    /// Mandatory tasks not yet done.
    pub mandatory_left: u32,
    pub value: Value,
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
        Ok(c)
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
        let end = start + d;
        if end > p.end_s {
            return Err(Blocker::EndOfSol);
        }
        if self.data_mb + task.data_mb > p.data_capacity_mb + DATA_EPS_MB {
            return Err(Blocker::DataVolume);
        }
        // A mandatory task whose window closes before `end` could never be appended again.
        if self.mandatory_left > u32::from(task.mandatory) {
            for &m in inst.mandatory_tasks() {
                if m != t && inst.task(m).latest_start_s < end && !self.done.contains(m) {
                    return Err(Blocker::MandatoryLost(m));
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
        let e = Self::idle(inst, self.energy_wh, start_s - self.time_s);
        self.energy_wh =
            (e + (p.recharge_w - task.power_w) * d as f64 / 3600.0).min(p.battery_capacity_wh);
        self.data_mb = (self.data_mb + task.data_mb - task.downlink_mb).max(0.0);
        self.time_s = start_s + d;
        self.driven_m += task.drive_m;
        self.mark_done(inst, t);
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
