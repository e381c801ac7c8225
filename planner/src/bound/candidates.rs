//! The candidates of a node: tasks not yet done that some completion could still run (see
//! [`candidates`] for the rules), with their earliest starts and their optimistic per-tier
//! utilities (campaign members at the campaign's optimistic slope). Both bounds start from
//! them.

use crate::instance::{Instance, Task, TaskId};
use crate::state::{Cursor, DATA_EPS_MB, DISTANCE_EPS_M, ENERGY_EPS_WH};
use crate::value::MAX_TIERS;

/// The candidates of a node and their optimistic per-tier utilities.
#[derive(Default)]
pub(super) struct Candidates {
    pub(super) ids: Vec<TaskId>,
    /// `pos[t]`: the index of task `t` in `ids`, `u32::MAX` when it is not a candidate.
    pub(super) pos: Vec<u32>,
    /// `utility[k][i]`: optimistic micro-points of `ids[i]` in tier `k`.
    pub(super) utility: [Vec<f64>; MAX_TIERS],
    /// Per tier, the capped utility sum over all candidates.
    pub(super) sum: [f64; MAX_TIERS],
    /// `release_s[i]`: the earliest time `ids[i]` can start in any completion, s: its window,
    /// its timeline, and each precondition's earliest end (see [`candidates`]).
    pub(super) release_s: Vec<i64>,
    /// Whether some candidate's release is later than both its own earliest start and the
    /// main timeline's free time (then release rows built from the static windows are loose).
    pub(super) tightened: bool,
    /// Buffers reused from node to node.
    ok: Vec<bool>,
    /// Earliest start per task, s (meaningful where `ok`).
    est: Vec<i64>,
    slopes: Vec<f64>,
    members: Vec<u32>,
    /// `(earliest end, metres)` of the drive tasks that can still run.
    drives: Vec<(i64, f64)>,
}

/// Fills `out` with the candidates of `cur`; `false` if a remaining mandatory task is not
/// one (the node is dead). `topo` lists the tasks with preconditions, each after its own
/// preconditions ([`topological`]).
///
/// A task is a candidate when some completion of `cur` could still run it. What rules it
/// out, each a property every completion has:
/// - its window: it cannot start by its latest start, or end by the end of the sol, even at
///   its *earliest start*: the later of its window's opening, when its timelines are free and
///   when each precondition can end at the earliest (a precondition's own earliest start plus
///   its duration, or its recorded end when it is done);
/// - a precondition that is neither done nor a candidate;
/// - energy and data: the battery cannot hold what it draws (even full, recharging from now
///   until its latest start), or it alone produces more data than the store holds;
/// - a state-based window: the metres driven have passed it, or the drives that can still run
///   cannot reach it. On one timeline it also cannot start before the earliest time those
///   drives can have covered the distance to it.
///
/// Ruling a task out can rule out others (its successors; the instances its drive was to
/// reach), so the rules repeat until nothing changes. Both bounds then count only candidates,
/// and the LP's release rows use their earliest starts.
pub(super) fn candidates(
    inst: &Instance,
    topo: &[u32],
    cur: &Cursor,
    out: &mut Candidates,
) -> bool {
    let p = inst.problem();
    let n = inst.tasks().len();
    let tasks = inst.tasks();
    let Candidates {
        ids,
        pos,
        utility,
        sum,
        release_s,
        tightened,
        ok,
        est,
        slopes,
        members,
        drives,
    } = out;
    ok.clear();
    ok.resize(n, false);
    est.clear();
    est.resize(n, i64::MAX);
    let two = inst.uses_link();
    let mut any_pre = false;
    let mut any_window = false;
    for (i, t) in tasks.iter().enumerate() {
        let id = TaskId(i as u32);
        if cur.done.contains(id) {
            continue;
        }
        let mut s = cur.ready_s(t.timeline).max(t.earliest_start_s);
        if two {
            s = s.max(cur.energy_t_s);
        }
        est[i] = s;
        let reachable = t
            .driven_window_m
            .is_none_or(|[_, hi]| cur.driven_m <= hi + DISTANCE_EPS_M);
        ok[i] = starts_in_window(t, s, p.end_s) && reachable && resources_allow(inst, cur, id);
        any_pre |= ok[i] && !t.preconditions.is_empty();
        any_window |= ok[i]
            && t.driven_window_m
                .is_some_and(|[lo, _]| lo - DISTANCE_EPS_M > cur.driven_m);
    }
    // Preconditions first, then the drives' reach, until nothing changes. Every pass only
    // turns candidates off or moves earliest starts later, so this ends; the cap is a guard.
    if any_pre {
        precedence_pass(inst, topo, cur, ok, est);
    }
    if any_window {
        for _ in 0..=n {
            if !distance_pass(inst, cur, ok, est, drives) {
                break;
            }
            if any_pre {
                precedence_pass(inst, topo, cur, ok, est);
            }
        }
    }
    if inst
        .mandatory_tasks()
        .iter()
        .any(|&m| !cur.done.contains(m) && !ok[m.index()])
    {
        return false;
    }
    ids.clear();
    ids.extend((0..n as u32).map(TaskId).filter(|t| ok[t.index()]));
    pos.clear();
    pos.resize(n, u32::MAX);
    for (j, t) in ids.iter().enumerate() {
        pos[t.index()] = j as u32;
    }
    release_s.clear();
    release_s.extend(ids.iter().map(|t| est[t.index()]));
    *tightened = ids
        .iter()
        .any(|t| est[t.index()] > tasks[t.index()].earliest_start_s.max(cur.time_s));
    slopes.clear();
    slopes.extend(
        inst.campaigns()
            .iter()
            .zip(&cur.counts)
            .map(|(c, &k)| c.optimistic_slope(k)),
    );
    members.clear();
    members.resize(inst.campaigns().len(), 0);
    for u in utility.iter_mut() {
        u.clear();
        u.resize(ids.len(), 0.0);
    }
    *sum = [0.0; MAX_TIERS];
    for (j, &id) in ids.iter().enumerate() {
        let t = inst.task(id);
        utility[t.tier][j] += t.utility_micro as f64;
        sum[t.tier] += t.utility_micro as f64;
        if let Some(c) = t.campaign {
            utility[inst.campaigns()[c].tier][j] += slopes[c];
            members[c] += 1;
        }
    }
    for (c, curve) in inst.campaigns().iter().enumerate() {
        let cap = curve.remaining_cap(cur.counts[c]).min(members[c]);
        sum[curve.tier] += slopes[c] * f64::from(cap);
    }
    true
}

/// Whether task `t` starting at `start_s` is inside its window and ends by `end_s`, the end
/// of the sol.
fn starts_in_window(t: &Task, start_s: i64, end_s: i64) -> bool {
    start_s <= t.latest_start_s && start_s + t.duration_s <= end_s
}

/// Whether the battery and the data store could ever carry task `id` after `cur`: the energy
/// it needs at its start (what it draws above the recharge) is at most the most the battery
/// can hold by its latest start (powers are ≥ 0, so no task adds energy), and its own data
/// fits the empty store (the store never holds less than nothing).
fn resources_allow(inst: &Instance, cur: &Cursor, id: TaskId) -> bool {
    let p = inst.problem();
    let t = inst.task(id);
    let need_wh = (t.power_w - p.recharge_w) * t.duration_s as f64 / 3600.0;
    let latest = t.latest_start_s.max(cur.energy_t_s);
    let most_wh = (cur.energy_wh + p.recharge_w * (latest - cur.energy_t_s) as f64 / 3600.0)
        .min(p.battery_capacity_wh);
    need_wh <= most_wh + ENERGY_EPS_WH && t.data_mb <= p.data_capacity_mb + DATA_EPS_MB
}

/// Preconditions in topological order: a task is out when a precondition is neither done
/// nor a candidate, and starts no earlier than each precondition can end.
fn precedence_pass(inst: &Instance, topo: &[u32], cur: &Cursor, ok: &mut [bool], est: &mut [i64]) {
    let p = inst.problem();
    for &i in topo {
        let i = i as usize;
        if !ok[i] {
            continue;
        }
        let t = &inst.tasks()[i];
        let mut s = est[i];
        for &q in &t.preconditions {
            if cur.done.contains(q) {
                // On one timeline a done task has ended by `time_s` (already in `est`); on
                // two its end is recorded (`i64::MIN` when done in the start state).
                if let Some(&e) = cur.ends_s.get(q.index()) {
                    s = s.max(e);
                }
            } else if ok[q.index()] {
                s = s.max(est[q.index()] + inst.tasks()[q.index()].duration_s);
            } else {
                ok[i] = false;
                break;
            }
        }
        est[i] = s;
        ok[i] = ok[i] && starts_in_window(t, s, p.end_s);
    }
}

/// State-based windows against the drives that can still run; `true` if anything changed.
/// A task whose window starts beyond the metres driven plus every remaining drive is out. On
/// one timeline (tasks run one after another, so a drive counts once it has ended) it also
/// cannot start before the earliest time the drives can cover the distance: sorted by their
/// earliest end, the first prefix that covers it (any set of drives that covers it has a
/// member ending no earlier).
fn distance_pass(
    inst: &Instance,
    cur: &Cursor,
    ok: &mut [bool],
    est: &mut [i64],
    drives: &mut Vec<(i64, f64)>,
) -> bool {
    let p = inst.problem();
    let tasks = inst.tasks();
    drives.clear();
    drives.extend(
        tasks
            .iter()
            .enumerate()
            .filter(|&(i, t)| ok[i] && t.drive_m > 0.0)
            .map(|(i, t)| (est[i] + t.duration_s, t.drive_m)),
    );
    let reach_m: f64 = drives.iter().map(|d| d.1).sum();
    drives.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut changed = false;
    for (i, t) in tasks.iter().enumerate() {
        let Some([lo, _]) = t.driven_window_m else {
            continue;
        };
        let short_m = lo - DISTANCE_EPS_M - cur.driven_m;
        if !ok[i] || short_m <= 0.0 {
            continue;
        }
        if short_m > reach_m {
            ok[i] = false;
            changed = true;
            continue;
        }
        if inst.uses_link() {
            continue;
        }
        let mut covered = 0.0;
        let mut at = i64::MAX;
        for &(end_s, m) in drives.iter() {
            covered += m;
            if covered >= short_m {
                at = end_s;
                break;
            }
        }
        if at > est[i] {
            est[i] = at;
            changed = true;
            ok[i] = starts_in_window(t, at, p.end_s);
        }
    }
    changed
}

/// The tasks that have preconditions, each after all of its (transitive) preconditions.
pub(super) fn topological(inst: &Instance) -> Vec<u32> {
    let tasks = inst.tasks();
    let mut placed = vec![false; tasks.len()];
    let mut out = Vec::new();
    // The precondition graph is acyclic (checked by `Instance::new`): each round places at
    // least one task.
    loop {
        let mut progress = false;
        for (i, t) in tasks.iter().enumerate() {
            if !placed[i] && t.preconditions.iter().all(|q| placed[q.index()]) {
                placed[i] = true;
                progress = true;
                if !t.preconditions.is_empty() {
                    out.push(i as u32);
                }
            }
        }
        if !progress {
            return out;
        }
    }
}
