//! Utility grains: every plan's value in a tier is a multiple of the tier's grain (the gcd of
//! its utilities), so a bound can be rounded down to it; the same gcd, over durations, sizes
//! the 0/1 time knapsacks.

use crate::instance::Instance;
use crate::value::{MAX_TIERS, Value, bound_micro};

/// Greatest common divisor (non-negative; `gcd(0, 0) = 0`).
pub(super) fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 { a.abs() } else { gcd(b, a % b) }
}

/// `e` rounded down to a multiple of `grain`.
pub(super) fn round_to_grain(e: i64, grain: i64) -> i64 {
    if grain > 1 {
        e.div_euclid(grain) * grain
    } else {
        e
    }
}

/// `base` plus the optimistic extra per tier, rounded down to the tier's grain: every
/// completion adds a multiple of the grain, so no completion reaches the next multiple.
pub(super) fn to_value(base: Value, extra: &[f64; MAX_TIERS], grain: &[i64; MAX_TIERS]) -> Value {
    let mut v = base;
    for ((t, e), g) in v.tiers_micro.iter_mut().zip(extra).zip(grain) {
        *t = t.saturating_add(round_to_grain(bound_micro(*e), *g));
    }
    v
}

/// Per tier, the greatest common divisor of every task utility and every campaign curve
/// value of that tier (1 when there are none): every plan's tier value, and every
/// difference of two plans' values, is a multiple of it.
pub(super) fn grains(inst: &Instance) -> [i64; MAX_TIERS] {
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
