//! Effective sample size, systematic resampling and the KLD sample-size bound.

use std::collections::BTreeSet;

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::settings::KldSettings;

/// Effective sample size `1 / Σ wᵢ²` of weights that sum to 1 (Kong, Liu and Wong 1994):
/// N for equal weights, 1 when one particle holds everything; 0 for no weights.
///
/// Weights that do not sum to 1 are normalised first (`(Σ w)² / Σ w²`).
#[must_use]
pub fn effective_sample_size(weights: &[f64]) -> f64 {
    let sum: f64 = weights.iter().sum();
    let sum_sq: f64 = weights.iter().map(|w| w * w).sum();
    if sum_sq > 0.0 {
        sum * sum / sum_sq
    } else {
        0.0
    }
}

/// Systematic resampling: `n` indices into `weights` (which sum to 1), each index `i` appearing
/// `⌊n·wᵢ⌋` or `⌈n·wᵢ⌉` times, in increasing order.
///
/// `u0` in `[0, 1)` is the one uniform draw; the pointers are `(u0 + k) / n` for `k = 0..n`
/// against the cumulative weights. Returns an empty vector when no weight is positive or
/// `n = 0`.
#[must_use]
pub fn systematic_indices(weights: &[f64], n: usize, u0: f64) -> Vec<usize> {
    let mut out = Vec::with_capacity(n);
    // Rounding can leave the final cumulative sum a little under a pointer: the last particle
    // with weight takes the rest (never a zero-weight one after it).
    let Some(last) = weights.iter().rposition(|&w| w > 0.0) else {
        return out;
    };
    let mut j = 0;
    let mut cdf = weights[0];
    for k in 0..n {
        let u = (u0 + k as f64) / n as f64;
        while cdf <= u && j < last {
            j += 1;
            cdf += weights[j];
        }
        out.push(j);
    }
    out
}

/// Fox's KLD bound: the number of particles for which, with probability `1 − δ`, the
/// Kullback-Leibler divergence between the particle approximation and the true posterior over
/// `bins` occupied bins stays below `epsilon`, with `z_quantile = z₁₋δ` (Fox 2003, eq. 10, with
/// the Wilson-Hilferty approximation of the χ² quantile):
///
/// `n = (k − 1) / (2ε) · (1 − 2 / (9(k − 1)) + √(2 / (9(k − 1))) · z₁₋δ)³`
///
/// 1 for `k ≤ 1` (a belief in one bin needs one particle to describe).
#[must_use]
pub fn kld_sample_count(bins: usize, epsilon: f64, z_quantile: f64) -> usize {
    if bins <= 1 {
        return 1;
    }
    let k1 = (bins - 1) as f64;
    let a = 2.0 / (9.0 * k1);
    let n = k1 / (2.0 * epsilon) * (1.0 - a + a.sqrt() * z_quantile).powi(3);
    n.ceil() as usize
}

/// KLD-adaptive resampling: indices drawn one at a time in proportion to `weights` until their
/// count reaches [`kld_sample_count`] of the bins (side `k.bin_m`) their `positions_m` occupy,
/// at least `k.min_particles` and at most `max`.
pub(super) fn kld_indices(
    weights: &[f64],
    positions_m: &[[f64; 2]],
    k: &KldSettings,
    max: usize,
    rng: &mut ChaCha8Rng,
) -> Vec<usize> {
    let mut cdf = Vec::with_capacity(weights.len());
    let mut acc = 0.0;
    for w in weights {
        acc += w;
        cdf.push(acc);
    }
    let Some(&total) = cdf.last() else {
        return Vec::new();
    };
    let mut bins = BTreeSet::new();
    let mut out = Vec::new();
    let last = cdf.len() - 1;
    while out.len() < max {
        let u = rng.random::<f64>() * total;
        let i = cdf.partition_point(|&c| c <= u).min(last);
        out.push(i);
        let [x, y] = positions_m[i];
        bins.insert(((x / k.bin_m).floor() as i64, (y / k.bin_m).floor() as i64));
        let need = kld_sample_count(bins.len(), k.epsilon, k.z_quantile).max(k.min_particles);
        if out.len() >= need {
            break;
        }
    }
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn ess_of_known_weights() {
        assert_eq!(effective_sample_size(&[0.25; 4]), 4.0);
        assert_eq!(effective_sample_size(&[0.0, 1.0, 0.0]), 1.0);
        // Two equal halves: 2; unnormalised weights give the same.
        assert!((effective_sample_size(&[0.5, 0.5]) - 2.0).abs() < 1e-12);
        assert!((effective_sample_size(&[3.0, 3.0]) - 2.0).abs() < 1e-12);
        // 1 / (0.7² + 0.2² + 0.1²) = 1 / 0.54.
        assert!((effective_sample_size(&[0.7, 0.2, 0.1]) - 1.0 / 0.54).abs() < 1e-12);
        assert_eq!(effective_sample_size(&[]), 0.0);
        assert_eq!(effective_sample_size(&[0.0, 0.0]), 0.0);
    }

    #[test]
    fn systematic_counts_are_floor_or_ceil_of_n_w() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for trial in 0..200 {
            let m = 1 + trial % 37;
            let raw: Vec<f64> = (0..m).map(|_| rng.random::<f64>().powi(3)).collect();
            let sum: f64 = raw.iter().sum();
            let w: Vec<f64> = raw.iter().map(|v| v / sum).collect();
            let n = 1 + (trial * 7) % 500;
            let u0 = rng.random::<f64>();
            let idx = systematic_indices(&w, n, u0);
            assert_eq!(idx.len(), n);
            assert!(idx.windows(2).all(|p| p[0] <= p[1]));
            let mut counts = vec![0usize; m];
            for i in idx {
                counts[i] += 1;
            }
            for (c, wi) in counts.iter().zip(&w) {
                let e = n as f64 * wi;
                // An integer within 1 of n·w is ⌊n·w⌋ or ⌈n·w⌉ (a hair of slack for the
                // rounding of the cumulative sum).
                assert!((*c as f64 - e).abs() < 1.0 + 1e-9, "count {c} vs {e}");
            }
        }
    }

    #[test]
    fn systematic_is_unbiased_over_the_draw() {
        // Averaged over u0, the count of each particle is exactly n·wᵢ.
        let w = [0.05, 0.6, 0.1, 0.25];
        let n = 7;
        let steps = 10_000;
        let mut mean = [0.0; 4];
        for s in 0..steps {
            let u0 = (s as f64 + 0.5) / steps as f64;
            for i in systematic_indices(&w, n, u0) {
                mean[i] += 1.0 / steps as f64;
            }
        }
        for (m, wi) in mean.iter().zip(&w) {
            assert!((m - n as f64 * wi).abs() < 1e-3, "{m} vs {}", n as f64 * wi);
        }
    }

    #[test]
    fn systematic_degenerate_inputs() {
        assert!(systematic_indices(&[], 5, 0.3).is_empty());
        assert!(systematic_indices(&[0.0, 0.0], 5, 0.3).is_empty());
        assert_eq!(
            systematic_indices(&[0.6, 0.399, 0.0], 4, 0.999),
            vec![0, 0, 1, 1]
        );
        assert!(systematic_indices(&[1.0], 0, 0.3).is_empty());
        assert_eq!(systematic_indices(&[1.0], 3, 0.99), vec![0, 0, 0]);
        // A sum a little under 1 still gives valid indices.
        assert_eq!(
            systematic_indices(&[0.5, 0.499_999], 2, 0.999_999),
            vec![0, 1]
        );
    }

    #[test]
    fn kld_bound_grows_with_bins() {
        assert_eq!(kld_sample_count(0, 0.05, 2.326), 1);
        assert_eq!(kld_sample_count(1, 0.05, 2.326), 1);
        // k = 2: (1 / 0.1)·(1 − 2/9 + √(2/9)·2.326)³ = 10 · 1.8745³ ≈ 65.9.
        assert_eq!(kld_sample_count(2, 0.05, 2.326), 66);
        let mut prev = 0;
        for k in [2, 5, 10, 50, 100, 1000] {
            let n = kld_sample_count(k, 0.05, 2.326);
            assert!(n > prev);
            prev = n;
        }
        // Large k: about (k − 1) / (2ε) · (1 + ...) — 1000 bins need ~11.8 k particles.
        let n = kld_sample_count(1000, 0.05, 2.326);
        assert!((11_000..13_000).contains(&n), "{n}");
    }

    #[test]
    fn kld_keeps_few_particles_for_a_concentrated_belief_and_many_for_a_spread_one() {
        let k = KldSettings::default();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let n = 5000;
        let w = vec![1.0 / n as f64; n];
        // All within one 0.5 m bin: the minimum.
        let tight: Vec<[f64; 2]> = (0..n)
            .map(|i| [10.1 + 0.3 * (i as f64 / n as f64), 20.1])
            .collect();
        assert_eq!(kld_indices(&w, &tight, &k, n, &mut rng).len(), 200);
        // Spread over 50 m × 50 m: 10,000 bins, so the cap.
        let spread: Vec<[f64; 2]> = (0..n)
            .map(|i| [(i % 71) as f64 * 0.7, (i / 71) as f64 * 0.7])
            .collect();
        assert_eq!(kld_indices(&w, &spread, &k, n, &mut rng).len(), n);
        assert!(kld_indices(&[], &[], &k, n, &mut rng).is_empty());
    }
}
