//! One memory budget for a whole command, checked before anything large is allocated.
//!
//! Sizes an input can ask for — a planning grid of 0.01 m cells, a recipe of 20 000 × 20 000
//! pixels, a 46 000 × 46 000 PNG that compresses to 2 MB — are computed from the file (its
//! fields, a raster's header) and summed against the budget *before* allocating, so a hostile
//! input gets one error naming the field instead of an abort from the allocator. The budget is
//! a value the command line passes down (`--memory-budget-mib`, default
//! [`MemoryBudget::DEFAULT_BYTES`]), not global state: library callers and tests choose theirs.

use std::fmt;

/// A memory allowance, bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryBudget {
    /// The allowance, bytes (default: [`MemoryBudget::DEFAULT_BYTES`], 2 GiB).
    pub limit_bytes: u64,
}

impl MemoryBudget {
    /// The default allowance: 2 GiB, about ten times what the largest bundled scenario needs
    /// and a twelfth of this project's 24 GiB machines.
    pub const DEFAULT_BYTES: u64 = 2 << 30;

    /// A budget of `limit_bytes`.
    #[must_use]
    pub const fn new(limit_bytes: u64) -> Self {
        Self { limit_bytes }
    }

    /// Whether `need_bytes` fit.
    #[must_use]
    pub const fn allows(&self, need_bytes: u64) -> bool {
        need_bytes <= self.limit_bytes
    }
}

impl Default for MemoryBudget {
    fn default() -> Self {
        Self::new(Self::DEFAULT_BYTES)
    }
}

impl fmt::Display for MemoryBudget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "over the memory budget of {} (--memory-budget-mib)",
            crate::input_file::human_bytes(self.limit_bytes)
        )
    }
}

/// `a × b × c`, saturating: sizes from hostile inputs must not wrap around to something small.
#[must_use]
pub fn bytes_of(counts: &[u64]) -> u64 {
    counts.iter().fold(1u64, |acc, &n| acc.saturating_mul(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_saturate_instead_of_wrapping() {
        assert_eq!(bytes_of(&[u64::MAX, 4]), u64::MAX);
        assert!(!MemoryBudget::default().allows(bytes_of(&[20_000, 20_000, 14])));
        assert!(MemoryBudget::default().allows(bytes_of(&[1000, 1000, 14])));
        assert_eq!(
            MemoryBudget::default().to_string(),
            "over the memory budget of 2 GiB (--memory-budget-mib)"
        );
    }
}
