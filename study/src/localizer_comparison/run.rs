//! Every candidate on every case, in parallel: the outcomes and their statistics.

use std::time::Instant;

use localization::benchmark_set::{
    BenchmarkCase, BenchmarkImaging, BenchmarkMaps, CaseResult, ErrorStats, MAX_PRIOR_OFFSET_M,
    benchmark_cases, render_case, report_of,
};
use localization::ekf::{ParkedSettings, parked_fix};
use localization::matcher::{MatchSettings, Method, OrbitalMap, RoverImages, localize};

use localization::particle::{PanoramaFix, PanoramaFixSettings, localize_panorama};
use rand::SeedableRng as _;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use sim::localizers::{LocalizationResult, StatisticalLocalizer};

use super::candidate::Candidate;

/// One localizer's outcome on one case.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Outcome {
    /// Distance of its result from the truth, metres (`None`: it could not run).
    error_m: Option<f64>,
    /// Whether the result passed its checks.
    accepted: bool,
    /// Whether it ran at all (inputs it could use).
    ran: bool,
    /// The radius it claims for an accepted result, metres (the statistical model's reported
    /// σ, a matcher's σ, a filter's 3σ disc).
    radius_m: Option<f64>,
    /// The localizer's own time, seconds.
    time_s: f64,
}

impl Outcome {
    /// It could not run (no usable input), after `time_s`.
    fn not_run(time_s: f64) -> Self {
        Self {
            error_m: None,
            accepted: false,
            ran: false,
            radius_m: None,
            time_s,
        }
    }

    /// It ran and refused its result (`error_m`: the refused result's error, if any).
    fn rejected(error_m: Option<f64>, time_s: f64) -> Self {
        Self {
            error_m,
            accepted: false,
            ran: true,
            radius_m: None,
            time_s,
        }
    }
}

/// One row of the comparison.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ComparisonRow {
    /// The localizer.
    pub localizer: &'static str,
    /// What it needs.
    pub needs: &'static str,
    /// Cases run.
    pub cases: usize,
    /// Errors of the results it accepted (what the rover would apply).
    pub accepted: ErrorStats,
    /// Errors of every result, accepted or not.
    pub all: ErrorStats,
    /// Accepted results whose error is within the radius the localizer claims for them (its
    /// σ, or a filter's 3σ disc).
    pub within_own_radius: usize,
    /// Results it rejected.
    pub rejected: usize,
    /// Cases it could not run at all.
    pub could_not_run: usize,
    /// Mean time of its own call per case, milliseconds.
    pub mean_ms_per_case: f64,
    /// Largest time of its own call, milliseconds.
    pub max_ms_per_case: f64,
}

/// What the comparison found: one row per candidate, and the matchers' full reports (for
/// `localize-bench`'s per-method tables).
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// One row per candidate, in the order asked.
    pub rows: Vec<ComparisonRow>,
    /// The matchers' reports, method and report.
    pub matcher_reports: Vec<(Method, localization::benchmark_set::BenchmarkReport)>,
}

/// A matcher's case row, as [`localization::benchmark_set::run_case`] makes it.
fn matcher_row(
    case: &BenchmarkCase,
    truth_m: [f64; 2],
    prior_m: [f64; 2],
    rendered: Result<(&OrbitalMap<'_>, &RoverImages<'_>), &str>,
    params: &MatchSettings,
) -> (CaseResult, f64) {
    let mut row = CaseResult::pending(case, truth_m, prior_m);
    let (map, images) = match rendered {
        Ok(v) => v,
        Err(e) => {
            row.failure = Some(e.to_string());
            return (row, 0.0);
        }
    };
    let start = Instant::now();
    let result = localize(map, images, prior_m, params);
    let time_s = start.elapsed().as_secs_f64();
    row.record(result);
    (row, time_s)
}

/// The seed of `candidate`'s own draws on `case` (a stream of the case's seed).
fn candidate_seed(case: &BenchmarkCase, stream: u64) -> u64 {
    let mut rng = ChaCha8Rng::seed_from_u64(case.seed);
    rng.set_stream(1 + stream);
    rand::RngExt::random(&mut rng)
}

/// One case under every candidate: the matchers' case rows and every candidate's outcome.
fn run_case(
    case: &BenchmarkCase,
    maps: &BenchmarkMaps,
    candidates: &[Candidate],
    imaging: &BenchmarkImaging,
) -> (Vec<CaseResult>, Vec<Outcome>) {
    let layers = maps.get(case.terrain);
    let search = MatchSettings::default();
    let draws = localization::benchmark_set::case_draws(case, layers);
    let (truth, prior) = (draws.truth_m, draws.prior_m);
    let rendered = if candidates.iter().any(|c| c.uses_imagery()) {
        render_case(case, layers, search.search_radius_m, imaging).map_err(|e| e.to_string())
    } else {
        Err("not rendered".into())
    };
    let views = rendered
        .as_ref()
        .map(|(_, orbital, rover)| (OrbitalMap::of(orbital), RoverImages::of(rover)));
    let views = match &views {
        Ok((m, r)) => Ok((m, r)),
        Err(e) => Err(e.as_str()),
    };
    let error_of = |p: [f64; 2]| (p[0] - truth[0]).hypot(p[1] - truth[1]);
    let prior_r = MAX_PRIOR_OFFSET_M;
    let mut rows = Vec::new();
    let mut outcomes = Vec::new();
    for (k, &candidate) in candidates.iter().enumerate() {
        let seed = candidate_seed(case, k as u64);
        let outcome = match candidate {
            Candidate::Statistical => {
                let mut rng = ChaCha8Rng::seed_from_u64(seed);
                let start = Instant::now();
                let result = StatisticalLocalizer::default().draw(&mut rng);
                let time_s = start.elapsed().as_secs_f64();
                match result {
                    LocalizationResult::Accepted { error_m, sigma_m } => Outcome {
                        error_m: Some(error_m[0].hypot(error_m[1])),
                        accepted: true,
                        ran: true,
                        radius_m: Some(sigma_m),
                        time_s,
                    },
                    LocalizationResult::Rejected { .. } => Outcome::rejected(None, time_s),
                }
            }
            Candidate::Matcher(method) => {
                let params = MatchSettings { method, ..search };
                let (row, time_s) = matcher_row(case, truth, prior, views, &params);
                let outcome = Outcome {
                    error_m: row.error_m,
                    accepted: row.error_m.is_some() && row.rejection.is_none(),
                    ran: row.failure.is_none(),
                    radius_m: row.sigma_m,
                    time_s,
                };
                rows.push(row);
                outcome
            }
            Candidate::Particle => match views {
                Err(_) => Outcome::not_run(0.0),
                Ok((map, images)) => {
                    let start = Instant::now();
                    let fix = localize_panorama(
                        prior,
                        prior_r,
                        map,
                        images,
                        &search,
                        &PanoramaFixSettings::default(),
                        seed,
                    );
                    let time_s = start.elapsed().as_secs_f64();
                    match fix {
                        Ok(PanoramaFix::Accepted(post)) => Outcome {
                            error_m: Some(error_of(post.mean_m)),
                            accepted: true,
                            ran: true,
                            radius_m: Some(post.disc_radius_m),
                            time_s,
                        },
                        Ok(PanoramaFix::Rejected { posterior, .. }) => {
                            Outcome::rejected(posterior.map(|p| error_of(p.mean_m)), time_s)
                        }
                        Err(_) => Outcome::not_run(time_s),
                    }
                }
            },
            Candidate::Ekf => {
                let offset = [prior[0] - truth[0], prior[1] - truth[1]];
                let start = Instant::now();
                let fix = parked_fix(&ParkedSettings::default(), offset, prior_r / 3.0, seed);
                let time_s = start.elapsed().as_secs_f64();
                match fix {
                    Ok(fix) => {
                        let disc = fix.ellipse().map(|e| e.disc_radius_m());
                        Outcome {
                            error_m: Some(fix.error_enu_m[0].hypot(fix.error_enu_m[1])),
                            accepted: disc.is_some_and(|d| d < prior_r),
                            ran: true,
                            radius_m: disc,
                            time_s,
                        }
                    }
                    Err(_) => Outcome::not_run(time_s),
                }
            }
        };
        outcomes.push(outcome);
    }
    (rows, outcomes)
}

/// Run `candidates` on `cases` (in parallel; the rows are the same on any thread count, the
/// times are not). `done(n)` is called as cases finish.
#[must_use]
pub fn compare(
    cases: &[BenchmarkCase],
    maps: &BenchmarkMaps,
    candidates: &[Candidate],
    done: &(dyn Fn(u64) + Sync),
) -> Comparison {
    let finished = std::sync::atomic::AtomicU64::new(0);
    let imaging = BenchmarkImaging::default();
    let per_case: Vec<(Vec<CaseResult>, Vec<Outcome>)> = cases
        .par_iter()
        .map(|case| {
            let r = run_case(case, maps, candidates, &imaging);
            done(finished.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            r
        })
        .collect();
    let mut rows = Vec::new();
    let mut matcher_reports = Vec::new();
    let mut matcher_index = 0;
    for (k, &candidate) in candidates.iter().enumerate() {
        let outcomes: Vec<Outcome> = per_case.iter().map(|(_, o)| o[k]).collect();
        if let Candidate::Matcher(method) = candidate {
            let case_rows = per_case
                .iter()
                .map(|(r, _)| r[matcher_index].clone())
                .collect();
            matcher_index += 1;
            matcher_reports.push((method, report_of(case_rows)));
        }
        let accepted: Vec<f64> = outcomes
            .iter()
            .filter(|o| o.accepted)
            .filter_map(|o| o.error_m)
            .collect();
        let all: Vec<f64> = outcomes.iter().filter_map(|o| o.error_m).collect();
        let could_not_run = outcomes.iter().filter(|o| !o.ran).count();
        let times: Vec<f64> = outcomes.iter().map(|o| o.time_s * 1e3).collect();
        rows.push(ComparisonRow {
            localizer: candidate.name(),
            needs: candidate.needs(),
            cases: cases.len(),
            accepted: ErrorStats::of(&accepted),
            all: ErrorStats::of(&all),
            within_own_radius: outcomes
                .iter()
                .filter(|o| o.accepted)
                .filter(|o| matches!((o.error_m, o.radius_m), (Some(e), Some(r)) if e <= r))
                .count(),
            rejected: outcomes.iter().filter(|o| o.ran && !o.accepted).count(),
            could_not_run,
            mean_ms_per_case: times.iter().sum::<f64>() / times.len().max(1) as f64,
            max_ms_per_case: times.iter().copied().fold(0.0, f64::max),
        });
    }
    Comparison {
        rows,
        matcher_reports,
    }
}

/// One run of the benchmark set: how many cases, from which seeds (`solsim localize-bench`'s
/// options).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BenchmarkRun {
    /// Number of synthetic post-drive panoramas (rocky, plain and dune terrain in thirds).
    pub cases: usize,
    /// Seed of the cases (positions, priors, lighting, wedges, noise).
    pub seed: u64,
    /// Seed of the three procedural benchmark maps.
    pub map_seed: u64,
}

impl BenchmarkRun {
    /// The three procedural benchmark maps and the cases on them, for [`compare`].
    #[must_use]
    pub fn generate(&self) -> (BenchmarkMaps, Vec<BenchmarkCase>) {
        (
            BenchmarkMaps::generate(self.map_seed),
            benchmark_cases(self.cases, self.seed),
        )
    }
}
