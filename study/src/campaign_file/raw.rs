//! The campaign file exactly as written (serde mirror, `deny_unknown_fields`), before
//! validation.

use serde::Deserialize;

/// The file as written.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(
    title = "solsim campaign file",
    description = "A one-sol campaign file of `solsim plan` (TOML): the sol's window, battery \
                   and data, activities and science campaigns. The schema checks names and \
                   types; `solsim plan` checks values (README, \"Campaign file format\")."
)]
pub(crate) struct RawCampaignFile {
    #[serde(default)]
    pub(crate) name: String,
    #[serde(default)]
    pub(crate) description: String,
    pub(crate) sol: RawSol,
    #[serde(default)]
    pub(crate) activities: Vec<RawActivity>,
    #[serde(default)]
    pub(crate) campaigns: Vec<RawCampaign>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSol {
    pub(crate) start_lmst: String,
    pub(crate) end_lmst: String,
    pub(crate) battery_capacity_wh: f64,
    pub(crate) initial_energy_wh: f64,
    pub(crate) net_recharge_w: f64,
    pub(crate) data_capacity_mb: f64,
    pub(crate) initial_data_mb: Option<f64>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawActivity {
    pub(crate) id: String,
    #[serde(default)]
    pub(crate) name: String,
    pub(crate) duration_min: Option<f64>,
    pub(crate) drive: Option<RawDrive>,
    pub(crate) earliest_start_lmst: Option<String>,
    pub(crate) latest_start_lmst: Option<String>,
    pub(crate) power_w: f64,
    pub(crate) data_mb: Option<f64>,
    pub(crate) downlink_mb: Option<f64>,
    #[serde(default)]
    pub(crate) preconditions: Vec<String>,
    #[serde(default)]
    pub(crate) mandatory: bool,
    pub(crate) campaign: Option<String>,
    pub(crate) tier: Option<i64>,
    pub(crate) utility: Option<f64>,
    pub(crate) timeline: Option<String>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawDrive {
    pub(crate) length_m: f64,
    pub(crate) rate_m_per_h: f64,
    pub(crate) min_segment_min: Option<f64>,
    pub(crate) max_segments: Option<i64>,
    pub(crate) split_at_m: Option<Vec<f64>>,
    pub(crate) latest_end_lmst: Option<String>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCampaign {
    pub(crate) id: String,
    pub(crate) intent: String,
    pub(crate) tier: Option<i64>,
    pub(crate) min_count: Option<i64>,
    pub(crate) max_count: Option<i64>,
    pub(crate) utility: f64,
    pub(crate) decay: Option<f64>,
    /// goal_set only.
    pub(crate) members: Option<Vec<String>>,
    /// periodic only.
    pub(crate) period_min: Option<f64>,
    pub(crate) tolerance_min: Option<f64>,
    pub(crate) first_due_lmst: Option<String>,
    pub(crate) until_lmst: Option<String>,
    /// state_based only.
    pub(crate) every_m: Option<f64>,
    pub(crate) tolerance_m: Option<f64>,
    /// periodic and state_based.
    pub(crate) template: Option<RawTemplate>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTemplate {
    pub(crate) id: Option<String>,
    #[serde(default)]
    pub(crate) name: String,
    pub(crate) duration_min: f64,
    pub(crate) power_w: f64,
    pub(crate) data_mb: Option<f64>,
    #[serde(default)]
    pub(crate) preconditions: Vec<String>,
}

/// A simulator scenario's `[science]` section: targets on the map and campaign intents in the
/// campaign-file schema.
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawScience {
    #[serde(default)]
    pub(crate) targets: Vec<RawTarget>,
    #[serde(default)]
    pub(crate) campaigns: Vec<RawCampaign>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTarget {
    pub(crate) id: String,
    #[serde(default)]
    pub(crate) name: String,
    pub(crate) position_m: crate::pair::Pair,
    pub(crate) within_m: f64,
    pub(crate) duration_min: f64,
    pub(crate) power_w: f64,
    pub(crate) data_mb: Option<f64>,
    pub(crate) revealed_sol: Option<u32>,
    pub(crate) revealed_lmst: Option<String>,
}
