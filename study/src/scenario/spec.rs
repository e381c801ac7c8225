//! [`ScenarioSpec`]: a scenario file read and checked field by field, before its maps are
//! read — stage one of `Scenario::load`. Each section of the file has its own loader (a
//! sibling module); this one runs them in a fixed order (the order the loader has always checked
//! the sections in, so a file with several faults reports the same first one) and keeps what
//! they return.

use std::path::{Path, PathBuf};

use sim::grid::planning_grid::GridSettings;
use sim::operations::calendar::Calendar;
use sim::operations::policy::OperationsRules;
use sim::operations::science::Science;
use sim::operations::sol_plan::SolPlanSettings;
use sim::rover::autonav::RoverSettings;
use sim::rover::uncertainty::UncertaintyModel;

use super::calendar::ComputedCalendar;
use super::map::MapFiles;
use super::onboard_localization::LocalizerSpec;
use super::raw::RawScenario;
use super::study_segment::StudySegment;
use super::{
    errors, grid, map, onboard_localization, operations, route, rover, science, sols,
    study_segment, uncertainty,
};
use crate::check::FieldCheck;
use crate::error::ScenarioError;
use crate::expect::{Expectation, Resolved, StatisticalExpectation};
use crate::ranges;

/// Scenario name, characters (it names output files).
const MAX_NAME_CHARS: usize = 100;

/// Whether `name` can name a scenario (it becomes output file and directory names); `Err` says
/// what is expected.
///
/// # Errors
/// The expectation, when `name` is empty, `.` or `..`, too long, or holds a path separator or a
/// control character.
pub fn check_name(name: &str) -> Result<(), String> {
    if name.trim().is_empty()
        || matches!(name.trim(), "." | "..")
        || name.chars().count() > MAX_NAME_CHARS
        || name.contains(['/', '\\'])
        || maps::input_file::first_unsafe_char(name).is_some()
    {
        return Err(format!(
            "a name usable as a directory name: 1 ..= {MAX_NAME_CHARS} characters, not \".\" or \"..\", without path separators or control characters"
        ));
    }
    Ok(())
}

/// A scenario file, validated, before its maps are read: stage one of `Scenario::load`.
#[derive(Debug)]
pub struct ScenarioSpec {
    /// The file it came from.
    pub path: PathBuf,
    /// Short name (used for output file names).
    pub name: String,
    /// One-paragraph description.
    pub description: String,
    /// SHA-256 of the scenario file's bytes, hex.
    pub sha256: String,
    /// Master seed.
    pub seed: u64,
    /// The map files, resolved against the scenario's folder.
    pub map: MapFiles,
    /// Planning-grid settings.
    pub grid: GridSettings,
    /// Route waypoints, map metres (on the map: checked by `Scenario::build`).
    pub route: Vec<[f64; 2]>,
    /// Operations calendar.
    pub calendar: Calendar,
    /// Rover and AutoNav settings.
    pub rover: RoverSettings,
    /// Uncertainty growth.
    pub model: UncertaintyModel,
    /// Which onboard localizer.
    pub localizer: LocalizerSpec,
    /// The HBS serial link rate, bytes per second (`hbs_link_rate_kb_per_s` × 1000): it times
    /// the transfer of the onboard localization's inputs, for every localizer.
    pub hbs_link_bytes_per_s: f64,
    /// Operator margin after an onboard localization, metres.
    pub operator_margin_m: f64,
    /// Each drive sol's plan settings: the post-drive imaging before a downlink pass
    /// (`post_drive_imaging_s`, [`SolPlanSettings::imaging_s`]), the defaults otherwise.
    pub sol_plan: SolPlanSettings,
    /// Plan lengths, the optional extension cap, the planners' passage margin.
    pub rules: OperationsRules,
    /// Science campaigns (target positions on the map: checked by `Scenario::build`).
    pub science: Science,
    /// Expected outcomes of one seeded run per strategy.
    pub expectations: Vec<Expectation>,
    /// Expected outcomes over a sweep (`runs = N`).
    pub statistical_expectations: Vec<StatisticalExpectation>,
    /// The stretch a study compares strategies on (`[study_segment]`).
    pub study_segment: Option<StudySegment>,
    /// Per-sol notes.
    pub notes: Vec<(u32, String)>,
    /// Whether any sol has historic data.
    pub has_history: bool,
    /// The calendar computed from Mars time (`[calendar]`), with the typed per-sol overrides.
    pub computed_calendar: Option<ComputedCalendar>,
    /// Per sol with a historic drive, where its distance comes from (`historic_source`).
    pub historic_sources: Vec<(u32, String)>,
}

impl ScenarioSpec {
    /// Reads and validates a scenario file without reading its maps (stage one of
    /// `Scenario::load`).
    ///
    /// # Errors
    /// A [`ScenarioError`] naming the file and the first field at fault.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let (raw, sha256) = crate::input::read_toml::<RawScenario>(path)?;
        Self::validate(path, raw, sha256)
    }

    /// [`ScenarioSpec::load`] of scenario text (`path` names it in errors and anchors its
    /// relative paths; nothing is read): what the fuzzer drives.
    ///
    /// # Errors
    /// A [`ScenarioError`] naming the file and the first field at fault.
    pub fn from_toml_str(path: &Path, text: &str) -> Result<Self, ScenarioError> {
        let raw = crate::input::parse_toml::<RawScenario>(path, text)?;
        Self::validate(path, raw, crate::input::sha256_hex(text.as_bytes()))
    }

    /// Every section through its loader, in the loader's fixed order (see the module doc); the
    /// first field at fault is the error.
    fn validate(path: &Path, raw: RawScenario, sha256: String) -> Result<Self, ScenarioError> {
        let c = FieldCheck { path };
        // The name becomes output file and directory names (`solsim-out/NAME/`): `.` and `..`
        // name the directory itself or its parent, and failed only at write time.
        if let Err(expected) = check_name(&raw.name) {
            return Err(c.err("name", expected, format!("{:?}", raw.name)));
        }
        let errors = errors::error_model(&c, &raw.errors)?;
        let rover = rover::rover_settings(&c, &raw.rover, errors)?;
        let grid = grid::grid_settings(&c, &raw.grid, &raw.rover, &rover)?;
        let model = uncertainty::uncertainty_model(&c, &raw.uncertainty)?;
        let onboard = onboard_localization::onboard_localization(&c, &raw.onboard_localization)?;
        let drive_window = operations::drive_window(&c, &raw.operations)?;
        let sols = sols::sols(&c, raw.calendar.as_ref(), &raw.sols, drive_window)?;
        let map = map::map_files(&c, &raw.map, path.parent().unwrap_or(Path::new(".")))?;
        let route = route::waypoints(&c, &raw.route)?;
        // Positions are checked against the map's extent when it is read (`Scenario::build`).
        let science = science::resolve_science(
            path,
            &raw.science,
            &|p| p.iter().all(|v| ranges::COORDINATE_M.contains(*v)),
            &format!("|x|, |y| ≤ {} m", ranges::COORDINATE_M.max),
        )?;
        let campaign_ids: Vec<&str> = science.campaign_ids().collect();
        let mut expectations = Vec::new();
        let mut statistical_expectations = Vec::new();
        for (i, e) in raw.expect.into_iter().enumerate() {
            match e.resolve(path, i, &sols.calendar, &campaign_ids)? {
                Resolved::Run(e) => expectations.push(e),
                Resolved::Sweep(e) => statistical_expectations.push(e),
            }
        }
        let study_segment =
            study_segment::study_segment(&c, raw.study_segment.as_ref(), &sols.calendar)?;
        let sol_plan = operations::sol_plan(&c, &raw.operations)?;
        let rules = operations::rules(&c, &raw.operations)?;
        Ok(ScenarioSpec {
            path: path.to_path_buf(),
            name: raw.name,
            description: raw.description,
            sha256,
            seed: raw.seed,
            map,
            grid,
            route,
            calendar: sols.calendar,
            rover,
            model,
            localizer: onboard.localizer,
            hbs_link_bytes_per_s: onboard.hbs_link_bytes_per_s,
            operator_margin_m: onboard.operator_margin_m,
            sol_plan,
            rules,
            science,
            expectations,
            statistical_expectations,
            study_segment,
            notes: sols.notes,
            has_history: sols.has_history,
            computed_calendar: sols.computed_calendar,
            historic_sources: sols.historic_sources,
        })
    }
}
