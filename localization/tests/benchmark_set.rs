//! The synthetic benchmark set: a small set runs, is deterministic across thread counts, and
//! its statistics are computed from its rows. Accuracy targets are not asserted (yet).
//!
//! The full 264-case run is `solsim localize-bench` (minutes in release).
#![allow(clippy::unwrap_used)]

use localization::benchmark_set::{
    BenchmarkMaps, BenchmarkReport, ErrorStats, TerrainKind, benchmark_cases, run_benchmark,
};
use localization::matcher::MatchSettings;

fn print(report: &BenchmarkReport, seconds: f64) {
    let s = |name: &str, e: &ErrorStats| {
        eprintln!(
            "{name:>9}: n {:3}  mean {:.3}  median {:.3}  p99 {:.3}  max {:.3}  >1 m {}  >2 m {}",
            e.count, e.mean_m, e.median_m, e.p99_m, e.max_m, e.over_1m, e.over_2m
        );
    };
    s("all", &report.all);
    s("accepted", &report.accepted);
    for (k, e) in &report.by_terrain {
        s(&format!("{k:?}"), e);
    }
    eprintln!(
        "rejections {:?}, failures {}, {seconds:.1} s",
        report.rejections, report.failures
    );
    // Error components across / along the ripple crests (crests run 20° east of north).
    let across = 110f64.to_radians();
    for r in &report.rows {
        if let (Some(e), true) = (r.estimate_m, r.error_m.is_some_and(|e| e > 1.0)) {
            let (dx, dy) = (e[0] - r.truth_m[0], e[1] - r.truth_m[1]);
            eprintln!(
                "  case {:3} {:?}: error across ripples {:+.2} m, along {:+.2} m",
                r.id,
                r.terrain,
                dx * across.sin() + dy * across.cos(),
                -dx * across.cos() + dy * across.sin()
            );
        }
    }
    for r in &report.rows {
        if r.error_m.is_none_or(|e| e > 0.75) || r.rejection.is_some() {
            eprintln!(
                "  case {:3} {:?} {} wedges {:?}: error {:?} σ {:?} ratio {:?} valid {:?} {:?} {:?}",
                r.id,
                r.terrain,
                r.wedges,
                r.lighting,
                r.error_m,
                r.sigma_m,
                r.peak_ratio,
                r.valid_fraction,
                r.rejection,
                r.failure
            );
        }
    }
}

#[test]
fn a_small_set_is_deterministic_and_its_stats_are_computed() {
    let maps = BenchmarkMaps::generate(1);
    let cases = benchmark_cases(24, 7);
    let params = MatchSettings::default();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run_benchmark(&cases, |k| maps.get(k), &params))
    };
    let t = std::time::Instant::now();
    let a = run(2);
    print(&a, t.elapsed().as_secs_f64());
    let b = run(1);
    assert_eq!(a, b);
    assert_eq!(a.rows.len(), 24);
    assert_eq!(a.failures, 0);
    assert!(a.rows.iter().zip(&cases).all(|(r, c)| r.id == c.id));
    let errors: Vec<f64> = a.rows.iter().filter_map(|r| r.error_m).collect();
    assert_eq!(a.all, ErrorStats::of(&errors));
    assert_eq!(a.all.count, 24);
    assert!(a.all.mean_m.is_finite() && a.all.max_m >= a.all.p99_m);
    assert!(a.all.p99_m >= a.all.median_m);
    let rejected: usize = a.rejections.iter().map(|(_, n)| n).sum();
    assert_eq!(a.accepted.count + rejected, 24);
    let kinds: usize = a.by_terrain.iter().map(|(_, e)| e.count).sum();
    assert_eq!(kinds, 24);
    assert!(
        a.by_terrain
            .iter()
            .all(|(k, e)| e.count == 8 && TerrainKind::ALL.contains(k))
    );
}
