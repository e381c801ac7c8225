//! Knapsacks over a *chain* of nested capacity rows (row `r` holds every item of rows `..=r`):
//! the fractional fill by density, exact for the LP relaxation, and the exact 0/1 time
//! knapsack by dynamic program. Deadline rows (everything due by `D`), release rows
//! (everything starting at or after `r`) and the single data row are such chains.

use super::candidates::Candidates;
use crate::instance::TaskId;

/// Fractional knapsack under *nested* capacity rows: item `i` (value `v`, weight `w`, in
/// row `row[j]` of candidate `j`) belongs to rows `row[j]..m`, and row `r` holds at most
/// `slack[r]` weight. The rows form a chain, so the feasible weights `y_i ∈ [0, w_i]` form a
/// polymatroid and the greedy fill by decreasing value density, each item taking what every
/// row it belongs to still holds, is the exact LP optimum. `items` are `(density, v, w, j)`
/// sorted by decreasing density ([`sort_items`]); `slack` is consumed.
pub(super) fn chain_fill(items: &[(f64, f64, f64, u32)], row: &[usize], slack: &mut [f64]) -> f64 {
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
pub(super) const MAX_DP_UNITS: i64 = 2048;

/// Buffers of [`chain_dp`].
#[derive(Default)]
pub(super) struct DpScratch {
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
pub(super) fn chain_dp(
    items: &[(f64, f64, f64, u32)],
    ch: &Chain,
    grain: i64,
    b: &mut DpScratch,
) -> f64 {
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
pub(super) fn sort_items(items: &mut [(f64, f64, f64, u32)]) {
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
/// candidates' use (the rows of the tasks are in [`Layout`](super::knapsack::Layout)).
pub(super) struct Chain<'r> {
    pub(super) row: &'r [usize],
    pub(super) slack: Vec<f64>,
}

/// A chain over the static rows `row` (per task) with keys `keys` (ascending) and the
/// capacity of the row with key `key` (clamped at 0: rows that hold no candidate may
/// otherwise be negative). `None` if the mandatory candidates alone overflow a row.
pub(super) fn chain<'r>(
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
