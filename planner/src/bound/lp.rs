//! The LP relaxation bound (see the [`bound`](crate::optimistic_bound) docs): rows of a
//! node's relaxation and a weak-duality certificate from clarabel's multipliers.
//!
//! ## References
//! Paper 003 §3.1 (optimistic plan quality for branch and bound).

use super::candidates::Candidates;
use super::knapsack::main_time_s;
use crate::instance::{Instance, TaskId};
use crate::state::Cursor;
use crate::value::MICRO_PER_POINT;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT};

/// The LP rows of a node: sparse columns over the optional candidates, right-hand sides
/// already reduced by the mandatory candidates fixed at 1.
pub(super) struct LpRows {
    /// Optional candidate positions in `Candidates::ids`.
    vars: Vec<usize>,
    /// Fixed (mandatory) candidate positions.
    fixed: Vec<usize>,
    /// `columns[v]`: (row, coefficient) in increasing row order.
    columns: Vec<Vec<(usize, f64)>>,
    rhs: Vec<f64>,
}

pub(super) fn lp_rows(inst: &Instance, cur: &Cursor, cand: &Candidates) -> Option<LpRows> {
    let p = inst.problem();
    let t0 = cur.time_s;
    let ids = &cand.ids;
    let pos_of = |t: TaskId| match cand.pos[t.index()] {
        u32::MAX => None,
        j => Some(j as usize),
    };
    let (vars, fixed): (Vec<usize>, Vec<usize>) =
        (0..ids.len()).partition(|&j| !inst.task(ids[j]).mandatory);
    let mut var_of = vec![usize::MAX; ids.len()];
    for (v, &j) in vars.iter().enumerate() {
        var_of[j] = v;
    }
    let mut columns: Vec<Vec<(usize, f64)>> = vec![Vec::new(); vars.len()];
    let mut rhs: Vec<f64> = Vec::new();
    let is_fixed = |j: usize| var_of[j] == usize::MAX;
    // Adds one row `Σ coef_j x_j ≤ b` over candidate positions, fixing mandatory ones.
    let mut add_row = |terms: &mut dyn Iterator<Item = (usize, f64)>, b: f64| -> bool {
        let row = rhs.len();
        let mut b = b;
        let mut any = false;
        for (j, c) in terms {
            if c == 0.0 {
                continue;
            }
            if is_fixed(j) {
                b -= c;
            } else {
                columns[var_of[j]].push((row, c));
                any = true;
            }
        }
        if !any {
            // Nothing free in the row: it is satisfied or the node is dead.
            return b >= -1e-6;
        }
        rhs.push(b);
        true
    };
    let deadline =
        |j: usize| (inst.task(ids[j]).latest_start_s + inst.task(ids[j]).duration_s).min(p.end_s);
    // Each candidate's earliest start in any completion (window, timelines, preconditions).
    let release = |j: usize| cand.release_s[j].max(t0);
    let mut deadlines: Vec<i64> = (0..ids.len()).map(deadline).collect();
    deadlines.sort_unstable();
    deadlines.dedup();
    let hours = |t: TaskId| main_time_s(inst.task(t)) as f64 / 3600.0;
    for &dl in &deadlines {
        // Only main-timeline time counts; a deadline before the main timeline is free holds
        // only link tasks (no main-timeline time).
        let h = ((dl - t0) as f64 / 3600.0).max(0.0);
        let mut it = (0..ids.len())
            .filter(|&j| deadline(j) <= dl)
            .map(|j| (j, hours(ids[j])));
        if !add_row(&mut it, h) {
            return None;
        }
        let mut it = (0..ids.len())
            .filter(|&j| deadline(j) <= dl)
            .map(|j| (j, inst.task(ids[j]).energy_wh()));
        let recharge_h = (dl - cur.energy_t_s) as f64 / 3600.0;
        if !add_row(&mut it, cur.energy_wh + p.recharge_w * recharge_h) {
            return None;
        }
    }
    let mut releases: Vec<i64> = (0..ids.len()).map(release).collect();
    releases.sort_unstable();
    releases.dedup();
    for &r in &releases {
        let mut it = (0..ids.len())
            .filter(|&j| release(j) >= r)
            .map(|j| (j, hours(ids[j])));
        if !add_row(&mut it, (p.end_s - r) as f64 / 3600.0) {
            return None;
        }
    }
    let mut it = (0..ids.len()).map(|j| {
        let t = inst.task(ids[j]);
        (j, t.data_mb - t.downlink_mb)
    });
    if !add_row(&mut it, p.data_capacity_mb - cur.data_mb) {
        return None;
    }
    for (c, curve) in inst.campaigns().iter().enumerate() {
        let members: Vec<usize> = (0..ids.len())
            .filter(|&j| inst.task(ids[j]).campaign == Some(c))
            .collect();
        let cap = curve.remaining_cap(cur.counts[c]);
        if members.len() as u32 > cap {
            let mut it = members.iter().map(|&j| (j, 1.0));
            if !add_row(&mut it, f64::from(cap)) {
                return None;
            }
        }
    }
    for (j, &t) in ids.iter().enumerate() {
        for &q in &inst.task(t).preconditions {
            if let Some(jq) = pos_of(q)
                && !is_fixed(jq)
            {
                // x_j ≤ x_q; with x_j fixed at 1 this forces x_q = 1.
                let mut it = [(j, 1.0), (jq, -1.0)].into_iter();
                if !add_row(&mut it, 0.0) {
                    return None;
                }
            }
        }
    }
    Some(LpRows {
        vars,
        fixed,
        columns,
        rhs,
    })
}

/// The certified LP bound of tier `k` in micro-points (added to the node's value).
pub(super) fn lp_bound_tier(rows: &LpRows, cand: &Candidates, k: usize) -> f64 {
    // Work in points: the solver prefers O(1) data.
    let u: Vec<f64> = rows
        .vars
        .iter()
        .map(|&j| cand.utility[k][j] / MICRO_PER_POINT)
        .collect();
    let fixed: f64 = rows.fixed.iter().map(|&j| cand.utility[k][j]).sum();
    let n = u.len();
    let m = rows.rhs.len();
    let z = if n == 0 || m == 0 {
        vec![0.0; m]
    } else {
        solve_duals(rows, &u).unwrap_or_else(|| vec![0.0; m])
    };
    // Weak duality: u·x ≤ z·b + Σ max(0, u − Aᵀz) for x ∈ [0, 1]ⁿ, Ax ≤ b, any z ≥ 0.
    let mut bound: f64 = z.iter().zip(&rows.rhs).map(|(zi, bi)| zi * bi).sum();
    let mut magnitude: f64 = z
        .iter()
        .zip(&rows.rhs)
        .map(|(zi, bi)| (zi * bi).abs())
        .sum();
    for (v, col) in rows.columns.iter().enumerate() {
        let atz: f64 = col.iter().map(|&(r, a)| a * z[r]).sum();
        magnitude += u[v].abs() + col.iter().map(|&(r, a)| (a * z[r]).abs()).sum::<f64>();
        bound += (u[v] - atz).max(0.0);
    }
    // The terms may cancel: cover their rounding with a margin relative to their size.
    fixed + (bound + 1e-9 * magnitude) * MICRO_PER_POINT
}

/// Clarabel's row multipliers (clipped to ≥ 0), or `None` if it could not be set up.
fn solve_duals(rows: &LpRows, u: &[f64]) -> Option<Vec<f64>> {
    let n = u.len();
    let m = rows.rhs.len();
    // A = [rows; I; −I], b = [rhs; 1; 0]: the box 0 ≤ x ≤ 1 as rows.
    let mut colptr = Vec::with_capacity(n + 1);
    let mut rowval = Vec::new();
    let mut nzval = Vec::new();
    colptr.push(0);
    for (v, col) in rows.columns.iter().enumerate() {
        for &(r, a) in col {
            rowval.push(r);
            nzval.push(a);
        }
        rowval.push(m + v);
        nzval.push(1.0);
        rowval.push(m + n + v);
        nzval.push(-1.0);
        colptr.push(rowval.len());
    }
    let a = CscMatrix::new(m + 2 * n, n, colptr, rowval, nzval);
    let mut b = rows.rhs.clone();
    b.extend(std::iter::repeat_n(1.0, n));
    b.extend(std::iter::repeat_n(0.0, n));
    let q: Vec<f64> = u.iter().map(|x| -x).collect();
    let pmat = CscMatrix::<f64>::zeros((n, n));
    let cones = [NonnegativeConeT(m + 2 * n)];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(100)
        .build()
        .ok()?;
    let mut solver = DefaultSolver::new(&pmat, &q, &a, &b, &cones, settings).ok()?;
    solver.solve();
    let z: Vec<f64> = solver.solution.z[..m]
        .iter()
        .map(|&x| if x.is_finite() { x.max(0.0) } else { 0.0 })
        .collect();
    Some(z)
}
