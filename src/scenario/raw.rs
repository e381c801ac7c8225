//! The scenario file exactly as written (serde mirror, `deny_unknown_fields`), before validation.

use std::path::PathBuf;

use serde::Deserialize;

use crate::expect::RawExpectation;

/// The file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScenario {
    pub(super) name: String,
    #[serde(default)]
    pub(super) description: String,
    pub(super) seed: u64,
    pub(super) map: RawMap,
    #[serde(default)]
    pub(super) grid: RawGrid,
    #[serde(default)]
    pub(super) rover: RawRover,
    #[serde(default)]
    pub(super) uncertainty: RawUncertainty,
    #[serde(default)]
    pub(super) onboard_localization: RawLocalizer,
    #[serde(default)]
    pub(super) operations: RawOperations,
    pub(super) route: RawRoute,
    pub(super) sols: Vec<RawSol>,
    #[serde(default)]
    pub(super) science: crate::cmd_plan::RawScience,
    #[serde(default)]
    pub(super) expect: Vec<RawExpectation>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMap {
    pub(super) appearance: PathBuf,
    pub(super) dem: PathBuf,
    pub(super) terrain: PathBuf,
    pub(super) zones: PathBuf,
    #[serde(default)]
    pub(super) dem_datum_m: f64,
    /// Needed only for PNG rasters, which carry no georeference.
    pub(super) resolution_m_per_px: Option<f64>,
    pub(super) origin_m: Option<[f64; 2]>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawGrid {
    pub(super) resolution_m: Option<f64>,
    pub(super) max_slope_deg: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPerTerrain {
    pub(super) sand: Option<f64>,
    pub(super) soil: Option<f64>,
    pub(super) bedrock: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRover {
    pub(super) footprint_radius_m: Option<f64>,
    pub(super) drive_rate_m_per_h: Option<f64>,
    pub(super) step_m: Option<f64>,
    pub(super) waypoint_tolerance_m: Option<f64>,
    pub(super) vo_success: Option<RawPerTerrain>,
    pub(super) slip_fraction: Option<RawPerTerrain>,
    pub(super) terrain_cost: Option<RawPerTerrain>,
    pub(super) vo_noise_fraction: Option<f64>,
    pub(super) heading_sigma_deg: Option<f64>,
    pub(super) edge_buffer_m: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawUncertainty {
    pub(super) k_vo: Option<f64>,
    pub(super) k_novo: Option<f64>,
    pub(super) initial_margin_m: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLocalizer {
    pub(super) localizer: Option<String>,
    pub(super) hbs_slowdown: Option<f64>,
    pub(super) mean_error_m: Option<f64>,
    pub(super) p99_error_m: Option<f64>,
    pub(super) failure_rate: Option<f64>,
    pub(super) reported_sigma_m: Option<f64>,
    pub(super) operator_margin_m: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOperations {
    pub(super) drive_start_lmst: Option<String>,
    pub(super) drive_end_lmst: Option<String>,
    pub(super) post_drive_imaging_s: Option<u32>,
    pub(super) max_extension_sols: Option<u32>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRoute {
    pub(super) waypoints: Vec<[f64; 2]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSol {
    pub(super) sol: u32,
    pub(super) uplink: Option<bool>,
    pub(super) restricted: Option<bool>,
    pub(super) downlink: Option<bool>,
    pub(super) downlink_lmst: Option<String>,
    pub(super) drive: Option<bool>,
    pub(super) historic_planning: Option<String>,
    pub(super) historic_distance_m: Option<f64>,
    pub(super) historic_novo_m: Option<f64>,
    pub(super) historic_fault: Option<String>,
    #[serde(default)]
    pub(super) note: String,
}
