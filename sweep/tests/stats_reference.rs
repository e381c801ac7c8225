//! `sweep::stats` against independent implementations: statsmodels (Wilson intervals), numpy
//! (quantiles, means) and scipy (normal quantile, percentile bootstrap), as computed by
//! `peers/stats_reference.py` on the inputs in `peers/stats_fixtures/cases.json` and committed in
//! `peers/stats_fixtures/expected.json`.

use std::path::{Path, PathBuf};

#[path = "../../tests/common/external.rs"]
mod external;

use serde::Deserialize;
use sweep::stats;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn fixtures() -> PathBuf {
    root().join("peers/stats_fixtures")
}

#[derive(Deserialize)]
struct Cases {
    z: Vec<f64>,
    wilson: Vec<WilsonCase>,
    quantile: Vec<QuantileCase>,
    bootstrap: Vec<BootstrapCase>,
}

#[derive(Deserialize)]
struct WilsonCase {
    successes: u64,
    n: u64,
    confidence: f64,
}

#[derive(Deserialize)]
struct QuantileCase {
    name: String,
    values: Vec<f64>,
    p: Vec<f64>,
}

#[derive(Deserialize)]
struct BootstrapCase {
    name: String,
    differences: Vec<f64>,
    n_resamples: usize,
    confidence: f64,
    seed: u64,
}

#[derive(Deserialize)]
struct Expected {
    z: Vec<ExpectedZ>,
    wilson: Vec<ExpectedWilson>,
    quantile: Vec<ExpectedQuantile>,
    bootstrap: Vec<ExpectedBootstrap>,
}

#[derive(Deserialize)]
struct ExpectedZ {
    confidence: f64,
    z: f64,
}

#[derive(Deserialize)]
struct ExpectedWilson {
    successes: u64,
    n: u64,
    lo: f64,
    hi: f64,
}

#[derive(Deserialize)]
struct ExpectedQuantile {
    name: String,
    q: Vec<f64>,
    mean: f64,
    median: f64,
    p5: f64,
    p95: f64,
}

#[derive(Deserialize)]
struct ExpectedBootstrap {
    name: String,
    n: usize,
    mean: f64,
    /// Population standard deviation (ddof = 0) of the differences.
    sd: f64,
    /// scipy's percentile interval; None where scipy declines (a single observation).
    percentile: Option<[f64; 2]>,
    /// scipy's BCa interval, for information only.
    bca: Option<[f64; 2]>,
}

fn load() -> (Cases, Expected) {
    let read = |name: &str| {
        std::fs::read_to_string(fixtures().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    let cases = serde_json::from_str(&read("cases.json")).expect("cases.json");
    let expected = serde_json::from_str(&read("expected.json")).expect("expected.json");
    (cases, expected)
}

/// Within `tol`, relative to the magnitude when that exceeds 1 (the mean of a 1000-run sample
/// is summed pairwise by numpy and sequentially here: they differ by a few ulp).
fn close(a: f64, e: f64, tol: f64) -> bool {
    (a - e).abs() <= tol * e.abs().max(1.0)
}

#[test]
fn z_matches_scipy() {
    let (cases, expected) = load();
    assert_eq!(cases.z.len(), expected.z.len());
    let mut worst = 0.0_f64;
    for e in &expected.z {
        let z = stats::z_for_confidence(e.confidence);
        worst = worst.max((z - e.z).abs());
        assert!(
            close(z, e.z, 1e-12),
            "confidence {}: rust {z}, scipy {}",
            e.confidence,
            e.z
        );
    }
    eprintln!(
        "scipy norm.isf: {} quantiles, worst difference {worst:e}",
        expected.z.len()
    );
}

#[test]
fn wilson_matches_statsmodels() {
    let (cases, expected) = load();
    assert_eq!(cases.wilson.len(), expected.wilson.len());
    let mut worst = 0.0_f64;
    for (c, e) in cases.wilson.iter().zip(&expected.wilson) {
        assert_eq!((c.successes, c.n), (e.successes, e.n));
        let i = stats::wilson(c.successes, c.n, c.confidence).expect("n > 0");
        for (a, b) in [(i.lo, e.lo), (i.hi, e.hi)] {
            worst = worst.max((a - b).abs());
            assert!(
                (a - b).abs() <= 1e-12,
                "{}/{} at {}: rust {i:?}, statsmodels [{}, {}]",
                c.successes,
                c.n,
                c.confidence,
                e.lo,
                e.hi
            );
        }
        assert!(0.0 <= i.lo && i.lo <= i.hi && i.hi <= 1.0, "{i:?}");
    }
    eprintln!(
        "statsmodels Wilson: {} intervals, worst difference {worst:e}",
        cases.wilson.len()
    );
}

#[test]
fn quantiles_and_spreads_match_numpy() {
    let (cases, expected) = load();
    assert_eq!(cases.quantile.len(), expected.quantile.len());
    let mut worst = 0.0_f64;
    for (c, e) in cases.quantile.iter().zip(&expected.quantile) {
        assert_eq!(c.name, e.name);
        let mut sorted = c.values.clone();
        sorted.sort_by(f64::total_cmp);
        for (&p, &q) in c.p.iter().zip(&e.q) {
            let got = stats::quantile(&sorted, p);
            worst = worst.max((got - q).abs());
            assert!(
                close(got, q, 1e-12),
                "{} at {p}: rust {got}, numpy {q}",
                c.name
            );
        }
        let s = stats::spread(&c.values).expect("non-empty");
        assert_eq!(s.n, c.values.len());
        for (what, got, want) in [
            ("mean", s.mean, e.mean),
            ("median", s.median, e.median),
            ("p5", s.p5, e.p5),
            ("p95", s.p95, e.p95),
        ] {
            assert!(
                close(got, want, 1e-12),
                "{} {what}: rust {got}, numpy {want}",
                c.name
            );
        }
    }
    eprintln!("numpy quantiles: worst difference {worst:e}");
}

/// Bootstrap endpoints: scipy draws from PCG64, solsim from ChaCha8, so each side estimates the
/// same percentile of the same bootstrap distribution with its own Monte Carlo error.
///
/// Tolerance. The bootstrap distribution of the mean of n values with population sd s is close
/// to normal with sd σ = s/√n. The α-quantile estimated from B resamples has standard error
/// √(α(1−α)/B) / f(q_α), with density f(q_α) = φ(z_α)/σ; for α = 0.025, B = 20 000 that is
/// 1.10e-3 / 0.0584 · σ = 0.0189 σ. The difference of two independent estimates has √2 times
/// that, and we allow 4 of those (a false alarm is a 6e-5 chance, and with fixed seeds a pass is
/// permanent): tol = 4·√2·0.0189·σ ≈ 0.107 σ (0.0076 s at n = 200). Data on a lattice (integers)
/// put the resample means on a lattice of step (smallest gap between values)/n, and the two
/// estimates may sit on neighbouring points, so one step is added. A wrong level, e.g. 5 % in
/// place of 2.5 %, would move an endpoint by (1.96 − 1.645)·σ = 0.31 σ: three times the
/// tolerance. The mean must agree to rounding.
#[test]
fn bootstrap_matches_scipy_within_monte_carlo_error() {
    let (cases, expected) = load();
    assert_eq!(cases.bootstrap.len(), expected.bootstrap.len());
    for (c, e) in cases.bootstrap.iter().zip(&expected.bootstrap) {
        assert_eq!(
            (c.name.as_str(), c.differences.len()),
            (e.name.as_str(), e.n)
        );
        let started = std::time::Instant::now();
        let r = stats::paired_bootstrap(&c.differences, c.n_resamples, c.confidence, c.seed)
            .expect("non-empty");
        let elapsed = started.elapsed();
        assert_eq!(r.n, e.n);
        assert!(
            close(r.mean, e.mean, 1e-12),
            "{}: mean rust {}, numpy {}",
            c.name,
            r.mean,
            e.mean
        );
        let Some([lo, hi]) = e.percentile else {
            // scipy declines one observation; the interval is the observation itself.
            assert_eq!(r.interval.lo, r.interval.hi, "{}", c.name);
            assert_eq!(r.interval.lo, c.differences[0], "{}", c.name);
            continue;
        };
        let n = c.differences.len() as f64;
        let sigma = e.sd / n.sqrt();
        let alpha = 0.5 * (1.0 - c.confidence);
        let z = stats::z_for_confidence(c.confidence);
        let density = (-0.5 * z * z).exp() / (2.0 * std::f64::consts::PI).sqrt();
        let endpoint_se = (alpha * (1.0 - alpha) / c.n_resamples as f64).sqrt() / density * sigma;
        let tol = 4.0 * std::f64::consts::SQRT_2 * endpoint_se + lattice_step(&c.differences) / n
            // Constant data: both sides give the value up to rounding of the mean.
            + 1e-12 * e.mean.abs().max(1.0);
        let bca = e
            .bca
            .map_or("-".to_string(), |[l, h]| format!("[{l:.4}, {h:.4}]"));
        eprintln!(
            "{:<18} rust [{:.4}, {:.4}]  scipy percentile [{lo:.4}, {hi:.4}]  tol {tol:.4}  \
             scipy BCa {bca}  ({} × {} in {:.1} ms)",
            c.name,
            r.interval.lo,
            r.interval.hi,
            c.n_resamples,
            c.differences.len(),
            elapsed.as_secs_f64() * 1e3
        );
        assert!(
            (r.interval.lo - lo).abs() <= tol && (r.interval.hi - hi).abs() <= tol,
            "{}: rust [{}, {}], scipy [{lo}, {hi}], tolerance {tol}",
            c.name,
            r.interval.lo,
            r.interval.hi
        );
    }
}

/// The smallest positive gap between two distinct values (0 for constant data).
fn lattice_step(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&gap| gap > 0.0)
        .fold(0.0, |smallest: f64, gap| {
            if smallest == 0.0 {
                gap
            } else {
                smallest.min(gap)
            }
        })
}

/// Re-runs statsmodels, numpy and scipy (in `peers/.venv`, made by `python3
/// peers/setup_venv.py`) and checks the committed expected.json is what they print today.
/// Without the venv the test fails, unless the run opted out of the external checks
/// (`scripts/test.sh --skip-external`, counted).
#[test]
fn committed_reference_is_current() {
    let Some(python) = external::peers_python(&root(), "re-running statsmodels, numpy and scipy")
    else {
        return;
    };
    let output = std::process::Command::new(python)
        .arg(root().join("peers/stats_reference.py"))
        .output()
        .expect("run stats_reference.py");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let committed = std::fs::read_to_string(fixtures().join("expected.json")).expect("expected");
    assert_eq!(
        String::from_utf8_lossy(&output.stdout),
        committed,
        "regenerate with: python3 peers/stats_reference.py --write"
    );
}

/// The brief's budget: 10 000 resamples of 1000 values well under 100 ms in release. Timing is
/// machine-dependent, so this runs on request:
/// `cargo test -p sweep --release --test stats_reference -- --ignored --nocapture`.
#[test]
#[ignore = "timing; run in release on request"]
fn paired_bootstrap_speed() {
    let d: Vec<f64> = (0..1000)
        .map(|i| (f64::from(i) * 0.618_034).fract() * 4.0 - 2.5)
        .collect();
    let mut best = f64::INFINITY;
    for seed in 0..5 {
        let started = std::time::Instant::now();
        let r = stats::paired_bootstrap(&d, 10_000, 0.95, seed).expect("non-empty");
        best = best.min(started.elapsed().as_secs_f64() * 1e3);
        assert!(r.interval.lo < r.interval.hi);
    }
    eprintln!("paired_bootstrap(1000 values, 10 000 resamples): best of 5 {best:.1} ms");
    assert!(best < 100.0, "{best} ms");
}
