//! What the onboard localizations on one map share: [`OnboardCache`].

use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use maps::{GeoTransform, MapLayers};

use crate::synthetic::{
    OrbitalProducts, OrbitalSettings, SyntheticError, TerrainStatics, TruthPatch, patch_grid,
    render_orbital_with, truth_patch_on,
};

/// Rendered patches kept, most recent first, by default: enough for every strategy of the runs
/// two threads have in progress to find the patch another strategy of its run rendered.
pub const DEFAULT_RECENT_RENDERS: usize = 8;

/// What every onboard localization on one map shares, filled as they run (share it through an
/// `Arc`; see [`super::run_onboard_with`]):
///
/// - the map's seed-independent terrain fields ([`TerrainStatics`]);
/// - the truth patch and orbital products of the most recent renders. Two strategies of one
///   study run share the world's seeds and often localize from estimates that round to the same
///   patch grid (within a metre of each other after the same drive): the second takes the first
///   one's render instead of making it again. A render is a pure function of its key (seeds,
///   grid, orbital settings), so a reused one is the very same result. When the grids differ
///   (by a metre or two), the nearest recent truth patch of the same world lends the pixels it
///   covers (each is a pure function of seed and position) and only the strips it misses are
///   computed; the orbital products, which depend on the grid, are rendered again.
pub struct OnboardCache {
    statics: TerrainStatics,
    /// Renders, most recent first, at most `capacity`.
    recent: Mutex<VecDeque<(RenderKey, Arc<Rendered>)>>,
    capacity: usize,
    /// Renders asked for, and those found among the recent ones.
    renders: AtomicU64,
    reused: AtomicU64,
}

/// A truth patch and the orbital products rendered from it.
#[derive(Debug)]
pub(crate) struct Rendered {
    pub(crate) patch: TruthPatch,
    pub(crate) orbital: OrbitalProducts,
}

/// Everything a render depends on besides the map.
#[derive(Clone, Debug, PartialEq)]
struct RenderKey {
    truth_seed: u64,
    orbital_seed: u64,
    /// The grid's corner and pixel size, as bits.
    geo_bits: [u64; 3],
    n: usize,
    orbital: OrbitalSettings,
}

impl std::fmt::Debug for OnboardCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let recent = self.recent.lock().map_or(0, |r| r.len());
        f.debug_struct("OnboardCache")
            .field("statics", &self.statics)
            .field("recent_renders", &recent)
            .field("capacity", &self.capacity)
            .field("renders", &self.renders.load(Ordering::Relaxed))
            .field("reused", &self.reused.load(Ordering::Relaxed))
            .finish()
    }
}

impl OnboardCache {
    /// The cache of the map `layers` for orbital products rendered with `orbital` (the
    /// settings of [`super::OnboardSettings::orbital`]; other settings are served too, without
    /// the terrain fields), keeping [`DEFAULT_RECENT_RENDERS`] renders.
    #[must_use]
    pub fn new(layers: Arc<MapLayers>, orbital: &OrbitalSettings) -> Self {
        Self {
            statics: TerrainStatics::new(layers, orbital.ripple_migration_m),
            recent: Mutex::new(VecDeque::new()),
            capacity: DEFAULT_RECENT_RENDERS,
            renders: AtomicU64::new(0),
            reused: AtomicU64::new(0),
        }
    }

    /// Renders asked for so far, and how many of them were recent ones reused.
    #[must_use]
    pub fn reuse(&self) -> (u64, u64) {
        (
            self.renders.load(Ordering::Relaxed),
            self.reused.load(Ordering::Relaxed),
        )
    }

    /// The terrain fields.
    #[must_use]
    pub fn statics(&self) -> &TerrainStatics {
        &self.statics
    }

    /// Whether this is the cache of `layers` (the same allocation).
    #[must_use]
    pub fn serves(&self, layers: &MapLayers) -> bool {
        self.statics.is_of(layers)
    }

    /// The truth patch of `layers` on the grid of [`crate::synthetic::truth_patch`]`(layers,
    /// center_m, half_size_m, truth_seed)` and its orbital products under `orbital` and
    /// `orbital_seed`: a recent render with the same key, or a new one (then kept).
    ///
    /// # Errors
    /// As [`crate::synthetic::truth_patch`] and [`crate::synthetic::render_orbital`].
    pub(crate) fn render(
        &self,
        layers: &MapLayers,
        center_m: [f64; 2],
        half_size_m: f64,
        truth_seed: u64,
        orbital_seed: u64,
        orbital: &OrbitalSettings,
    ) -> Result<Arc<Rendered>, SyntheticError> {
        let (geo, n) = patch_grid(layers, center_m, half_size_m)?;
        let key = RenderKey {
            truth_seed,
            orbital_seed,
            geo_bits: geo_bits(geo),
            n,
            orbital: *orbital,
        };
        self.renders.fetch_add(1, Ordering::Relaxed);
        if let Some(hit) = self.lookup(&key) {
            self.reused.fetch_add(1, Ordering::Relaxed);
            return Ok(hit);
        }
        let statics = self
            .statics
            .serves(layers, orbital.ripple_migration_m)
            .then_some(&self.statics);
        let fields = statics.and_then(|t| t.patch(geo, n));
        // A recent patch of the same world lends the pixels it covers, when coordinates on
        // this map's lattice are exact (where the terrain fields are served).
        let donor = statics.and_then(|_| self.donor(truth_seed, geo));
        let patch = truth_patch_on(
            layers,
            geo,
            n,
            truth_seed,
            fields.as_ref(),
            donor.as_ref().map(|d| &d.patch),
        );
        let orbital = render_orbital_with(&patch, orbital, orbital_seed, fields.as_ref())?;
        let rendered = Arc::new(Rendered { patch, orbital });
        self.keep(key, Arc::clone(&rendered));
        Ok(rendered)
    }

    fn lookup(&self, key: &RenderKey) -> Option<Arc<Rendered>> {
        let mut recent = self.recent.lock().unwrap_or_else(PoisonError::into_inner);
        let i = recent.iter().position(|(k, _)| k == key)?;
        let entry = recent.remove(i)?;
        let hit = Arc::clone(&entry.1);
        recent.push_front(entry);
        Some(hit)
    }

    /// The recent render of the world `truth_seed` whose grid corner is nearest to `geo`'s.
    fn donor(&self, truth_seed: u64, geo: GeoTransform) -> Option<Arc<Rendered>> {
        let recent = self.recent.lock().unwrap_or_else(PoisonError::into_inner);
        let distance = |r: &Rendered| {
            let o = r.patch.height_m.geo.origin_m;
            (o[0] - geo.origin_m[0])
                .abs()
                .max((o[1] - geo.origin_m[1]).abs())
        };
        recent
            .iter()
            .filter(|(k, _)| k.truth_seed == truth_seed)
            .min_by(|a, b| distance(&a.1).total_cmp(&distance(&b.1)))
            .map(|(_, r)| Arc::clone(r))
    }

    fn keep(&self, key: RenderKey, rendered: Arc<Rendered>) {
        let mut recent = self.recent.lock().unwrap_or_else(PoisonError::into_inner);
        // Another run may have rendered the same patch meanwhile: keep one.
        if !recent.iter().any(|(k, _)| *k == key) {
            recent.push_front((key, rendered));
            recent.truncate(self.capacity);
        }
    }
}

fn geo_bits(geo: GeoTransform) -> [u64; 3] {
    [
        geo.origin_m[0].to_bits(),
        geo.origin_m[1].to_bits(),
        geo.resolution_m_per_px.to_bits(),
    ]
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::benchmark_set::{BenchmarkMaps, TerrainKind};
    use crate::onboard::{OnboardRequest, OnboardSettings, run_onboard, run_onboard_with};

    #[test]
    fn runs_with_the_cache_equal_runs_without() {
        let maps = BenchmarkMaps::generate(1);
        let layers = Arc::new(maps.get(TerrainKind::Dunes).clone());
        let s = OnboardSettings::default();
        let cache = OnboardCache::new(Arc::clone(&layers), &s.orbital);
        let request = |prior_m: [f64; 2], truth_seed, sol_seed| OnboardRequest {
            truth_m: [300.0, 310.0],
            prior_m,
            uncertainty_m: 12.0,
            truth_seed,
            orbital_seed: 5,
            sol_seed,
        };
        // A render, the same again, one whose prior rounds to the same grid (another sol
        // seed: another rover image), another world, another grid.
        for req in [
            request([304.0, 306.0], 1, 3),
            request([304.0, 306.0], 1, 3),
            request([304.2, 305.9], 1, 4),
            request([304.2, 305.9], 2, 4),
            request([301.0, 309.0], 1, 4),
        ] {
            let with = run_onboard_with(&layers, Some(&cache), &req, &s);
            assert_eq!(with, run_onboard(&layers, &req, &s), "{req:?}");
        }
        assert_eq!(cache.reuse(), (5, 2));
        // Another map's cache is not used.
        let other = OnboardCache::new(Arc::new(maps.get(TerrainKind::Dunes).clone()), &s.orbital);
        let req = request([304.0, 306.0], 1, 3);
        assert_eq!(
            run_onboard_with(&layers, Some(&other), &req, &s),
            run_onboard(&layers, &req, &s)
        );
        assert_eq!(other.reuse(), (0, 0));
    }
}
