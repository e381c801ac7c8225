//! Scenario files (TOML): the map, the route, the calendar, the rover, and the expected outcomes.
//!
//! Two-stage loading (ripgrep's low-level / high-level args): [`RawScenario`] mirrors the file
//! exactly (`deny_unknown_fields`, so a typo is an error, not a silent default); [`Scenario::load`]
//! validates every field, resolves paths relative to the scenario file, loads the maps and zones
//! and builds the [`sim::Campaign`]. After that the rest of the code trusts a `Scenario`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use rayon::prelude::*;

use crate::check::Check;
use crate::error::ScenarioError;

pub mod ranges;
mod raw;

use crate::expect::{Expectation, Mismatch, StatisticalExpectation};
use localization::ekf::ParkedSettings;
use localization::matcher::Method;
use localization::onboard::OnboardSettings;
use localization::particle::{KldParams, ParticleParams, Resampling};
use maps::{GeoTransform, MapLayers, MemoryBudget, ZoneSet};
use ranges::PhysicalRange;
pub(crate) use raw::Pair;
pub use raw::RawScenario;
use raw::{RawErrors, RawPerTerrain, RawRover};
use sim::autonav::{PerTerrain, ProfileSlip, RoverParams, SlipModel};
use sim::calendar::{Calendar, HistoricSol, Planning, SolEntry};
use sim::campaign::{self, Campaign};
use sim::errors::{ErrorModel, ErrorPreset};
use sim::localizer::{
    EkfLocalizer, ImageryLocalizer, OnboardLocalizer, ParticleLocalizer, StatisticalLocalizer,
};
use sim::outcome::LegClearance;
use sim::planning_grid::{GridParams, PlanningGrid};
use sim::time::SOL_S;
use sim::uncertainty::UncertaintyModel;
use sim::{CampaignOutcome, Strategy};

/// Default settings, written once: the scenario-level defaults are the library ones.
const DEFAULT_OPERATOR_MARGIN_M: f64 = 1.0;
const DEFAULT_DRIVE_START: &str = "11:00";
const DEFAULT_DRIVE_END: &str = "15:00";
const DEFAULT_POST_DRIVE_IMAGING_S: u32 = 1800;

// Physical ranges: a finite value outside them would run to nonsense, so the loaders refuse
// it. Rates and lengths are in [`ranges`] (README, "Input formats", lists them all).
/// Heading knowledge error (1σ), degrees.
const MAX_HEADING_SIGMA_DEG: f64 = 45.0;
/// `grid.max_slope_deg`, degrees: below 1° natural ground is all hazard; 90° is a wall.
const SLOPE_LIMIT_DEG: PhysicalRange = PhysicalRange {
    min: 1.0,
    max: 90.0,
    unit: "degrees",
};
/// Particle-filter particles: below 100 a 30 m prior is sampled a particle per 9 m²; above
/// 100 000 an update holds hundreds of MB and takes seconds.
const MIN_PARTICLES: u32 = 100;
/// See [`MIN_PARTICLES`].
const MAX_PARTICLES: u32 = 100_000;
/// One orbiter pass of EKF ranging, s: a low orbiter is visible for under an hour.
const MAX_PASS_S: u32 = 3_600;
/// The default HBS link rate, KB/s: the flown 10 KB/s (paper 000 §6).
pub const DEFAULT_HBS_LINK_RATE_KB_PER_S: f64 = 10.0;
/// Terrain cost multiplier.
const MAX_TERRAIN_COST: f64 = 1_000.0;
/// Scenario name, characters (it names output files).
const MAX_NAME_CHARS: usize = 100;
/// Sols in one scenario (about 15 Mars years).
const MAX_SOLS: usize = 10_000;

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

/// A scenario file, validated, before its maps are read: stage one of [`Scenario::load`].
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
    pub grid: GridParams,
    /// Route waypoints, map metres (on the map: checked by [`Scenario::build`]).
    pub route: Vec<[f64; 2]>,
    /// Operations calendar.
    pub calendar: Calendar,
    /// Rover and AutoNav settings.
    pub rover: RoverParams,
    /// Uncertainty growth.
    pub model: UncertaintyModel,
    /// Which onboard localizer.
    pub localizer: LocalizerSpec,
    /// The HBS serial link rate, bytes per second (`hbs_link_rate_kb_per_s` × 1000): it times
    /// the transfer of the onboard localization's inputs, for every localizer.
    pub hbs_link_bytes_per_s: f64,
    /// Operator margin after an onboard localization, metres.
    pub operator_margin_m: f64,
    /// Post-drive imaging before a downlink pass, seconds.
    pub post_drive_imaging_s: u32,
    /// Plan lengths, the optional extension cap, the planners' passage margin.
    pub rules: sim::policy::OperationsRules,
    /// Science campaigns (target positions on the map: checked by [`Scenario::build`]).
    pub science: sim::science::Science,
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

/// A calendar computed from Mars time and the team's rules (`[calendar]`), and what the
/// scenario typed over it.
#[derive(Debug, Clone, PartialEq)]
pub struct ComputedCalendar {
    /// The rules.
    pub rules: sim::ops_calendar::TeamRules,
    /// What they give, per sol of the scenario.
    pub sols: Vec<sim::ops_calendar::ComputedSol>,
    /// Typed per-sol values that replace the computed ones (historic inputs): (sol, field,
    /// value).
    pub overrides: Vec<(u32, &'static str, bool)>,
}

/// `[study_segment]`: the stretch of the traverse a study compares strategies on — the sols
/// needed to drive `distance_m` metres counted from `from_sol` (`segment_sols` in a sweep's
/// `runs.parquet`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StudySegment {
    /// First sol counted (a sol of the calendar).
    pub from_sol: u32,
    /// Metres to cover.
    pub distance_m: f64,
}

/// The `[map]` section: files resolved against the scenario's folder.
#[derive(Clone, Debug)]
pub struct MapFiles {
    /// Orthoimage (u8), PNG or GeoTIFF.
    pub appearance: PathBuf,
    /// DEM: 16-bit centimetres above `dem_datum_m`, or f32 metres.
    pub dem: PathBuf,
    /// Terrain classes (u8).
    pub terrain: PathBuf,
    /// Keep-in / keep-out zones, GeoJSON.
    pub zones: PathBuf,
    /// Datum of a 16-bit centimetre DEM, metres.
    pub dem_datum_m: f64,
    /// Placement of PNG layers (GeoTIFFs carry their own).
    pub georef: Option<GeoTransform>,
}

/// The `[onboard_localization]` choice, before the maps an image-matching localizer needs
/// are read.
#[derive(Clone, Debug)]
pub enum LocalizerSpec {
    /// Errors drawn from the published statistics.
    Statistical(StatisticalLocalizer),
    /// Image matching on the co-processor model.
    Imagery {
        /// Census, NCC or MI.
        method: Method,
        /// Run-time multiplier on the co-processor.
        hbs_slowdown: f64,
    },
    /// Paper 002's particle filter on the census score surface.
    Particle {
        /// Particle count and resampling.
        params: ParticleParams,
        /// Run-time multiplier on the co-processor.
        hbs_slowdown: f64,
    },
    /// Paper 004's EKF, the parked rover ranging through one orbiter pass.
    Ekf(ParkedSettings),
}

/// Which localizer `onboard_localization.localizer` names.
enum LocalizerKind {
    Statistical,
    Imagery(Method),
    Particle,
    Ekf,
}

/// One item of a scenario's memory budget: the field it comes from, its bytes, and for a
/// raster the file and header (to name it in the error).
type BudgetItem<'a> = (
    &'a str,
    u64,
    Option<(&'a Path, maps::raster_io::RasterHeader)>,
);

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
    /// What to simulate.
    pub campaign: Campaign,
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

fn per_terrain(
    c: &Check<'_>,
    field: &str,
    raw: Option<RawPerTerrain>,
    default: PerTerrain,
    frac: bool,
) -> Result<PerTerrain, ScenarioError> {
    let Some(raw) = raw else { return Ok(default) };
    let one = |name: &str, v: Option<f64>, d: f64| -> Result<f64, ScenarioError> {
        let f = format!("{field}.{name}");
        match v {
            None => Ok(d),
            Some(v) if frac => c.fraction(&f, v),
            Some(v) if v.is_finite() && (1.0..=MAX_TERRAIN_COST).contains(&v) => Ok(v),
            Some(v) => Err(ScenarioError::field(
                c.path,
                f,
                format!("a cost multiplier 1 ..= {MAX_TERRAIN_COST}"),
                v,
            )),
        }
    };
    Ok(PerTerrain {
        sand: one("sand", raw.sand, default.sand)?,
        soil: one("soil", raw.soil, default.soil)?,
        bedrock: one("bedrock", raw.bedrock, default.bedrock)?,
    })
}

/// The `[errors]` section: a preset (`model`, default "calibrated") and field overrides.
/// `[rover] slip_model` and its settings: `"terrain"` (the default) refuses the profile's
/// settings rather than ignoring them.
fn slip_model(
    c: &Check<'_>,
    r: &RawRover,
    slip_sigma_relative: f64,
) -> Result<SlipModel, ScenarioError> {
    let profile = match r.slip_model.as_deref() {
        None | Some("terrain") => false,
        Some("profile") => true,
        Some(other) => {
            return Err(ScenarioError::field(
                c.path,
                "rover.slip_model",
                "\"terrain\" (slip per terrain class) or \"profile\" (slip by class, slope and heading from the rapier rover's profile)",
                format!("{other:?}"),
            ));
        }
    };
    if !profile {
        let stray = [
            ("rover.slip_aware_routing", r.slip_aware_routing.is_some()),
            ("rover.slip_limit", r.slip_limit.is_some()),
            ("rover.avoid_slip_above", r.avoid_slip_above.is_some()),
            ("rover.max_tilt_deg", r.max_tilt_deg.is_some()),
        ];
        if let Some(&(field, _)) = stray.iter().find(|(_, set)| *set) {
            return Err(ScenarioError::field(
                c.path,
                field,
                "no value unless rover.slip_model = \"profile\"",
                "a value".to_owned(),
            ));
        }
        return Ok(SlipModel::Terrain);
    }
    let d = ProfileSlip::default();
    let slip_limit = r.slip_limit.map_or(Ok(d.slip_limit), |v| {
        c.in_range("rover.slip_limit", v, 0.05, 0.95, "a fraction")
    })?;
    Ok(SlipModel::Profile(ProfileSlip {
        aware_routing: r.slip_aware_routing.unwrap_or(d.aware_routing),
        slip_limit,
        avoid_slip_above: r.avoid_slip_above.map_or(
            Ok(ProfileSlip::derived_avoid_slip_above(
                slip_limit,
                slip_sigma_relative,
            )),
            |v| c.in_range("rover.avoid_slip_above", v, 0.0, 0.95, "a fraction"),
        )?,
        max_tilt_deg: r.max_tilt_deg.map_or(Ok(d.max_tilt_deg), |v| {
            c.in_range("rover.max_tilt_deg", v, 1.0, 45.0, "degrees")
        })?,
    }))
}

fn error_model(c: &Check<'_>, raw: RawErrors) -> Result<ErrorModel, ScenarioError> {
    let preset = match raw.model.as_deref() {
        None => ErrorPreset::Calibrated,
        Some(name) => ErrorPreset::from_name(name).ok_or_else(|| {
            ScenarioError::field(
                c.path,
                "errors.model",
                "\"calibrated\" or \"stress\"",
                format!("{name:?}"),
            )
        })?,
    };
    let d = preset.model();
    let fraction = |field: &str, v: Option<f64>, d: f64| v.map_or(Ok(d), |v| c.fraction(field, v));
    Ok(ErrorModel {
        preset,
        heading_sigma_deg: raw.heading_sigma_deg.map_or(Ok(d.heading_sigma_deg), |v| {
            c.in_range(
                "errors.heading_sigma_deg",
                v,
                0.0,
                MAX_HEADING_SIGMA_DEG,
                "degrees",
            )
        })?,
        vo_scale_sigma: fraction(
            "errors.vo_scale_sigma",
            raw.vo_scale_sigma,
            d.vo_scale_sigma,
        )?,
        vo_noise_fraction: fraction(
            "errors.vo_noise_fraction",
            raw.vo_noise_fraction,
            d.vo_noise_fraction,
        )?,
        vo_failure: per_terrain(c, "errors.vo_failure", raw.vo_failure, d.vo_failure, true)?,
        slip_fraction: per_terrain(
            c,
            "errors.slip_fraction",
            raw.slip_fraction,
            d.slip_fraction,
            true,
        )?,
        slip_sigma_relative: fraction(
            "errors.slip_sigma_relative",
            raw.slip_sigma_relative,
            d.slip_sigma_relative,
        )?,
        ground_localization_sigma_m: raw
            .ground_localization_sigma_m
            .map_or(Ok(d.ground_localization_sigma_m), |v| {
                ranges::MARGIN_M.check(c, "errors.ground_localization_sigma_m", v)
            })?,
    })
}

impl ScenarioSpec {
    /// Reads and validates a scenario file without reading its maps (stage one of
    /// [`Scenario::load`]).
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

    fn validate(path: &Path, raw: RawScenario, sha256: String) -> Result<Self, ScenarioError> {
        let c = Check { path };
        let base = path.parent().unwrap_or(Path::new("."));
        // The name becomes output file and directory names (`solsim-out/NAME/`): `.` and `..`
        // name the directory itself or its parent, and failed only at write time.
        if let Err(expected) = check_name(&raw.name) {
            return Err(ScenarioError::field(
                path,
                "name",
                expected,
                format!("{:?}", raw.name),
            ));
        }

        // Rover, uncertainty, localizer, operations.
        let d = RoverParams::default();
        let r = raw.rover;
        let errors = error_model(&c, raw.errors)?;
        let slip = slip_model(&c, &r, errors.slip_sigma_relative)?;
        let rover = RoverParams {
            drive_rate_m_per_h: r.drive_rate_m_per_h.map_or(Ok(d.drive_rate_m_per_h), |v| {
                ranges::DRIVE_RATE_M_PER_H.check(&c, "rover.drive_rate_m_per_h", v)
            })?,
            step_m: r.step_m.map_or(Ok(d.step_m), |v| {
                ranges::STEP_M.check(&c, "rover.step_m", v)
            })?,
            waypoint_tolerance_m: r
                .waypoint_tolerance_m
                .map_or(Ok(d.waypoint_tolerance_m), |v| {
                    ranges::WAYPOINT_TOLERANCE_M.check(&c, "rover.waypoint_tolerance_m", v)
                })?,
            terrain_cost: per_terrain(
                &c,
                "rover.terrain_cost",
                r.terrain_cost,
                d.terrain_cost,
                false,
            )?,
            edge_buffer_m: r.edge_buffer_m.map_or(Ok(d.edge_buffer_m), |v| {
                ranges::MARGIN_M.check(&c, "rover.edge_buffer_m", v)
            })?,
            errors,
            slip_model: slip,
        };
        let gd = GridParams::default();
        let grid_params = GridParams {
            resolution_m: raw.grid.resolution_m.map_or(Ok(gd.resolution_m), |v| {
                ranges::GRID_RESOLUTION_M.check(&c, "grid.resolution_m", v)
            })?,
            footprint_radius_m: r
                .footprint_radius_m
                .map_or(Ok(gd.footprint_radius_m), |v| {
                    ranges::FOOTPRINT_RADIUS_M.check(&c, "rover.footprint_radius_m", v)
                })?,
            max_slope_deg: raw.grid.max_slope_deg.map_or(Ok(gd.max_slope_deg), |v| {
                SLOPE_LIMIT_DEG.check(&c, "grid.max_slope_deg", v)
            })?,
            gradient_layer: matches!(rover.slip_model, SlipModel::Profile(_)),
        };
        let ud = UncertaintyModel::default();
        let model = UncertaintyModel {
            k_vo: raw.uncertainty.k_vo.map_or(Ok(ud.k_vo), |v| {
                ranges::GROWTH_M_PER_M.check(&c, "uncertainty.k_vo", v)
            })?,
            k_novo: raw.uncertainty.k_novo.map_or(Ok(ud.k_novo), |v| {
                ranges::GROWTH_M_PER_M.check(&c, "uncertainty.k_novo", v)
            })?,
            initial_margin_m: raw
                .uncertainty
                .initial_margin_m
                .map_or(Ok(ud.initial_margin_m), |v| {
                    ranges::MARGIN_M.check(&c, "uncertainty.initial_margin_m", v)
                })?,
        };
        let l = raw.onboard_localization;
        let localizer_name = l.localizer.as_deref().unwrap_or("statistical");
        let kind = match localizer_name {
            "statistical" => LocalizerKind::Statistical,
            "particle" => LocalizerKind::Particle,
            "ekf" => LocalizerKind::Ekf,
            name => LocalizerKind::Imagery(Method::from_name(name).ok_or_else(|| {
                ScenarioError::field(
                    path,
                    "onboard_localization.localizer",
                    "\"statistical\", \"census\", \"ncc\", \"mi\", \"particle\" or \"ekf\"",
                    format!("{name:?}"),
                )
            })?),
        };
        // Each setting belongs to some localizers; given with another, it is refused rather
        // than silently ignored.
        const STATISTICAL: &[&str] = &["statistical"];
        const ON_HBS: &[&str] = &["census", "ncc", "mi", "particle"];
        const PARTICLE: &[&str] = &["particle"];
        const EKF: &[&str] = &["ekf"];
        let owned: [(&str, bool, &[&str]); 11] = [
            ("mean_error_m", l.mean_error_m.is_some(), STATISTICAL),
            ("p99_error_m", l.p99_error_m.is_some(), STATISTICAL),
            ("failure_rate", l.failure_rate.is_some(), STATISTICAL),
            (
                "reported_sigma_m",
                l.reported_sigma_m.is_some(),
                STATISTICAL,
            ),
            ("hbs_slowdown", l.hbs_slowdown.is_some(), ON_HBS),
            ("particle_count", l.particle_count.is_some(), PARTICLE),
            ("resampling", l.resampling.is_some(), PARTICLE),
            ("range_sigma_m", l.range_sigma_m.is_some(), EKF),
            ("pass_duration_s", l.pass_duration_s.is_some(), EKF),
            ("elevation_mask_deg", l.elevation_mask_deg.is_some(), EKF),
            ("image_resolution_m", l.image_resolution_m.is_some(), EKF),
        ];
        for (field, given, owners) in owned {
            if given && !owners.contains(&localizer_name) {
                return Err(ScenarioError::field(
                    path,
                    format!("onboard_localization.{field}"),
                    format!(
                        "no value: it sets the {} localizer{} only",
                        owners.join(", "),
                        if owners.len() > 1 { "s" } else { "" }
                    ),
                    format!("a value with localizer = {localizer_name:?}"),
                ));
            }
        }
        let hbs_slowdown = l
            .hbs_slowdown
            .map_or(Ok(OnboardSettings::default().hbs_slowdown), |v| {
                ranges::HBS_SLOWDOWN.check(&c, "onboard_localization.hbs_slowdown", v)
            })?;
        let mut particle = ParticleParams::default();
        if let Some(n) = l.particle_count {
            if !(MIN_PARTICLES..=MAX_PARTICLES).contains(&n) {
                return Err(ScenarioError::field(
                    path,
                    "onboard_localization.particle_count",
                    format!("{MIN_PARTICLES} ..= {MAX_PARTICLES} particles"),
                    n,
                ));
            }
            particle.particle_count = n as usize;
        }
        if let Some(r) = &l.resampling {
            particle.resampling = match r.as_str() {
                "systematic" => Resampling::Systematic,
                "kld" => Resampling::Kld(KldParams::default()),
                other => {
                    return Err(ScenarioError::field(
                        path,
                        "onboard_localization.resampling",
                        "\"systematic\" or \"kld\"",
                        format!("{other:?}"),
                    ));
                }
            };
        }
        let pd = ParkedSettings::default();
        let ekf = ParkedSettings {
            range_sigma_m: l.range_sigma_m.map_or(Ok(pd.range_sigma_m), |v| {
                ranges::RANGE_SIGMA_M.check(&c, "onboard_localization.range_sigma_m", v)
            })?,
            pass_duration_s: match l.pass_duration_s {
                None => pd.pass_duration_s,
                Some(v) if (60..=MAX_PASS_S).contains(&v) => v,
                Some(v) => {
                    return Err(ScenarioError::field(
                        path,
                        "onboard_localization.pass_duration_s",
                        format!("60 ..= {MAX_PASS_S} seconds"),
                        v,
                    ));
                }
            },
            elevation_mask_deg: l
                .elevation_mask_deg
                .map_or(Ok(pd.elevation_mask_deg), |v| {
                    c.in_range(
                        "onboard_localization.elevation_mask_deg",
                        v,
                        0.0,
                        80.0,
                        "degrees",
                    )
                })?,
            image_resolution_m: l
                .image_resolution_m
                .map(|v| {
                    ranges::IMAGE_RESOLUTION_M.check(
                        &c,
                        "onboard_localization.image_resolution_m",
                        v,
                    )
                })
                .transpose()?,
            ..pd
        };
        let hbs_link_bytes_per_s = 1_000.0
            * l.hbs_link_rate_kb_per_s
                .map_or(Ok(DEFAULT_HBS_LINK_RATE_KB_PER_S), |v| {
                    ranges::HBS_LINK_RATE_KB_PER_S.check(
                        &c,
                        "onboard_localization.hbs_link_rate_kb_per_s",
                        v,
                    )
                })?;
        let ld = StatisticalLocalizer::default();
        let statistical = StatisticalLocalizer {
            mean_error_m: l.mean_error_m.map_or(Ok(ld.mean_error_m), |v| {
                ranges::LOCALIZATION_ERROR_M.check(&c, "onboard_localization.mean_error_m", v)
            })?,
            p99_error_m: l.p99_error_m.map_or(Ok(ld.p99_error_m), |v| {
                ranges::LOCALIZATION_ERROR_M.check(&c, "onboard_localization.p99_error_m", v)
            })?,
            failure_rate: l.failure_rate.map_or(Ok(ld.failure_rate), |v| {
                c.fraction("onboard_localization.failure_rate", v)
            })?,
            reported_sigma_m: l.reported_sigma_m.map_or(Ok(ld.reported_sigma_m), |v| {
                ranges::MARGIN_M.check(&c, "onboard_localization.reported_sigma_m", v)
            })?,
            // The link rate is set with every localizer's, in `Scenario::build`.
            hbs: ld.hbs,
        };
        if statistical.p99_error_m <= statistical.mean_error_m * 1.05 {
            return Err(ScenarioError::field(
                path,
                "onboard_localization.p99_error_m",
                format!(
                    "more than 1.05 × mean_error_m ({} m)",
                    statistical.mean_error_m
                ),
                statistical.p99_error_m,
            ));
        }
        let operator_margin_m = l
            .operator_margin_m
            .map_or(Ok(DEFAULT_OPERATOR_MARGIN_M), |v| {
                ranges::MARGIN_M.check(&c, "onboard_localization.operator_margin_m", v)
            })?;
        let ops = raw.operations;
        let drive_start = c.lmst(
            "operations.drive_start_lmst",
            ops.drive_start_lmst
                .as_deref()
                .unwrap_or(DEFAULT_DRIVE_START),
        )?;
        let drive_end = c.lmst(
            "operations.drive_end_lmst",
            ops.drive_end_lmst.as_deref().unwrap_or(DEFAULT_DRIVE_END),
        )?;
        if drive_end <= drive_start {
            return Err(ScenarioError::field(
                path,
                "operations.drive_end_lmst",
                format!("a time after drive_start_lmst ({})", drive_start.lmst()),
                drive_end.lmst(),
            ));
        }

        // Calendar.
        if raw.sols.len() > MAX_SOLS {
            return Err(ScenarioError::field(
                path,
                "sols",
                format!("at most {MAX_SOLS} [[sols]] entries"),
                raw.sols.len(),
            ));
        }
        if raw.sols.is_empty() {
            return Err(ScenarioError::field(
                path,
                "sols",
                "at least one [[sols]] entry",
                "none",
            ));
        }
        let computed_calendar = match &raw.calendar {
            None => None,
            Some(cal) => Some(computed_calendar(&c, cal, &raw.sols)?),
        };
        let mut sols = Vec::with_capacity(raw.sols.len());
        let mut notes = Vec::new();
        let mut historic_sources = Vec::new();
        let mut has_history = false;
        for (i, s) in raw.sols.iter().enumerate() {
            let f = |name: &str| format!("sols[{i}].{name}");
            // In u64: the sol before may be u32::MAX.
            let next_sol = i.checked_sub(1).map(|p| u64::from(raw.sols[p].sol) + 1);
            if next_sol.is_some_and(|next| u64::from(s.sol) != next) {
                return Err(ScenarioError::field(
                    path,
                    f("sol"),
                    format!(
                        "sol {} (sols are consecutive)",
                        next_sol.unwrap_or_default()
                    ),
                    s.sol,
                ));
            }
            let computed = computed_calendar.as_ref().and_then(|cc| cc.sols.get(i));
            // The first sol's plan was uplinked before the range, if not on it.
            let uplink = s
                .uplink
                .unwrap_or_else(|| computed.is_none_or(|cs| cs.uplink || i == 0));
            if i == 0 && !uplink {
                return Err(ScenarioError::field(
                    path,
                    f("uplink"),
                    "true (the first sol starts a plan)",
                    "false",
                ));
            }
            let historic_planning = match s.historic_planning.as_deref() {
                None => None,
                Some("ground") => Some(Planning::Ground),
                Some("extension") => Some(Planning::Extension),
                Some(other) => {
                    return Err(ScenarioError::field(
                        path,
                        f("historic_planning"),
                        "\"ground\" or \"extension\"",
                        format!("{other:?}"),
                    ));
                }
            };
            if historic_planning.is_some() && !uplink {
                return Err(ScenarioError::field(
                    path,
                    f("historic_planning"),
                    "only on a sol with an uplink",
                    "a sol without one",
                ));
            }
            let historic = match (s.historic_distance_m, s.historic_novo_m) {
                (None, None) if s.historic_fault.is_none() => None,
                (Some(dist), novo) => {
                    let dist = ranges::SOL_DRIVE_M.check(&c, &f("historic_distance_m"), dist)?;
                    let novo = ranges::SOL_DRIVE_M.check(
                        &c,
                        &f("historic_novo_m"),
                        novo.unwrap_or(0.0),
                    )?;
                    if novo > dist {
                        return Err(ScenarioError::field(
                            path,
                            f("historic_novo_m"),
                            format!("at most historic_distance_m ({dist} m)"),
                            novo,
                        ));
                    }
                    let ended_in_fault = match s.historic_fault.as_deref() {
                        None => false,
                        Some("NO_PATH" | "KEEP_OUT" | "KEEP_IN") => true,
                        Some(other) => {
                            return Err(ScenarioError::field(
                                path,
                                f("historic_fault"),
                                "\"NO_PATH\", \"KEEP_OUT\" or \"KEEP_IN\"",
                                format!("{other:?}"),
                            ));
                        }
                    };
                    Some(HistoricSol {
                        distance_m: dist,
                        novo_m: novo,
                        ended_in_fault,
                    })
                }
                (None, _) => {
                    return Err(ScenarioError::field(
                        path,
                        f("historic_distance_m"),
                        "a distance whenever historic_novo_m or historic_fault is given",
                        "nothing",
                    ));
                }
            };
            has_history |= historic.is_some();
            let downlink_lmst = s
                .downlink_lmst
                .as_deref()
                .map(|t| c.lmst(&f("downlink_lmst"), t))
                .transpose()?;
            if !s.note.is_empty() {
                notes.push((s.sol, s.note.clone()));
            }
            if let Some(source) = &s.historic_source {
                if historic.is_none() {
                    return Err(ScenarioError::field(
                        path,
                        f("historic_source"),
                        "only with historic_distance_m",
                        format!("{source:?}"),
                    ));
                }
                historic_sources.push((s.sol, source.clone()));
            }
            let window = match (&s.historic_drive_start_lmst, &s.historic_drive_end_lmst) {
                (None, None) => None,
                (start, Some(end)) => {
                    let end = c.lmst(&f("historic_drive_end_lmst"), end)?;
                    let start = match start {
                        Some(t) => c.lmst(&f("historic_drive_start_lmst"), t)?,
                        None => drive_start,
                    };
                    if end <= start {
                        return Err(ScenarioError::field(
                            path,
                            f("historic_drive_end_lmst"),
                            format!("a time after the drive's start ({})", start.lmst()),
                            end.lmst(),
                        ));
                    }
                    Some((start, end))
                }
                (Some(_), None) => {
                    return Err(ScenarioError::field(
                        path,
                        f("historic_drive_end_lmst"),
                        "the end of the window whenever historic_drive_start_lmst is given",
                        "nothing",
                    ));
                }
            };
            // The sol's own AutoNav rate: the record's distance over its whole window, for a
            // historic drive that ended without a fault (its terrain and plan set the pace).
            let drive_rate_m_per_h = match (historic, &s.historic_drive_start_lmst, window) {
                (Some(h), Some(_), Some((start, end)))
                    if h.distance_m > 0.0 && !h.ended_in_fault =>
                {
                    Some(h.distance_m / ((end - start) as f64 / 3600.0))
                }
                _ => None,
            };
            sols.push(SolEntry {
                sol: s.sol,
                uplink,
                restricted: s
                    .restricted
                    .unwrap_or_else(|| computed.is_some_and(|cs| cs.restricted && uplink)),
                downlink: s.downlink.unwrap_or(true),
                downlink_lmst,
                drive_allowed: s.drive.unwrap_or(true),
                window,
                drive_rate_m_per_h,
                historic_planning,
                historic,
            });
        }
        let calendar = Calendar {
            sols,
            drive_start,
            drive_end,
        };

        // Map files, georeference, route: everything that does not need the maps read.
        let resolve = |p: &Path| {
            if p.is_absolute() {
                p.to_path_buf()
            } else {
                base.join(p)
            }
        };
        let georef = match (raw.map.resolution_m_per_px, raw.map.origin_m) {
            (None, None) => None,
            (Some(res), Some(raw::Pair(o))) => {
                ranges::MAP_RESOLUTION_M_PER_PX.check(&c, "map.resolution_m_per_px", res)?;
                for (i, v) in o.iter().enumerate() {
                    ranges::COORDINATE_M.check(&c, &format!("map.origin_m[{i}]"), *v)?;
                }
                Some(GeoTransform::new(o[0], o[1], res))
            }
            (Some(_), None) => {
                return Err(ScenarioError::field(
                    path,
                    "map.origin_m",
                    "[x, y] of the north-west corner, given with resolution_m_per_px",
                    "nothing",
                ));
            }
            (None, Some(_)) => {
                return Err(ScenarioError::field(
                    path,
                    "map.resolution_m_per_px",
                    "metres per pixel, given with origin_m",
                    "nothing",
                ));
            }
        };
        ranges::DEM_DATUM_M.check(&c, "map.dem_datum_m", raw.map.dem_datum_m)?;
        let map = MapFiles {
            appearance: resolve(&raw.map.appearance),
            dem: resolve(&raw.map.dem),
            terrain: resolve(&raw.map.terrain),
            zones: resolve(&raw.map.zones),
            dem_datum_m: raw.map.dem_datum_m,
            georef,
        };
        if !(2..=campaign::MAX_WAYPOINTS).contains(&raw.route.waypoints.len()) {
            return Err(ScenarioError::field(
                path,
                "route.waypoints",
                format!(
                    "2 ..= {} waypoints (the start and a goal at least)",
                    campaign::MAX_WAYPOINTS
                ),
                raw.route.waypoints.len(),
            ));
        }
        let waypoints: Vec<[f64; 2]> = raw.route.waypoints.iter().map(|w| w.0).collect();
        for (i, w) in waypoints.iter().enumerate() {
            for (k, v) in w.iter().enumerate() {
                ranges::COORDINATE_M.check(&c, &format!("route.waypoints[{i}][{k}]"), *v)?;
            }
        }
        // Positions are checked against the map's extent when it is read ([`Scenario::build`]).
        let science = crate::science::resolve_science(
            path,
            &raw.science,
            &|p| p.iter().all(|v| ranges::COORDINATE_M.contains(*v)),
            &format!("|x|, |y| ≤ {} m", ranges::COORDINATE_M.max),
        )?;
        let campaign_ids: Vec<&str> = science.campaign_ids().collect();
        let mut expectations = Vec::new();
        let mut statistical_expectations = Vec::new();
        for (i, e) in raw.expect.into_iter().enumerate() {
            match e.resolve(path, i, &calendar, &campaign_ids)? {
                crate::expect::Resolved::Run(e) => expectations.push(e),
                crate::expect::Resolved::Sweep(e) => statistical_expectations.push(e),
            }
        }
        let study_segment = match raw.study_segment {
            None => None,
            Some(g) => {
                if !calendar.sols.iter().any(|s| s.sol == g.from_sol) {
                    return Err(ScenarioError::field(
                        path,
                        "study_segment.from_sol",
                        "a sol of the calendar",
                        g.from_sol,
                    ));
                }
                ranges::STUDY_SEGMENT_M.check(&c, "study_segment.distance_m", g.distance_m)?;
                Some(StudySegment {
                    from_sol: g.from_sol,
                    distance_m: g.distance_m,
                })
            }
        };
        let post_drive_imaging_s = ops
            .post_drive_imaging_s
            .unwrap_or(DEFAULT_POST_DRIVE_IMAGING_S);
        if post_drive_imaging_s > SOL_S {
            return Err(ScenarioError::field(
                path,
                "operations.post_drive_imaging_s",
                format!("at most a sol ({SOL_S} s)"),
                post_drive_imaging_s,
            ));
        }
        let defaults = sim::policy::OperationsRules::default();
        let sols_field = |field: &str, v: Option<u32>, default: u32| {
            let v = v.unwrap_or(default);
            if v == 0 || v as usize > MAX_SOLS {
                Err(ScenarioError::field(
                    path,
                    format!("operations.{field}"),
                    format!("1 ..= {MAX_SOLS} sols"),
                    v,
                ))
            } else {
                Ok(v)
            }
        };
        let rules = sim::policy::OperationsRules {
            max_extension_sols: ops
                .max_extension_sols
                .map(|v| sols_field("max_extension_sols", Some(v), v))
                .transpose()?,
            max_drive_sols_per_plan: sols_field(
                "max_drive_sols_per_plan",
                ops.max_drive_sols_per_plan,
                defaults.max_drive_sols_per_plan,
            )?,
            extension_plan_sols: sols_field(
                "extension_plan_sols",
                ops.extension_plan_sols,
                defaults.extension_plan_sols,
            )?,
            passage_margin_m: ops
                .passage_margin_m
                .map_or(Ok(defaults.passage_margin_m), |v| {
                    ranges::MARGIN_M.check(&c, "operations.passage_margin_m", v)
                })?,
            preemptive_shortening: ops
                .preemptive_shortening
                .unwrap_or(defaults.preemptive_shortening),
            ground_extension_sols: match ops.ground_extension_sols {
                Some(0) => 0,
                v => sols_field("ground_extension_sols", v, defaults.ground_extension_sols)?,
            },
            ground_lookahead_plans: match ops.ground_lookahead_plans {
                Some(v) if !(1..=12).contains(&v) => {
                    return Err(ScenarioError::field(
                        path,
                        "operations.ground_lookahead_plans",
                        "1 ..= 12 plans",
                        v,
                    ));
                }
                v => v.unwrap_or(defaults.ground_lookahead_plans),
            },
        };
        Ok(ScenarioSpec {
            path: path.to_path_buf(),
            name: raw.name,
            description: raw.description,
            sha256,
            seed: raw.seed,
            map,
            grid: grid_params,
            route: waypoints,
            calendar,
            rover,
            model,
            hbs_link_bytes_per_s,
            localizer: match kind {
                LocalizerKind::Statistical => LocalizerSpec::Statistical(statistical),
                LocalizerKind::Imagery(method) => LocalizerSpec::Imagery {
                    method,
                    hbs_slowdown,
                },
                LocalizerKind::Particle => LocalizerSpec::Particle {
                    params: particle,
                    hbs_slowdown,
                },
                LocalizerKind::Ekf => LocalizerSpec::Ekf(ekf),
            },
            operator_margin_m,
            post_drive_imaging_s,
            rules,
            science,
            expectations,
            statistical_expectations,
            study_segment,
            notes,
            has_history,
            computed_calendar,
            historic_sources,
        })
    }
}

/// Largest sol a computed calendar covers (Mars time is good for any; this bounds the work).
const MAX_COMPUTED_SOL: u32 = 20_000;

/// `"HH:MM"` in Pasadena as hours after midnight.
fn pasadena_clock(c: &Check<'_>, field: &str, v: &str) -> Result<f64, ScenarioError> {
    sim::time::SolSeconds::parse_lmst(v)
        .filter(|_| v < "24:00")
        .map(|_| {
            let (h, m) = v.split_at(2);
            f64::from(h.parse::<u32>().unwrap_or(0))
                + f64::from(m[1..].parse::<u32>().unwrap_or(0)) / 60.0
        })
        .ok_or_else(|| {
            c.err(
                field,
                "a time of day in Pasadena \"HH:MM\", 00:00 to 23:59",
                format!("{v:?}"),
            )
        })
}

/// The `[calendar]` table: the team's rules (defaults of [`TeamRules::for_mission`] where not
/// given), computed over the scenario's sols, with the typed `uplink` / `restricted` values
/// of `[[sols]]` recorded as overrides.
fn computed_calendar(
    c: &Check<'_>,
    raw: &raw::RawCalendar,
    sols: &[raw::RawSol],
) -> Result<ComputedCalendar, ScenarioError> {
    use sim::ops_calendar::TeamRules;
    if raw.mission != "mars2020" {
        return Err(c.err(
            "calendar.mission",
            "\"mars2020\" (the mission whose Mars time and landing sol solsim knows)",
            format!("{:?}", raw.mission),
        ));
    }
    let Some(first) = sols.first() else {
        return Err(c.err("sols", "at least one [[sols]] entry", "none"));
    };
    let mut rules = TeamRules::for_mission(sim::mars_time::MARS_2020, 2020..=2040);
    if let Some(t) = &raw.uplink_lmst {
        rules.uplink_lmst = c.lmst("calendar.uplink_lmst", t)?;
    }
    if let Some(t) = &raw.relay_pass_lmst {
        rules.relay_pass_lmst = c.lmst("calendar.relay_pass_lmst", t)?;
    }
    if let Some(v) = raw.relay_latency_h {
        rules.relay_latency_h = ranges::CALENDAR_HOURS.check(c, "calendar.relay_latency_h", v)?;
    }
    if let Some(v) = raw.light_time_min {
        rules.light_time_min = ranges::LIGHT_TIME_MIN.check(c, "calendar.light_time_min", v)?;
    }
    if let Some(v) = raw.shift_hours {
        rules.shift_hours = ranges::CALENDAR_HOURS.check(c, "calendar.shift_hours", v)?;
    }
    if let Some(t) = &raw.shift_earliest_start_pt {
        rules.shift_earliest_start_pt_h = pasadena_clock(c, "calendar.shift_earliest_start_pt", t)?;
    }
    if let Some(t) = &raw.shift_latest_start_pt {
        rules.shift_latest_start_pt_h = pasadena_clock(c, "calendar.shift_latest_start_pt", t)?;
    }
    if rules.shift_latest_start_pt_h < rules.shift_earliest_start_pt_h {
        return Err(c.err(
            "calendar.shift_latest_start_pt",
            "a time at or after shift_earliest_start_pt",
            format!("{:.2} h", rules.shift_latest_start_pt_h),
        ));
    }
    for (i, d) in raw.holidays.iter().enumerate() {
        let day = sim::earth_time::Utc::parse_iso(&format!("{d}T12:00:00Z"))
            .filter(|_| d.len() == 10)
            .ok_or_else(|| {
                c.err(
                    &format!("calendar.holidays[{i}]"),
                    "a date \"YYYY-MM-DD\"",
                    format!("{d:?}"),
                )
            })?;
        rules.holidays.push(day.civil_day(0.0));
    }
    if let Some((i, s)) = sols
        .iter()
        .enumerate()
        .find(|(_, s)| s.sol > MAX_COMPUTED_SOL)
    {
        return Err(c.err(
            &format!("sols[{i}].sol"),
            format!("a sol within {MAX_COMPUTED_SOL} of landing for a computed calendar"),
            s.sol,
        ));
    }
    // One computed sol per entry from the first on: entries that are not consecutive are the
    // calendar's error, reported in order by the caller.
    let count = u32::try_from(sols.len()).unwrap_or(u32::MAX);
    let computed = rules.compute(first.sol..=first.sol.saturating_add(count - 1));
    let overrides = sols
        .iter()
        .flat_map(|s| {
            [
                s.uplink.map(|v| (s.sol, "uplink", v)),
                s.restricted.map(|v| (s.sol, "restricted", v)),
                s.downlink.map(|v| (s.sol, "downlink", v)),
                s.drive.map(|v| (s.sol, "drive", v)),
            ]
        })
        .flatten()
        .collect();
    Ok(ComputedCalendar {
        rules,
        sols: computed,
        overrides,
    })
}

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
    /// with its first [`crate::sanity::Severity::Error`]; [`Scenario::inspect_within`] lists
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
        match findings
            .iter()
            .find(|f| f.severity == crate::sanity::Severity::Error)
        {
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
    ) -> Result<(Self, Vec<crate::sanity::Finding>), ScenarioError> {
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
    ) -> Result<(Self, Vec<crate::sanity::Finding>), ScenarioError> {
        let scenario = Self::build_observed(ScenarioSpec::load(path)?, budget, on_leg)?;
        let findings = crate::sanity::findings(&scenario);
        Ok((scenario, findings))
    }

    /// Reads the maps and zones a validated [`ScenarioSpec`] names, checks the route and the
    /// science targets against the map, and builds the planning grid and leg clearances.
    ///
    /// # Errors
    /// A [`ScenarioError`] naming the file and the field at fault.
    pub fn build(spec: ScenarioSpec, budget: MemoryBudget) -> Result<Self, ScenarioError> {
        Self::build_observed(spec, budget, &|_, _| {})
    }

    /// [`Scenario::build`] with progress over the legs, as [`Scenario::inspect_observed`].
    ///
    /// # Errors
    /// As [`Scenario::build`].
    pub fn build_observed(
        spec: ScenarioSpec,
        budget: MemoryBudget,
        on_leg: &(dyn Fn(u64, u64) + Sync),
    ) -> Result<Self, ScenarioError> {
        let path = spec.path.as_path();
        let m = &spec.map;
        let map_error = |field: &str, source: maps::RasterError| ScenarioError::Map {
            path: path.to_path_buf(),
            field: field.to_string(),
            source: Box::new(source),
        };
        for (field, p) in [
            ("map.appearance", &m.appearance),
            ("map.dem", &m.dem),
            ("map.terrain", &m.terrain),
            ("map.zones", &m.zones),
        ] {
            if let Err(e) = maps::input_file::regular_file_len(p) {
                return Err(ScenarioError::field(
                    path,
                    field,
                    "an existing regular file (paths are relative to the scenario file)",
                    format!("{} ({e})", p.display()),
                ));
            }
        }
        // The memory the command will hold, before anything is decoded: each layer as read
        // (from its header: appearance and terrain u8; the DEM f32 plus its 16-bit decode
        // buffer and its slope layer), one planning grid, and one search per thread of the pool
        // that runs the strategies (grid size from the DEM's extent). Over the budget, the
        // largest item is named.
        let mut items: Vec<BudgetItem<'_>> = Vec::new();
        let mut dem_extent_m = None;
        for (field, p, bytes_per_px) in [
            ("map.appearance", &m.appearance, 1),
            ("map.dem", &m.dem, 10),
            ("map.terrain", &m.terrain, 1),
        ] {
            let h = maps::raster_io::read_header(p).map_err(|e| map_error(field, e))?;
            if field == "map.dem" {
                let res = m.georef.map(|g| g.resolution_m_per_px).or(h.pixel_size_m);
                dem_extent_m = res.map(|r| [h.width as f64 * r, h.height as f64 * r]);
            }
            items.push((field, h.bytes_as(bytes_per_px), Some((p.as_path(), h))));
        }
        let gradient = if spec.grid.gradient_layer {
            GridParams::GRADIENT_BYTES_PER_CELL
        } else {
            0
        };
        let per_cell = (PlanningGrid::BYTES_PER_CELL + gradient).saturating_add(
            PlanningGrid::SEARCH_BYTES_PER_CELL.saturating_mul(rayon::current_num_threads() as u64),
        );
        let grid_bytes = |extent_m: [f64; 2]| {
            let cells = PlanningGrid::cells_for(extent_m, spec.grid.resolution_m);
            (cells, maps::memory_budget::bytes_of(&[cells, per_cell]))
        };
        let grid_error = |extent_m: [f64; 2], total: u64| {
            let (cells, _) = grid_bytes(extent_m);
            ScenarioError::field(
                path,
                "grid.resolution_m",
                format!(
                    "a cell size whose planning grid fits the memory budget with the maps \
                     ({}; --memory-budget-mib)",
                    maps::input_file::human_bytes(budget.limit_bytes)
                ),
                format!(
                    "{} m: {cells} cells over {:.0} × {:.0} m need {}",
                    spec.grid.resolution_m,
                    extent_m[0],
                    extent_m[1],
                    maps::input_file::human_bytes(total)
                ),
            )
        };
        if let Some(extent_m) = dem_extent_m {
            items.push(("grid.resolution_m", grid_bytes(extent_m).1, None));
        }
        let total = items.iter().fold(0u64, |t, i| t.saturating_add(i.1));
        if !budget.allows(total) {
            let largest = items
                .iter()
                .max_by_key(|i| i.1)
                .expect("three layers at least");
            return Err(match (largest.2, dem_extent_m) {
                (Some((p, h)), _) => map_error(largest.0, h.over_budget(p, largest.1, budget)),
                (None, Some(extent_m)) => grid_error(extent_m, total),
                (None, None) => unreachable!("the grid item needs the DEM extent"),
            });
        }
        let layers = MapLayers::load(&m.appearance, &m.dem, &m.terrain, m.dem_datum_m, m.georef)
            .map_err(|source| {
                // Name the layer the error is about; a mismatch between layers names `map`.
                let field = [
                    ("map.appearance", &m.appearance),
                    ("map.dem", &m.dem),
                    ("map.terrain", &m.terrain),
                ]
                .into_iter()
                .find(|(_, p)| p.as_path() == source.path())
                .map_or("map", |(f, _)| f);
                map_error(field, source)
            })?;
        let map_crs = match m.georef {
            Some(_) => maps::MapCrs::Local,
            None => maps::raster_io::read_map_crs(&m.appearance)
                .map_err(|e| map_error("map.appearance", e))?,
        };
        let (x0, y0, x1, y1) = layers.dem.extent_m();
        let mut total = total;
        if dem_extent_m.is_none() {
            // A DEM placed by neither the scenario nor its own tags: its grid is known only now.
            let extent_m = [x1 - x0, y1 - y0];
            total = total.saturating_add(grid_bytes(extent_m).1);
            if !budget.allows(total) {
                return Err(grid_error(extent_m, total));
            }
        }
        // The zones' geometry counts too: refused from its vertex and polygon counts, before
        // it is converted, if it does not fit beside the maps and grid.
        let zones = ZoneSet::load_within(&m.zones, budget, total).map_err(|source| {
            ScenarioError::Zones {
                path: path.to_path_buf(),
                source: Box::new(source),
            }
        })?;

        let extent = format!("x {x0:.1}..{x1:.1} m, y {y0:.1}..{y1:.1} m");
        for (i, t) in spec.science.targets.iter().enumerate() {
            let [x, y] = t.position_m;
            if !layers.dem.contains_point(x, y) {
                return Err(ScenarioError::field(
                    path,
                    format!("science.targets[{i}].position_m"),
                    format!("a point on the map ({extent})"),
                    format!("[{x}, {y}]"),
                ));
            }
        }
        let grid = Arc::new(PlanningGrid::build(&zones, &layers, &spec.grid));
        // Waypoints are on the map when they are in a grid cell: the simulator places them in
        // cells, and a point within rounding of the map's south or east edge (y = 1e-60 over
        // y0 = 0) passes `contains_point` yet lies in no cell.
        if let Some(i) = spec.route.iter().position(|w| grid.cell_of(*w).is_none()) {
            let w = spec.route[i];
            return Err(ScenarioError::field(
                path,
                format!("route.waypoints[{i}]"),
                format!("a point on the map ({extent})"),
                format!("[{}, {}]", w[0], w[1]),
            ));
        }
        let layers = Arc::new(layers);
        let mut inputs_sha256 = Vec::new();
        for (field, p) in [
            ("map.appearance", &m.appearance),
            ("map.dem", &m.dem),
            ("map.terrain", &m.terrain),
            ("map.zones", &m.zones),
        ] {
            // Read already (and within the budget) to build the layers and zones.
            let bytes = maps::input_file::read_input(p, u64::MAX, maps::input_file::Follow::Yes)
                .map_err(|e| {
                    ScenarioError::field(
                        path,
                        field,
                        "a readable file",
                        format!("{} ({e})", p.display()),
                    )
                })?;
            inputs_sha256.push((field, p.clone(), crate::input::sha256_hex(&bytes)));
        }
        let mut localizer = match spec.localizer {
            LocalizerSpec::Statistical(statistical) => OnboardLocalizer::Statistical(statistical),
            LocalizerSpec::Imagery {
                method,
                hbs_slowdown,
            } => {
                let mut imagery = ImageryLocalizer::new(Arc::clone(&layers), method);
                imagery.settings.hbs_slowdown = hbs_slowdown;
                OnboardLocalizer::Imagery(Box::new(imagery))
            }
            LocalizerSpec::Particle {
                params,
                hbs_slowdown,
            } => {
                let mut particle = ParticleLocalizer::new(Arc::clone(&layers));
                particle.fix.params = params;
                particle.settings.hbs_slowdown = hbs_slowdown;
                OnboardLocalizer::Particle(Box::new(particle))
            }
            LocalizerSpec::Ekf(settings) => OnboardLocalizer::Ekf(EkfLocalizer {
                settings,
                ..EkfLocalizer::default()
            }),
        };
        localizer.set_link_bytes_per_s(spec.hbs_link_bytes_per_s);
        let campaign = Campaign {
            name: spec.name.clone(),
            seed: spec.seed,
            route: spec.route,
            calendar: spec.calendar,
            rover: spec.rover,
            model: spec.model,
            localizer,
            operator_margin_m: spec.operator_margin_m,
            post_drive_imaging_s: spec.post_drive_imaging_s,
            rules: spec.rules,
            grid,
            sol_plan: sim::sol_plan::SolPlanParams {
                imaging_s: i64::from(spec.post_drive_imaging_s),
                ..sim::sol_plan::SolPlanParams::default()
            },
            science: spec.science,
        };
        campaign
            .validate()
            .map_err(|source| ScenarioError::Campaign {
                path: path.to_path_buf(),
                source,
            })?;
        // The leg searches' time grows with the cells of their windows: refused over the cap
        // before they run.
        let search_cells = campaign::leg_search_cells(&campaign.grid, &campaign.route);
        if search_cells > campaign::MAX_LEG_SEARCH_CELLS {
            return Err(ScenarioError::field(
                path,
                "route.waypoints",
                format!(
                    "a route whose legs' passage searches (each leg's box and {} m around it) \
                     cover at most {} grid cells together",
                    campaign::LEG_WINDOW_MARGIN_M,
                    campaign::MAX_LEG_SEARCH_CELLS
                ),
                format!(
                    "{} legs covering {search_cells} cells of {} m",
                    campaign.route.len() - 1,
                    campaign.grid.geo.resolution_m_per_px
                ),
            ));
        }
        let legs_total = (campaign.route.len() - 1) as u64;
        let legs_done = std::sync::atomic::AtomicU64::new(0);
        let legs = campaign::leg_clearances_observed(&campaign, &|| {
            let done = legs_done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            on_leg(done, legs_total);
        });
        Ok(Scenario {
            path: spec.path,
            name: spec.name,
            description: spec.description,
            sha256: spec.sha256,
            campaign,
            expectations: spec.expectations,
            statistical_expectations: spec.statistical_expectations,
            study_segment: spec.study_segment,
            notes: spec.notes,
            computed_calendar: spec.computed_calendar,
            historic_sources: spec.historic_sources,
            has_history: spec.has_history,
            layers,
            zones: Arc::new(zones),
            legs,
            map_crs,
            inputs_sha256,
        })
    }

    /// The scenario's own seed (`seed` in the file): the one `solsim run` and `compare` use.
    #[must_use]
    pub fn seed(&self) -> u64 {
        self.campaign.seed
    }

    /// Runs `strategy` under `seed`. Nothing is read or rebuilt: the maps, zones, planning grid
    /// and leg clearances are the ones loaded once, shared with every other run.
    #[must_use]
    pub fn run(&self, strategy: Strategy, seed: u64) -> CampaignOutcome {
        let reseeded = Campaign {
            seed,
            ..self.campaign.clone()
        };
        campaign::run_campaign(&reseeded, strategy, &self.legs)
    }

    /// Runs `strategy` as run `run` of a study ([`sim::seeds::run_seed`]: run 0 is the scenario's
    /// own seed). Every strategy of one run index sees the same world.
    #[must_use]
    pub fn run_index(&self, strategy: Strategy, run: u64) -> CampaignOutcome {
        self.run(strategy, sim::seeds::run_seed(self.seed(), run))
    }

    /// Runs each of `strategies` under `seed`, in parallel; the outcomes come back in the order
    /// of `strategies` and do not depend on the thread count (each strategy has its own random
    /// stream).
    #[must_use]
    pub fn compare(&self, strategies: &[Strategy], seed: u64) -> Vec<CampaignOutcome> {
        strategies.par_iter().map(|&s| self.run(s, seed)).collect()
    }

    /// Runs the strategies the `[[expect]]` entries need (in parallel, under the scenario's
    /// seed) and checks every entry: one list of mismatches per expectation, in file order
    /// (empty = the expectation holds).
    #[must_use]
    pub fn check_expectations(&self) -> Vec<Vec<Mismatch>> {
        let mut needed: Vec<Strategy> = self
            .expectations
            .iter()
            .flat_map(Expectation::strategies)
            .collect();
        needed.sort_by_key(|s| s.stream_id());
        needed.dedup();
        let runs = self.compare(&needed, self.seed());
        let outcome = |s: Strategy| {
            let i = needed.iter().position(|&n| n == s).unwrap_or_default();
            &runs[i]
        };
        self.expectations.iter().map(|e| e.check(outcome)).collect()
    }

    /// The same scenario under another error model (the maps, zones and grid shared): what a
    /// statistical `[[expect]]` with `errors = "stress"` runs.
    #[must_use]
    pub fn with_errors(&self, errors: sim::errors::ErrorModel) -> Scenario {
        let mut s = self.clone();
        s.campaign.rover.errors = errors;
        s
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
