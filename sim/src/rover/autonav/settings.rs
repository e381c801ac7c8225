//! [`RoverSettings`]: the rover's and AutoNav's settings, with the slip model's
//! ([`SlipModel`], [`ProfileSlip`]), the range of each and their check
//! ([`RoverSettings::validate`]).

use maps::{PerTerrain, TerrainClass};

use crate::rover::errors::ErrorModel;
use crate::settings::field_error::FieldError;
use crate::settings::physical_range::{MARGIN_M, PhysicalRange};

/// Rover and AutoNav settings (plain struct; every field has a unit and a default).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RoverSettings {
    /// AutoNav drive rate, metres per hour of driving (default: 100; range
    /// [`RoverSettings::DRIVE_RATE_RANGE_M_PER_H`]).
    pub drive_rate_m_per_h: f64,
    /// Length of one AutoNav step, metres (default: 2.0; range [`RoverSettings::STEP_RANGE_M`]).
    pub step_m: f64,
    /// A waypoint counts as reached within this distance, metres (default: 2.0; range
    /// [`RoverSettings::WAYPOINT_TOLERANCE_RANGE_M`]).
    pub waypoint_tolerance_m: f64,
    /// Path-cost multiplier of entering a cell, per terrain class (default: sand 1.3, soil 1.0,
    /// bedrock 1.0; range [`RoverSettings::TERRAIN_COST_RANGE`]).
    pub terrain_cost: PerTerrain,
    /// AutoNav keeps this far from closed cells when it has room, metres (default: 5.0; range
    /// [`MARGIN_M`]).
    /// Shapes the path only; a passage is open as long as any cell of it is open.
    pub edge_buffer_m: f64,
    /// What the estimate does not know: heading, VO scale and noise, VO failures, slip,
    /// ground localization (default: [`ErrorModel::calibrated`]).
    pub errors: ErrorModel,
    /// Where slip comes from and whether AutoNav plans around it (default:
    /// [`SlipModel::Terrain`]).
    pub slip_model: SlipModel,
}

/// Where a step's slip comes from.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SlipModel {
    /// A mean per terrain class ([`ErrorModel::slip_fraction`]), whatever the slope; the path
    /// cost per terrain class ([`RoverSettings::terrain_cost`]). What every calibration used.
    Terrain,
    /// The slip profile of the rapier rover ([`crate::rover::slip_profile`]): the mean slip of a step
    /// by terrain class and the slope along and across its heading (the grid's DEM gradient),
    /// spread as [`ErrorModel::slip_sigma_relative`] says. High slip makes VO fail more often
    /// ([`super::VO_FAILURE_AT_FULL_SLIP`]); a step whose VO-measured slip exceeds `slip_limit`
    /// stops the drive (`SLIP` fault), as the flight software's slip check does.
    Profile(ProfileSlip),
}

/// Settings of [`SlipModel::Profile`] (plain struct).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ProfileSlip {
    /// Plan with slip (paper 003 §4): a move costs the drive time per metre of progress,
    /// `1 / (1 − predicted slip)` (times the edge-buffer penalty), and a move whose predicted
    /// slip exceeds `avoid_slip_above` or whose predicted tilt exceeds `max_tilt_deg` is a
    /// hazard. `false`: the terrain-class costs of [`RoverSettings::terrain_cost`], slope hazards
    /// only.
    pub aware_routing: bool,
    /// Predicted slip slip-aware routing treats as a hazard, fraction (default
    /// [`ProfileSlip::derived_avoid_slip_above`]: the prediction at which a step 2σ above it,
    /// by [`ErrorModel::slip_sigma_relative`], reaches `slip_limit`; 0.25 for the defaults;
    /// range [`ProfileSlip::AVOID_SLIP_ABOVE_RANGE`]).
    pub avoid_slip_above: f64,
    /// Slip the drive tolerates, fraction (default 0.5; range [`ProfileSlip::SLIP_LIMIT_RANGE`]):
    /// the onboard slip check stops the drive when VO measures a step above it. An operator's
    /// setting.
    pub slip_limit: f64,
    /// Chassis tilt slip-aware routing avoids, degrees (default 25; range
    /// [`ProfileSlip::MAX_TILT_RANGE_DEG`]).
    pub max_tilt_deg: f64,
}

impl Default for ProfileSlip {
    fn default() -> Self {
        Self {
            aware_routing: true,
            avoid_slip_above: Self::derived_avoid_slip_above(0.5, 0.5),
            slip_limit: 0.5,
            max_tilt_deg: 25.0,
        }
    }
}

impl ProfileSlip {
    /// The predicted slip whose step 2σ above it reaches `slip_limit`, when a step's slip spreads
    /// by `slip_sigma_relative` of its mean: `slip_limit / (1 + 2 σ)`. Below it the slip check
    /// trips on about 2 % of steps or fewer.
    #[must_use]
    pub fn derived_avoid_slip_above(slip_limit: f64, slip_sigma_relative: f64) -> f64 {
        slip_limit / (1.0 + 2.0 * slip_sigma_relative)
    }

    /// The slip limits a drive may have, fraction: below 5 % the check would stop drives on
    /// level soil, whose mean slip is 4 % ([`ErrorModel::calibrated`]); near 100 % the rover
    /// makes no progress before the check trips.
    pub const SLIP_LIMIT_RANGE: PhysicalRange = PhysicalRange::new(0.05, 0.95, "a fraction");
    /// The predicted slips slip-aware routing may treat as a hazard, fraction: 0 avoids every
    /// move that slips; the top is the slip limit's.
    pub const AVOID_SLIP_ABOVE_RANGE: PhysicalRange = PhysicalRange::new(0.0, 0.95, "a fraction");
    /// The chassis tilts slip-aware routing may avoid, degrees: below 1° every slope is
    /// avoided; Perseverance's rated tilt is 45°.
    pub const MAX_TILT_RANGE_DEG: PhysicalRange = PhysicalRange::new(1.0, 45.0, "degrees");

    /// Checks each setting against its range.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::SLIP_LIMIT_RANGE.check("slip_limit", self.slip_limit)?;
        Self::AVOID_SLIP_ABOVE_RANGE.check("avoid_slip_above", self.avoid_slip_above)?;
        Self::MAX_TILT_RANGE_DEG.check("max_tilt_deg", self.max_tilt_deg)?;
        Ok(())
    }
}

impl RoverSettings {
    /// The drive rates a rover may have, m/h: Perseverance's AutoNav drives on the order of
    /// 100 m/h (the record's 91.9 m/h, README) with a top speed near 150 m/h; 1000 leaves room
    /// for what-if studies, and below 1 m/h a four-hour window drives less than 4 m. A rate of
    /// 5e-324 m/h made the step time infinite and the drive time NaN, and the rover then drove
    /// without a time limit.
    pub const DRIVE_RATE_RANGE_M_PER_H: PhysicalRange =
        PhysicalRange::new(1.0, 1_000.0, "metres per hour");
    /// The AutoNav steps a rover may take, m: MER's AutoNav drove steps of tens of centimetres;
    /// below 0.25 m the [`super::MAX_STEPS_PER_SOL`] loop bound could end a whole-sol drive at
    /// the fastest rate early (1000 m/h × 88,775 s / 0.25 m = 98,640 steps), and a 5e-324 m step
    /// drove 0 m a sol. Above 10 m the rover would drive several body lengths between path
    /// checks.
    pub const STEP_RANGE_M: PhysicalRange = PhysicalRange::new(0.25, 10.0, "metres");
    /// The waypoint tolerances a rover may have, m: 1 cm is below any orbital map's precision
    /// (HiRISE pixels are 25 cm); beyond 100 m a waypoint no longer marks a place on the route.
    pub const WAYPOINT_TOLERANCE_RANGE_M: PhysicalRange = PhysicalRange::new(0.01, 100.0, "metres");
    /// The path-cost multipliers a terrain class may have: at least 1, the cost of distance,
    /// which A*'s octile heuristic assumes no move undercuts; 1000 already makes a class one
    /// the planner crosses only when nothing else is open.
    pub const TERRAIN_COST_RANGE: PhysicalRange =
        PhysicalRange::new(1.0, 1_000.0, "a cost multiplier");

    /// Checks every setting against its range: the error model first ([`ErrorModel::validate`],
    /// as `errors.…`), then the slip model's ([`ProfileSlip::validate`], as
    /// `slip_model.…`), then the rover's own.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        self.errors.validate().map_err(|e| e.within("errors"))?;
        if let SlipModel::Profile(profile) = &self.slip_model {
            profile.validate().map_err(|e| e.within("slip_model"))?;
        }
        Self::DRIVE_RATE_RANGE_M_PER_H.check("drive_rate_m_per_h", self.drive_rate_m_per_h)?;
        Self::STEP_RANGE_M.check("step_m", self.step_m)?;
        Self::WAYPOINT_TOLERANCE_RANGE_M
            .check("waypoint_tolerance_m", self.waypoint_tolerance_m)?;
        for class in TerrainClass::ALL {
            let cost = self.terrain_cost.get(class);
            if !Self::TERRAIN_COST_RANGE.contains(cost) {
                return Err(FieldError::new(
                    format!("terrain_cost.{}", class.name()),
                    format!(
                        "{} {} ..= {}",
                        Self::TERRAIN_COST_RANGE.unit,
                        Self::TERRAIN_COST_RANGE.min,
                        Self::TERRAIN_COST_RANGE.max
                    ),
                    cost,
                ));
            }
        }
        MARGIN_M.check("edge_buffer_m", self.edge_buffer_m)?;
        Ok(())
    }
}

impl Default for RoverSettings {
    fn default() -> Self {
        Self {
            drive_rate_m_per_h: 100.0,
            step_m: 2.0,
            waypoint_tolerance_m: 2.0,
            terrain_cost: PerTerrain {
                sand: 1.3,
                soil: 1.0,
                bedrock: 1.0,
            },
            edge_buffer_m: 5.0,
            errors: ErrorModel::calibrated(),
            slip_model: SlipModel::Terrain,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shortest step at the fastest rate covers a whole sol within the loop bound, so
    /// [`crate::rover::autonav::MAX_STEPS_PER_SOL`] never ends an in-range drive early.
    #[test]
    fn the_step_bound_holds_a_whole_sol_at_the_fastest_rate() {
        let metres =
            RoverSettings::DRIVE_RATE_RANGE_M_PER_H.max * f64::from(crate::time::SOL_S) / 3_600.0;
        let steps = metres / RoverSettings::STEP_RANGE_M.min;
        assert!(
            steps < crate::rover::autonav::MAX_STEPS_PER_SOL as f64,
            "{steps}"
        );
    }
}
