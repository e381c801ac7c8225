//! Grid benchmarks B3 (keep-out growth: exact EDT + threshold) and B4 (A*, 8-connected,
//! corner to corner), reported in BENCHMARKS.md (docs/design.md, "How benchmarks are taken").
//!
//! # Problem instances
//! All grids are square (`n × n`, n = 2000 and 4000) and generated here from fixed seeds:
//! - **Keep-out mask** ([`blob_mask`], seed [`SEED_MASK`]): discs of integer radius uniform in
//!   2..=20 cells, centres uniform over the grid, added until at least 5 % of the cells are
//!   covered (ChaCha8).
//! - **B3**: grow that mask by r = 10 cells (`sim::grid::edt::grow`), and, for comparison with a
//!   two-step peer, `squared_edt` followed by a separate threshold.
//! - **B4 weights** ([`astar_weights`], seed [`SEED_COST`]): cost uniform in [1, 2) per cell,
//!   `f32::INFINITY` on the keep-out mask, except within [`CORNER_CLEAR`] cells (Chebyshev) of
//!   the two corners so that start (0, 0) and goal (n−1, n−1) are free. The bench asserts
//!   that a path exists.
//!
//! # Peers on the same instances
//! With `SOLSIM_GRID_DUMP=<dir>` set, the bench first writes every instance as `.npy` files
//! (`mask_<n>.npy` bool, `grown_<n>_r10.npy` bool = our result, `weights_<n>.npy` float32 with
//! `inf` for blocked) and `astar_<n>.json` (our path cost and expansions) into `<dir>`;
//! `peers/bench_grid.py` loads them, so the peers solve exactly these problems and check their
//! results against ours. `peers/run_peer_benchmarks.sh` does both in one job.
//!
//! Threads: 1-thread figures run inside a `rayon` pool with `num_threads(1)` (`install`), the
//! 2-thread ones in a pool of 2.

mod common;

use common::write_npy;
use std::path::Path;
use std::time::Duration;

use criterion::{
    BenchmarkId, Criterion, SamplingMode, Throughput, criterion_group, criterion_main,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sim::grid::astar::AStar;
use sim::grid::edt;

/// Grid sizes (cells per side).
const SIZES: [usize; 2] = [2000, 4000];
/// Fraction of cells covered by keep-out blobs.
const BLOB_FRACTION: f64 = 0.05;
/// Keep-out growth radius of B3, cells.
const GROW_RADIUS_CELLS: f32 = 10.0;
/// Seed of the keep-out blobs.
const SEED_MASK: u64 = 1;
/// Seed of the A* cost field.
const SEED_COST: u64 = 2;
/// Cells (Chebyshev distance) around start and goal kept free of blobs in B4.
const CORNER_CLEAR: usize = 25;

/// Seeded random discs (radius 2..=20 cells) until `fraction` of the cells are covered.
fn blob_mask(width: usize, height: usize, seed: u64, fraction: f64) -> Vec<bool> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut mask = vec![false; width * height];
    let target = (fraction * (width * height) as f64).ceil() as usize;
    let mut covered = 0;
    while covered < target {
        let cx = rng.random_range(0..width) as i64;
        let cy = rng.random_range(0..height) as i64;
        let r: i64 = rng.random_range(2..=20);
        for y in (cy - r).max(0)..=(cy + r).min(height as i64 - 1) {
            for x in (cx - r).max(0)..=(cx + r).min(width as i64 - 1) {
                let i = y as usize * width + x as usize;
                if (x - cx).pow(2) + (y - cy).pow(2) <= r * r && !mask[i] {
                    mask[i] = true;
                    covered += 1;
                }
            }
        }
    }
    mask
}

/// B4 cost field: uniform [1, 2), blocked (`inf`) on `mask` except near the two corners.
fn astar_weights(n: usize, mask: &[bool], seed: u64) -> Vec<f32> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n * n)
        .map(|i| {
            let cost = rng.random_range(1.0_f32..2.0);
            let (r, c) = (i / n, i % n);
            let near_corner = (r < CORNER_CLEAR && c < CORNER_CLEAR)
                || (r >= n - CORNER_CLEAR && c >= n - CORNER_CLEAR);
            if mask[i] && !near_corner {
                f32::INFINITY
            } else {
                cost
            }
        })
        .collect()
}

fn bools(v: &[bool]) -> Vec<u8> {
    v.iter().map(|&b| u8::from(b)).collect()
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("rayon thread pool")
}

/// The grids of one size, and our results on them.
struct Instance {
    n: usize,
    mask: Vec<bool>,
    weights: Vec<f32>,
}

fn instance(n: usize) -> Instance {
    let mask = blob_mask(n, n, SEED_MASK, BLOB_FRACTION);
    let weights = astar_weights(n, &mask, SEED_COST);
    Instance { n, mask, weights }
}

/// Dumps the instance and our results for the Python peers.
fn dump(dir: &Path, inst: &Instance) {
    let n = inst.n;
    std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("creating {}: {e}", dir.display()));
    let grown = edt::grow(&inst.mask, n, n, GROW_RADIUS_CELLS);
    write_npy(
        &dir.join(format!("mask_{n}.npy")),
        "|b1",
        n,
        n,
        &bools(&inst.mask),
    );
    write_npy(
        &dir.join(format!("grown_{n}_r10.npy")),
        "|b1",
        n,
        n,
        &bools(&grown),
    );
    let w: Vec<u8> = inst.weights.iter().flat_map(|x| x.to_le_bytes()).collect();
    write_npy(&dir.join(format!("weights_{n}.npy")), "<f4", n, n, &w);
    let mut astar = AStar::new(n, n);
    let path = astar
        .plan(0, n * n - 1, 1.0, |i| inst.weights[i])
        .expect("B4 instance has a path");
    let json = format!(
        "{{\"n\": {n}, \"start\": [0, 0], \"goal\": [{g}, {g}], \"cost\": {:.9}, \
         \"expansions\": {}, \"path_cells\": {}, \"blocked_cells\": {}, \"grown_cells\": {}}}\n",
        path.cost,
        astar.expansions(),
        path.cells.len(),
        inst.mask.iter().filter(|&&b| b).count(),
        grown.iter().filter(|&&b| b).count(),
        g = n - 1,
    );
    std::fs::write(dir.join(format!("astar_{n}.json")), json).expect("writing astar json");
}

fn benches(c: &mut Criterion) {
    let instances: Vec<Instance> = SIZES.iter().map(|&n| instance(n)).collect();
    if let Some(dir) = std::env::var_os("SOLSIM_GRID_DUMP") {
        for inst in &instances {
            dump(Path::new(&dir), inst);
        }
    }
    let pools = [(1, pool(1)), (2, pool(2))];

    let mut b3 = c.benchmark_group("B3_keepout");
    b3.sampling_mode(SamplingMode::Flat)
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    for inst in &instances {
        let n = inst.n;
        b3.throughput(Throughput::Elements((n * n) as u64));
        for (threads, pool) in &pools {
            b3.bench_with_input(
                BenchmarkId::new(format!("grow_r10_{threads}thr"), n),
                inst,
                |b, inst| {
                    b.iter(|| pool.install(|| edt::grow(&inst.mask, n, n, GROW_RADIUS_CELLS)));
                },
            );
            b3.bench_with_input(
                BenchmarkId::new(format!("edt_then_threshold_{threads}thr"), n),
                inst,
                |b, inst| {
                    b.iter(|| {
                        pool.install(|| {
                            let d2 = edt::squared_edt(&inst.mask, n, n);
                            let r2 = GROW_RADIUS_CELLS * GROW_RADIUS_CELLS;
                            d2.iter().map(|&d| d <= r2).collect::<Vec<bool>>()
                        })
                    });
                },
            );
        }
    }
    b3.finish();

    let mut b4 = c.benchmark_group("B4_astar");
    b4.sampling_mode(SamplingMode::Flat)
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(8));
    for inst in &instances {
        let n = inst.n;
        let mut astar = AStar::new(n, n);
        // Throughput = expansions, so criterion reports expansions/s.
        let found = astar.plan(0, n * n - 1, 1.0, |i| inst.weights[i]);
        assert!(found.is_some(), "B4 instance {n}² has no path");
        b4.throughput(Throughput::Elements(astar.expansions() as u64));
        b4.bench_with_input(BenchmarkId::new("corner_to_corner", n), inst, |b, inst| {
            b.iter(|| astar.plan(0, n * n - 1, 1.0, |i| inst.weights[i]));
        });
    }
    b4.finish();
}

criterion_group!(grid, benches);
criterion_main!(grid);
