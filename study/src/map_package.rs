//! The onboard map package of a scenario ([`localization::map_package`]) under the scenario's
//! seeds: the simulator's seed derivation ([`sim::seeds`]) gives the package the same truth
//! terrain and orbital world the simulator's onboard localizer matches against, one world per
//! scenario seed.

use std::path::Path;

use localization::map_package::{
    MapPackage, MapPackageError, PackageOptions, PackageSource, RenderSettings,
};
use sim::seeds::{Purpose, RunSeeds};

use crate::Scenario;

/// [`RenderSettings`] from a scenario seed.
pub trait SeededRenderSettings {
    /// The settings of the package of a scenario whose file says `seed = scenario_seed`.
    #[must_use]
    fn for_seed(scenario_seed: u64) -> Self;
}

impl SeededRenderSettings for RenderSettings {
    fn for_seed(seed: u64) -> Self {
        // The package is of run 0: the world the scenario's own runs see.
        let run = RunSeeds::new(seed, 0);
        RenderSettings::with_seeds(
            run.stream(Purpose::WorldTruth).seed,
            run.stream(Purpose::WorldOrbital).seed,
            run.stream(Purpose::PackageSensorNoise).seed,
            run.stream(Purpose::PackageDemNoise).seed,
        )
    }
}

/// The package of `scenario`'s route on its map, read from `file`, laid out with `options`.
///
/// # Errors
/// [`MapPackageError::Layout`] naming `file`: the corridor cannot be laid out on the map.
pub fn package_of<'a>(
    scenario: &'a Scenario,
    file: &'a Path,
    options: &PackageOptions,
) -> Result<MapPackage<'a>, MapPackageError> {
    let source = PackageSource {
        name: &scenario.name,
        file,
        sha256: &scenario.sha256,
        seed: scenario.seed,
        map_crs: &scenario.map_crs,
    };
    MapPackage::new(
        &scenario.layers,
        &scenario.settings.route,
        options,
        RenderSettings::for_seed(scenario.seed),
        source,
    )
}
