//! `Scenario::load` and its variants: stage one ([`ScenarioSpec::load`]), the maps
//! (`Scenario::build`), then the scenario as a whole ([`crate::sanity`]), whose first error
//! refuses it.

use std::path::Path;

use maps::MemoryBudget;

use super::Scenario;
use super::spec::ScenarioSpec;
use crate::error::ScenarioError;
use crate::sanity::{Finding, Severity, findings};

impl Scenario {
    /// Read, validate and resolve a scenario file (maps and zones included) within the default
    /// [`MemoryBudget`].
    ///
    /// # Errors
    /// A [`ScenarioError`] naming the file and the first field at fault.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        Self::load_within(path, MemoryBudget::default())
    }

    /// [`Scenario::load`] within `budget`: the map rasters (from their headers) and the
    /// planning grid (from the map's extent and `grid.resolution_m`) must fit it together,
    /// which is checked before any of them is allocated.
    ///
    /// # Errors
    /// A [`ScenarioError`] naming the file and the first field at fault.
    ///
    /// A scenario whose fields are each well formed but whose whole makes no sense (a route in
    /// degrees, a waypoint in a keep-out, a leg closed at r = 0: [`crate::sanity`]) is refused
    /// with its first [`Severity::Error`]; [`Scenario::inspect_within`] lists
    /// them all.
    pub fn load_within(path: &Path, budget: MemoryBudget) -> Result<Self, ScenarioError> {
        Self::load_observed(path, budget, &|_, _| {})
    }

    /// [`Scenario::load_within`] with progress over the route's legs, as
    /// [`Scenario::inspect_observed`].
    ///
    /// # Errors
    /// As [`Scenario::load_within`].
    pub fn load_observed(
        path: &Path,
        budget: MemoryBudget,
        on_leg: &(dyn Fn(u64, u64) + Sync),
    ) -> Result<Self, ScenarioError> {
        let (scenario, findings) = Self::inspect_observed(path, budget, on_leg)?;
        match findings.iter().find(|f| f.severity == Severity::Error) {
            Some(f) => Err(f.to_error(path)),
            None => Ok(scenario),
        }
    }

    /// Load like [`Scenario::load_within`], but return the scenario with every
    /// [`crate::sanity`] finding, errors included, instead of refusing it: what
    /// `solsim validate` prints.
    ///
    /// # Errors
    /// A [`ScenarioError`] naming the file and the first field at fault, when a field is
    /// malformed or a file cannot be read.
    pub fn inspect_within(
        path: &Path,
        budget: MemoryBudget,
    ) -> Result<(Self, Vec<Finding>), ScenarioError> {
        Self::inspect_observed(path, budget, &|_, _| {})
    }

    /// [`Scenario::inspect_within`], calling `on_leg(done, total)` as the route's passage
    /// clearances are searched, leg by leg (the long part of loading a long route; from any
    /// thread).
    ///
    /// # Errors
    /// As [`Scenario::inspect_within`].
    pub fn inspect_observed(
        path: &Path,
        budget: MemoryBudget,
        on_leg: &(dyn Fn(u64, u64) + Sync),
    ) -> Result<(Self, Vec<Finding>), ScenarioError> {
        let scenario = Self::build_observed(ScenarioSpec::load(path)?, budget, on_leg)?;
        let findings = findings(&scenario);
        Ok((scenario, findings))
    }
}
