//! The campaign file exactly as written (serde mirror, `deny_unknown_fields`), before
//! validation.

use serde::Deserialize;

/// The file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCampaignFile {
    #[serde(default)]
    pub(super) name: String,
    #[serde(default)]
    pub(super) description: String,
    pub(super) sol: RawSol,
    #[serde(default)]
    pub(super) activities: Vec<RawActivity>,
    #[serde(default)]
    pub(super) campaigns: Vec<RawCampaign>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSol {
    pub(super) start_lmst: String,
    pub(super) end_lmst: String,
    pub(super) battery_capacity_wh: f64,
    pub(super) initial_energy_wh: f64,
    pub(super) net_recharge_w: f64,
    pub(super) data_capacity_mb: f64,
    pub(super) initial_data_mb: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawActivity {
    pub(super) id: String,
    #[serde(default)]
    pub(super) name: String,
    pub(super) duration_min: Option<f64>,
    pub(super) drive: Option<RawDrive>,
    pub(super) earliest_start_lmst: Option<String>,
    pub(super) latest_start_lmst: Option<String>,
    pub(super) power_w: f64,
    pub(super) data_mb: Option<f64>,
    pub(super) downlink_mb: Option<f64>,
    #[serde(default)]
    pub(super) preconditions: Vec<String>,
    #[serde(default)]
    pub(super) mandatory: bool,
    pub(super) campaign: Option<String>,
    pub(super) tier: Option<i64>,
    pub(super) utility: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDrive {
    pub(super) length_m: f64,
    pub(super) rate_m_per_h: f64,
    pub(super) min_segment_min: Option<f64>,
    pub(super) max_segments: Option<i64>,
    pub(super) split_at_m: Option<Vec<f64>>,
    pub(super) latest_end_lmst: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCampaign {
    pub(super) id: String,
    pub(super) intent: String,
    pub(super) tier: Option<i64>,
    pub(super) min_count: Option<i64>,
    pub(super) max_count: Option<i64>,
    pub(super) utility: f64,
    pub(super) decay: Option<f64>,
    /// goal_set only.
    pub(super) members: Option<Vec<String>>,
    /// periodic only.
    pub(super) period_min: Option<f64>,
    pub(super) tolerance_min: Option<f64>,
    pub(super) first_due_lmst: Option<String>,
    pub(super) until_lmst: Option<String>,
    /// state_based only.
    pub(super) every_m: Option<f64>,
    pub(super) tolerance_m: Option<f64>,
    /// periodic and state_based.
    pub(super) template: Option<RawTemplate>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTemplate {
    pub(super) id: Option<String>,
    #[serde(default)]
    pub(super) name: String,
    pub(super) duration_min: f64,
    pub(super) power_w: f64,
    pub(super) data_mb: Option<f64>,
    #[serde(default)]
    pub(super) preconditions: Vec<String>,
}

/// A simulator scenario's `[science]` section: targets on the map and campaign intents in the
/// campaign-file schema.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScience {
    #[serde(default)]
    pub(super) targets: Vec<RawTarget>,
    #[serde(default)]
    pub(super) campaigns: Vec<RawCampaign>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTarget {
    pub(super) id: String,
    #[serde(default)]
    pub(super) name: String,
    pub(super) position_m: [f64; 2],
    pub(super) within_m: f64,
    pub(super) duration_min: f64,
    pub(super) power_w: f64,
    pub(super) data_mb: Option<f64>,
    pub(super) revealed_sol: Option<u32>,
    pub(super) revealed_lmst: Option<String>,
}
