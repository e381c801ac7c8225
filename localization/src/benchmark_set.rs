//! A synthetic stand-in for the paper's benchmark of 264 post-drive panoramas (paper 000 §4):
//! seeded cases over rocky, plain and dune terrain, 3–5 stereo wedges and a spread of lighting
//! differences from the orbital image, each rendered with every error source of
//! [`crate::synthetic`], localized from a prior up to ~20 m off, and scored.
//!
//! - [`benchmark_cases`] draws the cases (`n`, seed); the paper's set has [`PAPER_CASE_COUNT`].
//! - [`BenchmarkMaps::generate`] makes the three procedural terrain maps in memory
//!   ([`terrain_settings`] defines them).
//! - [`run_benchmark`] renders and localizes every case (rayon over cases; the results are
//!   collected in case order and the statistics computed sequentially, so the report does not
//!   depend on the thread count) and returns a [`BenchmarkReport`].
//!
//! ```no_run
//! use localization::benchmark_set::{BenchmarkMaps, benchmark_cases, run_benchmark};
//! use localization::matcher::MatchSettings;
//!
//! let maps = BenchmarkMaps::generate(1);
//! let cases = benchmark_cases(24, 7);
//! let report = run_benchmark(&cases, |k| maps.get(k), &MatchSettings::default());
//! println!("mean error {:.2} m", report.all.mean_m);
//! ```

use crate::synthetic::{OrbitalProducts, RoverObservation, SyntheticError};
use maps::procedural::{DuneField, TerrainSettings, generate};
use maps::{GeoTransform, MapLayers};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

mod report;

pub use report::{BenchmarkReport, CaseResult, ErrorStats, report_of};

use crate::matcher::{MatchSettings, OrbitalMap, RoverImages, localize};
use crate::synthetic::{
    ORTHO_RESOLUTION_M_PER_PX, ORTHO_SIZE_PX, OrbitalSettings, RoverImagingSettings,
    render_orbital, render_rover, truth_patch,
};

/// Panoramas in the paper's benchmark (paper 000 §4).
pub const PAPER_CASE_COUNT: usize = 264;
/// Side of each procedural benchmark map, metres (1 m pixels).
pub const MAP_SIZE_M: usize = 600;
/// Largest distance of the prior from the true position, metres.
pub const MAX_PRIOR_OFFSET_M: f64 = 20.0;
/// True positions are drawn at least this far from the map edge, metres: room for the prior
/// offset, the search radius, half the orthomosaic and the patch margin.
const POSITION_MARGIN_M: f64 = 140.0;
/// Extra truth patch beyond the search window, metres (shadows cast from outside the patch
/// are missing, so keep them out of the window).
pub(crate) const PATCH_MARGIN_M: f64 = 4.0;

/// The terrain type of a benchmark case (paper 000 Fig. 8: rocky, plains, dunes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TerrainKind {
    /// Mostly bedrock with craters: rich texture, many rocks.
    Rocky,
    /// Mostly soil: weaker texture, few rocks.
    Plain,
    /// Large bedform (dune / megaripple) fields: loose sand with wavy, forking ripples on the
    /// bedforms, coarse lag, scattered rocks and bedrock in the troughs between them; the
    /// hardest class (least texture, repetitive, sand that moves between epochs).
    Dunes,
}

impl TerrainKind {
    /// Every kind, in order.
    pub const ALL: [TerrainKind; 3] = [TerrainKind::Rocky, TerrainKind::Plain, TerrainKind::Dunes];

    /// `rocky`, `plain` or `dunes`, as printed and serialised.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            TerrainKind::Rocky => "rocky",
            TerrainKind::Plain => "plain",
            TerrainKind::Dunes => "dunes",
        }
    }
}

/// The generator settings of the procedural map of `kind` ([`MAP_SIZE_M`] square, 1 m
/// pixels, x and y in `0..MAP_SIZE_M`).
#[must_use]
pub fn terrain_settings(kind: TerrainKind, seed: u64) -> TerrainSettings {
    let size = MAP_SIZE_M;
    let base = TerrainSettings {
        seed,
        width_px: size,
        height_px: size,
        geo: GeoTransform::new(0.0, size as f64, 1.0),
        ..TerrainSettings::default()
    };
    let half = size as f64 / 2.0;
    match kind {
        TerrainKind::Rocky => TerrainSettings {
            bedrock_fraction: 0.7,
            sand_fraction: 0.05,
            crater_density_per_km2: 25.0,
            crater_radius_min_m: 3.0,
            crater_radius_max_m: 40.0,
            ridge_count: 4,
            ..base
        },
        TerrainKind::Plain => TerrainSettings {
            bedrock_fraction: 0.05,
            sand_fraction: 0.05,
            relief_m: 5.0,
            crater_density_per_km2: 2.0,
            ridge_count: 0,
            ..base
        },
        // Bedform fields like those Perseverance drove past (Séítah; the Kerrlaguna and
        // Honeyguide megaripple fields): large bedforms about 1–2 m tall (NASA Perseverance
        // mission updates, 2025: megaripples ~1 m, Hazyview up to ~2 m), here a main field of
        // 20 m spacing and 2 m crest to trough whose crests run 30° east of north, crossed in
        // the north-west by a smaller set (12 m, 0.8 m, crests at 75°) and in the south-east by
        // another (15 m, 1 m, crests at 345°), so orientation and spacing vary over the map and
        // crests interfere where fields overlap. The spacings, heights and azimuths are a
        // judgement. The troughs between them are armoured lag and bedrock, not sand (see
        // `synthetic::truth`); the decimetre ripples on the loose sand come from the truth patch.
        TerrainKind::Dunes => TerrainSettings {
            dune_fields: vec![
                DuneField {
                    center_m: [half, half],
                    radius_m: 1.5 * half,
                    wavelength_m: 20.0,
                    amplitude_m: 1.0,
                    crest_azimuth_deg: 30.0,
                },
                DuneField {
                    center_m: [0.3 * size as f64, 0.7 * size as f64],
                    radius_m: 0.45 * size as f64,
                    wavelength_m: 12.0,
                    amplitude_m: 0.4,
                    crest_azimuth_deg: 75.0,
                },
                DuneField {
                    center_m: [0.72 * size as f64, 0.3 * size as f64],
                    radius_m: 0.4 * size as f64,
                    wavelength_m: 15.0,
                    amplitude_m: 0.5,
                    crest_azimuth_deg: 345.0,
                },
            ],
            sand_fraction: 0.6,
            bedrock_fraction: 0.05,
            crater_density_per_km2: 0.5,
            ridge_count: 0,
            ..base
        },
    }
}

/// The three benchmark maps, generated once.
#[derive(Clone, Debug)]
pub struct BenchmarkMaps {
    /// Map of [`TerrainKind::Rocky`].
    pub rocky: MapLayers,
    /// Map of [`TerrainKind::Plain`].
    pub plain: MapLayers,
    /// Map of [`TerrainKind::Dunes`].
    pub dunes: MapLayers,
}

impl BenchmarkMaps {
    /// Generates the three maps of [`terrain_settings`] from `seed` (about a second in release).
    #[must_use]
    pub fn generate(seed: u64) -> Self {
        Self {
            rocky: generate(&terrain_settings(TerrainKind::Rocky, seed)),
            plain: generate(&terrain_settings(TerrainKind::Plain, seed.wrapping_add(1))),
            dunes: generate(&terrain_settings(TerrainKind::Dunes, seed.wrapping_add(2))),
        }
    }

    /// The map of `kind`.
    #[must_use]
    pub fn get(&self, kind: TerrainKind) -> &MapLayers {
        match kind {
            TerrainKind::Rocky => &self.rocky,
            TerrainKind::Plain => &self.plain,
            TerrainKind::Dunes => &self.dunes,
        }
    }
}

/// How the rover's sun differs from the orbital image's mid-afternoon sun.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
pub enum LightingKind {
    /// Post-drive, mid-afternoon like the orbital image (the usual case, paper 000 §4).
    Afternoon,
    /// Late afternoon: lower sun, longer shadows.
    LateAfternoon,
    /// Mid-drive, late morning: the sun on the other side, shadows reversed.
    LateMorning,
}

/// One benchmark panorama.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BenchmarkCase {
    /// Index in the set.
    pub id: usize,
    /// Terrain type (which benchmark map).
    pub terrain: TerrainKind,
    /// Stereo wedges in the panorama, 3..=5.
    pub wedges: u8,
    /// Class of the lighting difference.
    pub lighting: LightingKind,
    /// The rover's sun azimuth, degrees clockwise from north (the orbital sun is at
    /// [`OrbitalSettings::default`]'s 250°).
    pub sun_azimuth_deg: f64,
    /// The rover's sun elevation, degrees (the orbital sun is at 35°).
    pub sun_elevation_deg: f64,
    /// Seed of everything else: position, prior offset, truth, orbital and rover renders.
    pub seed: u64,
}

/// `n` benchmark cases drawn from `seed` (the paper's set has [`PAPER_CASE_COUNT`]).
///
/// Terrain cycles rocky, plain, dunes (a third each); wedges are 5 in half the cases, 4 and 3 in
/// a quarter each (Perseverance usually takes five, sometimes three or four, paper 000 §4);
/// lighting is mid-afternoon like the orbital image in 60 % (sun azimuth 230–290°, elevation
/// 25–45°), late afternoon in 25 % (260–300°, 10–22°) and late morning in 15 % (60–120°,
/// 30–50°). These shares are a judgement: the paper says most panoramas are post-drive
/// afternoon and some mid-drive late morning, without numbers.
#[must_use]
pub fn benchmark_cases(n: usize, seed: u64) -> Vec<BenchmarkCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|id| {
            let terrain = TerrainKind::ALL[id % 3];
            let u: f64 = rng.random();
            let wedges = if u < 0.5 {
                5
            } else if u < 0.75 {
                4
            } else {
                3
            };
            let l: f64 = rng.random();
            let (lighting, az, el) = if l < 0.6 {
                (LightingKind::Afternoon, [230.0, 290.0], [25.0, 45.0])
            } else if l < 0.85 {
                (LightingKind::LateAfternoon, [260.0, 300.0], [10.0, 22.0])
            } else {
                (LightingKind::LateMorning, [60.0, 120.0], [30.0, 50.0])
            };
            let mut draw = |[lo, hi]: [f64; 2]| lo + (hi - lo) * rng.random::<f64>();
            let sun_azimuth_deg = draw(az);
            let sun_elevation_deg = draw(el);
            BenchmarkCase {
                id,
                terrain,
                wedges,
                lighting,
                sun_azimuth_deg,
                sun_elevation_deg,
                seed: rng.random(),
            }
        })
        .collect()
}

/// Renders and localizes every case against `layers_for(case.terrain)` with `params` and the
/// default imaging settings ([`OrbitalSettings::default`], [`RoverImagingSettings::default`] with
/// the case's wedges and sun).
///
/// Per case, from its seed: a true position uniform over the map at least 140 m from its
/// edge, a prior offset uniform in direction with a length uniform in 0..[`MAX_PRIOR_OFFSET_M`];
/// a truth patch centred on the prior covering the search window (prior ± search radius ±
/// half the orthomosaic ± 4 m); the orbital products of it; the rover observation at the
/// true position; [`localize`] with both DEMs. The error is the distance of the estimate from
/// the true position. Cases run in parallel; rows come back in case order and the statistics
/// are computed sequentially from them, so the report is the same on any thread count.
pub fn run_benchmark<'a, F>(
    cases: &[BenchmarkCase],
    layers_for: F,
    params: &MatchSettings,
) -> BenchmarkReport
where
    F: Fn(TerrainKind) -> &'a MapLayers + Sync,
{
    run_benchmark_with(cases, layers_for, params, &BenchmarkImaging::default())
}

/// The imaging settings of a benchmark run: the defaults, or any error source switched off or
/// scaled for an ablation. The rover's `wedge_count` and sun ranges are overridden per case.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct BenchmarkImaging {
    /// Orbital products settings.
    pub orbital: OrbitalSettings,
    /// Rover imaging settings (wedges and sun taken from each case).
    pub rover: RoverImagingSettings,
}

/// [`run_benchmark`] with explicit imaging settings.
pub fn run_benchmark_with<'a, F>(
    cases: &[BenchmarkCase],
    layers_for: F,
    params: &MatchSettings,
    imaging: &BenchmarkImaging,
) -> BenchmarkReport
where
    F: Fn(TerrainKind) -> &'a MapLayers + Sync,
{
    run_benchmark_reporting(cases, layers_for, params, imaging, &|_| {})
}

/// [`run_benchmark_with`], calling `done(n)` as cases finish (`n` of them so far, from any
/// thread, in no particular order): for a progress bar.
pub fn run_benchmark_reporting<'a, F>(
    cases: &[BenchmarkCase],
    layers_for: F,
    params: &MatchSettings,
    imaging: &BenchmarkImaging,
    done: &(dyn Fn(u64) + Sync),
) -> BenchmarkReport
where
    F: Fn(TerrainKind) -> &'a MapLayers + Sync,
{
    let finished = std::sync::atomic::AtomicU64::new(0);
    let rows: Vec<CaseResult> = cases
        .par_iter()
        .map(|case| {
            let row = run_case(case, layers_for(case.terrain), params, imaging);
            done(finished.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            row
        })
        .collect();
    report_of(rows)
}

/// What a benchmark case draws from its seed, in this order: the true position (at least
/// 140 m inside the map), the prior (up to [`MAX_PRIOR_OFFSET_M`] from it in a uniform
/// direction), and the seeds of the truth patch, the orbital and the rover rendering.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CaseDraws {
    /// True rover position, map metres.
    pub truth_m: [f64; 2],
    /// The prior the matcher starts from, map metres.
    pub prior_m: [f64; 2],
    /// Seed of the truth patch.
    pub truth_seed: u64,
    /// Seed of the orbital rendering.
    pub orbital_seed: u64,
    /// Seed of the rover rendering.
    pub rover_seed: u64,
}

/// The draws of `case` on its terrain's `layers` (what [`run_benchmark`] renders and scores).
#[must_use]
pub fn case_draws(case: &BenchmarkCase, layers: &MapLayers) -> CaseDraws {
    let mut rng = ChaCha8Rng::seed_from_u64(case.seed);
    let (x0, y0, x1, y1) = layers.dem.extent_m();
    let (lo_x, hi_x) = (
        x0.min(x1) + POSITION_MARGIN_M,
        x0.max(x1) - POSITION_MARGIN_M,
    );
    let (lo_y, hi_y) = (
        y0.min(y1) + POSITION_MARGIN_M,
        y0.max(y1) - POSITION_MARGIN_M,
    );
    let truth_m = [
        lo_x + (hi_x - lo_x).max(0.0) * rng.random::<f64>(),
        lo_y + (hi_y - lo_y).max(0.0) * rng.random::<f64>(),
    ];
    let angle = std::f64::consts::TAU * rng.random::<f64>();
    let dist = MAX_PRIOR_OFFSET_M * rng.random::<f64>();
    let prior_m = [
        truth_m[0] + dist * angle.cos(),
        truth_m[1] + dist * angle.sin(),
    ];
    let (truth_seed, orbital_seed, rover_seed): (u64, u64, u64) =
        (rng.random(), rng.random(), rng.random());
    CaseDraws {
        truth_m,
        prior_m,
        truth_seed,
        orbital_seed,
        rover_seed,
    }
}

/// One case: render, localize, score.
/// Render `case` on its terrain's `layers` as [`run_benchmark`] does: its [`case_draws`], the
/// truth patch centred on the prior covering a search window of `search_radius_m` (± half the
/// orthomosaic ± a 4 m margin), its orbital products and the rover's observation at the
/// true position with the case's wedges and sun.
///
/// # Errors
/// [`SyntheticError`] if the patch or the observation cannot be rendered.
pub fn render_case(
    case: &BenchmarkCase,
    layers: &MapLayers,
    search_radius_m: f64,
    imaging: &BenchmarkImaging,
) -> Result<(CaseDraws, OrbitalProducts, RoverObservation), SyntheticError> {
    let draws = case_draws(case, layers);
    let half_ortho_m = 0.5 * ORTHO_SIZE_PX as f64 * ORTHO_RESOLUTION_M_PER_PX;
    let half_size_m = search_radius_m + half_ortho_m + PATCH_MARGIN_M;
    let rover_settings = RoverImagingSettings {
        wedge_count: usize::from(case.wedges),
        sun_azimuth_range_deg: [case.sun_azimuth_deg; 2],
        sun_elevation_range_deg: [case.sun_elevation_deg; 2],
        ..imaging.rover
    };
    let patch = truth_patch(layers, draws.prior_m, half_size_m, draws.truth_seed)?;
    let orbital = render_orbital(&patch, &imaging.orbital, draws.orbital_seed)?;
    let rover = render_rover(&patch, draws.truth_m, &rover_settings, draws.rover_seed)?;
    Ok((draws, orbital, rover))
}

/// Render and localize one case (one row of [`run_benchmark_with`]).
#[must_use]
pub fn run_case(
    case: &BenchmarkCase,
    layers: &MapLayers,
    params: &MatchSettings,
    imaging: &BenchmarkImaging,
) -> CaseResult {
    let CaseDraws {
        truth_m, prior_m, ..
    } = case_draws(case, layers);
    let mut row = CaseResult::pending(case, truth_m, prior_m);
    let (orbital, rover) = match render_case(case, layers, params.search_radius_m, imaging) {
        Ok((_, orbital, rover)) => (orbital, rover),
        Err(e) => {
            row.failure = Some(e.to_string());
            return row;
        }
    };
    row.heading_error_deg = Some(rover.geometry_errors.heading_error_deg);
    let map = OrbitalMap::of(&orbital);
    let images = RoverImages::of(&rover);
    row.record(localize(&map, &images, prior_m, params));
    row
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_known_errors() {
        let e: Vec<f64> = (1..=100).map(|k| f64::from(k) * 0.03).collect();
        let s = ErrorStats::of(&e);
        assert_eq!(s.count, 100);
        assert!((s.mean_m - 1.515).abs() < 1e-12);
        assert!((s.median_m - 1.515).abs() < 1e-12);
        assert!((s.p99_m - 2.97).abs() < 1e-12);
        assert!((s.max_m - 3.0).abs() < 1e-12);
        assert_eq!((s.over_1m, s.over_2m), (67, 34));
        assert_eq!(ErrorStats::of(&[]), ErrorStats::default());
    }

    #[test]
    fn cases_spread_over_terrain_wedges_and_lighting() {
        let cases = benchmark_cases(PAPER_CASE_COUNT, 1);
        assert_eq!(cases.len(), 264);
        assert_eq!(cases, benchmark_cases(PAPER_CASE_COUNT, 1));
        for k in TerrainKind::ALL {
            assert_eq!(cases.iter().filter(|c| c.terrain == k).count(), 88);
        }
        for w in 3..=5 {
            assert!(cases.iter().filter(|c| c.wedges == w).count() > 40);
        }
        let morning = cases
            .iter()
            .filter(|c| c.lighting == LightingKind::LateMorning)
            .count();
        assert!((20..70).contains(&morning), "{morning}");
        assert!(cases.iter().all(|c| (3..=5).contains(&c.wedges)));
    }
}
