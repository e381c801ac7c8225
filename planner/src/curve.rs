//! A campaign's utility curve in exact micro-points ([`CampaignCurve`]), as an instance holds it.

/// A campaign's utility curve, resolved to exact micro-points.
#[derive(Debug, Clone, PartialEq)]
pub struct CampaignCurve {
    /// Campaign id.
    pub id: String,
    /// Tier index (0 is tier 1).
    pub tier: usize,
    /// `utility_micro[n]` is the utility of `n` members for `n ≤ max_count`; beyond, it stays
    /// at `utility_micro[max_count]`.
    pub utility_micro: Vec<i64>,
}

impl CampaignCurve {
    /// Utility of `n` members, micro-points.
    #[must_use]
    pub fn utility(&self, n: u32) -> i64 {
        let i = (n as usize).min(self.utility_micro.len() - 1);
        self.utility_micro[i]
    }

    /// An optimistic utility per further member once `n` are in the plan: the steepest
    /// average increment `max_m (f(n+m) − f(n)) / m`, so `f(n+m) − f(n) ≤ m × slope` for every
    /// `m` (valid even below `min_count`, where `f` is not concave).
    #[must_use]
    pub fn optimistic_slope(&self, n: u32) -> f64 {
        let base = self.utility(n);
        let max = self.utility_micro.len() - 1;
        let mut best = 0.0f64;
        for k in (n as usize + 1)..=max {
            let m = (k - n as usize) as f64;
            best = best.max((self.utility_micro[k] - base) as f64 / m);
        }
        best
    }

    /// Members that can still add utility once `n` are in the plan.
    #[must_use]
    pub fn remaining_cap(&self, n: u32) -> u32 {
        (self.utility_micro.len() as u32 - 1).saturating_sub(n)
    }
}
