//! Calibrates the particle filter's likelihood — its temperature `T` and registration σ — on
//! the synthetic benchmark set.
//!
//! `cargo run --release -p localization --example particle_temperature [-- CASES [METHOD]]`
//! (default: all 264 cases, census; METHOD is `census`, `ncc` or `mi`).
//!
//! Each case of `benchmark_cases(264, 2024)` on `BenchmarkMaps::generate(1)` is rendered as
//! `localize-bench` renders it (same position, seeds, wedges and sun, both DEMs, default
//! imaging), except that the truth patch is centred on the true position. The
//! score surface over ±20 m around the true position is turned into a posterior over the
//! offsets with a flat prior by the particle filter's own likelihood
//! (`particle::likelihood_grid`: `exp(−(s − s_min) / T)` convolved with a Gaussian of the
//! registration σ) and scored by the log density it puts at the true position (bilinear, as
//! the filter reads it), in ln(1/m²). That is a proper scoring rule: a belief too sharp is
//! punished when the peak misses the truth by the usual ~0.3 m, one too broad by spreading
//! over metres or over other places. The pair with the best mean log score over the cases is
//! the calibration; the second table gives, at the best σ, the share of truths inside the
//! posterior's 1σ/2σ/3σ ellipse (a 2-D Gaussian has 39 / 86 / 99 %) and the mean distance of
//! the posterior mean from the truth.

use localization::benchmark_set::{BenchmarkMaps, TerrainKind, benchmark_cases};
use localization::matcher::{
    MatchSettings, Method, OrbitalMap, RoverImages, ScoreSurface, score_surface,
};
use localization::particle::likelihood_grid;
use localization::synthetic::{
    ORTHO_RESOLUTION_M_PER_PX, ORTHO_SIZE_PX, OrbitalSettings, RoverImagingSettings,
    render_orbital, render_rover, truth_patch,
};
use rayon::prelude::*;

/// Half side of the scored window around the truth, metres.
const WINDOW_M: f64 = 20.0;
/// The benchmark's extra truth patch beyond the search window, metres
/// (`benchmark_set::PATCH_MARGIN_M`).
const PATCH_MARGIN_M: f64 = 4.0;

/// One case's terrain and (log density at the truth, Mahalanobis², error of the mean).
type Row = (TerrainKind, (f64, f64, f64));

struct Case {
    terrain: TerrainKind,
    truth_m: [f64; 2],
    surface: ScoreSurface,
}

fn render(
    case: &localization::benchmark_set::BenchmarkCase,
    maps: &BenchmarkMaps,
    p: &MatchSettings,
) -> Option<Case> {
    // The benchmark's own draws for this case.
    let layers = maps.get(case.terrain);
    let localization::benchmark_set::CaseDraws {
        truth_m,
        prior_m,
        truth_seed,
        orbital_seed,
        rover_seed,
    } = localization::benchmark_set::case_draws(case, layers);
    let half_ortho_m = 0.5 * ORTHO_SIZE_PX as f64 * ORTHO_RESOLUTION_M_PER_PX;
    // Centred on the truth (the benchmark centres its patch on the prior, up to 20 m away,
    // which would not hold the window around the truth).
    let _ = prior_m;
    let half_size_m = WINDOW_M + half_ortho_m + PATCH_MARGIN_M;
    let rover_settings = RoverImagingSettings {
        wedge_count: usize::from(case.wedges),
        sun_azimuth_range_deg: [case.sun_azimuth_deg; 2],
        sun_elevation_range_deg: [case.sun_elevation_deg; 2],
        ..RoverImagingSettings::default()
    };
    let patch = truth_patch(layers, truth_m, half_size_m, truth_seed).ok()?;
    let orbital = render_orbital(&patch, &OrbitalSettings::default(), orbital_seed).ok()?;
    let rover = render_rover(&patch, truth_m, &rover_settings, rover_seed).ok()?;
    let map = OrbitalMap::of(&orbital);
    let images = RoverImages::of(&rover);
    let surface = score_surface(&map, &images, truth_m, [WINDOW_M; 2], p).ok()?;
    Some(Case {
        terrain: case.terrain,
        truth_m,
        surface,
    })
}

/// Per case, temperature `t` and registration σ: (log density at the truth, Mahalanobis² of
/// the truth, distance of the posterior mean from the truth). Only offsets within `half_m` of
/// the truth on both axes count (the prior's extent).
fn score(case: &Case, t: f64, sigma_m: f64, half_m: f64) -> Option<(f64, f64, f64)> {
    let s = &case.surface;
    let res = s.resolution_m_per_px;
    let inside = |[x, y]: [f64; 2]| {
        (x - case.truth_m[0]).abs() <= half_m && (y - case.truth_m[1]).abs() <= half_m
    };
    let s_min = s
        .scores
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    // Exactly the filter's likelihood.
    let lik = likelihood_grid(s, s_min, t, sigma_m);
    let (mut z, mut mx, mut my) = (0.0, 0.0, 0.0);
    let mut pts = Vec::new();
    for row in 0..s.height {
        for col in 0..s.width {
            let pos = s.position_m(col as f64, row as f64);
            let w = lik[row * s.width + col];
            if w > 0.0 && inside(pos) {
                z += w;
                mx += w * pos[0];
                my += w * pos[1];
                pts.push((w, pos[0], pos[1]));
            }
        }
    }
    let (fx, fy) = s.offset_of(case.truth_m);
    let (c0, r0) = (fx.floor() as usize, fy.floor() as usize);
    let (tx, ty) = (fx - c0 as f64, fy - r0 as f64);
    let at = |c: usize, r: usize| lik[r.min(s.height - 1) * s.width + c.min(s.width - 1)];
    let l_truth = (at(c0, r0) * (1.0 - tx) + at(c0 + 1, r0) * tx) * (1.0 - ty)
        + (at(c0, r0 + 1) * (1.0 - tx) + at(c0 + 1, r0 + 1) * tx) * ty;
    if !(z > 0.0 && l_truth > 0.0) {
        return None;
    }
    let (mx, my) = (mx / z, my / z);
    let (mut cxx, mut cxy, mut cyy) = (0.0, 0.0, 0.0);
    for (w, x, y) in pts {
        let (dx, dy) = (x - mx, y - my);
        cxx += w * dx * dx;
        cxy += w * dx * dy;
        cyy += w * dy * dy;
    }
    // Each grid cell also spreads its mass over res² (variance res²/12 per axis).
    let (cxx, cxy, cyy) = (
        cxx / z + res * res / 12.0,
        cxy / z,
        cyy / z + res * res / 12.0,
    );
    let log_density = l_truth.ln() - z.ln() - 2.0 * res.ln();
    let (dx, dy) = (case.truth_m[0] - mx, case.truth_m[1] - my);
    let det = cxx * cyy - cxy * cxy;
    let maha2 = (cyy * dx * dx - 2.0 * cxy * dx * dy + cxx * dy * dy) / det;
    Some((log_density, maha2, dx.hypot(dy)))
}

/// Mean log density at the truth over the cases (cases where it is 0 count as ln 1e-300).
fn mean_log(cases: &[Case], t: f64, sigma_m: f64, half_m: f64) -> f64 {
    let v: Vec<f64> = cases
        .par_iter()
        .map(|c| score(c, t, sigma_m, half_m).map_or(-690.8, |r| r.0))
        .collect();
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(264);
    let method = args
        .get(2)
        .and_then(|a| Method::from_name(a))
        .unwrap_or(Method::Census);
    let p = MatchSettings {
        method,
        ..MatchSettings::default()
    };
    let maps = BenchmarkMaps::generate(1);
    let started = std::time::Instant::now();
    let cases: Vec<Case> = benchmark_cases(n, 2024)
        .par_iter()
        .filter_map(|c| render(c, &maps, &p))
        .collect();
    eprintln!(
        "{} of {n} cases rendered and scored ({method}, ±{WINDOW_M} m) in {:.1} s",
        cases.len(),
        started.elapsed().as_secs_f64()
    );
    let temps: Vec<f64> = (0..=24)
        .map(|k| 0.0005 * 10f64.powf(k as f64 / 12.0))
        .collect();
    let sigmas = [0.0, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5];
    // The log score over T × registration σ.
    print!("| T \\ σ_reg (m) |");
    for sg in sigmas {
        print!(" {sg} |");
    }
    println!();
    println!("|---|{}", "---|".repeat(sigmas.len()));
    let mut best = (f64::NEG_INFINITY, 0.0, 0.0);
    for &t in &temps {
        print!("| {t:.5} |");
        for sg in sigmas {
            let m = mean_log(&cases, t, sg, WINDOW_M);
            if m > best.0 {
                best = (m, t, sg);
            }
            print!(" {m:.3} |");
        }
        println!();
    }
    let (_, t_best, sg_best) = best;
    // The detail at the best σ: per terrain, coverage, error of the mean.
    println!("\nAt σ_reg = {sg_best} m:\n");
    println!(
        "| T | mean log density at truth (ln 1/m²) | rocky | plain | dunes | truth in 1σ / 2σ / 3σ | mean error of posterior mean (m) |"
    );
    println!("|---|---|---|---|---|---|---|");
    for &t in &temps {
        let rows: Vec<Row> = cases
            .iter()
            .filter_map(|c| score(c, t, sg_best, WINDOW_M).map(|r| (c.terrain, r)))
            .collect();
        let mean = |f: &dyn Fn(&Row) -> Option<f64>| {
            let v: Vec<f64> = rows.iter().filter_map(f).collect();
            v.iter().sum::<f64>() / v.len().max(1) as f64
        };
        let inside = |k2: f64| {
            rows.iter().filter(|r| r.1.1 <= k2).count() as f64 / rows.len().max(1) as f64 * 100.0
        };
        println!(
            "| {t:.5} | {:.3} | {:.3} | {:.3} | {:.3} | {:.0} / {:.0} / {:.0} % | {:.3} |",
            mean(&|r| Some(r.1.0)),
            mean(&|r| (r.0 == TerrainKind::Rocky).then_some(r.1.0)),
            mean(&|r| (r.0 == TerrainKind::Plain).then_some(r.1.0)),
            mean(&|r| (r.0 == TerrainKind::Dunes).then_some(r.1.0)),
            inside(1.0),
            inside(4.0),
            inside(9.0),
            mean(&|r| Some(r.1.2)),
        );
    }
    // Refine T at the best σ, for the full window and two smaller priors.
    println!();
    for half_m in [WINDOW_M, 10.0, 5.0] {
        let (lo, hi) = (t_best / 1.5, t_best * 1.5);
        let fine = (0..=40)
            .map(|k| lo * (hi / lo).powf(f64::from(k) / 40.0))
            .map(|t| (mean_log(&cases, t, sg_best, half_m), t))
            .fold(
                (f64::NEG_INFINITY, 0.0),
                |a, b| if b.0 > a.0 { b } else { a },
            );
        println!(
            "best T = {:.5} at σ_reg = {sg_best} m (mean log density {:.3} ln 1/m², {} cases, {method}, ±{half_m} m)",
            fine.1,
            fine.0,
            cases.len()
        );
    }
}
