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

mod raw;

use crate::expect::{Expectation, Mismatch};
use localization::matcher::Method;
use localization::onboard::OnboardSettings;
use maps::{GeoTransform, MapLayers, ZoneSet};
use raw::RawPerTerrain;
pub use raw::RawScenario;
use sim::autonav::{PerTerrain, RoverParams};
use sim::calendar::{Calendar, HistoricSol, Planning, SolEntry};
use sim::campaign::{self, Campaign};
use sim::localizer::{ImageryLocalizer, OnboardLocalizer, StatisticalLocalizer};
use sim::outcome::LegClearance;
use sim::planning_grid::{GridParams, PlanningGrid};
use sim::uncertainty::UncertaintyModel;
use sim::{CampaignOutcome, Strategy};

/// Default settings, written once: the scenario-level defaults are the library ones.
const DEFAULT_OPERATOR_MARGIN_M: f64 = 1.0;
const DEFAULT_DRIVE_START: &str = "11:00";
const DEFAULT_DRIVE_END: &str = "15:00";
const DEFAULT_POST_DRIVE_IMAGING_S: u32 = 1800;
const DEFAULT_MAX_EXTENSION_SOLS: u32 = 3;

/// A validated scenario, ready to run.
#[derive(Debug)]
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
    /// Expected outcomes checked by `solsim regress`.
    pub expectations: Vec<Expectation>,
    /// Per-sol notes from the file.
    pub notes: Vec<(u32, String)>,
    /// Whether any sol has historic data (so the `replay` strategy is meaningful).
    pub has_history: bool,
    /// The map layers (appearance, DEM, terrain class), loaded once and shared.
    pub layers: Arc<MapLayers>,
    /// The keep-in / keep-out zones, loaded once and shared.
    pub zones: Arc<ZoneSet>,
    /// The route's passage clearance per leg (independent of strategy and seed), computed once.
    pub legs: Vec<LegClearance>,
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
            Some(v) if v.is_finite() && v >= 1.0 => Ok(v),
            Some(v) => Err(ScenarioError::field(c.path, f, "a cost multiplier ≥ 1", v)),
        }
    };
    Ok(PerTerrain {
        sand: one("sand", raw.sand, default.sand)?,
        soil: one("soil", raw.soil, default.soil)?,
        bedrock: one("bedrock", raw.bedrock, default.bedrock)?,
    })
}

impl Scenario {
    /// Read, validate and resolve a scenario file (maps and zones included).
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let (raw, sha256) = crate::input::read_toml::<RawScenario>(path)?;
        Self::resolve(path, raw, sha256)
    }

    fn resolve(path: &Path, raw: RawScenario, sha256: String) -> Result<Self, ScenarioError> {
        let c = Check { path };
        let base = path.parent().unwrap_or(Path::new("."));
        if raw.name.trim().is_empty() || raw.name.contains(['/', '\\']) {
            return Err(ScenarioError::field(
                path,
                "name",
                "a non-empty name without path separators",
                format!("{:?}", raw.name),
            ));
        }

        // Rover, uncertainty, localizer, operations.
        let d = RoverParams::default();
        let r = raw.rover;
        let rover = RoverParams {
            drive_rate_m_per_h: r.drive_rate_m_per_h.map_or(Ok(d.drive_rate_m_per_h), |v| {
                c.positive("rover.drive_rate_m_per_h", v, "metres per hour")
            })?,
            step_m: r
                .step_m
                .map_or(Ok(d.step_m), |v| c.positive("rover.step_m", v, "metres"))?,
            waypoint_tolerance_m: r
                .waypoint_tolerance_m
                .map_or(Ok(d.waypoint_tolerance_m), |v| {
                    c.positive("rover.waypoint_tolerance_m", v, "metres")
                })?,
            vo_success: per_terrain(&c, "rover.vo_success", r.vo_success, d.vo_success, true)?,
            slip_fraction: per_terrain(
                &c,
                "rover.slip_fraction",
                r.slip_fraction,
                d.slip_fraction,
                true,
            )?,
            terrain_cost: per_terrain(
                &c,
                "rover.terrain_cost",
                r.terrain_cost,
                d.terrain_cost,
                false,
            )?,
            vo_noise_fraction: r.vo_noise_fraction.map_or(Ok(d.vo_noise_fraction), |v| {
                c.fraction("rover.vo_noise_fraction", v)
            })?,
            heading_sigma_deg: r.heading_sigma_deg.map_or(Ok(d.heading_sigma_deg), |v| {
                c.non_negative("rover.heading_sigma_deg", v, "degrees")
            })?,
            edge_buffer_m: r.edge_buffer_m.map_or(Ok(d.edge_buffer_m), |v| {
                c.non_negative("rover.edge_buffer_m", v, "metres")
            })?,
        };
        let gd = GridParams::default();
        let grid_params = GridParams {
            resolution_m: raw.grid.resolution_m.map_or(Ok(gd.resolution_m), |v| {
                c.positive("grid.resolution_m", v, "metres")
            })?,
            footprint_radius_m: r
                .footprint_radius_m
                .map_or(Ok(gd.footprint_radius_m), |v| {
                    c.non_negative("rover.footprint_radius_m", v, "metres")
                })?,
            max_slope_deg: raw.grid.max_slope_deg.map_or(Ok(gd.max_slope_deg), |v| {
                c.positive("grid.max_slope_deg", v, "degrees")
            })?,
        };
        let ud = UncertaintyModel::default();
        let model = UncertaintyModel {
            k_vo: raw.uncertainty.k_vo.map_or(Ok(ud.k_vo), |v| {
                c.non_negative("uncertainty.k_vo", v, "metres per metre")
            })?,
            k_novo: raw.uncertainty.k_novo.map_or(Ok(ud.k_novo), |v| {
                c.non_negative("uncertainty.k_novo", v, "metres per metre")
            })?,
            initial_margin_m: raw
                .uncertainty
                .initial_margin_m
                .map_or(Ok(ud.initial_margin_m), |v| {
                    c.non_negative("uncertainty.initial_margin_m", v, "metres")
                })?,
        };
        let l = raw.onboard_localization;
        let localizer_name = l.localizer.as_deref().unwrap_or("statistical");
        let method = match localizer_name {
            "statistical" => None,
            name => Some(Method::from_name(name).ok_or_else(|| {
                ScenarioError::field(
                    path,
                    "onboard_localization.localizer",
                    "\"statistical\", \"census\", \"ncc\" or \"mi\"",
                    format!("{name:?}"),
                )
            })?),
        };
        if method.is_some() {
            for (field, given) in [
                ("mean_error_m", l.mean_error_m.is_some()),
                ("p99_error_m", l.p99_error_m.is_some()),
                ("failure_rate", l.failure_rate.is_some()),
                ("reported_sigma_m", l.reported_sigma_m.is_some()),
            ] {
                if given {
                    return Err(ScenarioError::field(
                        path,
                        format!("onboard_localization.{field}"),
                        "no value: it sets the statistical localizer only",
                        format!("a value with localizer = {localizer_name:?}"),
                    ));
                }
            }
        } else if l.hbs_slowdown.is_some() {
            return Err(ScenarioError::field(
                path,
                "onboard_localization.hbs_slowdown",
                "no value: it sets the image-matching localizers (census, ncc, mi) only",
                "a value with localizer = \"statistical\"",
            ));
        }
        let hbs_slowdown = l
            .hbs_slowdown
            .map_or(Ok(OnboardSettings::default().hbs_slowdown), |v| {
                c.positive("onboard_localization.hbs_slowdown", v, "seconds per second")
            })?;
        let ld = StatisticalLocalizer::default();
        let statistical = StatisticalLocalizer {
            mean_error_m: l.mean_error_m.map_or(Ok(ld.mean_error_m), |v| {
                c.positive("onboard_localization.mean_error_m", v, "metres")
            })?,
            p99_error_m: l.p99_error_m.map_or(Ok(ld.p99_error_m), |v| {
                c.positive("onboard_localization.p99_error_m", v, "metres")
            })?,
            failure_rate: l.failure_rate.map_or(Ok(ld.failure_rate), |v| {
                c.fraction("onboard_localization.failure_rate", v)
            })?,
            reported_sigma_m: l.reported_sigma_m.map_or(Ok(ld.reported_sigma_m), |v| {
                c.non_negative("onboard_localization.reported_sigma_m", v, "metres")
            })?,
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
                c.non_negative("onboard_localization.operator_margin_m", v, "metres")
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
        if raw.sols.is_empty() {
            return Err(ScenarioError::field(
                path,
                "sols",
                "at least one [[sols]] entry",
                "none",
            ));
        }
        let mut sols = Vec::with_capacity(raw.sols.len());
        let mut notes = Vec::new();
        let mut has_history = false;
        for (i, s) in raw.sols.iter().enumerate() {
            let f = |name: &str| format!("sols[{i}].{name}");
            if i > 0 && s.sol != raw.sols[i - 1].sol + 1 {
                return Err(ScenarioError::field(
                    path,
                    f("sol"),
                    format!("sol {} (sols are consecutive)", raw.sols[i - 1].sol + 1),
                    s.sol,
                ));
            }
            let uplink = s.uplink.unwrap_or(true);
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
                    let dist = c.non_negative(&f("historic_distance_m"), dist, "metres")?;
                    let novo =
                        c.non_negative(&f("historic_novo_m"), novo.unwrap_or(0.0), "metres")?;
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
            sols.push(SolEntry {
                sol: s.sol,
                uplink,
                restricted: s.restricted.unwrap_or(false),
                downlink: s.downlink.unwrap_or(true),
                downlink_lmst,
                drive_allowed: s.drive.unwrap_or(true),
                historic_planning,
                historic,
            });
        }
        let calendar = Calendar {
            sols,
            drive_start,
            drive_end,
        };

        // Maps, zones, grid, route.
        let resolve = |p: &Path| {
            if p.is_absolute() {
                p.to_path_buf()
            } else {
                base.join(p)
            }
        };
        let georef = match (raw.map.resolution_m_per_px, raw.map.origin_m) {
            (None, None) => None,
            (Some(res), Some(o)) => {
                c.positive("map.resolution_m_per_px", res, "metres per pixel")?;
                c.finite("map.origin_m[0]", o[0])?;
                c.finite("map.origin_m[1]", o[1])?;
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
        c.finite("map.dem_datum_m", raw.map.dem_datum_m)?;
        for (field, p) in [
            ("map.appearance", &raw.map.appearance),
            ("map.dem", &raw.map.dem),
            ("map.terrain", &raw.map.terrain),
            ("map.zones", &raw.map.zones),
        ] {
            let full = resolve(p);
            if !full.is_file() {
                return Err(ScenarioError::field(
                    path,
                    field,
                    "an existing file (paths are relative to the scenario file)",
                    full.display(),
                ));
            }
        }
        let layers = MapLayers::load(
            &resolve(&raw.map.appearance),
            &resolve(&raw.map.dem),
            &resolve(&raw.map.terrain),
            raw.map.dem_datum_m,
            georef,
        )
        .map_err(|source| ScenarioError::Map {
            path: path.to_path_buf(),
            field: "map".into(),
            source: Box::new(source),
        })?;
        let zones =
            ZoneSet::load(&resolve(&raw.map.zones)).map_err(|source| ScenarioError::Zones {
                path: path.to_path_buf(),
                source: Box::new(source),
            })?;

        if raw.route.waypoints.len() < 2 {
            return Err(ScenarioError::field(
                path,
                "route.waypoints",
                "at least two waypoints (the start and a goal)",
                raw.route.waypoints.len(),
            ));
        }
        let (x0, y0, x1, y1) = layers.dem.extent_m();
        for (i, w) in raw.route.waypoints.iter().enumerate() {
            let field = format!("route.waypoints[{i}]");
            c.finite(&format!("{field}[0]"), w[0])?;
            c.finite(&format!("{field}[1]"), w[1])?;
            if !layers.dem.contains_point(w[0], w[1]) {
                return Err(ScenarioError::field(
                    path,
                    field,
                    format!("a point on the map (x {x0:.1}..{x1:.1} m, y {y0:.1}..{y1:.1} m)"),
                    format!("[{}, {}]", w[0], w[1]),
                ));
            }
        }
        let science = crate::science::resolve_science(
            path,
            &raw.science,
            &|p| layers.dem.contains_point(p[0], p[1]),
            &format!("x {x0:.1}..{x1:.1} m, y {y0:.1}..{y1:.1} m"),
        )?;
        let grid = Arc::new(PlanningGrid::build(&zones, &layers, &grid_params));
        let layers = Arc::new(layers);
        let post_drive_imaging_s = ops
            .post_drive_imaging_s
            .unwrap_or(DEFAULT_POST_DRIVE_IMAGING_S);
        let localizer = match method {
            None => OnboardLocalizer::Statistical(statistical),
            Some(method) => {
                let mut imagery = ImageryLocalizer::new(Arc::clone(&layers), method);
                imagery.settings.hbs_slowdown = hbs_slowdown;
                OnboardLocalizer::Imagery(Box::new(imagery))
            }
        };

        let campaign_ids: Vec<&str> = science.campaign_ids().collect();
        let expectations = raw
            .expect
            .into_iter()
            .enumerate()
            .map(|(i, e)| e.resolve(path, i, &calendar, &campaign_ids))
            .collect::<Result<Vec<_>, _>>()?;

        let campaign = Campaign {
            name: raw.name.clone(),
            seed: raw.seed,
            route: raw.route.waypoints,
            calendar,
            rover,
            model,
            localizer,
            operator_margin_m,
            post_drive_imaging_s,
            max_extension_sols: ops.max_extension_sols.unwrap_or(DEFAULT_MAX_EXTENSION_SOLS),
            grid,
            sol_plan: sim::sol_plan::SolPlanParams {
                imaging_s: i64::from(post_drive_imaging_s),
                ..sim::sol_plan::SolPlanParams::default()
            },
            science,
        };
        let legs = campaign::leg_clearances(&campaign);
        Ok(Scenario {
            path: path.to_path_buf(),
            name: raw.name.clone(),
            description: raw.description,
            sha256,
            campaign,
            expectations,
            notes,
            has_history,
            layers,
            zones: Arc::new(zones),
            legs,
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
        if seed == self.campaign.seed {
            campaign::run_campaign(&self.campaign, strategy, &self.legs)
        } else {
            let reseeded = Campaign {
                seed,
                ..self.campaign.clone()
            };
            campaign::run_campaign(&reseeded, strategy, &self.legs)
        }
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

    /// The strategies that make sense for this scenario (`replay` only with historic data).
    #[must_use]
    pub fn strategies(&self) -> Vec<sim::Strategy> {
        sim::Strategy::ALL
            .into_iter()
            .filter(|s| *s != sim::Strategy::Replay || self.has_history)
            .collect()
    }
}
