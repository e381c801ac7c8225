//! What a benchmark run reports: one [`CaseResult`] per case, and the accuracy statistics over
//! them ([`ErrorStats`], [`BenchmarkReport`], [`report_of`]).

use super::{BenchmarkCase, LightingKind, TerrainKind};
use crate::matcher::Rejection;

/// The outcome of one case.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CaseResult {
    /// The case's id.
    pub id: usize,
    /// Its terrain.
    pub terrain: TerrainKind,
    /// Its wedge count.
    pub wedges: u8,
    /// Its lighting class.
    pub lighting: LightingKind,
    /// True rover position, map metres.
    pub truth_m: [f64; 2],
    /// Prior position given to the matcher, map metres.
    pub prior_m: [f64; 2],
    /// The matcher's estimate, map metres (`None` if the case failed to run).
    pub estimate_m: Option<[f64; 2]>,
    /// Distance of the estimate from the truth, metres (`None` if the case failed to run).
    pub error_m: Option<f64>,
    /// The matcher's σ, metres.
    pub sigma_m: Option<f64>,
    /// The matcher's peak ratio.
    pub peak_ratio: Option<f64>,
    /// Valid fraction of the orthomosaic.
    pub valid_fraction: Option<f64>,
    /// Why the matcher rejected its result, if it did.
    pub rejection: Option<Rejection>,
    /// Why the case could not be run at all (bad synthetic input or localize error), if so.
    pub failure: Option<String>,
    /// Heading error the rover mosaic was rendered with, degrees (truth, diagnostics).
    pub heading_error_deg: Option<f64>,
}

impl CaseResult {
    /// The row of `case` before localization: its truth and prior, nothing estimated yet.
    #[must_use]
    pub fn pending(case: &BenchmarkCase, truth_m: [f64; 2], prior_m: [f64; 2]) -> Self {
        Self {
            id: case.id,
            terrain: case.terrain,
            wedges: case.wedges,
            lighting: case.lighting,
            truth_m,
            prior_m,
            estimate_m: None,
            error_m: None,
            sigma_m: None,
            peak_ratio: None,
            valid_fraction: None,
            rejection: None,
            failure: None,
            heading_error_deg: None,
        }
    }

    /// Record the matcher's outcome: its estimate, error, σ, peak ratio, valid fraction and
    /// verdict, or the failure.
    pub fn record(&mut self, result: Result<crate::matcher::MatchResult, impl std::fmt::Display>) {
        match result {
            Ok(m) => {
                self.estimate_m = Some(m.position_m);
                self.error_m = Some(
                    (m.position_m[0] - self.truth_m[0]).hypot(m.position_m[1] - self.truth_m[1]),
                );
                self.sigma_m = Some(m.sigma_m);
                self.peak_ratio = Some(m.peak_ratio);
                self.valid_fraction = Some(m.valid_fraction);
                self.rejection = m.rejection;
            }
            Err(e) => self.failure = Some(e.to_string()),
        }
    }
}

/// Error statistics over a set of cases, metres.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct ErrorStats {
    /// Cases counted.
    pub count: usize,
    /// Mean error.
    pub mean_m: f64,
    /// Median error.
    pub median_m: f64,
    /// 99th percentile (nearest rank).
    pub p99_m: f64,
    /// Largest error.
    pub max_m: f64,
    /// Cases with an error over 1 m.
    pub over_1m: usize,
    /// Cases with an error over 2 m.
    pub over_2m: usize,
}

impl ErrorStats {
    /// Statistics of `errors` (any order; NaN-free). Empty input gives all zeros.
    #[must_use]
    pub fn of(errors: &[f64]) -> Self {
        if errors.is_empty() {
            return Self::default();
        }
        let mut e = errors.to_vec();
        e.sort_by(f64::total_cmp);
        let n = e.len();
        let median_m = if n % 2 == 1 {
            e[n / 2]
        } else {
            0.5 * (e[n / 2 - 1] + e[n / 2])
        };
        // Nearest rank: the smallest value with at least 99 % of the values at or below it.
        let rank = ((0.99 * n as f64).ceil() as usize).clamp(1, n);
        Self {
            count: n,
            mean_m: e.iter().sum::<f64>() / n as f64,
            median_m,
            p99_m: e[rank - 1],
            max_m: e[n - 1],
            over_1m: e.iter().filter(|&&v| v > 1.0).count(),
            over_2m: e.iter().filter(|&&v| v > 2.0).count(),
        }
    }
}

/// What a benchmark run found.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BenchmarkReport {
    /// Statistics over every case that ran, accepted or not (the paper reports all 264).
    pub all: ErrorStats,
    /// Statistics over the cases the matcher accepted.
    pub accepted: ErrorStats,
    /// Statistics per terrain kind (every case that ran), in [`TerrainKind::ALL`] order.
    pub by_terrain: Vec<(TerrainKind, ErrorStats)>,
    /// Rejections by reason ([`Rejection::NAMES`]: `too_few_valid`, `ambiguous`, `imprecise`, `on_window_edge`),
    /// with counts, in that order, zero counts left out.
    pub rejections: Vec<(&'static str, usize)>,
    /// Cases that could not be run.
    pub failures: usize,
    /// One row per case, in case order.
    pub rows: Vec<CaseResult>,
}

/// The report of finished rows (statistics computed sequentially, in row order).
#[must_use]
pub fn report_of(rows: Vec<CaseResult>) -> BenchmarkReport {
    let all: Vec<f64> = rows.iter().filter_map(|r| r.error_m).collect();
    let accepted: Vec<f64> = rows
        .iter()
        .filter(|r| r.rejection.is_none())
        .filter_map(|r| r.error_m)
        .collect();
    let by_terrain = TerrainKind::ALL
        .iter()
        .map(|&k| {
            let e: Vec<f64> = rows
                .iter()
                .filter(|r| r.terrain == k)
                .filter_map(|r| r.error_m)
                .collect();
            (k, ErrorStats::of(&e))
        })
        .collect();
    let rejections = Rejection::NAMES
        .into_iter()
        .map(|name| {
            let n = rows
                .iter()
                .filter(|r| r.rejection.as_ref().map(Rejection::name) == Some(name))
                .count();
            (name, n)
        })
        .filter(|&(_, n)| n > 0)
        .collect();
    BenchmarkReport {
        all: ErrorStats::of(&all),
        accepted: ErrorStats::of(&accepted),
        by_terrain,
        rejections,
        failures: rows.iter().filter(|r| r.failure.is_some()).count(),
        rows,
    }
}
