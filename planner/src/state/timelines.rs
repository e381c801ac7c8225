//! The two-timeline part of the cursor (see the [`state`](super) module docs): when each
//! timeline is free, the battery simulated piece by piece through overlapping tasks, the
//! earliest time a further task could start, and the earliest start the battery allows
//! while another task runs.

use super::{Blocker, Cursor, ENERGY_EPS_WH, Running};
use crate::instance::{Instance, Task, TaskId};
use crate::problem::{Problem, Timeline};

/// Piecewise-exact battery from energy `e` at `t`: idle recharge plus the power of every task
/// of `running` (and `extra`) while it runs, clipped at capacity, up to the last end (at least
/// `stop_s`). Returns the energy at `stop_s` (`e` if `stop_s ≤ t`) and the lowest energy,
/// before clipping, at the end of a piece during which some task runs (`f64::INFINITY` if
/// none does).
pub(super) fn sweep(
    inst: &Instance,
    mut t: i64,
    mut e: f64,
    running: &[Running],
    extra: Option<Running>,
    stop_s: i64,
) -> (f64, f64) {
    let p: &Problem = inst.problem();
    let all = || running.iter().chain(extra.iter());
    let mut at_stop = e;
    let mut low = f64::INFINITY;
    loop {
        let mut next = if stop_s > t { stop_s } else { i64::MAX };
        for r in all() {
            if r.start_s > t {
                next = next.min(r.start_s);
            }
            if r.end_s > t {
                next = next.min(r.end_s);
            }
        }
        if next == i64::MAX {
            return (at_stop, low);
        }
        let mut draw_w = 0.0;
        let mut draining = false;
        for r in all() {
            if r.start_s <= t && r.end_s >= next {
                draw_w += inst.task(r.task).power_w;
                draining = true;
            }
        }
        e += (p.recharge_w - draw_w) * (next - t) as f64 / 3600.0;
        if draining {
            low = low.min(e);
        }
        e = e.min(p.battery_capacity_wh);
        t = next;
        if t == stop_s {
            at_stop = e;
        }
    }
}

impl Cursor {
    /// When every timeline `timeline` holds is free.
    pub(crate) fn ready_s(&self, timeline: Timeline) -> i64 {
        match timeline {
            Timeline::Main => self.time_s,
            Timeline::HbsLink => self.link_free_s,
            Timeline::MainAndHbsLink => self.time_s.max(self.link_free_s),
        }
    }

    /// Mark `timeline` busy until `end_s` by task `t` (two timelines).
    pub(super) fn hold(&mut self, timeline: Timeline, t: TaskId, end_s: i64) {
        if timeline.uses_main() {
            self.time_s = self.time_s.max(end_s);
        }
        if timeline.uses_link() {
            self.link_free_s = self.link_free_s.max(end_s);
        }
        self.ends_s[t.index()] = end_s;
    }

    /// Move the energy's time forward to the earliest time a further task could start (at
    /// least `floor_s`), simulating the running tasks up to it (two timelines). A task
    /// cannot start before its timelines are free, its window opens and its preconditions
    /// have ended — or, for an undone precondition, could have ended at the earliest.
    pub(super) fn settle(&mut self, inst: &Instance, floor_s: i64) {
        const IMPOSSIBLE: i64 = i64::MAX;
        let n = inst.tasks().len();
        let mut stack = [0i64; 64];
        let mut heap = Vec::new();
        let lower: &mut [i64] = if n <= stack.len() {
            &mut stack[..n]
        } else {
            heap.resize(n, 0);
            &mut heap
        };
        let mut next = IMPOSSIBLE;
        for &t in inst.topological_order() {
            if self.done.contains(t) {
                continue;
            }
            let task = inst.task(t);
            let mut lo = self.ready_s(task.timeline).max(task.earliest_start_s);
            for &q in &task.preconditions {
                lo = lo.max(if self.done.contains(q) {
                    self.ends_s[q.index()]
                } else {
                    lower[q.index()].saturating_add(inst.task(q).duration_s)
                });
            }
            lower[t.index()] = if lo <= task.latest_start_s {
                next = next.min(lo);
                lo
            } else {
                IMPOSSIBLE
            };
        }
        if next == IMPOSSIBLE {
            next = self.time_s.max(self.link_free_s);
        }
        let t = next.max(floor_s).max(self.energy_t_s);
        if t > self.energy_t_s {
            let (e, _) = sweep(
                inst,
                self.energy_t_s,
                self.energy_wh,
                &self.running,
                None,
                t,
            );
            self.energy_wh = e;
            self.energy_t_s = t;
            self.running.retain(|r| r.end_s > t);
        }
    }

    /// Move "now" forward to `t_s` (no further task starts before it): the start of the step
    /// the simulator has just run, so nothing is placed before it.
    pub(crate) fn advance_to(&mut self, inst: &Instance, t_s: i64) {
        if inst.uses_link() {
            self.settle(inst, t_s);
        }
    }

    /// The lowest battery energy from now to the end of every running task, Wh (the energy
    /// now on a single timeline).
    pub(crate) fn lowest_energy_wh(&self, inst: &Instance) -> f64 {
        let (_, low) = sweep(
            inst,
            self.energy_t_s,
            self.energy_wh,
            &self.running,
            None,
            self.energy_t_s,
        );
        self.energy_wh.min(low)
    }

    /// On two timelines: the earliest start once its timelines are free, its preconditions
    /// have ended and its window has opened, at which the battery carries `task` and every
    /// task still running; else after the end of a running task, else after recharging.
    pub(super) fn battery_start_timelines(
        &self,
        inst: &Instance,
        task: &Task,
        t: TaskId,
    ) -> Result<i64, Blocker> {
        let p = inst.problem();
        let d = task.duration_s;
        let mut lower = self
            .ready_s(task.timeline)
            .max(task.earliest_start_s)
            .max(self.energy_t_s);
        for &q in &task.preconditions {
            lower = lower.max(self.ends_s[q.index()]);
        }
        if lower > task.latest_start_s {
            return Err(Blocker::WindowMissed);
        }
        if (p.recharge_w - task.power_w) * d as f64 / 3600.0
            < -p.battery_capacity_wh - ENERGY_EPS_WH
        {
            return Err(Blocker::Battery);
        }
        let fits = |s: i64| {
            let run = Running {
                task: t,
                start_s: s,
                end_s: s + d,
            };
            let (_, low) = sweep(
                inst,
                self.energy_t_s,
                self.energy_wh,
                &self.running,
                Some(run),
                s,
            );
            low >= -ENERGY_EPS_WH
        };
        if fits(lower) {
            return Ok(lower);
        }
        // Wait for a running task to end ...
        let mut ends: Vec<i64> = self
            .running
            .iter()
            .map(|r| r.end_s)
            .filter(|&e| e > lower)
            .collect();
        ends.sort_unstable();
        for &s in &ends {
            if s > task.latest_start_s {
                return Err(Blocker::Battery);
            }
            if fits(s) {
                return Ok(s);
            }
        }
        // ... then, alone, for the recharge (the single-timeline rule).
        if p.recharge_w <= 0.0 {
            return Err(Blocker::Battery);
        }
        let from = ends.last().copied().unwrap_or(lower).max(lower);
        let (e, _) = sweep(
            inst,
            self.energy_t_s,
            self.energy_wh,
            &self.running,
            None,
            from,
        );
        let net_wh = (p.recharge_w - task.power_w) * d as f64 / 3600.0;
        let wait = ((-net_wh - ENERGY_EPS_WH - e) * 3600.0 / p.recharge_w).ceil();
        let mut start = from + (wait.max(0.0) as i64).min(p.end_s);
        while start <= task.latest_start_s && !fits(start) {
            start += 1;
        }
        if start > task.latest_start_s {
            return Err(Blocker::Battery);
        }
        Ok(start)
    }
}
