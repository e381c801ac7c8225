//! Localization benchmarks B1 (exact masked census Hamming scores at every offset) and B2 (one
//! full `localization::matcher::localize` call), reported in BENCHMARKS.md
//! (docs/design.md, "How benchmarks are taken") ("Localization: exact census scores").
//!
//! # Problem instances (flight size, seeded)
//! - **B1**: a 480² map of uniform random bytes (ChaCha8, seed [`SEED_B1`]), all valid; the
//!   template is its 240² patch at column [`PLANT`].0, row [`PLANT`].1 with 5 % of the pixels
//!   invalid at random and a rear-occlusion wedge (a 108° = 30 % sector centred on south, about
//!   the template centre) invalid too. Both are census-transformed; 241² = 58,081 offsets are
//!   scored by the packed brute-force kernel (`hamming_scores`) and by the bit-plane FFT
//!   (`hamming_scores_fft`); the bench asserts both are identical and the planted offset scores 0.
//! - **B2**: an 800² orbital appearance at 0.25 m (smooth seeded texture, as in the matcher
//!   tests) with a 200² orbital DEM at 1 m; the rover orthomosaic is the 240² patch around the
//!   truth through a different monotonic camera response, with the same 5 % + wedge invalidity,
//!   and the rover DEM its 60² patch (+3 m vertical offset). The prior is 11.5 m east and
//!   7.25 m south of the truth; the 30 m search radius gives a 480² appearance window and a
//!   122² DEM window (60² + 2·30 + 2 margin cells). The bench asserts the offset error < 0.1 px.
//!
//! # Peer on the same instance
//! With `SOLSIM_CENSUS_DUMP=<dir>`, the B1 census images are written as `.npy` (`uint8`:
//! `template_codes`, `template_valid`, `map_codes`, `map_valid`) with `census_checksum.json`
//! (sum of mismatch and valid counts over all offsets); `peers/bench_census.py` solves the same
//! instance and checks its sums; it also times the whole B2 peer pipeline (numpy census
//! transforms, 24 × cv2 `TM_CCORR`, cv2 masked `TM_SQDIFF` DEM term, argmin and sub-pixel fit) on
//! seeded inputs of B2's sizes. `peers/run_peer_benchmarks.sh census` does both in one job.
//!
//! Threads: each figure runs inside a `rayon` pool of 1 or 2 threads (`install`).

mod common;

use common::write_npy;
use std::path::Path;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use localization::census::{CensusImage, census_transform, hamming_scores, hamming_scores_fft};
use localization::matcher::{MatchSettings, OrbitalMap, RoverImages, localize};
use localization::synthetic::sinusoid_texture;
use maps::{GeoTransform, Raster};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Template side, pixels.
const T: usize = 240;
/// Map side, pixels (±120 px of search).
const M: usize = 480;
/// Seed of the B1 images and of every invalidity mask.
const SEED_B1: u64 = 2026;
/// Where the B1 template is cut from the map (column, row) = the true offset.
const PLANT: (usize, usize) = (137, 94);
/// Fraction of template pixels invalid at random.
const INVALID: f64 = 0.05;
/// Fraction of the full circle covered by the rear wedge.
const WEDGE: f64 = 0.30;

/// Seeded validity of a `T × T` template: 5 % random holes plus the rear wedge.
fn template_validity(seed: u64) -> Vec<bool> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let c = (T as f64 - 1.0) / 2.0;
    (0..T * T)
        .map(|i| {
            let hole = rng.random::<f64>() < INVALID;
            let (x, y) = ((i % T) as f64 - c, (i / T) as f64 - c);
            // Angle from "south" (+row direction), in turns; the wedge is |angle| < WEDGE / 2.
            let turns = x.atan2(y).abs() / std::f64::consts::TAU;
            let wedge = turns < WEDGE / 2.0 && (x != 0.0 || y != 0.0);
            !(hole || wedge)
        })
        .collect()
}

/// The B1 instance: (template census, map census).
fn b1_instance() -> (CensusImage, CensusImage) {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED_B1);
    let map: Vec<u8> = (0..M * M).map(|_| rng.random()).collect();
    let patch: Vec<u8> = (0..T * T)
        .map(|i| map[(PLANT.1 + i / T) * M + PLANT.0 + i % T])
        .collect();
    let template = census_transform(&patch, &template_validity(SEED_B1 + 1), T, T);
    let map = census_transform(&map, &vec![true; M * M], M, M);
    (template, map)
}

fn dump(dir: &Path, template: &CensusImage, map: &CensusImage, sums: (u64, u64)) {
    std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("creating {}: {e}", dir.display()));
    for (name, img) in [("template", template), ("map", map)] {
        let (w, h) = (img.width, img.height);
        write_npy(
            &dir.join(format!("{name}_codes.npy")),
            "|u1",
            h,
            w,
            &img.codes,
        );
        write_npy(
            &dir.join(format!("{name}_valid.npy")),
            "|u1",
            h,
            w,
            &img.valid,
        );
    }
    let json = format!(
        "{{\"offsets\": [{}, {}], \"mismatch_sum\": {}, \"valid_sum\": {}, \"plant\": [{}, {}]}}\n",
        map.width - template.width + 1,
        map.height - template.height + 1,
        sums.0,
        sums.1,
        PLANT.0,
        PLANT.1
    );
    let path = dir.join("census_checksum.json");
    std::fs::write(&path, json).unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("rayon thread pool")
}

fn bench_b1(c: &mut Criterion) {
    let (template, map) = b1_instance();
    let brute = hamming_scores(&template, &map).expect("B1 brute force");
    let fft = hamming_scores_fft(&template, &map).expect("B1 FFT");
    assert_eq!(brute, fft, "B1: FFT and brute force disagree");
    assert_eq!(
        brute.best_offset(1),
        Some(PLANT),
        "B1: planted offset not found"
    );
    let sums = (
        brute.mismatch.iter().map(|&v| u64::from(v)).sum::<u64>(),
        brute.valid.iter().map(|&v| u64::from(v)).sum::<u64>(),
    );
    println!(
        "B1 checksum: mismatch_sum = {}, valid_sum = {}",
        sums.0, sums.1
    );
    if let Some(dir) = std::env::var_os("SOLSIM_CENSUS_DUMP") {
        dump(Path::new(&dir), &template, &map, sums);
    }
    let mut g = c.benchmark_group("census_b1");
    g.sample_size(10).warm_up_time(Duration::from_secs(1));
    for threads in [1, 2] {
        let pool = pool(threads);
        g.bench_with_input(BenchmarkId::new("brute", threads), &threads, |b, _| {
            b.iter(|| pool.install(|| hamming_scores(&template, &map).expect("brute")));
        });
        g.bench_with_input(BenchmarkId::new("fft", threads), &threads, |b, _| {
            b.iter(|| pool.install(|| hamming_scores_fft(&template, &map).expect("fft")));
        });
    }
    g.finish();
}

fn bench_b2(c: &mut Criterion) {
    let geo = GeoTransform::new(0.0, 200.0, 0.25);
    let map = sinusoid_texture(800, 800, geo, 11);
    let dem_u8 = sinusoid_texture(200, 200, GeoTransform::new(0.0, 200.0, 1.0), 12);
    let dem = Raster {
        data: dem_u8.data.iter().map(|&v| f32::from(v) / 20.0).collect(),
        width: dem_u8.width,
        height: dem_u8.height,
        geo: dem_u8.geo,
    };
    let truth = [100.0, 90.0];
    let (tc, tr) = map.geo.pixel_of(truth[0], truth[1]);
    let mut ortho = map
        .try_crop(tc as usize - T / 2, tr as usize - T / 2, T, T)
        .expect("B2 template on the map");
    for v in &mut ortho.data {
        *v = (f64::from(*v).powf(0.8) * 2.0).min(255.0) as u8;
    }
    let valid = template_validity(SEED_B1 + 2);
    let (dc, dr) = dem.geo.pixel_of(truth[0], truth[1]);
    let mut rdem = dem
        .try_crop(dc as usize - 30, dr as usize - 30, 60, 60)
        .expect("B2 rover DEM on the map");
    for v in &mut rdem.data {
        *v += 3.0;
    }
    let dvalid = vec![true; 60 * 60];
    let rover = RoverImages {
        ortho: &ortho,
        ortho_valid: &valid,
        dem: Some((&rdem, &dvalid)),
    };
    let orbital = OrbitalMap {
        appearance: &map,
        dem: Some(&dem),
    };
    let prior = [truth[0] + 11.5, truth[1] - 7.25];
    let params = MatchSettings::default();
    let m = localize(&orbital, &rover, prior, &params).expect("B2 localize");
    let err_px = (m.position_m[0] - truth[0]).hypot(m.position_m[1] - truth[1]) / 0.25;
    println!(
        "B2: offset error {err_px:.4} px, rejection {:?}",
        m.rejection
    );
    assert!(err_px < 0.1 && m.rejection.is_none(), "B2: {m:?}");
    let mut g = c.benchmark_group("localize_b2");
    g.sample_size(10).warm_up_time(Duration::from_secs(1));
    for threads in [1, 2] {
        let pool = pool(threads);
        g.bench_with_input(BenchmarkId::new("localize", threads), &threads, |b, _| {
            b.iter(|| pool.install(|| localize(&orbital, &rover, prior, &params).expect("B2")));
        });
    }
    g.finish();
}

criterion_group!(benches, bench_b1, bench_b2);
criterion_main!(benches);
