//! Optimistic bounds: no plan extending a partial plan is worth more than these.
//!
//! Both bounds start from the *candidates*: tasks not yet done that could still start inside
//! their window and the sol, whose state-based window is still reachable and whose
//! preconditions are done or candidates themselves. A remaining mandatory task that is not a
//! candidate kills the node. Campaign members are valued at the campaign's
//! [`optimistic_slope`](crate::CampaignCurve::optimistic_slope), which makes every
//! per-member sum an over-estimate of the campaign's real (possibly non-concave) gain.
//!
//! * [`BoundKind::Knapsack`]: per tier, the minimum of a capped utility sum and four
//!   fractional knapsacks, each keeping one resource and dropping the others: time under
//!   nested deadline rows, time under nested release rows, energy under the deadline rows,
//!   and net data. Nested rows form a chain, so a greedy fill by density solves each exactly
//!   ([`chain_fill`]); the density orders and rows are precomputed per instance ([`Layout`]).
//!   Mandatory tasks are forced in and their use reserved first. Precedences between two
//!   optional candidates enter every knapsack as Lagrange multipliers: part of a task's
//!   utility moves to its precondition, so a task is not valued without paying for the
//!   precondition it needs. Three refinements use the incumbent: a tier whose bound ties it
//!   is coupled to the next tier by a Lagrangian multiplier (a better completion must also
//!   keep the tied tier's tasks), a node the fractional knapsacks leave undecided by less
//!   than one task's value gets the 0/1 time knapsacks, solved exactly by a dynamic program
//!   over the chain ([`chain_dp`]), and evaluation stops once the comparison is decided.
//!
//! Every tier bound is rounded down to the tier's *grain*, the gcd of all its utilities
//! ([`grains`]): with whole-point utilities a fractional bound of 40.7 points becomes 40.
//! * [`BoundKind::Lp`]: per tier, a linear relaxation solved with clarabel: `x ∈ [0, 1]` per
//!   optional candidate, mandatory ones fixed at 1, and rows for time and energy before every
//!   candidate deadline, time after every release, net data, campaign caps and precedences
//!   (`x_i ≤ x_j`). An interior-point optimum is only approximate, so the bound is not the
//!   solver's objective but a weak-duality certificate built from its multipliers `z ≥ 0`:
//!   `u·x ≤ z·b + Σ_i max(0, u_i − (Aᵀz)_i)` for every `x ∈ [0, 1]ⁿ` with `Ax ≤ b`. It holds
//!   for any `z ≥ 0`, so a failed or inaccurate solve can only loosen the bound, never make
//!   it wrong.
//!
//! ## References
//! Paper 003 §3.1: "the optimistic maximum quality of any plan based on the candidate partial
//! plan must exceed the pessimistic minimum quality prediction of all other candidates".

use crate::bound_lp::{lp_bound_tier, lp_rows};
use crate::instance::{Instance, TaskId};
use crate::plan::{BoundKind, SearchStats};
use crate::state::{Cursor, DISTANCE_EPS_M};
use crate::value::{MAX_TIERS, Value, ceil_micro};
use std::cell::{OnceCell, RefCell};
use std::time::Instant;

/// The candidates of a node and their optimistic per-tier utilities.
#[derive(Default)]
pub(crate) struct Candidates {
    pub(crate) ids: Vec<TaskId>,
    /// `utility[k][i]`: optimistic micro-points of `ids[i]` in tier `k`.
    pub(crate) utility: [Vec<f64>; MAX_TIERS],
    /// Per tier, the capped utility sum over all candidates.
    pub(crate) sum: [f64; MAX_TIERS],
    /// Buffers reused from node to node.
    ok: Vec<bool>,
    slopes: Vec<f64>,
    members: Vec<u32>,
}

/// Fills `out` with the candidates of `cur`; `false` if a remaining mandatory task is not
/// one (the node is dead). `topo` lists the tasks with preconditions, each after its own
/// preconditions ([`topological`]).
fn candidates(inst: &Instance, topo: &[u32], cur: &Cursor, out: &mut Candidates) -> bool {
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
        let s = cur.time_s.max(t.earliest_start_s);
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
fn topological(inst: &Instance) -> Vec<u32> {
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

/// Fractional knapsack under *nested* capacity rows: item `i` (value `v`, weight `w`, in
/// row `row[j]` of candidate `j`) belongs to rows `row[j]..m`, and row `r` holds at most
/// `slack[r]` weight. The rows form a chain, so the feasible weights `y_i ∈ [0, w_i]` form a
/// polymatroid and the greedy fill by decreasing value density, each item taking what every
/// row it belongs to still holds, is the exact LP optimum. `items` are `(density, v, w, j)`
/// sorted by decreasing density ([`sort_items`]); `slack` is consumed.
fn chain_fill(items: &[(f64, f64, f64, u32)], row: &[usize], slack: &mut [f64]) -> f64 {
    // A row never holds more than any later row (which contains it): suffix minima.
    let m = slack.len();
    for r in (0..m.saturating_sub(1)).rev() {
        slack[r] = slack[r].min(slack[r + 1]);
    }
    let mut total = 0.0;
    for &(_, v, w, j) in items {
        if w <= 0.0 {
            total += v;
            continue;
        }
        let k = row[j as usize];
        let room = slack[k];
        if room <= 0.0 {
            continue;
        }
        let y = w.min(room);
        total += v * y / w;
        // Row k and every later row lose y; earlier rows are capped by row k's new slack.
        for s in &mut slack[k..] {
            *s -= y;
        }
        let cap = slack[k];
        for s in slack[..k].iter_mut().rev() {
            if *s > cap {
                *s = cap;
            } else {
                break;
            }
        }
    }
    total
}

/// Largest time knapsack, in duration grains, that [`chain_dp`] solves.
const MAX_DP_UNITS: i64 = 2048;

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 { a.abs() } else { gcd(b, a % b) }
}

/// Buffers of [`chain_dp`].
#[derive(Default)]
struct DpScratch {
    /// `best[x]`: the most utility of a 0/1 choice using exactly `x` grains.
    best: Vec<f64>,
    prev: Vec<f64>,
    /// `(row, grains, utility)` per item.
    items: Vec<(usize, usize, f64)>,
    /// Row capacities in grains.
    caps: Vec<usize>,
}

/// The *0/1* version of [`chain_fill`] for time: `items` `(density, v, w, t)` with `w` a
/// duration, a multiple of `grain` seconds, and the chain `ch`. A task runs whole or not at
/// all, so the 0/1 optimum over the chain's rows is an upper bound too (every completion's
/// task set satisfies every row), and often a point or more below the fractional one: the
/// fractional fill credits the part of a task that does not fit. Rows nest, so a dynamic
/// program over the time used, adding the items row by row and cutting the table at each
/// row's capacity once all of that row's items are in, is exact. A row capacity `c` s
/// becomes `⌊c / grain⌋` grains: a sum of multiples of the grain fits in `c` exactly when it
/// fits in that.
fn chain_dp(items: &[(f64, f64, f64, u32)], ch: &Chain, grain: i64, b: &mut DpScratch) -> f64 {
    let DpScratch {
        best,
        prev,
        items: its,
        caps,
    } = b;
    let g = grain as f64;
    // Suffix minima, as in chain_fill: a row never holds more than any later row. A row the
    // mandatory tasks overfill by a rounding error holds 0.
    caps.clear();
    caps.resize(ch.slack.len(), 0);
    let mut low = f64::INFINITY;
    for (c, &s) in caps.iter_mut().zip(&ch.slack).rev() {
        low = low.min(s);
        *c = (low / g + 1e-9).floor().max(0.0) as usize;
    }
    its.clear();
    its.extend(
        items
            .iter()
            .map(|&(_, v, w, t)| (ch.row[t as usize], (w / g).round() as usize, v)),
    );
    its.sort_unstable_by_key(|x| x.0);
    let total = caps.last().copied().unwrap_or(0);
    best.clear();
    best.resize(total + 1, f64::NEG_INFINITY);
    best[0] = 0.0;
    let mut hi = 0;
    let mut i = 0;
    while i < its.len() {
        let r = its[i].0;
        while i < its.len() && its[i].0 == r {
            let (_, w, v) = its[i];
            i += 1;
            if w > total {
                continue;
            }
            let top = (hi + w).min(total);
            // best[x] = max(best[x], best[x − w] + v) for x in w..=top, from the old values:
            // through a copy, so the loop vectorises.
            prev.clear();
            prev.extend_from_slice(&best[..=top - w]);
            for (d, &q) in best[w..=top].iter_mut().zip(prev.iter()) {
                *d = d.max(q + v);
            }
            hi = top;
        }
        // Every item of the rows up to r is in: the time they use is capped by row r.
        let c = caps[r];
        if hi > c {
            best[c + 1..=hi].fill(f64::NEG_INFINITY);
            hi = c;
        }
    }
    best[..=hi].iter().fold(0.0, |a, &b| a.max(b))
}

/// Sorts `(density, v, w, j)` by decreasing density (weightless items first).
fn sort_items(items: &mut [(f64, f64, f64, u32)]) {
    items.sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.3.cmp(&b.3)));
}

/// Test helper: [`chain_fill`] on `(v, w, row)` items, one item per candidate.
#[cfg(test)]
fn chain_knapsack(items: &mut [(f64, f64, usize)], slack: &mut [f64]) -> f64 {
    let row: Vec<usize> = items.iter().map(|x| x.2).collect();
    let mut it: Vec<(f64, f64, f64, u32)> = items
        .iter()
        .enumerate()
        .filter(|(_, x)| x.0 > 0.0)
        .map(|(j, x)| {
            let d = if x.1 <= 0.0 { f64::INFINITY } else { x.0 / x.1 };
            (d, x.0, x.1, j as u32)
        })
        .collect();
    sort_items(&mut it);
    chain_fill(&it, &row, slack)
}

/// The rows of one resource for [`chain_fill`]: each row's capacity, after the mandatory
/// candidates' use (the rows of the tasks are in [`Layout`]).
struct Chain<'r> {
    row: &'r [usize],
    slack: Vec<f64>,
}

/// A chain over the static rows `row` (per task) with keys `keys` (ascending) and the
/// capacity of the row with key `key` (clamped at 0: rows that hold no candidate may
/// otherwise be negative). `None` if the mandatory candidates alone overflow a row.
fn chain<'r>(
    cand: &Candidates,
    mandatory: &[bool],
    row: &'r [usize],
    keys: &[i64],
    weight: impl Fn(TaskId) -> f64,
    capacity: impl Fn(i64) -> f64,
) -> Option<Chain<'r>> {
    let mut slack: Vec<f64> = keys.iter().map(|&k| capacity(k).max(0.0)).collect();
    for (j, &t) in cand.ids.iter().enumerate() {
        if mandatory[j] {
            let w = weight(t);
            for s in &mut slack[row[t.index()]..] {
                *s -= w;
            }
        }
    }
    if slack.iter().any(|&s| s < -1e-6) {
        return None;
    }
    Some(Chain { row, slack })
}

/// One resource of [`knapsack_bound`]: its weight per task and the chains (by index) that
/// use it.
type Run<'a> = (&'a dyn Fn(TaskId) -> f64, [Option<usize>; 2]);

/// Buffers [`knapsack_bound`] reuses from node to node (no allocation per bound).
#[derive(Default)]
pub(crate) struct Scratch {
    jof: Vec<u32>,
    mandatory: Vec<bool>,
    items: Vec<(f64, f64, f64, u32)>,
    slack: Vec<f64>,
    util: Vec<f64>,
    touched: Vec<bool>,
    extra: Vec<(f64, f64, f64, u32)>,
    active: Vec<(u32, u32)>,
    titems: Vec<(f64, f64, f64, u32)>,
    dp: DpScratch,
}

/// λ multipliers (times a per-tier scale) of the lexicographic coupling, in trial order.
const LAMBDAS: [f64; 3] = [1.0, 0.25, 4.0];

/// What the knapsack bound precomputes per instance: the chain rows of every task (by
/// deadline, and by earliest start for the release rows) and, when no campaign makes
/// utilities depend on the node, every density order, so a node sorts nothing.
pub(crate) struct Layout {
    dl_row: Vec<usize>,
    dl_keys: Vec<i64>,
    rl_row: Vec<usize>,
    rl_keys: Vec<i64>,
    zero_row: Vec<usize>,
    /// The gcd of all task durations, s, when the integer time knapsacks are small enough
    /// to solve ([`chain_dp`]); 0 otherwise.
    dur_grain: i64,
    /// Precedences `(successor, predecessor)`, successors deepest in the precedence graph
    /// first.
    pairs: Vec<(u32, u32)>,
    /// Coupling scale per tier k ≥ 1: total utility of tier k over tier k−1.
    scale: [f64; MAX_TIERS],
    /// `plain[k][r]`: optional tasks with tier-k utility by decreasing utility per unit of
    /// resource r (time, energy, data); `coupled[k][l][r]` the same for `u_k + λ_l·u_{k−1}`.
    orders: Option<Orders>,
}

/// Tasks with their static density, densest first.
type Order = [Vec<(u32, f64)>; 3];

struct Orders {
    plain: Vec<Order>,
    coupled: Vec<Vec<Order>>,
}

fn rows_of(keys_per_task: &[i64]) -> (Vec<usize>, Vec<i64>) {
    let mut keys = keys_per_task.to_vec();
    keys.sort_unstable();
    keys.dedup();
    let row = keys_per_task
        .iter()
        .map(|k| keys.binary_search(k).unwrap_or(0))
        .collect();
    (row, keys)
}

impl Layout {
    pub(crate) fn new(inst: &Instance) -> Self {
        let p = inst.problem();
        let tasks = inst.tasks();
        let n = tasks.len();
        let dl: Vec<i64> = tasks
            .iter()
            .map(|x| (x.latest_start_s + x.duration_s).min(p.end_s))
            .collect();
        // Releases as negated keys, so that rows nest in ascending key order too.
        let rl: Vec<i64> = tasks.iter().map(|x| -x.earliest_start_s).collect();
        let (dl_row, dl_keys) = rows_of(&dl);
        let (rl_row, rl_keys) = rows_of(&rl);
        let mut total = [0.0f64; MAX_TIERS];
        for x in tasks {
            total[x.tier] += x.utility_micro as f64;
        }
        let mut scale = [1.0; MAX_TIERS];
        for k in 1..MAX_TIERS {
            scale[k] = (total[k].max(1.0) / total[k - 1].max(1.0)).max(1e-3);
        }
        let weight = |t: usize, r: usize| {
            let x = &tasks[t];
            [x.duration_s as f64, x.energy_wh(), x.data_mb][r]
        };
        let order = |util: &dyn Fn(usize) -> f64| -> Order {
            std::array::from_fn(|r| {
                let mut items: Vec<(f64, f64, f64, u32)> = (0..n)
                    .filter(|&t| !tasks[t].mandatory && util(t) > 0.0)
                    .map(|t| {
                        let w = weight(t, r);
                        let d = if w <= 0.0 { f64::INFINITY } else { util(t) / w };
                        (d, util(t), w, t as u32)
                    })
                    .collect();
                sort_items(&mut items);
                items.iter().map(|x| (x.3, x.0)).collect()
            })
        };
        let u = |t: usize, k: usize| {
            if tasks[t].tier == k {
                tasks[t].utility_micro as f64
            } else {
                0.0
            }
        };
        let orders = inst.campaigns().is_empty().then(|| Orders {
            plain: (0..MAX_TIERS).map(|k| order(&|t| u(t, k))).collect(),
            coupled: (0..MAX_TIERS)
                .map(|k| {
                    if k == 0 {
                        return Vec::new();
                    }
                    LAMBDAS
                        .iter()
                        .map(|lam| {
                            let l = lam * scale[k];
                            order(&|t| u(t, k) + l * u(t, k - 1))
                        })
                        .collect()
                })
                .collect(),
        });
        let mut depth = vec![0usize; n];
        // Longest precondition chain below each task (the graph is acyclic).
        for _ in 0..n {
            let mut changed = false;
            for t in 0..n {
                for q in &tasks[t].preconditions {
                    if depth[t] < depth[q.index()] + 1 {
                        depth[t] = depth[q.index()] + 1;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        let mut pairs: Vec<(u32, u32)> = (0..n)
            .flat_map(|t| tasks[t].preconditions.iter().map(move |q| (t as u32, q.0)))
            .collect();
        pairs.sort_by_key(|&(t, q)| (std::cmp::Reverse(depth[t as usize]), t, q));
        let g = tasks.iter().fold(0, |g, x| gcd(g, x.duration_s));
        let span = p.end_s - p.start_s;
        let dur_grain = if g > 0 && span / g <= MAX_DP_UNITS {
            g
        } else {
            0
        };
        Self {
            dl_row,
            dl_keys,
            rl_row,
            rl_keys,
            zero_row: vec![0; n],
            dur_grain,
            pairs,
            scale,
            orders,
        }
    }
}

/// The knapsack bound per tier in micro-points (added to the node's value), or `None` if
/// the node is dead.
///
/// Per tier, the minimum of the capped utility sum and four fractional knapsacks: time under
/// the candidates' deadlines (every task due by `D` must fit in `[now, D]`), time under their
/// releases (every task starting at or after `r` must fit in `[r, end]`), energy under the
/// deadlines (what the tasks due by `D` draw is at most the battery now plus the recharge
/// until `D`; clipping only loses energy) and net data.
///
/// `need` (incumbent minus the node's value, per tier) and `grain` enable the lexicographic
/// coupling below and early exits once the comparison with the incumbent is decided (then
/// the returned bound of a pruned node may be looser than the full minimum, never lower
/// than needed to prune it); without them every tier is bounded fully, on its own.
fn knapsack_bound(
    inst: &Instance,
    layout: &Layout,
    cur: &Cursor,
    cand: &Candidates,
    need: Option<[i64; MAX_TIERS]>,
    grain: &[i64; MAX_TIERS],
    scratch: &mut Scratch,
) -> Option<[f64; MAX_TIERS]> {
    let p = inst.problem();
    let now = cur.time_s;
    let tasks = inst.tasks();
    let Scratch {
        jof,
        mandatory,
        items,
        slack,
        util: ubuf,
        touched,
        extra,
        active,
        titems,
        dp,
    } = scratch;
    jof.clear();
    jof.resize(tasks.len(), u32::MAX);
    mandatory.clear();
    items.clear();
    slack.clear();
    let mut downlink = 0.0;
    for (j, &t) in cand.ids.iter().enumerate() {
        let x = &tasks[t.index()];
        jof[t.index()] = j as u32;
        mandatory.push(x.mandatory);
        downlink += x.downlink_mb;
    }
    // Precedences between two optional candidates: every completion that runs i also runs
    // its precondition q (it is not done yet), so x_i ≤ x_q. The knapsacks below relax them
    // by Lagrange multipliers (see `solve`). Mandatory tasks are forced in anyway.
    active.clear();
    for &(i, q) in &layout.pairs {
        let (ji, jq) = (jof[i as usize], jof[q as usize]);
        if ji != u32::MAX && jq != u32::MAX && !mandatory[ji as usize] && !mandatory[jq as usize] {
            active.push((ji, jq));
        }
    }
    let dur = |t: TaskId| tasks[t.index()].duration_s as f64;
    let energy = |t: TaskId| tasks[t.index()].energy_wh();
    let data = |t: TaskId| tasks[t.index()].data_mb;
    let data_cap = p.data_capacity_mb - cur.data_mb + downlink;
    // The four chains: time by deadline, time by release, energy by deadline, data. With an
    // incumbent they are built on first use (most nodes are pruned by the first); a chain
    // the mandatory tasks alone overflow then yields −∞, which prunes the dead node too.
    let make = |c: usize| match c {
        0 => chain(cand, mandatory, &layout.dl_row, &layout.dl_keys, dur, |d| {
            (d - now) as f64
        }),
        1 => chain(cand, mandatory, &layout.rl_row, &layout.rl_keys, dur, |r| {
            (p.end_s - now.max(-r)) as f64
        }),
        2 => chain(
            cand,
            mandatory,
            &layout.dl_row,
            &layout.dl_keys,
            energy,
            |d| cur.energy_wh + p.recharge_w * (d - now) as f64 / 3600.0,
        ),
        _ => chain(cand, mandatory, &layout.zero_row, &[0], data, |_| data_cap),
    };
    let cells: [OnceCell<Option<Chain>>; 4] = Default::default();
    let eager = if need.is_some() { 1 } else { 4 };
    for (c, cell) in cells.iter().enumerate().take(eager) {
        cell.get_or_init(|| make(c)).as_ref()?;
    }
    let mut fixed = [0.0; MAX_TIERS];
    for (j, _) in mandatory.iter().enumerate().filter(|(_, m)| **m) {
        for (k, f) in fixed.iter_mut().enumerate() {
            *f += cand.utility[k][j];
        }
    }
    // The smallest of the four knapsacks with per-candidate utility `util(j)`, stopping as
    // soon as it is at most `cutoff`. `order` is the static density order per resource, if
    // any.
    let mut solve = |util: &dyn Fn(usize) -> f64,
                     order: Option<&Order>,
                     fixed: f64,
                     start: f64,
                     cutoff: f64| {
        let mut best = start;
        let runs: [Run; 3] = [
            (&dur, [Some(0), Some(1)]),
            (&energy, [Some(2), None]),
            (&data, [Some(3), None]),
        ];
        for (r, (weight, chains)) in runs.into_iter().enumerate() {
            items.clear();
            ubuf.clear();
            ubuf.extend((0..mandatory.len()).map(util));
            touched.clear();
            touched.resize(mandatory.len(), false);
            // Precedences, relaxed: for μ ≥ 0, u·x ≤ u·x + μ·(x_q − x_i) on every completion
            // (x_i ≤ x_q), so moving μ of i's utility to its precondition q keeps the
            // knapsack an upper bound, for any μ, per resource. The μ that gives i and q the
            // same density prices the pair like one merged task, which stops the fill from
            // taking a dense i without paying for q's time, energy or data: the root bound
            // of B6 n = 80 seed 1 drops from 99 to 88 points (optimum 83). Pairs are taken
            // successors deepest first, so a chain passes utility down to its root.
            let mut moved = false;
            for &(ji, jq) in active.iter() {
                let (ji, jq) = (ji as usize, jq as usize);
                let (wi, wq) = (weight(cand.ids[ji]), weight(cand.ids[jq]));
                if wi + wq <= 0.0 {
                    continue;
                }
                let mu = (ubuf[ji] * wq - ubuf[jq] * wi) / (wi + wq);
                if mu > 0.0 {
                    ubuf[ji] -= mu;
                    ubuf[jq] += mu;
                    touched[ji] = true;
                    touched[jq] = true;
                    moved = true;
                }
            }
            let item = |j: usize, u: f64| {
                let t = cand.ids[j];
                let w = weight(t);
                let d = if w <= 0.0 { f64::INFINITY } else { u / w };
                (d, u, w, t.0)
            };
            match order {
                Some(o) if !moved => {
                    for &(t, _) in &o[r] {
                        let j = jof[t as usize];
                        if j != u32::MAX {
                            let u = ubuf[j as usize];
                            if u > 0.0 {
                                items.push((0.0, u, weight(TaskId(t)), t));
                            }
                        }
                    }
                }
                Some(o) => {
                    // The untouched candidates keep the static order; the few whose utility
                    // moved are sorted and merged in.
                    extra.clear();
                    for (j, &m) in mandatory.iter().enumerate() {
                        if touched[j] && !m && ubuf[j] > 0.0 {
                            extra.push(item(j, ubuf[j]));
                        }
                    }
                    sort_items(extra);
                    let mut e = 0;
                    for &(t, d) in &o[r] {
                        let j = jof[t as usize];
                        if j == u32::MAX || touched[j as usize] {
                            continue;
                        }
                        let u = ubuf[j as usize];
                        if u > 0.0 {
                            let x = (d, u, weight(TaskId(t)), t);
                            while e < extra.len()
                                && (extra[e].0 > x.0 || (extra[e].0 == x.0 && extra[e].3 < x.3))
                            {
                                items.push(extra[e]);
                                e += 1;
                            }
                            items.push(x);
                        }
                    }
                    items.extend_from_slice(&extra[e..]);
                }
                None => {
                    for (j, &m) in mandatory.iter().enumerate() {
                        if !m && ubuf[j] > 0.0 {
                            items.push(item(j, ubuf[j]));
                        }
                    }
                    sort_items(items);
                }
            }
            for c in chains.into_iter().flatten() {
                let Some(ch) = cells[c].get_or_init(|| make(c)) else {
                    return f64::NEG_INFINITY;
                };
                slack.clear();
                slack.extend_from_slice(&ch.slack);
                best = best.min(fixed + chain_fill(items, ch.row, slack));
                if best <= cutoff {
                    return best;
                }
            }
            if r == 0 && cutoff > f64::NEG_INFINITY {
                titems.clear();
                titems.extend_from_slice(items);
            }
        }
        // Not decided by the fractional knapsacks: the integer time knapsacks may decide it.
        // The 0/1 optimum is rarely more than one item's value below the fractional one, so
        // the dynamic program (≈ 10× a greedy fill) only runs when that could decide.
        if cutoff > f64::NEG_INFINITY
            && layout.dur_grain > 0
            && best - cutoff <= titems.iter().fold(0.0f64, |a, x| a.max(x.1))
        {
            for c in [1, 0] {
                let Some(ch) = cells[c].get_or_init(|| make(c)) else {
                    return f64::NEG_INFINITY;
                };
                best = best.min(fixed + chain_dp(titems, ch, layout.dur_grain, dp));
                if best <= cutoff {
                    return best;
                }
            }
        }
        best
    };
    // Whether tiers before k tie the incumbent exactly (so tier k decides).
    let rounded = |x: f64, k: usize| round_to_grain(ceil_micro(x), grain[k]);
    let mut out = [0.0; MAX_TIERS];
    let mut tied = need.is_some();
    for k in 0..MAX_TIERS {
        out[k] = cand.sum[k];
        if out[k] > 0.0 {
            // Decided once the rounded bound falls below the need (prune), or to it on a
            // later tier (also prune, after the coupling below may only lower it).
            let cutoff = match need {
                Some(need) if tied => need[k] as f64 - grain[k] as f64,
                _ => f64::NEG_INFINITY,
            };
            let order = layout.orders.as_ref().map(|o| &o.plain[k]);
            out[k] = solve(
                &|j| cand.utility[k][j],
                order,
                fixed[k],
                cand.sum[k],
                cutoff,
            );
        }
        // Lexicographic coupling. When the bound only ties the incumbent on the tiers before
        // k, a completion that beats it must gain at least `need[k-1]` in tier k-1 (and
        // exactly the bound before). For any λ ≥ 0 its tier-k gain is then at most
        // max(u_k + λ·u_{k-1}) − λ·need[k-1] (Lagrangian relaxation), which accounts for
        // the resources the tier-(k-1) tasks must take.
        if let Some(need) = need
            && tied
            && k > 0
        {
            let j = k - 1;
            if out[k] > 0.0 && cand.sum[j] > 0.0 && rounded(out[k], k) > need[k] {
                for (li, lambda) in LAMBDAS.iter().enumerate() {
                    let l = lambda * layout.scale[k];
                    let order = layout.orders.as_ref().map(|o| &o.coupled[k][li]);
                    let cutoff = need[k] as f64 + l * need[j] as f64;
                    let coupled = solve(
                        &|i| cand.utility[k][i] + l * cand.utility[j][i],
                        order,
                        fixed[k] + l * fixed[j],
                        f64::INFINITY,
                        cutoff,
                    ) - l * need[j] as f64;
                    // Cancelling terms: keep a margin of the sum's size.
                    out[k] = out[k].min(coupled + 1e-9 * (l * cand.sum[j] + cand.sum[k]));
                    if rounded(out[k], k) <= need[k] {
                        break;
                    }
                }
            }
        }
        if tied && let Some(need) = need {
            let r = rounded(out[k], k);
            if r < need[k] {
                // Decided: the node cannot beat the incumbent.
                break;
            }
            tied = r == need[k];
        }
    }
    Some(out)
}

/// `e` rounded down to a multiple of `grain`.
fn round_to_grain(e: i64, grain: i64) -> i64 {
    if grain > 1 {
        e.div_euclid(grain) * grain
    } else {
        e
    }
}

/// Evaluates bounds for the search, lazily tier by tier, and counts the work.
pub(crate) struct Bounder<'a> {
    inst: &'a Instance,
    kind: BoundKind,
    tier_used: [bool; MAX_TIERS],
    grain: [i64; MAX_TIERS],
    layout: Layout,
    scratch: RefCell<Scratch>,
    cand: RefCell<Candidates>,
    topo: Vec<u32>,
}

impl<'a> Bounder<'a> {
    pub(crate) fn new(inst: &'a Instance, kind: BoundKind) -> Self {
        let mut tier_used = [false; MAX_TIERS];
        for t in inst.tasks() {
            if t.utility_micro > 0 {
                tier_used[t.tier] = true;
            }
        }
        for c in inst.campaigns() {
            if c.utility_micro.iter().any(|&u| u > 0) {
                tier_used[c.tier] = true;
            }
        }
        Self {
            inst,
            kind,
            tier_used,
            grain: grains(inst),
            layout: Layout::new(inst),
            scratch: RefCell::default(),
            cand: RefCell::default(),
            topo: topological(inst),
        }
    }

    /// An optimistic value of any plan extending `cur`, or `None` when no completion that
    /// beats `incumbent` exists (or no completion holds every mandatory task). With an
    /// incumbent, tiers are refined by the LP only until the comparison is decided.
    pub(crate) fn evaluate(
        &self,
        cur: &Cursor,
        incumbent: Option<Value>,
        stats: &mut SearchStats,
    ) -> Option<Value> {
        let inst = self.inst;
        let clock = Instant::now();
        let mut cand = self.cand.borrow_mut();
        if !candidates(inst, &self.topo, cur, &mut cand) {
            return None;
        }
        let cand = &*cand;
        let mut ub = cand.sum;
        if matches!(self.kind, BoundKind::Knapsack | BoundKind::Both) {
            stats.knapsack_evals += 1;
            let need = incumbent
                .map(|inc| std::array::from_fn(|k| inc.tiers_micro[k] - cur.value.tiers_micro[k]));
            let k = knapsack_bound(
                inst,
                &self.layout,
                cur,
                cand,
                need,
                &self.grain,
                &mut self.scratch.borrow_mut(),
            );
            stats.knapsack_time += clock.elapsed();
            ub = k?;
        }
        let mut bound = to_value(cur.value, &ub, &self.grain);
        if let Some(inc) = incumbent
            && bound <= inc
        {
            return None;
        }
        if !matches!(self.kind, BoundKind::Lp | BoundKind::Both) {
            return Some(bound);
        }
        let clock = Instant::now();
        let rows = lp_rows(inst, cur, cand);
        let Some(rows) = rows else {
            stats.lp_time += clock.elapsed();
            return None;
        };
        for k in 0..MAX_TIERS {
            if self.tier_used[k] && ub[k] > 0.0 {
                stats.lp_solves += 1;
                let lp = lp_bound_tier(&rows, cand, k);
                ub[k] = ub[k].min(lp);
                bound = to_value(cur.value, &ub, &self.grain);
            }
            match incumbent {
                // Without an incumbent nothing can be pruned; tier 1 orders the frontier.
                None => break,
                Some(inc) => match bound.tiers_micro[k].cmp(&inc.tiers_micro[k]) {
                    std::cmp::Ordering::Less => {
                        stats.lp_time += clock.elapsed();
                        return None;
                    }
                    std::cmp::Ordering::Greater => break,
                    std::cmp::Ordering::Equal => {}
                },
            }
        }
        stats.lp_time += clock.elapsed();
        if incumbent.is_some_and(|inc| bound <= inc) {
            return None;
        }
        Some(bound)
    }
}

/// `base` plus the optimistic extra per tier, rounded down to the tier's grain: every
/// completion adds a multiple of the grain, so no completion reaches the next multiple.
fn to_value(base: Value, extra: &[f64; MAX_TIERS], grain: &[i64; MAX_TIERS]) -> Value {
    let mut v = base;
    for ((t, e), g) in v.tiers_micro.iter_mut().zip(extra).zip(grain) {
        *t = t.saturating_add(round_to_grain(ceil_micro(*e), *g));
    }
    v
}

/// Per tier, the greatest common divisor of every task utility and every campaign curve
/// value of that tier (1 when there are none): every plan's tier value, and every
/// difference of two plans' values, is a multiple of it.
fn grains(inst: &Instance) -> [i64; MAX_TIERS] {
    fn gcd(a: i64, b: i64) -> i64 {
        if b == 0 { a.abs() } else { gcd(b, a % b) }
    }
    let mut g = [0i64; MAX_TIERS];
    for t in inst.tasks() {
        g[t.tier] = gcd(g[t.tier], t.utility_micro);
    }
    for c in inst.campaigns() {
        for &u in &c.utility_micro {
            g[c.tier] = gcd(g[c.tier], u);
        }
    }
    g.map(|x| x.max(1))
}

/// An optimistic value of every plan that extends `state` (all tiers fully evaluated), or
/// `None` when the bound proves that no extension holds every mandatory activity.
///
/// This is the bound the search prunes with; it is public so it can be tested and compared.
///
/// # Errors
/// [`PlanError::InvalidState`](crate::PlanError::InvalidState) for a malformed `state`.
pub fn optimistic_bound(
    instance: &Instance,
    state: &crate::State,
    kind: BoundKind,
) -> Result<Option<Value>, crate::PlanError> {
    let cur = Cursor::new(instance, state)?;
    let mut cand = Candidates::default();
    if !candidates(instance, &topological(instance), &cur, &mut cand) {
        return Ok(None);
    }
    let mut ub = cand.sum;
    if matches!(kind, BoundKind::Knapsack | BoundKind::Both) {
        match knapsack_bound(
            instance,
            &Layout::new(instance),
            &cur,
            &cand,
            None,
            &grains(instance),
            &mut Scratch::default(),
        ) {
            Some(k) => ub = k,
            None => return Ok(None),
        }
    }
    if matches!(kind, BoundKind::Lp | BoundKind::Both) {
        let Some(rows) = lp_rows(instance, &cur, &cand) else {
            return Ok(None);
        };
        for (k, u) in ub.iter_mut().enumerate() {
            if *u > 0.0 {
                *u = u.min(lp_bound_tier(&rows, &cand, k));
            }
        }
    }
    Ok(Some(to_value(cur.value, &ub, &grains(instance))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chain_knapsack_degenerate_inputs() {
        assert_eq!(chain_knapsack(&mut [], &mut [10.0]), 0.0);
        // Zero capacity still takes weightless items.
        assert_eq!(
            chain_knapsack(&mut [(3.0, 0.0, 0), (5.0, 1.0, 0)], &mut [0.0]),
            3.0
        );
        // Densest first, then a fraction.
        let v = chain_knapsack(&mut [(4.0, 4.0, 0), (6.0, 2.0, 0)], &mut [3.0]);
        assert!((v - 7.0).abs() < 1e-12);
    }

    #[test]
    fn chain_knapsack_respects_nested_rows() {
        // Row 0 (early deadline) holds 2, row 1 holds 10. The dense item of row 0 takes 2 of
        // its 4; the other fills 8 of row 1's remaining room.
        let v = chain_knapsack(&mut [(8.0, 4.0, 0), (10.0, 10.0, 1)], &mut [2.0, 10.0]);
        assert!((v - (4.0 + 8.0)).abs() < 1e-12, "{v}");
        // A later row tighter than an earlier one caps it.
        let v = chain_knapsack(&mut [(8.0, 4.0, 0)], &mut [5.0, 1.0]);
        assert!((v - 2.0).abs() < 1e-12, "{v}");
    }
}
