//! Settings of each drive sol's activity plan: power, durations, data volumes, the planning
//! window and the search budget (plain struct; units and defaults on each field).

use crate::settings::field_error::FieldError;
use crate::time::{SOL_S, SolSeconds};

/// Settings of the per-sol plan (plain struct; units and defaults on each field).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SolPlanSettings {
    /// Battery capacity, Wh (default: 2,400 — two ~43 Ah Li-ion batteries at ~28 V).
    pub battery_capacity_wh: f64,
    /// Battery charge when the sol's plan starts, fraction of capacity (default: 0.8).
    pub initial_charge: f64,
    /// Net recharge while idle: MMRTG output minus the idle load, W (default: 40; judgement).
    pub recharge_w: f64,
    /// Power above idle while driving, W (default: 180; judgement).
    pub drive_power_w: f64,
    /// Heating before the drive, s (default: 1,800; judgement).
    pub heating_s: i64,
    /// Heating power, W (default: 60; judgement).
    pub heating_power_w: f64,
    /// Post-drive NavCam panorama, s (default: 1,800; a scenario's `post_drive_imaging_s`).
    pub imaging_s: i64,
    /// Panorama power, W (default: 40; judgement).
    pub imaging_power_w: f64,
    /// Panorama data volume, MB (default: 150; judgement).
    pub imaging_data_mb: f64,
    /// SunFind before the localization imaging, s (default: 300; judgement).
    pub sunfind_s: i64,
    /// Co-processor power while transferring and running, W (default: 15; judgement).
    pub hbs_power_w: f64,
    /// Compare the two results and apply, s (default: 60; judgement).
    pub compare_apply_s: i64,
    /// Onboard data volume available, MB (default: 4,000; judgement).
    pub data_capacity_mb: f64,
    /// Communication pass, s (default: 600).
    pub comm_pass_s: i64,
    /// Data a pass downlinks, MB (default: 500; judgement).
    pub comm_downlink_mb: f64,
    /// Wake-up: start of the planning window, seconds after local midnight (default: 09:00
    /// LMST; earlier if the heating before the drive starts earlier).
    pub sol_start: SolSeconds,
    /// End of the planning window, seconds after local midnight (default: 17:00 LMST).
    pub sol_end: SolSeconds,
    /// Node budget of each search (deterministic; default: 20,000).
    pub node_budget: u64,
    /// How far science stops interleaved with a split drive may stretch the drive past its
    /// window, s (default: 3,600 — judgement: AutoNav drives until mid-afternoon at most).
    pub drive_stretch_s: i64,
}

impl Default for SolPlanSettings {
    fn default() -> Self {
        Self {
            battery_capacity_wh: 2_400.0,
            initial_charge: 0.8,
            recharge_w: 40.0,
            drive_power_w: 180.0,
            heating_s: 1_800,
            heating_power_w: 60.0,
            imaging_s: 1_800,
            imaging_power_w: 40.0,
            imaging_data_mb: 150.0,
            sunfind_s: 300,
            hbs_power_w: 15.0,
            compare_apply_s: 60,
            data_capacity_mb: 4_000.0,
            comm_pass_s: 600,
            comm_downlink_mb: 500.0,
            sol_start: SolSeconds(33_291), // 09:00 LMST
            sol_end: SolSeconds(62_882),   // 17:00 LMST
            node_budget: 20_000,
            drive_stretch_s: 3_600,
        }
    }
}

impl SolPlanSettings {
    /// Checks that every duration lies within a sol (0 ..= 88,775 s): the plan covers one sol.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first duration outside a sol.
    pub fn validate(&self) -> Result<(), FieldError> {
        for (field, duration_s) in [
            ("heating_s", self.heating_s),
            ("imaging_s", self.imaging_s),
            ("sunfind_s", self.sunfind_s),
            ("compare_apply_s", self.compare_apply_s),
            ("comm_pass_s", self.comm_pass_s),
            ("drive_stretch_s", self.drive_stretch_s),
        ] {
            if duration_s < 0 {
                return Err(FieldError::new(
                    field,
                    "a duration of 0 s or more",
                    duration_s,
                ));
            }
            if duration_s > i64::from(SOL_S) {
                return Err(FieldError::new(
                    field,
                    format!("at most a sol ({SOL_S} s)"),
                    duration_s,
                ));
            }
        }
        Ok(())
    }
}
