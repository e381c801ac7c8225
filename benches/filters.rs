//! Filter benchmarks: one step of the EKF (`localization::ekf`, paper 004) and one measurement
//! update of the particle filter (`localization::particle`, paper 002) with its resampling,
//! reported in BENCHMARKS.md ("Filters: one EKF step and one particle-filter update").
//!
//! # Problem instances (seeded)
//! - **EKF** (`ekf_step`, `ekf_predict`, `ekf_window`): the bias-estimating 8-state filter
//!   `[e, n, v_e, v_n, ψ, b_ax, b_ay, b_g]` with Table 1 case 4 settings, streams of
//!   [`simulate`] seed [`EKF_SEED`]. The filter starts from `filter_streams`' estimate and
//!   covariance one second before the orbiter's first range; a *step* is one second as
//!   `filter_streams` takes it, `predict` (RK4 + `Φ P Φᵀ + Q`) then one `try_update_range`
//!   (the fix that `filter_streams` applies after it is not part of the step). `ekf_step` times
//!   the first second of the pass, `ekf_predict` its `predict` alone, and `ekf_window` all
//!   consecutive seconds with a range (one iteration = the whole window; divide by its length).
//! - **Particle filter** (`pf_update`): case [`CASE_INDEX`] of `localize-bench`'s default set
//!   (`benchmark_cases(264, 2024)` on `BenchmarkMaps::generate(1)`) rendered by `render_case`
//!   with a 30 m search radius and the default imaging; N = 1000 or 5000 particles drawn
//!   (seed [`PF_SEED`]) from `Prior::from_uncertainty_disc(prior, 20 m)` — what
//!   `localize_panorama` starts from — and one `ParticleFilter::update` (census with both
//!   DEMs, default `MatchSettings`) from a clone of that filter per iteration. `score_surface`
//!   alone over the same window shows how much of the update the census scores take.
//! - `pf_resample`: `systematic_indices` of the weights the update leaves when it does not
//!   resample (`resample_threshold` 0), with the fixed pointer offset [`RESAMPLE_U0`].
//! - `pf_reweight`: `update_with_scores` with each particle's bilinear census score from that
//!   surface (`ScoreSurface::score_at`): likelihood `exp(−(s − s_min)/T)`, normalisation,
//!   effective sample size and, when it falls below N/2, systematic resampling from the
//!   weighted particles with roughening — the update without the score surface.
//!
//! # Peer on the same instances
//! With `SOLSIM_FILTERS_DUMP=<dir>` the bench writes what `peers/bench_filters.py` needs:
//! `ekf_window.json` (frame, start state and covariance, Q, R, the window's IMU samples and
//! ranges, and our state and covariance after the window, which the peer must reproduce),
//! `pf_weights_<N>.npy` with `pf_resample_<N>.json` and `pf_indices_<N>.npy` (our indices, which
//! the peers must reproduce), and `pf_particles_<N>.npy`, `pf_scores_<N>.npy` (NaN: no score),
//! `pf_reweight_<N>.json` (our effective sample size after reweighting). The peer runs filterpy
//! 2.0.0's `ExtendedKalmanFilter` and `systematic_resample`, and numpy. `peers/run_peer_benchmarks.sh
//! filters` does both in one job.
//!
//! Threads: the EKF and resampling are sequential; `pf_update` and `score_surface` run inside a
//! `rayon` pool of 1 or 2 threads (`install`), as in `benches/localize.rs`.

mod common;

use std::path::Path;
use std::time::Duration;

use common::write_npy;
use criterion::{BatchSize, BenchmarkId, Criterion, criterion_group, criterion_main};
use localization::benchmark_set::{
    BenchmarkImaging, BenchmarkMaps, PAPER_CASE_COUNT, benchmark_cases, render_case,
};
use localization::ekf::{
    CaseSettings, Ekf, ImuSample, MARS_RADIUS_M, NavigationFrame, RangeMeasurement, STATE_DIM,
    StateCovariance, Table1Case, filter_streams, simulate,
};
use localization::matcher::{MatchSettings, OrbitalMap, RoverImages, score_surface};
use localization::particle::{ParticleFilter, ParticleSettings, Prior, systematic_indices};
use serde_json::{Value, json};

/// Seed of the EKF's drive and sensor streams (the seed `tests/ekf_filterpy.rs` checks).
const EKF_SEED: u64 = 5;
/// Seed of `localize-bench`'s default cases, and of its maps.
const CASE_SEED: u64 = 2024;
const MAP_SEED: u64 = 1;
/// Which case of that set is rendered.
const CASE_INDEX: usize = 0;
/// Search radius the case is rendered for, metres (the matcher's default).
const SEARCH_RADIUS_M: f64 = 30.0;
/// Radius of the prior disc around the case's prior, metres (read as 3σ).
const PRIOR_RADIUS_M: f64 = 20.0;
/// Seed of the particle filter's draws.
const PF_SEED: u64 = 11;
/// Particle counts.
const COUNTS: [usize; 2] = [1000, 5000];
/// The pointer offset of the timed systematic resampling (any value in [0, 1)).
const RESAMPLE_U0: f64 = 0.371_215_6;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("rayon thread pool")
}

fn dump_dir() -> Option<std::path::PathBuf> {
    let dir = std::path::PathBuf::from(std::env::var_os("SOLSIM_FILTERS_DUMP")?);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("creating {}: {e}", dir.display()));
    Some(dir)
}

fn write_json(path: &Path, value: &Value) {
    std::fs::write(path, value.to_string())
        .unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
}

/// A 2-D `float64` array (little-endian) as `.npy`.
fn write_f64_npy(path: &Path, rows: usize, cols: usize, data: &[f64]) {
    let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
    write_npy(path, "<f8", rows, cols, &bytes);
}

// ---------------------------------------------------------------------------------------------
// EKF

/// One second of the filter: IMU samples at its start and end, and its range.
struct Second {
    u0: ImuSample,
    u1: ImuSample,
    range: RangeMeasurement,
}

struct EkfInstance {
    frame: NavigationFrame,
    range_variance_m2: f64,
    /// The process noise `Q` the filter adds per step.
    process_noise: StateCovariance,
    /// The filter one second before the window.
    start: Ekf,
    /// The consecutive seconds with a range, from the first.
    window: Vec<Second>,
}

impl EkfInstance {
    fn new() -> Self {
        let settings = CaseSettings::table1(Table1Case::Case4);
        let sim = simulate(&settings, EKF_SEED).expect("the Table 1 settings are valid");
        let tuning = settings.tuning(&sim.truth[0]);
        let run = filter_streams(&settings.frame, &tuning, &sim.truth, &sim.streams)
            .expect("the Table 1 tuning is valid");
        let ranges = &sim.streams.ranges;
        let first = ranges.first().expect("the orbiter passes").t_s;
        let window: Vec<Second> = ranges
            .iter()
            .zip(first..)
            .take_while(|(r, t)| r.t_s == *t)
            .map(|(r, t)| {
                let (u0, u1) = (sim.streams.imu[t as usize - 1], sim.streams.imu[t as usize]);
                assert_eq!((u0.t_s + 1, u1.t_s), (t, t), "one IMU sample per second");
                Second { u0, u1, range: *r }
            })
            .collect();
        let before = &run.steps[first as usize - 1];
        assert_eq!(before.truth.t_s + 1, first);
        let start = Ekf::new(before.estimate, before.covariance, tuning.process_noise)
            .expect("filter_streams' state is a valid start");
        Self {
            frame: settings.frame,
            range_variance_m2: tuning.range_variance_m2,
            process_noise: tuning.process_noise,
            start,
            window,
        }
    }

    /// `predict` then the range update of `s` (`true` if the update was applied).
    fn step(&self, ekf: &mut Ekf, s: &Second) -> bool {
        ekf.predict(&s.u0, &s.u1, f64::from(s.u1.t_s) - f64::from(s.u0.t_s));
        ekf.try_update_range(
            &self.frame,
            f64::from(s.range.t_s),
            s.range.range_m,
            &s.range.orbiter_position_mci_m,
            self.range_variance_m2,
        )
        .is_some()
    }

    /// The filter after the whole window.
    fn run_window(&self) -> Ekf {
        let mut ekf = self.start.clone();
        for s in &self.window {
            assert!(
                self.step(&mut ekf, s),
                "range update rejected at {}",
                s.range.t_s
            );
        }
        ekf
    }

    fn dump(&self, dir: &Path) {
        let matrix = |m: &StateCovariance| -> Vec<Vec<f64>> {
            (0..STATE_DIM)
                .map(|i| (0..STATE_DIM).map(|j| m[(i, j)]).collect())
                .collect()
        };
        let end = self.run_window();
        let imu = |u: &ImuSample| {
            json!({
                "t_s": u.t_s,
                "accel": u.accel_body_m_per_s2.iter().collect::<Vec<_>>(),
                "yaw_rate": u.yaw_rate_rad_per_s,
            })
        };
        let f = &self.frame;
        let value = json!({
            "case": "Table 1 case 4, bias-estimating",
            "seed": EKF_SEED,
            "frame": {
                "latitude_deg": f.site.latitude_deg,
                "longitude_deg": f.site.longitude_deg,
                "radius_m": MARS_RADIUS_M,
                "rotation_rad_per_s": f.rotation_rad_per_s,
                "prime_meridian_at_epoch_rad": f.prime_meridian_at_epoch_rad,
            },
            "x0": self.start.state().iter().collect::<Vec<_>>(),
            "P0": matrix(self.start.covariance()),
            "Q": matrix(&self.process_noise),
            "range_variance_m2": self.range_variance_m2,
            "steps": self.window.iter().map(|s| json!({
                "u0": imu(&s.u0),
                "u1": imu(&s.u1),
                "t_s": s.range.t_s,
                "range_m": s.range.range_m,
                "orbiter_mci_m": s.range.orbiter_position_mci_m.iter().collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
            "x_end": end.state().iter().collect::<Vec<_>>(),
            "P_end": matrix(end.covariance()),
        });
        write_json(&dir.join("ekf_window.json"), &value);
    }
}

fn bench_ekf(c: &mut Criterion) {
    let inst = EkfInstance::new();
    println!(
        "EKF: window of {} seconds with a range ({}..={} s), Table 1 case 4, seed {EKF_SEED}",
        inst.window.len(),
        inst.window[0].range.t_s,
        inst.window[inst.window.len() - 1].range.t_s
    );
    if let Some(dir) = dump_dir() {
        inst.dump(&dir);
    }
    let first = &inst.window[0];
    let mut g = c.benchmark_group("ekf_step");
    g.warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    g.bench_function("predict_range", |b| {
        b.iter_batched_ref(
            || inst.start.clone(),
            |ekf| inst.step(ekf, first),
            BatchSize::SmallInput,
        );
    });
    g.finish();
    let mut g = c.benchmark_group("ekf_predict");
    g.warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    g.bench_function("predict", |b| {
        b.iter_batched_ref(
            || inst.start.clone(),
            |ekf| ekf.predict(&first.u0, &first.u1, 1.0),
            BatchSize::SmallInput,
        );
    });
    g.finish();
    let mut g = c.benchmark_group("ekf_window");
    g.warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    g.bench_with_input(
        BenchmarkId::new("predict_range", inst.window.len()),
        &inst.window,
        |b, window| {
            b.iter_batched_ref(
                || inst.start.clone(),
                |ekf| window.iter().filter(|s| inst.step(ekf, s)).count(),
                BatchSize::SmallInput,
            );
        },
    );
    g.finish();
}

// ---------------------------------------------------------------------------------------------
// Particle filter

/// Centre and half extent of the score surface `ParticleFilter::update` computes for `pf`
/// (its code, repeated: the particles' bounding box plus the margin, clipped to where the
/// orthomosaic fits on the map); the particles must fit in one tile.
fn update_window(
    pf: &ParticleFilter,
    orbital: &OrbitalMap<'_>,
    rover: &RoverImages<'_>,
) -> ([f64; 2], [f64; 2]) {
    let map = orbital.appearance;
    let res = map.geo.resolution_m_per_px;
    let (x0, y0, x1, y1) = map.extent_m();
    let half_w = rover.ortho.width as f64 * res / 2.0 + 2.0 * res;
    let half_h = rover.ortho.height as f64 * res / 2.0 + 2.0 * res;
    let feasible = [x0 + half_w, y0 + half_h, x1 - half_w, y1 - half_h];
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for (p, w) in pf.positions_m().iter().zip(pf.weights()) {
        let on_map = p[0] >= feasible[0]
            && p[0] <= feasible[2]
            && p[1] >= feasible[1]
            && p[1] <= feasible[3];
        if *w > 0.0 && on_map {
            b = [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ];
        }
    }
    let params = pf.params();
    assert!(
        b[2] - b[0] < 2.0 * params.max_surface_half_extent_m
            && b[3] - b[1] < 2.0 * params.max_surface_half_extent_m,
        "the particles span more than one tile"
    );
    let m = params.surface_margin_m;
    let lo = [(b[0] - m).max(feasible[0]), (b[1] - m).max(feasible[1])];
    let hi = [(b[2] + m).min(feasible[2]), (b[3] + m).min(feasible[3])];
    (
        [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])],
        [0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1])],
    )
}

fn bench_pf(c: &mut Criterion) {
    let maps = BenchmarkMaps::generate(MAP_SEED);
    let cases = benchmark_cases(PAPER_CASE_COUNT, CASE_SEED);
    let case = &cases[CASE_INDEX];
    let (draws, orbital, rover) = render_case(
        case,
        maps.get(case.terrain),
        SEARCH_RADIUS_M,
        &BenchmarkImaging::default(),
    )
    .expect("the benchmark case renders");
    let map = OrbitalMap::of(&orbital);
    let images = RoverImages::of(&rover);
    let match_params = MatchSettings::default();
    let prior = Prior::from_uncertainty_disc(draws.prior_m, PRIOR_RADIUS_M);
    let off = |p: [f64; 2]| (p[0] - draws.truth_m[0]).hypot(p[1] - draws.truth_m[1]);
    println!(
        "PF: case {CASE_INDEX} of benchmark_cases({PAPER_CASE_COUNT}, {CASE_SEED}) ({:?}, {} \
         wedges), map {}x{} px; prior {:.2} m from the truth, disc {PRIOR_RADIUS_M} m",
        case.terrain,
        case.wedges,
        orbital.appearance.width,
        orbital.appearance.height,
        off(draws.prior_m),
    );
    let dir = dump_dir();
    let mut prepared = Vec::new();
    for n in COUNTS {
        let params = ParticleSettings {
            particle_count: n,
            ..ParticleSettings::default()
        };
        let fresh = ParticleFilter::new(&prior, params, PF_SEED).expect("valid prior and params");
        let (center, half) = update_window(&fresh, &map, &images);
        let surface =
            score_surface(&map, &images, center, half, &match_params).expect("the case scores");
        // What one update does, for the report.
        let mut pf = fresh.clone();
        let report = pf.update(&map, &images, &match_params).expect("update");
        let post = pf.posterior();
        println!(
            "PF N = {n}: surface {}x{} offsets ({:.1} x {:.1} m); update: {} surface(s), ESS \
             after reweighting {:.1}, resampled on the grid: {}; posterior mean {:.2} m from \
             the truth, 1σ semi-major {:.2} m",
            surface.width,
            surface.height,
            2.0 * half[0],
            2.0 * half[1],
            report.surfaces,
            report.effective_sample_size,
            report.resampled_on_grid,
            off(post.mean_m),
            post.ellipse.semi_major_m,
        );
        // The weights the update leaves when it does not resample.
        let mut weights_only = ParticleFilter::new(
            &prior,
            ParticleSettings {
                resample_threshold: 0.0,
                ..params
            },
            PF_SEED,
        )
        .expect("valid prior and params");
        let r = weights_only
            .update(&map, &images, &match_params)
            .expect("update");
        assert!(r.skipped.is_none() && !r.resampled, "{r:?}");
        let weights = weights_only.weights().to_vec();
        let indices = systematic_indices(&weights, n, RESAMPLE_U0);
        let scores: Vec<Option<f64>> = fresh
            .positions_m()
            .iter()
            .map(|&p| surface.score_at(p))
            .collect();
        let mut reweighted = fresh.clone();
        let rw = reweighted
            .update_with_scores(&scores)
            .expect("one score each");
        if let Some(dir) = &dir {
            write_f64_npy(&dir.join(format!("pf_weights_{n}.npy")), n, 1, &weights);
            let idx: Vec<u8> = indices
                .iter()
                .flat_map(|&i| (i as i64).to_le_bytes())
                .collect();
            write_npy(&dir.join(format!("pf_indices_{n}.npy")), "<i8", n, 1, &idx);
            write_json(
                &dir.join(format!("pf_resample_{n}.json")),
                &json!({ "n": n, "u0": RESAMPLE_U0 }),
            );
            let flat: Vec<f64> = fresh.positions_m().iter().flatten().copied().collect();
            write_f64_npy(&dir.join(format!("pf_particles_{n}.npy")), n, 2, &flat);
            let s: Vec<f64> = scores.iter().map(|s| s.unwrap_or(f64::NAN)).collect();
            write_f64_npy(&dir.join(format!("pf_scores_{n}.npy")), n, 1, &s);
            write_json(
                &dir.join(format!("pf_reweight_{n}.json")),
                &json!({
                    "n": n,
                    "temperature": params.temperature,
                    "resample_threshold": params.resample_threshold,
                    "roughening_m": params.roughening_m,
                    "effective_sample_size": rw.effective_sample_size,
                    "resampled": rw.resampled,
                    "scored_fraction": rw.scored_fraction,
                }),
            );
        }
        prepared.push((n, fresh, center, half, weights, scores));
    }

    let mut g = c.benchmark_group("pf_update");
    g.sample_size(10).warm_up_time(Duration::from_secs(1));
    for threads in [1, 2] {
        let pool = pool(threads);
        for (n, fresh, center, half, _, _) in &prepared {
            g.bench_with_input(
                BenchmarkId::new(format!("n{n}"), threads),
                &threads,
                |b, _| {
                    b.iter_batched_ref(
                        || fresh.clone(),
                        |pf| {
                            pool.install(|| {
                                pf.update(&map, &images, &match_params).expect("update")
                            })
                        },
                        BatchSize::SmallInput,
                    );
                },
            );
            g.bench_with_input(
                BenchmarkId::new(format!("score_surface_n{n}"), threads),
                &threads,
                |b, _| {
                    b.iter(|| {
                        pool.install(|| {
                            score_surface(&map, &images, *center, *half, &match_params)
                                .expect("surface")
                        })
                    });
                },
            );
        }
    }
    g.finish();

    let mut g = c.benchmark_group("pf_resample");
    g.warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for (n, _, _, _, weights, _) in &prepared {
        g.bench_with_input(
            BenchmarkId::new("systematic_indices", n),
            weights,
            |b, w| b.iter(|| systematic_indices(w, *n, RESAMPLE_U0)),
        );
    }
    g.finish();

    let mut g = c.benchmark_group("pf_reweight");
    g.warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for (n, fresh, _, _, _, scores) in &prepared {
        g.bench_with_input(BenchmarkId::new("update_with_scores", n), scores, |b, s| {
            b.iter_batched_ref(
                || fresh.clone(),
                |pf| pf.update_with_scores(s).expect("one score each"),
                BatchSize::SmallInput,
            );
        });
    }
    g.finish();
}

criterion_group!(benches, bench_ekf, bench_pf);
criterion_main!(benches);
