//! The scenario file exactly as written (serde mirror, `deny_unknown_fields`), before validation.

use std::path::PathBuf;

use maps::PerTerrain;
use serde::Deserialize;

use crate::expect::raw::RawExpectation;
use crate::pair::Pair;

/// The file as written.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(
    title = "solsim scenario",
    description = "A solsim scenario file (TOML): map, rover, error model, operations rules, \
                   route, calendar of sols, science and [[expect]] entries. The schema checks \
                   names and types; `solsim validate` checks values, files and the whole \
                   (README, \"Input formats\")."
)]
pub struct RawScenario {
    pub(crate) name: String,
    #[serde(default)]
    pub(crate) description: String,
    pub(crate) seed: u64,
    pub(crate) map: RawMap,
    #[serde(default)]
    pub(crate) grid: RawGrid,
    #[serde(default)]
    pub(crate) rover: RawRover,
    #[serde(default)]
    pub(crate) errors: RawErrors,
    #[serde(default)]
    pub(crate) uncertainty: RawUncertainty,
    #[serde(default)]
    pub(crate) onboard_localization: RawLocalizer,
    #[serde(default)]
    pub(crate) operations: RawOperations,
    pub(crate) route: RawRoute,
    pub(crate) calendar: Option<RawCalendar>,
    pub(crate) sols: Vec<RawSol>,
    #[serde(default)]
    pub(crate) science: crate::campaign_file::raw::RawScience,
    pub(crate) study_segment: Option<RawStudySegment>,
    #[serde(default)]
    pub(crate) expect: Vec<RawExpectation>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawStudySegment {
    pub(crate) from_sol: u32,
    pub(crate) distance_m: f64,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMap {
    pub(crate) appearance: PathBuf,
    pub(crate) dem: PathBuf,
    pub(crate) terrain: PathBuf,
    pub(crate) zones: PathBuf,
    #[serde(default)]
    pub(crate) dem_datum_m: f64,
    /// Needed only for PNG rasters, which carry no georeference.
    pub(crate) resolution_m_per_px: Option<f64>,
    pub(crate) origin_m: Option<Pair>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawGrid {
    pub(crate) resolution_m: Option<f64>,
    pub(crate) max_slope_deg: Option<f64>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPerTerrain {
    pub(crate) sand: Option<f64>,
    pub(crate) soil: Option<f64>,
    pub(crate) bedrock: Option<f64>,
}

impl RawPerTerrain {
    /// The values given, `default`'s for the classes not given (none given: `default`).
    pub(crate) fn over(raw: Option<&Self>, default: PerTerrain) -> PerTerrain {
        let Some(raw) = raw else { return default };
        PerTerrain {
            sand: raw.sand.unwrap_or(default.sand),
            soil: raw.soil.unwrap_or(default.soil),
            bedrock: raw.bedrock.unwrap_or(default.bedrock),
        }
    }
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawRover {
    pub(crate) footprint_radius_m: Option<f64>,
    pub(crate) drive_rate_m_per_h: Option<f64>,
    pub(crate) step_m: Option<f64>,
    pub(crate) waypoint_tolerance_m: Option<f64>,
    pub(crate) terrain_cost: Option<RawPerTerrain>,
    pub(crate) edge_buffer_m: Option<f64>,
    pub(crate) slip_model: Option<String>,
    pub(crate) slip_aware_routing: Option<bool>,
    pub(crate) slip_limit: Option<f64>,
    pub(crate) avoid_slip_above: Option<f64>,
    pub(crate) max_tilt_deg: Option<f64>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawErrors {
    pub(crate) model: Option<String>,
    pub(crate) heading_sigma_deg: Option<f64>,
    pub(crate) vo_scale_sigma: Option<f64>,
    pub(crate) vo_noise_fraction: Option<f64>,
    pub(crate) vo_failure: Option<RawPerTerrain>,
    pub(crate) slip_fraction: Option<RawPerTerrain>,
    pub(crate) slip_sigma_relative: Option<f64>,
    pub(crate) ground_localization_sigma_m: Option<f64>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawUncertainty {
    pub(crate) k_vo: Option<f64>,
    pub(crate) k_novo: Option<f64>,
    pub(crate) initial_margin_m: Option<f64>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLocalizer {
    pub(crate) localizer: Option<String>,
    pub(crate) hbs_slowdown: Option<f64>,
    pub(crate) hbs_link_rate_kb_per_s: Option<f64>,
    pub(crate) mean_error_m: Option<f64>,
    pub(crate) p99_error_m: Option<f64>,
    pub(crate) failure_rate: Option<f64>,
    pub(crate) reported_sigma_m: Option<f64>,
    pub(crate) operator_margin_m: Option<f64>,
    pub(crate) particle_count: Option<u32>,
    pub(crate) resampling: Option<String>,
    pub(crate) range_sigma_m: Option<f64>,
    pub(crate) pass_duration_s: Option<u32>,
    pub(crate) elevation_mask_deg: Option<f64>,
    pub(crate) image_resolution_m: Option<f64>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawOperations {
    pub(crate) drive_start_lmst: Option<String>,
    pub(crate) drive_end_lmst: Option<String>,
    pub(crate) post_drive_imaging_s: Option<u32>,
    pub(crate) max_extension_sols: Option<u32>,
    pub(crate) max_drive_sols_per_plan: Option<u32>,
    pub(crate) extension_plan_sols: Option<u32>,
    pub(crate) passage_margin_m: Option<f64>,
    pub(crate) preemptive_shortening: Option<bool>,
    pub(crate) ground_extension_sols: Option<u32>,
    pub(crate) ground_lookahead_plans: Option<u32>,
}

/// `[calendar]`: uplinks and restricted sols computed from Mars time and the team's rules
/// (`sim::operations::ops_calendar`), instead of typed per sol.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCalendar {
    pub(crate) mission: String,
    pub(crate) uplink_lmst: Option<String>,
    pub(crate) relay_pass_lmst: Option<String>,
    pub(crate) relay_latency_h: Option<f64>,
    pub(crate) light_time_min: Option<f64>,
    pub(crate) shift_earliest_start_pt: Option<String>,
    pub(crate) shift_latest_start_pt: Option<String>,
    pub(crate) shift_hours: Option<f64>,
    #[serde(default)]
    pub(crate) holidays: Vec<String>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawRoute {
    pub(crate) waypoints: Vec<Pair>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSol {
    pub(crate) sol: u32,
    pub(crate) uplink: Option<bool>,
    pub(crate) restricted: Option<bool>,
    pub(crate) downlink: Option<bool>,
    pub(crate) downlink_lmst: Option<String>,
    pub(crate) drive: Option<bool>,
    pub(crate) historic_planning: Option<String>,
    pub(crate) historic_distance_m: Option<f64>,
    pub(crate) historic_novo_m: Option<f64>,
    pub(crate) historic_fault: Option<String>,
    pub(crate) historic_drive_start_lmst: Option<String>,
    pub(crate) historic_drive_end_lmst: Option<String>,
    pub(crate) historic_source: Option<String>,
    #[serde(default)]
    pub(crate) note: String,
}
