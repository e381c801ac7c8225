//! Statistics a study reports: per-strategy [`spread`]s of per-run figures ([`quantile`] by
//! linear interpolation), rates with [`wilson`] score intervals, and the [`paired_bootstrap`]
//! interval of a strategy's mean per-run difference from the baseline, all at a confidence turned
//! into a normal quantile by [`z_for_confidence`].
//!
//! Every function is a pure function of its arguments: sums run sequentially in the given order
//! and the bootstrap draws from a seeded ChaCha8 stream, so a study's report is bit-identical
//! across runs, thread counts and platforms. `peers/stats_reference.py` computes the same figures
//! with statsmodels, numpy and scipy; `sweep/tests/stats_reference.rs` compares them.
//!
//! ## References
//! - E. B. Wilson (1927), "Probable inference, the law of succession, and statistical
//!   inference", JASA 22(158), 209–212: the score interval.
//! - R. J. Hyndman, Y. Fan (1996), "Sample quantiles in statistical packages", The American
//!   Statistician 50(4), 361–365: definition 7, numpy's default.
//! - B. Efron, R. J. Tibshirani (1993), *An Introduction to the Bootstrap*, ch. 13: the
//!   percentile interval.
//! - P. J. Acklam (2003), "An algorithm for computing the inverse normal cumulative distribution
//!   function": the starting point that one Halley step refines.

use rand::{RngExt as _, SeedableRng as _};
use rand_chacha::ChaCha8Rng;

/// A closed interval [lo, hi], in the unit of the statistic it bounds.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Interval {
    /// Lower end.
    pub lo: f64,
    /// Upper end, `hi >= lo`.
    pub hi: f64,
}

/// Mean, median, 5th and 95th percentile of n values, in the unit of the values.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Spread {
    /// Number of values (at least 1).
    pub n: usize,
    /// Arithmetic mean, summed sequentially in the given order.
    pub mean: f64,
    /// [`quantile`] at 0.5.
    pub median: f64,
    /// [`quantile`] at 0.05.
    pub p5: f64,
    /// [`quantile`] at 0.95.
    pub p95: f64,
}

/// Mean paired difference with a percentile bootstrap interval, in the unit of the differences.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PairedDifference {
    /// Number of paired differences (runs).
    pub n: usize,
    /// Mean difference (strategy − baseline), summed sequentially in run order.
    pub mean: f64,
    /// Percentile bootstrap interval of the mean.
    pub interval: Interval,
}

/// The two-sided standard normal quantile for the given confidence (0.95 → 1.959963984540054):
/// the z with P(|Z| ≤ z) = `confidence`, i.e. `scipy.stats.norm.isf((1 - confidence) / 2)`.
///
/// # Method
/// Acklam's rational approximation of the inverse normal CDF (relative error < 1.15e-9) at the
/// lower tail 0.5·(1 − confidence) (the tail, not 1 minus it, keeps full relative precision
/// when confidence is near 1), refined by one Halley step on the normal CDF computed from
/// `erfc`. Agrees with scipy to 2e-15 for confidences from 1e-6 to 1 − 1e-10.
///
/// # Units
/// Standard deviations (dimensionless).
///
/// # Panics
/// If `confidence` is not in the open interval (0, 1).
#[must_use]
pub fn z_for_confidence(confidence: f64) -> f64 {
    assert!(
        confidence > 0.0 && confidence < 1.0,
        "confidence must be in (0, 1), got {confidence}"
    );
    -normal_quantile(0.5 * (1.0 - confidence))
}

/// The `p`-quantile of `sorted` by linear interpolation between order statistics: Hyndman–Fan
/// definition 7, `numpy.quantile`'s default, and bit for bit numpy's arithmetic (the virtual
/// index (n − 1)·p, interpolated from the nearer order statistic).
///
/// `sorted` must be ascending and NaN-free (checked in debug builds); with infinite values the
/// interpolation may give NaN, as numpy's does.
///
/// # Units
/// Those of the values.
///
/// # Panics
/// If `sorted` is empty or `p` is not in [0, 1].
#[must_use]
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    assert!(!sorted.is_empty(), "quantile of no values");
    assert!(
        (0.0..=1.0).contains(&p),
        "quantile level must be in [0, 1], got {p}"
    );
    debug_assert!(
        sorted.is_sorted_by(|a, b| a <= b),
        "quantile needs ascending, NaN-free values"
    );
    let last = sorted.len() - 1;
    let index = last as f64 * p;
    if index >= last as f64 {
        return sorted[last];
    }
    let below = index.floor();
    let gamma = index - below;
    // `below` is in [0, last), so the cast is exact.
    let i = below as usize;
    let (a, b) = (sorted[i], sorted[i + 1]);
    let diff = b - a;
    // As numpy's _lerp: from the nearer order statistic (exact at both ends), so the two agree
    // bit for bit.
    if gamma >= 0.5 {
        b - diff * (1.0 - gamma)
    } else {
        a + diff * gamma
    }
}

/// Mean, median, 5th and 95th percentile of `values` ([`quantile`], type 7); `None` when
/// `values` is empty.
///
/// The mean is summed sequentially in the given order, so it is deterministic for a given order.
/// The values must be NaN-free (checked in debug builds); sorting uses [`f64::total_cmp`].
///
/// # Units
/// Those of the values.
#[must_use]
pub fn spread(values: &[f64]) -> Option<Spread> {
    if values.is_empty() {
        return None;
    }
    debug_assert!(values.iter().all(|v| !v.is_nan()), "spread of NaN values");
    let mut sorted = values.to_vec();
    sorted.sort_unstable_by(f64::total_cmp);
    Some(Spread {
        n: values.len(),
        mean: sequential_sum(values) / values.len() as f64,
        median: quantile(&sorted, 0.5),
        p5: quantile(&sorted, 0.05),
        p95: quantile(&sorted, 0.95),
    })
}

/// The Wilson score interval of a proportion `successes / n` at the given two-sided
/// `confidence` (e.g. 0.95); `None` when `n == 0`.
///
/// # Method
/// With p̂ = successes / n and z = [`z_for_confidence`]`(confidence)`:
/// centre (p̂ + z²/2n) / (1 + z²/n), half-width z·√(p̂(1 − p̂)/n + z²/4n²) / (1 + z²/n),
/// clipped to [0, 1]; the operations are those of statsmodels'
/// `proportion_confint(successes, n, alpha=1 - confidence, method="wilson")`, which it matches
/// to ~1e-16. The end at 0 successes is exactly 0 and the end at n successes exactly 1 (their
/// true values, where the formula leaves a rounding residue).
///
/// # Units
/// A proportion in [0, 1]. Exact for counts below 2⁵³.
///
/// # Panics
/// If `successes > n` or `confidence` is not in (0, 1).
#[must_use]
pub fn wilson(successes: u64, n: u64, confidence: f64) -> Option<Interval> {
    assert!(successes <= n, "{successes} successes out of {n}");
    let z = z_for_confidence(confidence);
    if n == 0 {
        return None;
    }
    let n_f = n as f64;
    let p = successes as f64 / n_f;
    let z2 = z * z;
    let denom = 1.0 + z2 / n_f;
    let centre = (p + z2 / (2.0 * n_f)) / denom;
    let half = z * (p * (1.0 - p) / n_f + z2 / (4.0 * n_f * n_f)).sqrt() / denom;
    let lo = if successes == 0 {
        0.0
    } else {
        (centre - half).clamp(0.0, 1.0)
    };
    let hi = if successes == n {
        1.0
    } else {
        (centre + half).clamp(0.0, 1.0)
    };
    Some(Interval { lo, hi })
}

/// The mean of per-run paired `differences` (strategy − baseline) with a percentile bootstrap
/// interval at the given two-sided `confidence`; `None` when `differences` is empty.
///
/// # Method
/// `resamples` times, draw n run indices with replacement from
/// `ChaCha8Rng::seed_from_u64(seed)` (`random_range(0..n)`, rand 0.10) and take the mean of
/// their differences (summed sequentially); sort the resample means and take [`quantile`] at
/// (1 − confidence)/2 and (1 + confidence)/2. Resampling whole runs keeps each strategy paired
/// with the baseline on the same world. When all differences are equal the result is that value
/// with the degenerate interval [d, d] (the resample means would only add rounding).
///
/// The result is a pure function of the arguments, bit-identical across runs and platforms
/// (IEEE arithmetic in a fixed order; rand draws 32-bit indices for n < 2³²). It matches scipy's
/// `bootstrap(..., method="percentile")` within Monte Carlo error; the generators differ.
/// Cost: n × `resamples` draws, one allocation of `resamples` means (10 000 × 1000 values take
/// about 30 ms in release).
///
/// The differences must be NaN-free (checked in debug builds).
///
/// # Units
/// Those of the differences (e.g. sols to goal).
///
/// # Panics
/// If `resamples == 0` or `confidence` is not in (0, 1).
#[must_use]
pub fn paired_bootstrap(
    differences: &[f64],
    resamples: usize,
    confidence: f64,
    seed: u64,
) -> Option<PairedDifference> {
    assert!(resamples > 0, "a bootstrap needs at least one resample");
    assert!(
        confidence > 0.0 && confidence < 1.0,
        "confidence must be in (0, 1), got {confidence}"
    );
    let &first = differences.first()?;
    debug_assert!(
        differences.iter().all(|d| !d.is_nan()),
        "paired_bootstrap of NaN differences"
    );
    let n = differences.len();
    if differences.iter().all(|&d| d == first) {
        return Some(PairedDifference {
            n,
            mean: first,
            interval: Interval {
                lo: first,
                hi: first,
            },
        });
    }
    let n_f = n as f64;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut means = Vec::with_capacity(resamples);
    for _ in 0..resamples {
        let mut sum = 0.0;
        for _ in 0..n {
            sum += differences[rng.random_range(0..n)];
        }
        means.push(sum / n_f);
    }
    // Equal keys under total_cmp are equal bits, so the unstable sort is deterministic.
    means.sort_unstable_by(f64::total_cmp);
    Some(PairedDifference {
        n,
        mean: sequential_sum(differences) / n_f,
        interval: Interval {
            lo: quantile(&means, 0.5 * (1.0 - confidence)),
            hi: quantile(&means, 0.5 * (1.0 + confidence)),
        },
    })
}

/// Left-to-right sum (not `Iterator::sum`, whose order and start value are not promised).
fn sequential_sum(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |acc, v| acc + v)
}

/// Acklam's approximation of the standard normal inverse CDF, relative error < 1.15e-9, for
/// `p` in (0, 1).
fn normal_quantile_acklam(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    const P_LOW: f64 = 0.024_25;
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < P_LOW {
        tail((-2.0 * p.ln()).sqrt())
    } else if p <= 1.0 - P_LOW {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    } else {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    }
}

/// The standard normal inverse CDF for `p` in (0, 1): Acklam's value refined by one Halley step
/// (cubic convergence takes its 1e-9 to rounding level).
fn normal_quantile(p: f64) -> f64 {
    let x = normal_quantile_acklam(p);
    if x == 0.0 {
        return x;
    }
    // Φ(x) − p, with Φ from erfc so the lower tail keeps its relative precision.
    let e = 0.5 * erfc(-x / std::f64::consts::SQRT_2) - p;
    let u = e * (2.0 * std::f64::consts::PI).sqrt() * (0.5 * x * x).exp();
    x - u / (1.0 + 0.5 * x * u)
}

/// The complementary error function, relative error ~1e-15 for x ≥ 0 (measured against scipy),
/// 2 − erfc(−x) below.
fn erfc(x: f64) -> f64 {
    if x < 0.0 {
        return 2.0 - erfc(-x);
    }
    let x2 = x * x;
    // The subtraction 1 − erf costs the series ~1e-16/erfc(x) relative: < 2e-15 below 1 (but
    // 1e-14 at 1.5). The continued fraction needs < 200 terms above 1.
    if x < 1.0 {
        // erf(x) = 2/√π · e^(−x²) · Σ 2ᵏ x²ᵏ⁺¹ / (2k + 1)!!: positive terms, no cancellation.
        let mut term = x;
        let mut sum = x;
        let mut k = 0.0;
        while term > sum * 1e-17 {
            k += 1.0;
            term *= 2.0 * x2 / (2.0 * k + 1.0);
            sum += term;
        }
        1.0 - std::f64::consts::FRAC_2_SQRT_PI * (-x2).exp() * sum
    } else {
        // erfc(x) = e^(−x²)/√π · 1/(x + (1/2)/(x + (2/2)/(x + (3/2)/(x + …)))), by modified
        // Lentz.
        const TINY: f64 = 1e-300;
        let mut f = x;
        let mut c = x;
        let mut d = 0.0;
        for k in 1..=500 {
            let a = 0.5 * f64::from(k);
            d = x + a * d;
            d = if d == 0.0 { TINY } else { d };
            c = x + a / c;
            c = if c == 0.0 { TINY } else { c };
            d = 1.0 / d;
            let delta = c * d;
            f *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        0.5 * std::f64::consts::FRAC_2_SQRT_PI * (-x2).exp() / f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_for_95_percent() {
        assert!((z_for_confidence(0.95) - 1.959_963_984_540_054).abs() < 1e-15);
        // scipy.stats.norm.isf(0.005), isf(0.05), isf(0.25).
        assert!((z_for_confidence(0.99) - 2.575_829_303_548_900_4).abs() < 1e-14);
        assert!((z_for_confidence(0.9) - 1.644_853_626_951_472_9).abs() < 1e-14);
        assert!((z_for_confidence(0.5) - 0.674_489_750_196_081_7).abs() < 1e-14);
    }

    #[test]
    fn z_is_monotone_and_continuous_at_acklam_region_edges() {
        let mut previous = 0.0;
        for i in 1..2000 {
            let z = z_for_confidence(f64::from(i) / 2000.0);
            assert!(z > previous, "at {i}");
            previous = z;
        }
        // The central/tail switch of Acklam's approximation is at tail 0.02425.
        let edge = 1.0 - 2.0 * 0.024_25;
        let gap = z_for_confidence(edge + 1e-12) - z_for_confidence(edge - 1e-12);
        assert!(gap > 0.0 && gap < 1e-10, "{gap}");
    }

    #[test]
    fn acklam_coefficients_are_acklams() {
        // A typo in a coefficient would still be hidden by the Halley step at first order, so
        // check the raw approximation's published accuracy against the refined value.
        for i in 1..1000 {
            let p = f64::from(i) / 1000.0;
            let exact = normal_quantile(p);
            let raw = normal_quantile_acklam(p);
            assert!(
                (raw - exact).abs() <= 1.2e-9 * exact.abs().max(1e-3),
                "p = {p}"
            );
        }
    }

    #[test]
    fn erfc_against_scipy() {
        // scipy.special.erfc at full repr.
        let cases = [
            (0.0, 1.0),
            (0.5, 0.4795001221869535),
            (1.0, 0.15729920705028516),
            (1.499, 0.03401396234814331),
            (1.5, 0.03389485352468927),
            (1.8, 0.010909498364269283),
            (2.0, 0.004677734981047266),
            (3.0, 2.2090496998585445e-05),
            (5.0, 1.5374597944280347e-12),
            (-1.0, 1.8427007929497148),
        ];
        for (x, expected) in cases {
            let got = erfc(x);
            assert!(
                (got - expected).abs() <= 4e-15 * expected,
                "erfc({x}) = {got}, scipy {expected}"
            );
        }
    }

    #[test]
    fn wilson_at_zero_and_all_successes_stays_in_unit_interval() {
        for n in [1, 2, 10, 40, 1000, 1_000_000] {
            let none = wilson(0, n, 0.95).expect("n > 0");
            assert_eq!(none.lo, 0.0);
            assert!(none.hi > 0.0 && none.hi < 1.0);
            let all = wilson(n, n, 0.95).expect("n > 0");
            assert_eq!(all.hi, 1.0);
            assert!(all.lo > 0.0 && all.lo < 1.0);
            // Symmetric: the interval for n of n mirrors the one for 0 of n.
            assert!((all.lo - (1.0 - none.hi)).abs() < 1e-15);
        }
        assert_eq!(wilson(0, 0, 0.95), None);
        // statsmodels: proportion_confint(2, 40, alpha=0.05, method="wilson").
        let i = wilson(2, 40, 0.95).expect("n > 0");
        assert!((i.lo - 0.013_820_667_386_148_344).abs() < 1e-12, "{i:?}");
        assert!((i.hi - 0.165_038_773_691_409_62).abs() < 1e-12, "{i:?}");
    }

    #[test]
    #[should_panic(expected = "successes out of")]
    fn wilson_refuses_more_successes_than_trials() {
        let _ = wilson(3, 2, 0.95);
    }

    #[test]
    fn quantile_interpolates_linearly() {
        let v = [1.0, 2.0, 4.0, 8.0];
        assert_eq!(quantile(&v, 0.0), 1.0);
        assert_eq!(quantile(&v, 1.0), 8.0);
        assert_eq!(quantile(&v, 0.5), 3.0);
        assert_eq!(quantile(&v, 0.25), 1.75);
        assert_eq!(quantile(&[7.0], 0.3), 7.0);
        assert_eq!(quantile(&[1.0, 2.0], 0.5), 1.5);
        assert_eq!(quantile(&[3.0, 3.0, 3.0], 0.7), 3.0);
    }

    #[test]
    fn spread_of_nothing_and_of_one_value() {
        assert_eq!(spread(&[]), None);
        let one = spread(&[-2.5]).expect("one value");
        assert_eq!(
            one,
            Spread {
                n: 1,
                mean: -2.5,
                median: -2.5,
                p5: -2.5,
                p95: -2.5
            }
        );
        let s = spread(&[3.0, 1.0, 2.0]).expect("three values");
        assert_eq!((s.n, s.mean, s.median), (3, 2.0, 2.0));
        assert!((s.p5 - 1.1).abs() < 1e-15 && (s.p95 - 2.9).abs() < 1e-15);
    }

    /// Small integers like "sols to goal" differences, from a fixed formula.
    fn lattice_differences(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| f64::from(((i * 7 + i / 3) % 5) as u8) - 3.0)
            .collect()
    }

    #[test]
    fn paired_bootstrap_is_deterministic_for_a_seed() {
        let d = lattice_differences(200);
        let a = paired_bootstrap(&d, 2000, 0.95, 42).expect("non-empty");
        let b = paired_bootstrap(&d, 2000, 0.95, 42).expect("non-empty");
        assert_eq!(a.interval.lo.to_bits(), b.interval.lo.to_bits());
        assert_eq!(a.interval.hi.to_bits(), b.interval.hi.to_bits());
        assert_eq!(a.mean.to_bits(), b.mean.to_bits());
        assert!(a.interval.lo < a.mean && a.mean < a.interval.hi, "{a:?}");
    }

    #[test]
    fn another_seed_gives_a_different_but_close_interval() {
        let d: Vec<f64> = (0..500)
            .map(|i| (f64::from(i) * 0.618_034).fract() * 4.0 - 2.5)
            .collect();
        let a = paired_bootstrap(&d, 5000, 0.95, 1).expect("non-empty");
        let b = paired_bootstrap(&d, 5000, 0.95, 2).expect("non-empty");
        assert_eq!(a.mean, b.mean);
        assert_ne!(a.interval, b.interval);
        // Monte Carlo error of a 2.5 % endpoint from B = 5000 resamples: √(α(1−α)/B)/φ(1.96)
        // = 0.038 standard errors of the mean (sd ≈ 1.15 for these values uniform on
        // [−2.5, 1.5)), so two seeds differ by ≈ 0.054 of them in sd: 0.15 allows 2.8 sd.
        let sd_of_mean = 1.15 / (500.0_f64).sqrt();
        assert!(
            (a.interval.lo - b.interval.lo).abs() < 0.15 * sd_of_mean,
            "{a:?} {b:?}"
        );
        assert!(
            (a.interval.hi - b.interval.hi).abs() < 0.15 * sd_of_mean,
            "{a:?} {b:?}"
        );
        // And the interval is about ±1.96 standard errors wide.
        let width = a.interval.hi - a.interval.lo;
        assert!(
            (width / (2.0 * 1.96 * sd_of_mean) - 1.0).abs() < 0.05,
            "{width}"
        );
    }

    #[test]
    fn constant_differences_give_a_degenerate_interval() {
        for d in [0.0, -0.7, 0.1, 3.0] {
            let values = vec![d; 37];
            let r = paired_bootstrap(&values, 100, 0.95, 9).expect("non-empty");
            assert_eq!(
                r,
                PairedDifference {
                    n: 37,
                    mean: d,
                    interval: Interval { lo: d, hi: d }
                }
            );
        }
        let one = paired_bootstrap(&[2.5], 10, 0.95, 0).expect("non-empty");
        assert_eq!(one.interval, Interval { lo: 2.5, hi: 2.5 });
        assert_eq!(paired_bootstrap(&[], 100, 0.95, 0), None);
    }

    /// Determinism golden: seed 7, 1000 resamples of the lattice data. A mismatch means the
    /// reported intervals of every study changed: the resampling code, rand's `random_range` or
    /// the ChaCha8 stream changed (e.g. a rand upgrade, or rand's `unbiased` feature switched on).
    #[test]
    fn paired_bootstrap_golden() {
        let r = paired_bootstrap(&lattice_differences(200), 1000, 0.95, 7).expect("non-empty");
        assert_eq!(
            (
                r.mean.to_bits(),
                r.interval.lo.to_bits(),
                r.interval.hi.to_bits()
            ),
            (
                13_830_464_383_662_245_806,
                13_831_410_139_583_993_610,
                13_828_753_015_803_845_018
            ),
            "{r:?}"
        );
    }
}
