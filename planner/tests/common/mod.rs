//! An exhaustive reference planner, written independently of the search: every order of
//! every subset of the remaining tasks, each task at its earliest feasible second (found
//! here by bisection on the battery level, not by the search's closed form).

#![allow(dead_code, clippy::unwrap_used)]

use planner::{
    DATA_EPS_MB, DISTANCE_EPS_M, ENERGY_EPS_WH, Instance, MAX_TIERS, Plan, PlanStep, State, TaskId,
    Value,
};

/// The reference simulator's state.
#[derive(Clone, Debug)]
pub struct Sim {
    pub time_s: i64,
    pub energy_wh: f64,
    pub data_mb: f64,
    pub driven_m: f64,
    pub done: Vec<bool>,
    pub order: Vec<TaskId>,
    pub steps: Vec<PlanStep>,
}

impl Sim {
    pub fn new(inst: &Instance, s: &State) -> Self {
        let mut done = vec![false; inst.tasks().len()];
        for t in &s.done {
            done[t.index()] = true;
        }
        Self {
            time_s: s.time_s,
            energy_wh: s.energy_wh,
            data_mb: s.data_mb,
            driven_m: s.driven_m,
            done,
            order: s.done.clone(),
            steps: Vec::new(),
        }
    }

    pub fn state(&self) -> State {
        State {
            time_s: self.time_s,
            energy_wh: self.energy_wh,
            data_mb: self.data_mb,
            driven_m: self.driven_m,
            done: self.order.clone(),
            running: Vec::new(),
        }
    }

    fn energy_at(&self, inst: &Instance, t: i64) -> f64 {
        let p = inst.problem();
        (self.energy_wh + p.recharge_w * (t - self.time_s) as f64 / 3600.0)
            .min(p.battery_capacity_wh)
    }

    /// The earliest feasible start of `id`, or `None`.
    pub fn start_of(&self, inst: &Instance, id: TaskId) -> Option<i64> {
        let p = inst.problem();
        let t = inst.task(id);
        if self.done[id.index()] || t.preconditions.iter().any(|q| !self.done[q.index()]) {
            return None;
        }
        if let Some([lo, hi]) = t.driven_window_m
            && (self.driven_m < lo - DISTANCE_EPS_M || self.driven_m > hi + DISTANCE_EPS_M)
        {
            return None;
        }
        if self.data_mb + t.data_mb > p.data_capacity_mb + DATA_EPS_MB {
            return None;
        }
        let net = (p.recharge_w - t.power_w) * t.duration_s as f64 / 3600.0;
        let ok = |s: i64| self.energy_at(inst, s) + net >= -ENERGY_EPS_WH;
        let lo = self.time_s.max(t.earliest_start_s);
        let hi = t.latest_start_s.min(p.end_s - t.duration_s);
        if lo > hi || !ok(hi) {
            return None;
        }
        // Energy at the start never decreases with a later start: bisect for the first fit.
        let (mut a, mut b) = (lo, hi);
        while a < b {
            let m = a + (b - a) / 2;
            if ok(m) { b = m } else { a = m + 1 }
        }
        Some(a)
    }

    pub fn push(&mut self, inst: &Instance, id: TaskId, start: i64) {
        let p = inst.problem();
        let t = inst.task(id);
        let e = self.energy_at(inst, start);
        self.energy_wh = (e + (p.recharge_w - t.power_w) * t.duration_s as f64 / 3600.0)
            .min(p.battery_capacity_wh);
        self.data_mb = (self.data_mb + t.data_mb - t.downlink_mb).max(0.0);
        self.driven_m += t.drive_m;
        self.time_s = start + t.duration_s;
        self.done[id.index()] = true;
        self.order.push(id);
        self.steps.push(PlanStep {
            task: id,
            start_s: start,
            end_s: self.time_s,
        });
    }
}

/// Value of a set of done tasks, from the model's utilities and campaign curves.
pub fn value_of(inst: &Instance, done: &[bool]) -> Value {
    let mut v = [0i64; MAX_TIERS];
    let mut counts = vec![0u32; inst.campaigns().len()];
    for (i, t) in inst.tasks().iter().enumerate() {
        if done[i] {
            v[t.tier] += t.utility_micro;
            if let Some(c) = t.campaign {
                counts[c] += 1;
            }
        }
    }
    for (c, curve) in inst.campaigns().iter().enumerate() {
        v[curve.tier] += curve.utility(counts[c]);
    }
    Value { tiers_micro: v }
}

/// The best value (and one plan reaching it) over every sequence from `state` holding every
/// mandatory task; `None` when there is none.
pub fn exhaustive(inst: &Instance, state: &State) -> Option<(Value, Plan)> {
    let mut best = None;
    let root = Sim::new(inst, state);
    dfs(inst, &root, &mut best);
    best
}

fn dfs(inst: &Instance, sim: &Sim, best: &mut Option<(Value, Plan)>) {
    if inst.mandatory_tasks().iter().all(|m| sim.done[m.index()]) {
        let v = value_of(inst, &sim.done);
        if best.as_ref().is_none_or(|(b, _)| v > *b) {
            *best = Some((
                v,
                Plan {
                    steps: sim.steps.clone(),
                },
            ));
        }
    }
    for i in 0..inst.tasks().len() {
        let id = TaskId(i as u32);
        if let Some(s) = sim.start_of(inst, id) {
            let mut next = sim.clone();
            next.push(inst, id, s);
            dfs(inst, &next, best);
        }
    }
}

/// Random feasible prefixes of a plan, as replanning states.
pub fn random_states(inst: &Instance, rng: &mut rand_chacha::ChaCha8Rng, n: usize) -> Vec<State> {
    use rand::RngExt;
    let mut out = vec![State::initial(inst)];
    for _ in 0..n {
        let mut sim = Sim::new(inst, &State::initial(inst));
        let depth = rng.random_range(1..=3);
        for _ in 0..depth {
            let next: Vec<(TaskId, i64)> = (0..inst.tasks().len() as u32)
                .map(TaskId)
                .filter_map(|t| sim.start_of(inst, t).map(|s| (t, s)))
                .collect();
            if next.is_empty() {
                break;
            }
            let (t, s) = next[rng.random_range(0..next.len())];
            sim.push(inst, t, s);
        }
        out.push(sim.state());
    }
    out
}
