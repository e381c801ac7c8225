//! Anytime branch and bound forward in time (paper 003 §3.1).
//!
//! A node is a partial plan; it is expanded by appending, one at a time, every task that can
//! follow it, each started as early as possible (see [`state`](crate::State) for why that is
//! complete). A child is kept only if its optimistic bound (see [`BoundKind`]) beats the
//! incumbent, the best plan found so far. Expanded nodes are also completed greedily (each of
//! the first 256, then every 16th), and that pessimistic completion becomes the incumbent
//! when it is better.
//!
//! The search runs in two phases:
//! - **the dive** ([`dive_nodes`](SearchSettings::dive_nodes) expansions): children are
//!   pushed best-last onto a stack, so the search dives depth-first, and every
//!   [`resort_every`](SearchSettings::resort_every) expansions the whole frontier is sorted
//!   by bound, the hybrid depth-first / best-first order of the paper. Incumbents come fast;
//!   bounds are the knapsacks' alone.
//! - **the proof**: the time-indexed bounds are tuned at the root toward the incumbent and
//!   join every node's bound; the paths their tuning walked are tried as plans (a Lagrangian
//!   heuristic); and the frontier is kept sorted, best-first, ties to the deeper node. On the
//!   B6 n = 160 instances this proves in 241–475 expansions where the knapsack bounds alone
//!   took 602–7 650.
//!
//! Stopped by a budget, it returns the incumbent with the best bound over the frontier, an
//! honest optimality gap.
//!
//! A child that reaches the same set of done tasks as an earlier node, but no earlier, with
//! no more energy and no less data, is dropped as dominated (a memo keyed by the done set
//! keeps the Pareto front; see [`SearchSettings::dominance`]).
//!
//! With only a node budget the result is a deterministic function of the input: ties are
//! broken by task id and node creation order, never by time or hash order.
//!
//! ## References
//! Paper 003 §3.1, "Using Campaign Intent to Guide Planning".

use crate::bound::Bounder;
use crate::error::PlanError;
use crate::instance::{Instance, TaskId};
use crate::plan::{Plan, PlanOutcome, PlanStatus, PlanStep, SearchSettings, SearchStats};
use crate::problem::Problem;
use crate::state::{Cursor, State, TaskSet};
use crate::value::{MAX_TIERS, Value};
use std::collections::{BinaryHeap, HashMap};
use std::time::Instant;

/// Every expanded node is completed greedily up to this many expansions ...
const GREEDY_EVERY_NODE_UNTIL: u64 = 256;
/// ... and after that every this many.
const GREEDY_EVERY: u64 = 16;

/// Most (time, energy, data) entries the dominance memo keeps before it stops growing.
const MAX_MEMO_ENTRIES: usize = 1 << 20;

/// Plan `problem` from the start of its window.
///
/// # Errors
/// A [`PlanError`] if the problem is malformed. A problem whose mandatory activities cannot
/// all fit is not an error: the outcome's status is [`PlanStatus::Infeasible`].
pub fn plan(problem: &Problem, settings: &SearchSettings) -> Result<PlanOutcome, PlanError> {
    let inst = Instance::new(problem)?;
    plan_from(&inst, &State::initial(&inst), settings)
}

/// Plan (or replan) `instance` from `state`: the time, energy, data and metres now, and the
/// tasks already done.
///
/// # Errors
/// [`PlanError::InvalidState`] if `state` is malformed.
pub fn plan_from(
    instance: &Instance,
    state: &State,
    settings: &SearchSettings,
) -> Result<PlanOutcome, PlanError> {
    let root = Cursor::new(instance, state)?;
    Ok(Search::new(instance, settings).run(root))
}

/// What the dominance memo keeps of a node (its done set is the key).
struct MemoEntry {
    /// When the main timeline is free.
    time_s: i64,
    /// Energy at `energy_t_s`.
    energy_wh: f64,
    data_mb: f64,
    /// End of each task (two timelines; empty on one).
    ends_s: Vec<i64>,
    energy_t_s: i64,
    link_free_s: i64,
    /// No task runs after `energy_t_s`.
    idle: bool,
}

impl MemoEntry {
    /// Whether this node can run every completion of `other` (same done set) at least as
    /// well. On one timeline: no later, no less energy, no more data. On two: the same end
    /// times (so the same running tasks and energy instant) with no less energy and no more
    /// data; or no task running here, both timelines free no later, and the battery, idling
    /// to `other`'s energy instant, at least `other`'s there — `other`'s running tasks only
    /// hold its timelines longer and drain its battery further.
    fn dominates(&self, other: &MemoEntry, inst: &Instance) -> bool {
        if self.data_mb > other.data_mb {
            return false;
        }
        if !inst.uses_link() {
            return self.time_s <= other.time_s && self.energy_wh >= other.energy_wh;
        }
        if self.ends_s == other.ends_s && self.energy_t_s == other.energy_t_s {
            return self.energy_wh >= other.energy_wh;
        }
        let p = inst.problem();
        let idled = |e: f64, dt_s: i64| {
            (e + p.recharge_w * dt_s as f64 / 3600.0).min(p.battery_capacity_wh)
        };
        self.idle
            && self.energy_t_s <= other.energy_t_s
            && self.time_s <= other.time_s
            && self.link_free_s <= other.link_free_s
            && idled(self.energy_wh, other.energy_t_s - self.energy_t_s) >= other.energy_wh
    }
}

#[derive(Clone)]
struct Node {
    cur: Cursor,
    steps: Vec<PlanStep>,
    bound: Value,
    /// Creation order, the deterministic tie-break.
    serial: u64,
}

struct Search<'a> {
    inst: &'a Instance,
    settings: &'a SearchSettings,
    bounder: Bounder<'a>,
    stats: SearchStats,
    best: Option<(Value, Vec<PlanStep>)>,
    serial: u64,
    /// Per set of done tasks, the Pareto front of the nodes reached so far.
    memo: HashMap<TaskSet, Vec<MemoEntry>>,
    memo_entries: usize,
}

impl<'a> Search<'a> {
    fn new(inst: &'a Instance, settings: &'a SearchSettings) -> Self {
        Self {
            inst,
            settings,
            bounder: Bounder::new(inst, settings.bound),
            stats: SearchStats::default(),
            best: None,
            serial: 0,
            memo: HashMap::new(),
            memo_entries: 0,
        }
    }

    /// Whether a node already reached the same done set no later, with no less energy and
    /// no more data. Such a node can run every completion of `cur` (idle until `cur`'s time,
    /// then follow it) and has the same value, so `cur` is redundant. Records `cur`
    /// otherwise. On two timelines ([`MemoEntry::dominates`]) the earlier node must have no
    /// task still running, or else the same end times, running tasks and energy instant.
    fn dominated(&mut self, cur: &Cursor) -> bool {
        if !self.settings.dominance {
            return false;
        }
        let key = || MemoEntry {
            time_s: cur.time_s,
            energy_wh: cur.energy_wh,
            data_mb: cur.data_mb,
            ends_s: cur.ends_s.clone(),
            energy_t_s: cur.energy_t_s,
            link_free_s: cur.link_free_s,
            idle: cur.running.is_empty(),
        };
        match self.memo.get_mut(&cur.done) {
            Some(front) => {
                let key = key();
                if front.iter().any(|e| e.dominates(&key, self.inst)) {
                    return true;
                }
                let before = front.len();
                front.retain(|e| !key.dominates(e, self.inst));
                self.memo_entries -= before - front.len();
                if self.memo_entries < MAX_MEMO_ENTRIES {
                    front.push(key);
                    self.memo_entries += 1;
                }
            }
            None => {
                if self.memo_entries < MAX_MEMO_ENTRIES {
                    self.memo.insert(cur.done.clone(), vec![key()]);
                    self.memo_entries += 1;
                }
            }
        }
        false
    }

    fn incumbent(&self) -> Option<Value> {
        self.best.as_ref().map(|b| b.0)
    }

    /// Make `cur` the incumbent if it is complete and better; its steps are only built then.
    fn offer(&mut self, cur: &Cursor, steps: impl FnOnce() -> Vec<PlanStep>) {
        if cur.mandatory_left == 0 && self.incumbent().is_none_or(|v| cur.value > v) {
            self.best = Some((cur.value, steps()));
        }
    }

    fn run(mut self, root: Cursor) -> PlanOutcome {
        let clock = Instant::now();
        let mut frontier = Frontier::Stack(Vec::new());
        self.offer(&root, Vec::new);
        self.greedy(&root, &[]);
        if let Some(bound) = self
            .bounder
            .evaluate(&root, self.incumbent(), &mut self.stats)
        {
            frontier.push(Node {
                cur: root.clone(),
                steps: Vec::new(),
                bound,
                serial: 0,
            });
        }
        let mut exhausted = true;
        let mut proving = false;
        while let Some(node) = frontier.pop() {
            if !proving && self.stats.nodes_expanded >= self.settings.dive_nodes {
                // The dive is over: bound with the time-indexed paths too (their tuning is
                // the cost of a few dozen nodes), try the tuning's paths as plans, and go
                // best-first.
                proving = true;
                frontier.go_best_first();
                let deadline = self.settings.time_budget.map(|b| clock + b);
                self.bounder
                    .start_indexed(&root, self.incumbent(), deadline);
                self.follow_paths(&root, &[], clock);
            }
            if self.incumbent().is_some_and(|v| node.bound <= v) {
                self.stats.nodes_pruned += 1;
                continue;
            }
            let over_nodes = self
                .settings
                .node_budget
                .is_some_and(|b| self.stats.nodes_expanded >= b);
            let over_time = self
                .settings
                .time_budget
                .is_some_and(|b| clock.elapsed() >= b);
            if over_nodes || over_time {
                frontier.push(node);
                exhausted = false;
                break;
            }
            self.stats.nodes_expanded += 1;
            // Greedy completions pay early (anytime incumbents); later the dive finds the
            // incumbents and a completion per node would cost ~20 % of the search for nothing.
            let e = self.stats.nodes_expanded;
            if e > 1 && (e <= GREEDY_EVERY_NODE_UNTIL || e.is_multiple_of(GREEDY_EVERY)) {
                self.greedy(&node.cur, &node.steps);
            }
            // A coupled time-indexed bound tunes at the first node that ties a tier: its
            // paths too are worth trying.
            self.follow_paths(&node.cur, &node.steps, clock);
            let children = self.expand(&node);
            frontier.extend(children);
            if self
                .stats
                .nodes_expanded
                .is_multiple_of(self.settings.resort_every.max(1))
            {
                frontier.sort();
            }
        }
        let incumbent = self.incumbent();
        let frontier_bound = frontier
            .nodes()
            .filter(|n| incumbent.is_none_or(|v| n.bound > v))
            .map(|n| n.bound)
            .max();
        self.stats.total_time = clock.elapsed();
        let (status, value, mut steps) = match self.best.take() {
            Some((v, s)) => (
                if exhausted || frontier_bound.is_none() {
                    PlanStatus::Optimal
                } else {
                    PlanStatus::Feasible
                },
                v,
                s,
            ),
            None => (
                if exhausted || frontier_bound.is_none() {
                    PlanStatus::Infeasible
                } else {
                    PlanStatus::NoPlanFound
                },
                root.value,
                Vec::new(),
            ),
        };
        // On two timelines a plan may append a link task after a main one that starts later:
        // steps are reported in start order (a stable sort; already so on one timeline).
        steps.sort_by_key(|s| s.start_s);
        let best_bound = match (status, frontier_bound) {
            (PlanStatus::Optimal, _) | (_, None) => value,
            (_, Some(b)) => b.max(value),
        };
        PlanOutcome {
            status,
            plan: Plan { steps },
            value,
            best_bound,
            stats: self.stats,
        }
    }

    /// Children of `node` that survive the bound; complete ones are offered as incumbents.
    fn expand(&mut self, node: &Node) -> Vec<Node> {
        let mut children = Vec::new();
        // One cursor reused for every child (most are pruned), and a child's steps are only
        // built when it is kept or becomes the incumbent.
        let mut cur = node.cur.clone();
        let with = |step: PlanStep| {
            let mut steps = Vec::with_capacity(node.steps.len() + 1);
            steps.extend_from_slice(&node.steps);
            steps.push(step);
            steps
        };
        for i in 0..self.inst.tasks().len() {
            let t = TaskId(i as u32);
            let Some(start) = node.cur.earliest_start(self.inst, t) else {
                continue;
            };
            cur.clone_from(&node.cur);
            cur.append(self.inst, t, start, None);
            let step = PlanStep {
                task: t,
                start_s: start,
                end_s: start + self.inst.task(t).duration_s,
            };
            self.stats.nodes_generated += 1;
            self.offer(&cur, || with(step));
            if self.dominated(&cur) {
                self.stats.nodes_dominated += 1;
                continue;
            }
            match self
                .bounder
                .evaluate(&cur, self.incumbent(), &mut self.stats)
            {
                Some(bound) => {
                    self.serial += 1;
                    children.push(Node {
                        cur: cur.clone(),
                        steps: with(step),
                        bound,
                        serial: self.serial,
                    });
                }
                None => self.stats.nodes_pruned += 1,
            }
        }
        children
    }

    /// [`Search::follow`] for each path the time-indexed bounds' tuning walked (none when
    /// nothing was tuned since the last call), within the time budget.
    fn follow_paths(&mut self, start: &Cursor, prefix: &[PlanStep], clock: Instant) {
        for order in self.bounder.take_paths() {
            if self
                .settings
                .time_budget
                .is_some_and(|b| clock.elapsed() >= b)
            {
                break;
            }
            self.follow(start, prefix, &order);
        }
    }

    /// A completion of `start` that appends the tasks of `order` that can still run, each as
    /// early as it can, then completes greedily ([`Search::greedy`]); offered as incumbents.
    fn follow(&mut self, start: &Cursor, prefix: &[PlanStep], order: &[TaskId]) {
        let mut cur = start.clone();
        let mut steps = prefix.to_vec();
        for &t in order {
            if let Some(s) = cur.earliest_start(self.inst, t) {
                self.run_task(&mut cur, &mut steps, t, s);
            }
        }
        self.offer(&cur, || steps.clone());
        self.greedy(&cur, &steps);
    }

    /// Appends task `t` started at `start_s` to `cur` and its step to `steps`.
    fn run_task(&self, cur: &mut Cursor, steps: &mut Vec<PlanStep>, t: TaskId, start_s: i64) {
        cur.append(self.inst, t, start_s, None);
        steps.push(PlanStep {
            task: t,
            start_s,
            end_s: start_s + self.inst.task(t).duration_s,
        });
    }

    /// Pessimistic completions of `cur`: two greedy rules, each appending the best next task
    /// until none fits. The better complete one is offered as an incumbent.
    fn greedy(&mut self, start: &Cursor, prefix: &[PlanStep]) {
        for mandatory_first in [false, true] {
            let mut cur = start.clone();
            let mut steps = prefix.to_vec();
            loop {
                let mut pick: Option<(Key, TaskId, i64)> = None;
                for i in 0..self.inst.tasks().len() {
                    let t = TaskId(i as u32);
                    let Some(s) = cur.earliest_start(self.inst, t) else {
                        continue;
                    };
                    let key = greedy_key(self.inst, &cur, t, s, mandatory_first);
                    if pick.as_ref().is_none_or(|(k, _, _)| key > *k) {
                        pick = Some((key, t, s));
                    }
                }
                let Some((_, t, s)) = pick else { break };
                self.run_task(&mut cur, &mut steps, t, s);
            }
            self.offer(&cur, || steps.clone());
        }
    }
}

/// The open nodes: a stack during the dive (children pushed best-last, so the search dives;
/// sorted by [`pop_order`] every `resort_every` expansions), a heap by [`pop_order`] during
/// the proof (best-first).
enum Frontier {
    Stack(Vec<Node>),
    Heap(BinaryHeap<ByPopOrder>),
}

/// A node ordered by [`pop_order`] (a total order: serials are unique).
struct ByPopOrder(Node);

impl PartialEq for ByPopOrder {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other).is_eq()
    }
}
impl Eq for ByPopOrder {}
impl PartialOrd for ByPopOrder {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for ByPopOrder {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        pop_order(&self.0, &other.0)
    }
}

impl Frontier {
    fn pop(&mut self) -> Option<Node> {
        match self {
            Self::Stack(v) => v.pop(),
            Self::Heap(h) => h.pop().map(|n| n.0),
        }
    }

    fn push(&mut self, node: Node) {
        match self {
            Self::Stack(v) => v.push(node),
            Self::Heap(h) => h.push(ByPopOrder(node)),
        }
    }

    /// Adds the children of an expanded node; on the stack the best last, so it is next.
    fn extend(&mut self, mut children: Vec<Node>) {
        match self {
            Self::Stack(v) => {
                children.sort_by(pop_order);
                v.extend(children);
            }
            Self::Heap(h) => h.extend(children.into_iter().map(ByPopOrder)),
        }
    }

    /// Sorts the stack (a heap is always in order).
    fn sort(&mut self) {
        if let Self::Stack(v) = self {
            v.sort_by(pop_order);
        }
    }

    /// From now on, always pops the first node in [`pop_order`].
    fn go_best_first(&mut self) {
        if let Self::Stack(v) = self {
            *self = Self::Heap(std::mem::take(v).into_iter().map(ByPopOrder).collect());
        }
    }

    fn nodes(&self) -> Box<dyn Iterator<Item = &Node> + '_> {
        match self {
            Self::Stack(v) => Box::new(v.iter()),
            Self::Heap(h) => Box::new(h.iter().map(|n| &n.0)),
        }
    }
}

/// The frontier's order, the node popped next last: the higher bound; on a tie the deeper
/// node (it is nearer a complete plan, so incumbents come sooner); then the older one.
fn pop_order(a: &Node, b: &Node) -> std::cmp::Ordering {
    a.bound
        .cmp(&b.bound)
        .then(a.steps.len().cmp(&b.steps.len()))
        .then(b.serial.cmp(&a.serial))
}

/// Greedy preference: (mandatory first?, utility rate per tier, earlier end). Larger is
/// better; compared lexicographically.
type Key = (bool, [i64; MAX_TIERS], i64);

fn greedy_key(inst: &Instance, cur: &Cursor, t: TaskId, start: i64, mandatory_first: bool) -> Key {
    let task = inst.task(t);
    let mut gain = [0.0f64; MAX_TIERS];
    gain[task.tier] += task.utility_micro as f64;
    if let Some(c) = task.campaign {
        let curve = &inst.campaigns()[c];
        gain[curve.tier] += curve.optimistic_slope(cur.counts[c]);
    }
    // Utility per hour of sol used, waiting included.
    let used_h = ((start + task.duration_s - cur.time_s).max(1)) as f64 / 3600.0;
    let rate = gain.map(|g| (g / used_h) as i64);
    (
        mandatory_first && task.mandatory,
        rate,
        -(start + task.duration_s),
    )
}
