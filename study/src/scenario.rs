//! Scenario files (TOML): the map, the route, the calendar, the rover, and the expected outcomes.
//!
//! Two-stage loading (ripgrep's low-level / high-level args): [`RawScenario`] mirrors the file
//! exactly (`deny_unknown_fields`, so a typo is an error, not a silent default);
//! [`ScenarioSpec`] checks every field, and [`Scenario::load`] then reads the maps and zones and
//! builds the simulator's [`Settings`]. After that the rest of the code trusts a `Scenario`.
//!
//! The loader is one module per section of the file. Each fills the section's defaults into
//! the simulator's settings struct and runs that struct's own check, where its ranges are
//! defined (`RoverSettings::validate`, `Calendar::validate`, …), naming the file's field when one
//! is at fault (`rover.step_m`, `uncertainty.k_vo`, `sols[3].historic_novo_m`):
//!
//! | section | module | settings |
//! |---|---|---|
//! | `[map]` | `map` | [`MapFiles`] |
//! | `[grid]` (and `rover.footprint_radius_m`) | `grid` | `GridSettings` |
//! | `[rover]` | `rover` | `RoverSettings` |
//! | `[errors]` | `errors` | `ErrorModel` |
//! | `[uncertainty]` | `uncertainty` | `UncertaintyModel` |
//! | `[onboard_localization]` | `onboard_localization` | [`LocalizerSpec`] |
//! | `[operations]` | `operations` | `OperationsRules`, `SolPlanSettings`, the drive window |
//! | `[calendar]` | `calendar` | `TeamRules`, [`ComputedCalendar`] |
//! | `[[sols]]` | `sols` | `Calendar` |
//! | `[route]` | `route` | the waypoints |
//! | `[science]` | `science` | `Science` |
//! | `[study_segment]` | `study_segment` | [`StudySegment`] |
//! | `[[expect]]` | [`crate::expect`] | [`Expectation`], [`StatisticalExpectation`] |

use std::path::PathBuf;
use std::sync::Arc;

use rayon::prelude::*;

use crate::expect::{Expectation, StatisticalExpectation};
use maps::{MapLayers, ZoneSet};
use sim::Settings;
use sim::run::outcome::LegClearance;
use sim::seeds::RunSeeds;
use sim::{CampaignOutcome, Strategy};

mod build;
mod calendar;
mod errors;
mod grid;
mod load;
mod map;
mod onboard_localization;
mod operations;
mod raw;
mod route;
mod rover;
mod science;
mod sols;
mod spec;
mod study_segment;
mod uncertainty;

pub use calendar::ComputedCalendar;
pub use map::MapFiles;
pub use onboard_localization::{DEFAULT_HBS_LINK_RATE_KB_PER_S, LocalizerSpec};
pub use raw::RawScenario;
pub use spec::{ScenarioSpec, check_name};
pub use study_segment::StudySegment;

/// A validated scenario, ready to run. Cloning shares the maps, zones and planning grid.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The file it came from.
    pub path: PathBuf,
    /// Short name (used for output file names).
    pub name: String,
    /// One-paragraph description.
    pub description: String,
    /// SHA-256 of the scenario file's bytes, hex.
    pub sha256: String,
    /// The scenario's own seed (`seed` in the file): run 0's, the one `solsim run` and
    /// `compare` use.
    pub seed: u64,
    /// The simulator's settings, shared by every strategy and run.
    pub settings: Settings,
    /// Expected outcomes of one seeded run per strategy, checked by `solsim regress`.
    pub expectations: Vec<Expectation>,
    /// Expected outcomes over a sweep (`runs = N`), checked by `solsim regress`.
    pub statistical_expectations: Vec<StatisticalExpectation>,
    /// The stretch a study compares strategies on (`[study_segment]`).
    pub study_segment: Option<StudySegment>,
    /// Per-sol notes from the file.
    pub notes: Vec<(u32, String)>,
    /// The calendar computed from Mars time (`[calendar]`), with the typed overrides.
    pub computed_calendar: Option<ComputedCalendar>,
    /// Per sol with a historic drive, where its distance comes from.
    pub historic_sources: Vec<(u32, String)>,
    /// Whether any sol has historic data (so the `replay` strategy is meaningful).
    pub has_history: bool,
    /// The map layers (appearance, DEM, terrain class), loaded once and shared.
    pub layers: Arc<MapLayers>,
    /// The keep-in / keep-out zones, loaded once and shared.
    pub zones: Arc<ZoneSet>,
    /// The route's passage clearance per leg (independent of strategy and seed), computed once.
    pub legs: Vec<LegClearance>,
    /// Where the map lies on Mars: the appearance GeoTIFF's CRS ([`maps::MapCrs::Local`] for a
    /// PNG, a file without a Mars CRS, or a map placed by `map.origin_m`, which overrides the
    /// file's georeference).
    pub map_crs: maps::MapCrs,
    /// Each file the scenario reads besides itself — field (`map.appearance`, `map.dem`,
    /// `map.terrain`, `map.zones`), path, SHA-256 (hex) — so an output can name the exact
    /// inputs it came from.
    pub inputs_sha256: Vec<(&'static str, PathBuf, String)>,
}

impl Scenario {
    /// The scenario's own seed (`seed` in the file): the one `solsim run` and `compare` use.
    #[must_use]
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The seeds of run 0, the scenario's own seed: what `solsim run` and `compare` run.
    #[must_use]
    pub fn seeds(&self) -> RunSeeds {
        RunSeeds::new(self.seed, 0)
    }

    /// A [`sim::Simulation`] of `strategy` under `seeds`, before its first sol: step it a sol at
    /// a time and look at the rover between sols. The maps, zones, planning grid and leg
    /// clearances are the ones loaded once.
    ///
    /// ```
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// use study::Scenario;
    /// use sim::Strategy;
    ///
    /// let scenario = Scenario::load("../scenarios/sol383-386.toml".as_ref())?;
    /// let mut sim = scenario.simulation(Strategy::Replay, scenario.seeds());
    /// let mut radii = Vec::new();
    /// while let Some(sol) = sim.step() {
    ///     radii.push((sol.sol, sol.drove, sim.uncertainty_m()));
    /// }
    /// // Sol 385 drives into the passage with the disc grown since the last ground fix.
    /// let (_, drove, r) = radii.iter().find(|(s, ..)| *s == 385).copied().unwrap();
    /// assert!(drove && r > 20.0, "r = {r:.1} m");
    /// let outcome = sim.finish();
    /// assert_eq!(outcome.sols.len(), radii.len());
    /// # Ok(()) }
    /// ```
    #[must_use]
    pub fn simulation(&self, strategy: Strategy, seeds: RunSeeds) -> sim::Simulation<'_> {
        sim::Simulation::new(&self.settings, strategy, &self.legs, seeds)
    }

    /// Runs `strategy` under `seeds` to the calendar's end. Nothing is read or rebuilt: the
    /// maps, zones, planning grid and leg clearances are the ones loaded once, shared with every
    /// other run.
    #[must_use]
    pub fn run(&self, strategy: Strategy, seeds: RunSeeds) -> CampaignOutcome {
        self.simulation(strategy, seeds).finish()
    }

    /// Runs `strategy` as run `run` of a study (run 0 is the scenario's own seed). Every
    /// strategy of one run index sees the same world.
    #[must_use]
    pub fn run_index(&self, strategy: Strategy, run: u64) -> CampaignOutcome {
        self.run(strategy, RunSeeds::new(self.seed, run))
    }

    /// Runs each of `strategies` under `seeds`, in parallel; the outcomes come back in the
    /// order of `strategies` and do not depend on the thread count (each strategy has its own
    /// random stream).
    #[must_use]
    pub fn compare(&self, strategies: &[Strategy], seeds: RunSeeds) -> Vec<CampaignOutcome> {
        strategies.par_iter().map(|&s| self.run(s, seeds)).collect()
    }

    /// The strategies that make sense for this scenario (`replay` only with historic data).
    #[must_use]
    pub fn strategies(&self) -> Vec<sim::Strategy> {
        sim::Strategy::ALL
            .into_iter()
            .filter(|s| *s != sim::Strategy::Replay || self.has_history)
            .collect()
    }
}
