//! The knapsack bound ([`BoundKind::Knapsack`](crate::BoundKind::Knapsack)): per tier, the
//! minimum of the capped utility sum and four fractional knapsacks over chains of nested rows
//! (time by deadline, time by release, energy by deadline, net data), with precedences priced
//! in, the lexicographic coupling of tied tiers and the 0/1 time knapsacks when the fractional
//! ones leave a node undecided; and [`Layout`], what it precomputes per instance.
//!
//! ## References
//! Paper 003 §3.1 (optimistic plan quality for branch and bound).

use super::candidates::Candidates;
use super::chain::{Chain, DpScratch, MAX_DP_UNITS, chain, chain_dp, chain_fill, sort_items};
use super::grain::{gcd, round_to_grain};
use crate::instance::{Instance, TaskId};
use crate::state::Cursor;
use crate::value::{MAX_TIERS, bound_micro};
use std::cell::OnceCell;

/// One resource of [`knapsack_bound`]: its weight per task and the chains (by index) that
/// use it.
type Run<'a> = (&'a dyn Fn(TaskId) -> f64, [Option<usize>; 2]);

/// Buffers [`knapsack_bound`] reuses from node to node (no allocation per bound).
#[derive(Default)]
pub(super) struct Scratch {
    mandatory: Vec<bool>,
    items: Vec<(f64, f64, f64, u32)>,
    slack: Vec<f64>,
    util: Vec<f64>,
    touched: Vec<bool>,
    extra: Vec<(f64, f64, f64, u32)>,
    active: Vec<(u32, u32)>,
    titems: Vec<(f64, f64, f64, u32)>,
    dp: DpScratch,
    /// Release rows of a node whose candidates' earliest starts are later than their windows.
    rl_row: Vec<usize>,
    rl_keys: Vec<i64>,
}

/// λ multipliers (times a per-tier scale) of the lexicographic coupling, in trial order.
const LAMBDAS: [f64; 3] = [1.0, 0.25, 4.0];

/// What the knapsack bound precomputes per instance: the chain rows of every task (by
/// deadline, and by earliest start for the release rows) and, when no campaign makes
/// utilities depend on the node, every density order, so a node sorts nothing.
pub(super) struct Layout {
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

/// The main-timeline time a task takes, s: its duration, or 0 for a task on the HBS link
/// alone, which overlaps main-timeline tasks (the time knapsacks are over the main timeline).
pub(super) fn main_time_s(t: &crate::instance::Task) -> i64 {
    if t.timeline.uses_main() {
        t.duration_s
    } else {
        0
    }
}

fn rows_of(keys_per_task: &[i64]) -> (Vec<usize>, Vec<i64>) {
    let (mut row, mut keys) = (Vec::new(), Vec::new());
    fill_rows(
        keys_per_task.len(),
        keys_per_task.iter().copied().enumerate(),
        &mut row,
        &mut keys,
    );
    (row, keys)
}

/// Chain rows from `(task, key)` pairs: `keys` the distinct keys ascending, `row[task]` the
/// index of its key (0 for the `n` tasks not listed).
fn fill_rows(
    n: usize,
    items: impl Iterator<Item = (usize, i64)> + Clone,
    row: &mut Vec<usize>,
    keys: &mut Vec<i64>,
) {
    keys.clear();
    keys.extend(items.clone().map(|(_, k)| k));
    keys.sort_unstable();
    keys.dedup();
    row.clear();
    row.resize(n, 0);
    for (t, k) in items {
        row[t] = keys.binary_search(&k).unwrap_or(0);
    }
}

impl Layout {
    pub(super) fn new(inst: &Instance) -> Self {
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
            [main_time_s(x) as f64, x.energy_wh(), x.data_mb][r]
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
        let g = tasks.iter().fold(0, |g, x| gcd(g, main_time_s(x)));
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
pub(super) fn knapsack_bound(
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
        mandatory,
        items,
        slack,
        util: ubuf,
        touched,
        extra,
        active,
        titems,
        dp,
        rl_row: rl_row_buf,
        rl_keys: rl_keys_buf,
    } = scratch;
    // The candidate index of each task (u32::MAX: not a candidate).
    let jof = &cand.pos;
    mandatory.clear();
    items.clear();
    slack.clear();
    let mut downlink = 0.0;
    for &t in &cand.ids {
        let x = &tasks[t.index()];
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
    // Release rows: the static ones (by earliest start) unless a candidate's earliest start
    // in this node is later (a precondition's earliest end, the drives' reach): then this
    // node's own rows, keyed the same way.
    let (rl_row, rl_keys): (&[usize], &[i64]) = if cand.tightened {
        let releases = cand.ids.iter().zip(&cand.release_s);
        let items = releases.map(|(t, &r)| (t.index(), -r));
        fill_rows(tasks.len(), items, rl_row_buf, rl_keys_buf);
        (rl_row_buf, rl_keys_buf)
    } else {
        (&layout.rl_row, &layout.rl_keys)
    };
    let dur = |t: TaskId| main_time_s(&tasks[t.index()]) as f64;
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
        1 => chain(cand, mandatory, rl_row, rl_keys, dur, |r| {
            (p.end_s - now.max(-r)) as f64
        }),
        2 => chain(
            cand,
            mandatory,
            &layout.dl_row,
            &layout.dl_keys,
            energy,
            |d| cur.energy_wh + p.recharge_w * (d - cur.energy_t_s) as f64 / 3600.0,
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
    let rounded = |x: f64, k: usize| round_to_grain(bound_micro(x), grain[k]);
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
