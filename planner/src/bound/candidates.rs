//! The candidates of a node: tasks not yet done that could still start inside their window
//! and the sol, whose state-based window is still reachable and whose preconditions are done
//! or candidates themselves, with their optimistic per-tier utilities (campaign members at the
//! campaign's optimistic slope). Both bounds start from them.

use crate::instance::{Instance, TaskId};
use crate::state::{Cursor, DISTANCE_EPS_M};
use crate::value::MAX_TIERS;

/// The candidates of a node and their optimistic per-tier utilities.
#[derive(Default)]
pub(super) struct Candidates {
    pub(super) ids: Vec<TaskId>,
    /// `utility[k][i]`: optimistic micro-points of `ids[i]` in tier `k`.
    pub(super) utility: [Vec<f64>; MAX_TIERS],
    /// Per tier, the capped utility sum over all candidates.
    pub(super) sum: [f64; MAX_TIERS],
    /// Buffers reused from node to node.
    ok: Vec<bool>,
    slopes: Vec<f64>,
    members: Vec<u32>,
}

/// Fills `out` with the candidates of `cur`; `false` if a remaining mandatory task is not
/// one (the node is dead). `topo` lists the tasks with preconditions, each after its own
/// preconditions ([`topological`]).
pub(super) fn candidates(
    inst: &Instance,
    topo: &[u32],
    cur: &Cursor,
    out: &mut Candidates,
) -> bool {
    let p = inst.problem();
    let n = inst.tasks().len();
    let Candidates {
        ids,
        utility,
        sum,
        ok,
        slopes,
        members,
    } = out;
    ok.clear();
    ok.resize(n, false);
    let mut any_pre = false;
    for (i, t) in inst.tasks().iter().enumerate() {
        let id = TaskId(i as u32);
        if cur.done.contains(id) {
            continue;
        }
        let s = cur.ready_s(t.timeline).max(t.earliest_start_s);
        let reachable = t
            .driven_window_m
            .is_none_or(|[_, hi]| cur.driven_m <= hi + DISTANCE_EPS_M);
        ok[i] = s <= t.latest_start_s && s + t.duration_s <= p.end_s && reachable;
        any_pre |= ok[i] && !t.preconditions.is_empty();
    }
    // A task needs every precondition done or a candidate; preconditions are settled first.
    if any_pre {
        for &i in topo {
            let i = i as usize;
            if ok[i]
                && inst.tasks()[i]
                    .preconditions
                    .iter()
                    .any(|&q| !cur.done.contains(q) && !ok[q.index()])
            {
                ok[i] = false;
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
