//! Plan quality: one exact integer utility per priority tier, compared lexicographically.
//!
//! Utilities are stored in micro-points (`round(points × 10⁶)`), so sums are exact and do
//! not depend on the order in which a plan is built — the search and an exhaustive
//! enumeration agree bit for bit, and tier 1 is never traded for any amount of tier 2.
//!
//! ## Why it cannot overflow
//! Every activity utility and every campaign's per-member utility is at most
//! [`MAX_UTILITY`] = 10⁴ points = 10¹⁰ micro-points, and an instance has at most
//! [`MAX_TASKS`] = 4096 tasks, each a member of at most one campaign. A campaign's utility
//! is at most its first-member utility times its member count (decay ≤ 1), so one tier sums
//! to at most `4096 × 10¹⁰ + 4096 × 10¹⁰ ≈ 8.2 × 10¹³` micro-points, five orders of magnitude
//! below `i64::MAX ≈ 9.2 × 10¹⁸`. Bounds computed in `f64` are clamped to ±10¹⁸ before they
//! are converted.

use serde::{Deserialize, Serialize};

/// Number of priority tiers (1 is the highest).
pub const MAX_TIERS: usize = 4;
/// Largest utility, in points, of one activity or of one campaign's first member.
pub const MAX_UTILITY: f64 = 1e4;
/// Largest number of tasks (activities after drives are split) in one instance.
pub const MAX_TASKS: usize = 4096;
/// Micro-points per utility point.
pub const MICRO_PER_POINT: f64 = 1e6;

/// Plan quality: utility per tier in micro-points. `Ord` is lexicographic, tier 1 first,
/// so a higher tier is never traded for any amount of a lower one.
#[derive(
    Debug, Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize,
)]
pub struct Value {
    /// `tiers_micro[0]` is tier 1. Unit: micro-points (10⁻⁶ utility point).
    pub tiers_micro: [i64; MAX_TIERS],
}

impl Value {
    /// The empty plan's value.
    pub const ZERO: Value = Value {
        tiers_micro: [0; MAX_TIERS],
    };

    /// Utility of tier `tier` (1-based) in points.
    ///
    /// # Panics
    /// If `tier` is 0 or above [`MAX_TIERS`].
    #[must_use]
    pub fn points(&self, tier: usize) -> f64 {
        self.tiers_micro[tier - 1] as f64 / MICRO_PER_POINT
    }

    /// Utility per tier in points, tier 1 first.
    #[must_use]
    pub fn to_points(&self) -> [f64; MAX_TIERS] {
        self.tiers_micro.map(|m| m as f64 / MICRO_PER_POINT)
    }
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = self.to_points();
        write!(f, "[{:.3}, {:.3}, {:.3}, {:.3}]", p[0], p[1], p[2], p[3])
    }
}

/// Points to micro-points; the caller has checked `0 ≤ points ≤ MAX_UTILITY`.
pub(crate) fn micro(points: f64) -> i64 {
    (points * MICRO_PER_POINT).round() as i64
}

/// An upper bound in `f64` micro-points on a value that is a whole number of micro-points
/// (every plan's value is), turned into the largest whole number it allows: the floor of the
/// bound plus its rounding margin. No plan is worth more than `⌊bound⌋` when the bound is
/// exact, and the margin keeps that true for the bound as computed.
///
/// It used to take the ceiling: an exact bound of 7 400 000 became 7 400 001, one micro-point
/// above an optimum that reached it, and a search could then only prove that optimum by
/// exhausting the tree (issue 16: 8 210 nodes instead of 10 on a simulator sol problem).
pub(crate) fn bound_micro(bound: f64) -> i64 {
    if bound.is_nan() {
        return i64::MAX / 4;
    }
    // The relative margin covers the rounding of the sums of non-negative terms that produced
    // `bound` (callers with cancelling terms add their own margin).
    let b = bound + 1e-9 * bound.abs();
    b.floor().clamp(-1e18, 1e18) as i64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiers_compare_lexicographically() {
        let a = Value {
            tiers_micro: [1, 0, 0, 0],
        };
        let b = Value {
            tiers_micro: [0, i64::MAX, 0, 0],
        };
        assert!(a > b);
        assert_eq!(bound_micro(0.0), 0);
        assert_eq!(bound_micro(10.0), 10);
        // A sum that lands a rounding error below a whole number still allows it.
        assert_eq!(bound_micro(7_400_000.0 - 1e-9), 7_400_000);
        assert_eq!(bound_micro(7_400_000.6), 7_400_000);
        assert_eq!(micro(MAX_UTILITY), 10_000_000_000);
    }
}
