//! One seed derivation for every random stream of solsim.
//!
//! Every random draw — a strategy run's VO failures, slip, heading error and localization
//! errors; the rendered world and the orbital map the onboard localizer matches against; the
//! noise of an onboard map package — comes from the [`RunSeeds`] of a run, derived once when
//! the run starts from (scenario seed, run index):
//!
//! 1. the run's master seed: the scenario's `seed` itself for run 0 (what `solsim run` and
//!    `compare` use), a sub-seed of it salted by the run index for a sweep's run `run ≥ 1`;
//! 2. the purpose's stream under that master ([`RunSeeds::stream`]): a strategy run is the
//!    ChaCha8 stream `stream_id` of the master seed (so the strategies of one run are
//!    independent streams of one generator); a world or noise field is the master seed salted
//!    by its purpose.
//!
//! Hence the same run index gives every strategy the same world (truth terrain, orbital map),
//! and the simulator's onboard localizer and `solsim map package` see one and the same orbital
//! world for one scenario seed.
//!
//! The salts are fixed forever: changing one changes every output that depends on it, which
//! the determinism goldens catch.
//!
//! ```
//! use sim::seeds::{Purpose, RunSeeds};
//! use sim::Strategy;
//!
//! let run0 = RunSeeds::new(385, 0);
//! assert_eq!(run0.master(), 385); // run 0 is the scenario's own seed
//! let run7 = RunSeeds::new(385, 7);
//! // Every strategy of run 7 sees the same world, through its own stream.
//! let (g, o) = (run7.stream(Purpose::Strategy(Strategy::Ground)), run7.stream(Purpose::Strategy(Strategy::Onboard)));
//! assert_eq!(g.seed, o.seed);
//! assert_ne!(g.stream, o.stream);
//! ```

use maps::procedural::noise::sub_seed;
use rand::SeedableRng as _;
use rand_chacha::ChaCha8Rng;

use crate::operations::strategy::Strategy;

/// What a random stream is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Purpose {
    /// A strategy's run: its VO failures, slip, heading error, localization errors and the
    /// per-sol seeds of the imagery it renders.
    Strategy(Strategy),
    /// The true terrain the rover drives on (fine detail, rocks, ripples) at 25 cm.
    WorldTruth,
    /// The orbital map made of that terrain (HiRISE stand-in: its epoch, albedo change,
    /// orthorectification errors).
    WorldOrbital,
    /// The sensor noise of a map package's orthoimage, per world pixel.
    PackageSensorNoise,
    /// The DEM noise of a map package, per world cell.
    PackageDemNoise,
}

/// Salt of a sweep run's master seed (run `k ≥ 1` uses `RUN_SALT + k`).
const RUN_SALT: u64 = 0x5255_4E00_0000_0000;
/// Salts of the world and package fields under a run's master seed.
const SALT_WORLD_TRUTH: u64 = 0x7275_7468;
const SALT_WORLD_ORBITAL: u64 = 0x6f72_6269;
const SALT_PACKAGE_SENSOR_NOISE: u64 = 0x5041_434B_0003;
const SALT_PACKAGE_DEM_NOISE: u64 = 0x5041_434B_0004;

/// A ChaCha8 seed and stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StreamSeed {
    /// The generator's seed (`ChaCha8Rng::seed_from_u64`), also the seed of hash-based fields.
    pub seed: u64,
    /// The generator's stream (`set_stream`); 0 for fields.
    pub stream: u64,
}

impl StreamSeed {
    /// The generator of this stream.
    #[must_use]
    pub fn rng(self) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(self.stream);
        rng
    }
}

/// The seeds of one run: everything random in it comes from here.
///
/// Derived once, when the run starts, from (scenario seed, run index) ([`RunSeeds::new`]),
/// and passed to the simulation; the settings carry no seed of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RunSeeds {
    master: u64,
}

impl RunSeeds {
    /// The seeds of run `run` of a scenario whose file says `seed = scenario_seed` (run 0 is
    /// the scenario's own seed).
    #[must_use]
    pub fn new(scenario_seed: u64, run: u64) -> Self {
        let master = if run == 0 {
            scenario_seed
        } else {
            sub_seed(scenario_seed, RUN_SALT.wrapping_add(run))
        };
        Self { master }
    }

    /// The seeds of a run whose master seed is known: the `seed` a run's outcome records
    /// ([`crate::CampaignOutcome::seed`]), to run it again.
    #[must_use]
    pub fn from_master(master: u64) -> Self {
        Self { master }
    }

    /// The run's master seed (what its outcome records).
    #[must_use]
    pub fn master(self) -> u64 {
        self.master
    }

    /// The stream for `purpose` in this run (see the module docs).
    #[must_use]
    pub fn stream(self, purpose: Purpose) -> StreamSeed {
        let field = |salt| StreamSeed {
            seed: sub_seed(self.master, salt),
            stream: 0,
        };
        match purpose {
            Purpose::Strategy(s) => StreamSeed {
                seed: self.master,
                stream: s.stream_id(),
            },
            Purpose::WorldTruth => field(SALT_WORLD_TRUTH),
            Purpose::WorldOrbital => field(SALT_WORLD_ORBITAL),
            Purpose::PackageSensorNoise => field(SALT_PACKAGE_SENSOR_NOISE),
            Purpose::PackageDemNoise => field(SALT_PACKAGE_DEM_NOISE),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::RngExt as _;

    #[test]
    fn run_zero_is_the_scenario_seed_and_runs_differ() {
        assert_eq!(RunSeeds::new(385, 0).master(), 385);
        let runs: std::collections::HashSet<u64> =
            (0..1000).map(|r| RunSeeds::new(385, r).master()).collect();
        assert_eq!(runs.len(), 1000);
    }

    #[test]
    fn strategies_share_the_world_but_not_their_streams() {
        let a = RunSeeds::new(7, 3).stream(Purpose::Strategy(Strategy::Ground));
        let b = RunSeeds::new(7, 3).stream(Purpose::Strategy(Strategy::Onboard));
        assert_eq!(a.seed, b.seed);
        assert_ne!(a.stream, b.stream);
        assert_ne!(a.rng().random::<u64>(), b.rng().random::<u64>());
        let w = RunSeeds::new(7, 3).stream(Purpose::WorldTruth);
        assert_ne!(w, RunSeeds::new(7, 3).stream(Purpose::WorldOrbital));
        assert_ne!(w, RunSeeds::new(7, 4).stream(Purpose::WorldTruth));
    }

    /// A snapshot of draws and derived seeds (committed constants): a change of a salt, of
    /// the derivation or of `rand_chacha` changes every output, so it must show up here first.
    #[test]
    fn draws_are_stable() {
        let mut rng = RunSeeds::new(385, 0)
            .stream(Purpose::Strategy(Strategy::Onboard))
            .rng();
        assert_eq!(
            [rng.random::<u64>(), rng.random::<u64>()],
            [10_084_762_352_482_079_060, 13_290_252_253_637_988_929]
        );
        assert_eq!(RunSeeds::new(385, 1).master(), 4_671_436_292_528_185_721);
        assert_eq!(
            RunSeeds::new(385, 0).stream(Purpose::WorldTruth).seed,
            17_178_454_889_591_092_722
        );
    }
}
