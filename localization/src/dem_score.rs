//! The DEM term of the matcher (paper 000 §5): the mean-removed mean squared height difference
//! between the rover DEM and the orbital DEM at every integer offset, mapped to `[0, 1)`.
//!
//! At an offset, over the `n` valid rover cells that land on finite map cells, with
//! `d = rover − map`: `msd = Σd²/n − (Σd/n)²` (the unknown vertical offset between the two DEMs
//! is removed with the mean), and the score is `msd / (msd + dem_scale²)`; `+inf` where fewer
//! than a quarter of the valid rover cells overlap finite map cells.
//!
//! # Exactness
//! The sums are accumulated cell by cell in the rover's row-major order, exactly as the plain
//! quadruple loop does (kept as the reference in the tests), so every score is **bit-identical**
//! to it: `localize` results do not change. Algebraic shortcuts (integral images or an FFT of
//! `Σw·r²`, `Σw·r·m`, `Σw·m²`) would reorder the floating-point sums and change the last bits
//! of the scores (and so of `MatchResult`), which the matcher's callers compare bit for bit
//! (redundant runs on the HBS). The speed comes from doing the *same* operations for many offsets
//! at once instead: each SIMD lane is one horizontal offset, all lanes stream the same rover cell
//! against adjacent map cells, and each lane keeps its own sequential sums.
//!
//! # Performance
//! 60² rover cells over a 122² map window (63² offsets, the matcher at flight size), 2-vCPU KVM
//! Xeon, `-C target-cpu=native`: 15.8 ms for the scalar loop, about 2 ms here on one thread. Offset rows run in parallel
//! on the current `rayon` pool; every score is a sequential sum, so the result does not depend
//! on the thread count.

use maps::Raster;
use rayon::prelude::*;

/// Horizontal offsets scored together (SIMD lanes of one pass over the rover cells).
const LANES: usize = 16;

/// Mean-removed DEM misfit at every integer offset of `rover` (template) inside `map`, mapped to
/// `[0, 1)`; `+inf` where fewer than a quarter of the valid rover cells overlap finite map
/// cells. Returns `(offset columns, offset rows, scores)` (row-major).
///
/// A rover cell takes part when `rover_valid` is set and its height is finite; a map cell when
/// its height is finite.
///
/// # Panics
/// If `rover_valid` has fewer entries than the rover DEM, or the rover DEM is larger than `map`.
pub(crate) fn dem_scores(
    rover: &Raster<f32>,
    rover_valid: &[bool],
    map: &Raster<f32>,
    dem_scale_m: f64,
) -> (usize, usize, Vec<f64>) {
    let (ow, oh) = (map.width + 1 - rover.width, map.height + 1 - rover.height);
    // The map in f64 (exact), each row padded to a whole number of lane blocks past the last
    // offset, so every block reads in bounds; the padding lanes are discarded.
    let pw = ow.next_multiple_of(LANES) + rover.width - 1;
    let mut padded = vec![0.0f64; pw * map.height];
    for (dst, src) in padded
        .chunks_exact_mut(pw)
        .zip(map.data.chunks_exact(map.width))
    {
        for (d, &s) in dst.iter_mut().zip(src) {
            *d = f64::from(s);
        }
    }
    // Only valid rover cells take part: (offset of the cell in the padded map, height).
    let cells: Vec<(usize, f64)> = (0..rover.width * rover.height)
        .filter(|&i| rover_valid[i] && rover.data[i].is_finite())
        .map(|i| {
            (
                (i / rover.width) * pw + i % rover.width,
                f64::from(rover.data[i]),
            )
        })
        .collect();
    let all_finite = map.data.iter().all(|v| v.is_finite());
    let (n_valid, scale2) = (cells.len(), dem_scale_m * dem_scale_m);
    let mut out = vec![0.0f64; ow * oh];
    out.par_chunks_mut(ow).enumerate().for_each(|(dy, row)| {
        let map_row = &padded[dy * pw..];
        for (b, chunk) in row.chunks_mut(LANES).enumerate() {
            let m = &map_row[b * LANES..];
            let (n, sd, sdd) = if all_finite {
                sums_dispatch::<false>(&cells, m)
            } else {
                sums_dispatch::<true>(&cells, m)
            };
            for (l, o) in chunk.iter_mut().enumerate() {
                let n = if all_finite { n_valid } else { n[l] as usize };
                *o = if n > 0 && n * 4 >= n_valid {
                    let mean = sd[l] / n as f64;
                    let msd = (sdd[l] / n as f64 - mean * mean).max(0.0);
                    msd / (msd + scale2)
                } else {
                    f64::INFINITY
                };
            }
        }
    });
    (ow, oh, out)
}

/// Per-lane (count, Σd, Σd²) of [`sums`], on the widest SIMD the CPU has (chosen at run time;
/// the operations, and so the results, are the same on every path).
fn sums_dispatch<const CHECK: bool>(
    cells: &[(usize, f64)],
    map: &[f64],
) -> ([u32; LANES], [f64; LANES], [f64; LANES]) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the CPU supports AVX-512F (checked just above).
            return unsafe { sums_avx512::<CHECK>(cells, map) };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above).
            return unsafe { sums_avx2::<CHECK>(cells, map) };
        }
    }
    sums::<CHECK>(cells, map)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn sums_avx512<const CHECK: bool>(
    cells: &[(usize, f64)],
    map: &[f64],
) -> ([u32; LANES], [f64; LANES], [f64; LANES]) {
    sums::<CHECK>(cells, map)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn sums_avx2<const CHECK: bool>(
    cells: &[(usize, f64)],
    map: &[f64],
) -> ([u32; LANES], [f64; LANES], [f64; LANES]) {
    sums::<CHECK>(cells, map)
}

/// For the `LANES` horizontal offsets whose map cells start at `map[0]`: the number of rover
/// cells on finite map cells (`CHECK`; without it the map is known to be finite and the count
/// is left 0), `Σd` and `Σd²` with `d = rover − map`, each lane summed sequentially in the
/// order of `cells` (the reference loop's order, so the sums are bit-identical to it).
#[inline(always)]
fn sums<const CHECK: bool>(
    cells: &[(usize, f64)],
    map: &[f64],
) -> ([u32; LANES], [f64; LANES], [f64; LANES]) {
    let (mut n, mut sd, mut sdd) = ([0u32; LANES], [0.0f64; LANES], [0.0f64; LANES]);
    for &(k, r) in cells {
        let m: &[f64; LANES] = map[k..k + LANES]
            .try_into()
            .expect("slice of LANES elements");
        for l in 0..LANES {
            let d = r - m[l];
            if CHECK {
                // Branch-free, but the same sums as skipping the cell: a skipped lane keeps its
                // value exactly.
                let ok = m[l].is_finite();
                n[l] += u32::from(ok);
                sd[l] = if ok { sd[l] + d } else { sd[l] };
                sdd[l] = if ok { sdd[l] + d * d } else { sdd[l] };
            } else {
                sd[l] += d;
                sdd[l] += d * d;
            }
        }
    }
    (n, sd, sdd)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use maps::GeoTransform;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The reference: the plain loop over offsets and valid rover cells (the matcher's original
    /// `dem_scores`).
    fn dem_scores_reference(
        rover: &Raster<f32>,
        rover_valid: &[bool],
        map: &Raster<f32>,
        dem_scale_m: f64,
    ) -> (usize, usize, Vec<f64>) {
        let (ow, oh) = (map.width + 1 - rover.width, map.height + 1 - rover.height);
        let cells: Vec<(usize, f64)> = (0..rover.width * rover.height)
            .filter(|&i| rover_valid[i] && rover.data[i].is_finite())
            .map(|i| {
                (
                    (i / rover.width) * map.width + i % rover.width,
                    f64::from(rover.data[i]),
                )
            })
            .collect();
        let n_valid = cells.len();
        let scale2 = dem_scale_m * dem_scale_m;
        let mut out = Vec::with_capacity(ow * oh);
        for dy in 0..oh {
            for dx in 0..ow {
                let base = dy * map.width + dx;
                let (mut n, mut sd, mut sdd) = (0usize, 0.0f64, 0.0f64);
                for &(k, r) in &cells {
                    let m = map.data[base + k];
                    if m.is_finite() {
                        let d = r - f64::from(m);
                        n += 1;
                        sd += d;
                        sdd += d * d;
                    }
                }
                out.push(if n > 0 && n * 4 >= n_valid {
                    let mean = sd / n as f64;
                    let msd = (sdd / n as f64 - mean * mean).max(0.0);
                    msd / (msd + scale2)
                } else {
                    f64::INFINITY
                });
            }
        }
        (ow, oh, out)
    }

    /// A seeded random DEM (heights in metres) with `holes` fraction of non-finite cells.
    fn random_dem(w: usize, h: usize, holes: f64, rng: &mut ChaCha8Rng) -> Raster<f32> {
        let mut r = Raster::filled(w, h, GeoTransform::new(0.0, 100.0, 1.0), 0.0f32);
        for v in &mut r.data {
            *v = if rng.random::<f64>() < holes {
                [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][rng.random_range(0..3usize)]
            } else {
                rng.random_range(-20.0f32..20.0)
            };
        }
        r
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    #[test]
    fn bit_identical_to_the_reference_on_random_dems_with_holes() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let sizes = [
            ((1, 1), (1, 1)),
            ((1, 1), (20, 3)),
            ((3, 2), (3, 2)),
            ((5, 4), (21, 17)),
            ((7, 9), (40, 33)),
            ((16, 16), (48, 31)),
            ((17, 5), (50, 20)),
            ((30, 30), (62, 62)),
        ];
        for &((rw, rh), (mw, mh)) in &sizes {
            for (rover_holes, map_holes, invalid) in [
                (0.0, 0.0, 0.0),
                (0.1, 0.0, 0.2),
                (0.0, 0.05, 0.0),
                (0.2, 0.3, 0.3),
            ] {
                let rover = random_dem(rw, rh, rover_holes, &mut rng);
                let map = random_dem(mw, mh, map_holes, &mut rng);
                let valid: Vec<bool> = (0..rw * rh)
                    .map(|_| rng.random::<f64>() >= invalid)
                    .collect();
                let want = dem_scores_reference(&rover, &valid, &map, 0.3);
                let got = dem_scores(&rover, &valid, &map, 0.3);
                assert_eq!((got.0, got.1), (want.0, want.1));
                assert_eq!(
                    bits(&got.2),
                    bits(&want.2),
                    "{rw}×{rh} over {mw}×{mh}, holes {rover_holes}/{map_holes}, invalid {invalid}"
                );
            }
        }
    }

    #[test]
    fn flight_size_is_bit_identical_and_thread_count_independent() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        // A smooth-ish DEM: the true offset gives a near-zero misfit (the hard case for any
        // reordered sum).
        let mut map = random_dem(122, 122, 0.0, &mut rng);
        for v in &mut map.data {
            *v = (*v * 0.05).round() * 0.25;
        }
        let mut rover = Raster::filled(60, 60, map.geo, 0.0f32);
        for y in 0..60 {
            for x in 0..60 {
                rover.data[y * 60 + x] = map.data[(y + 33) * 122 + x + 21] + 3.0;
            }
        }
        let valid = vec![true; 3600];
        let want = dem_scores_reference(&rover, &valid, &map, 0.3);
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| dem_scores(&rover, &valid, &map, 0.3))
        };
        let (one, two) = (run(1), run(2));
        assert_eq!(bits(&one.2), bits(&want.2));
        assert_eq!(bits(&two.2), bits(&want.2));
        let best = (0..one.2.len())
            .min_by(|&a, &b| one.2[a].total_cmp(&one.2[b]))
            .unwrap();
        assert_eq!((best % one.0, best / one.0), (21, 33));
    }
}
