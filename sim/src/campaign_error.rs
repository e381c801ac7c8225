//! What makes a hand-built [`Campaign`] unusable, checked by [`Campaign::validate`].
//!
//! A campaign loaded from a scenario file is validated field by field by the `study` crate,
//! which names the file and the TOML field. A library user who builds a `Campaign` in code gets
//! the same guarantees from [`Campaign::validate`], so the runner never meets a route off its
//! grid, a calendar with gaps, a drive window that ends before it starts or a NaN rate.

use crate::autonav::RoverParams;
use crate::campaign::Campaign;
use crate::time::SolSeconds;

/// Why a [`Campaign`] cannot be run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CampaignError {
    /// Fewer than two waypoints (a start and a goal).
    #[error("route: expected at least two waypoints (a start and a goal), got {waypoints}")]
    RouteTooShort {
        /// How many there are.
        waypoints: usize,
    },
    /// A waypoint outside the planning grid (or not finite).
    #[error("route[{index}]: expected a point on the planning grid, got [{}, {}]", position_m[0], position_m[1])]
    WaypointOffGrid {
        /// Index in the route.
        index: usize,
        /// The waypoint, map metres.
        position_m: [f64; 2],
    },
    /// No sols.
    #[error("calendar: expected at least one sol, got none")]
    EmptyCalendar,
    /// Sols must follow each other, one per entry.
    #[error("calendar.sols[{index}]: expected sol {expected} (sols are consecutive), got {found}")]
    SolsNotConsecutive {
        /// Index in the calendar.
        index: usize,
        /// The sol that should be there.
        expected: u32,
        /// The sol that is.
        found: u32,
    },
    /// The first sol must start a plan.
    #[error("calendar.sols[0]: expected an uplink (the first sol starts a plan)")]
    FirstSolWithoutUplink,
    /// The drive window is empty or leaves the sol.
    #[error(
        "calendar: expected a drive window inside the sol with its end after its start, got {} s to {} s",
        .start.0,
        .end.0
    )]
    DriveWindow {
        /// Start.
        start: SolSeconds,
        /// End.
        end: SolSeconds,
    },
    /// A numeric parameter outside its range.
    #[error("{name}: expected {expected}, got {value:?}")]
    Parameter {
        /// The parameter, e.g. `rover.step_m`.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        expected: &'static str,
    },
    /// A planning-grid layer of the wrong length.
    #[error("grid.{layer}: expected {cells} cells (width × height), got {len}")]
    GridLayer {
        /// The layer.
        layer: &'static str,
        /// Its length.
        len: usize,
        /// Width × height.
        cells: usize,
    },
}

impl Campaign {
    /// Checks that the campaign can be run: the route on the grid, consecutive sols with an
    /// uplink first, a drive window inside the sol, finite positive rates and steps,
    /// probabilities within 0..1, non-negative uncertainty coefficients and margins, and grid
    /// layers of the grid's size.
    ///
    /// # Errors
    /// The first [`CampaignError`] found.
    pub fn validate(&self) -> Result<(), CampaignError> {
        let g = &self.grid;
        let cells = g.width * g.height;
        for (layer, len) in [
            ("clearance_m", g.clearance_m.len()),
            ("keep_out_clearance_m", g.keep_out_clearance_m.len()),
            ("keep_in_clearance_m", g.keep_in_clearance_m.len()),
            ("hazard", g.hazard.len()),
            ("terrain", g.terrain.len()),
        ] {
            if len != cells {
                return Err(CampaignError::GridLayer { layer, len, cells });
            }
        }
        if self.route.len() < 2 {
            return Err(CampaignError::RouteTooShort {
                waypoints: self.route.len(),
            });
        }
        for (index, &p) in self.route.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) || g.cell_of(p).is_none() {
                return Err(CampaignError::WaypointOffGrid {
                    index,
                    position_m: p,
                });
            }
        }
        let cal = &self.calendar;
        let Some(first) = cal.sols.first() else {
            return Err(CampaignError::EmptyCalendar);
        };
        if !first.uplink {
            return Err(CampaignError::FirstSolWithoutUplink);
        }
        for (index, w) in cal.sols.windows(2).enumerate() {
            if w[1].sol != w[0].sol.wrapping_add(1) {
                return Err(CampaignError::SolsNotConsecutive {
                    index: index + 1,
                    expected: w[0].sol.wrapping_add(1),
                    found: w[1].sol,
                });
            }
        }
        if let Some(e) = cal.sols.iter().find(|e| {
            e.drive_rate_m_per_h
                .is_some_and(|v| !(v > 0.0 && v.is_finite()))
        }) {
            return Err(CampaignError::Parameter {
                name: "sols[].drive_rate_m_per_h",
                value: e.drive_rate_m_per_h.unwrap_or(f64::NAN),
                expected: "a positive, finite rate, metres per hour",
            });
        }
        let windows = std::iter::once((cal.drive_start, cal.drive_end))
            .chain(cal.sols.iter().filter_map(|e| e.window));
        for (start, end) in windows {
            if start < SolSeconds::MIDNIGHT || end <= start || end > SolSeconds::END_OF_SOL {
                return Err(CampaignError::DriveWindow { start, end });
            }
        }
        let r = &self.rover;
        // (parameter, value, what is allowed)
        let params = [
            (
                "rover.drive_rate_m_per_h",
                r.drive_rate_m_per_h,
                Rule::Range(
                    RoverParams::DRIVE_RATE_RANGE_M_PER_H,
                    "1 ..= 1000 metres per hour",
                ),
            ),
            (
                "rover.step_m",
                r.step_m,
                Rule::Range(RoverParams::STEP_RANGE_M, "0.25 ..= 10 metres"),
            ),
            (
                "rover.waypoint_tolerance_m",
                r.waypoint_tolerance_m,
                Rule::Range(
                    RoverParams::WAYPOINT_TOLERANCE_RANGE_M,
                    "0.01 ..= 100 metres",
                ),
            ),
            (
                "errors.vo_failure.sand",
                r.errors.vo_failure.sand,
                Rule::Fraction,
            ),
            (
                "errors.vo_failure.soil",
                r.errors.vo_failure.soil,
                Rule::Fraction,
            ),
            (
                "errors.vo_failure.bedrock",
                r.errors.vo_failure.bedrock,
                Rule::Fraction,
            ),
            (
                "errors.slip_fraction.sand",
                r.errors.slip_fraction.sand,
                Rule::Fraction,
            ),
            (
                "errors.slip_fraction.soil",
                r.errors.slip_fraction.soil,
                Rule::Fraction,
            ),
            (
                "errors.slip_fraction.bedrock",
                r.errors.slip_fraction.bedrock,
                Rule::Fraction,
            ),
            (
                "errors.slip_sigma_relative",
                r.errors.slip_sigma_relative,
                Rule::NonNegative,
            ),
            (
                "errors.vo_noise_fraction",
                r.errors.vo_noise_fraction,
                Rule::Fraction,
            ),
            (
                "errors.vo_scale_sigma",
                r.errors.vo_scale_sigma,
                Rule::Fraction,
            ),
            (
                "errors.heading_sigma_deg",
                r.errors.heading_sigma_deg,
                Rule::NonNegative,
            ),
            (
                "errors.ground_localization_sigma_m",
                r.errors.ground_localization_sigma_m,
                Rule::NonNegative,
            ),
            ("rover.edge_buffer_m", r.edge_buffer_m, Rule::NonNegative),
            ("model.k_vo", self.model.k_vo, Rule::NonNegative),
            ("model.k_novo", self.model.k_novo, Rule::NonNegative),
            (
                "model.initial_margin_m",
                self.model.initial_margin_m,
                Rule::NonNegative,
            ),
            (
                "operator_margin_m",
                self.operator_margin_m,
                Rule::NonNegative,
            ),
            ("rover.terrain_cost.sand", r.terrain_cost.sand, Rule::Cost),
            ("rover.terrain_cost.soil", r.terrain_cost.soil, Rule::Cost),
            (
                "rover.terrain_cost.bedrock",
                r.terrain_cost.bedrock,
                Rule::Cost,
            ),
        ];
        for (name, value, rule) in params {
            if !rule.allows(value) {
                return Err(CampaignError::Parameter {
                    name,
                    value,
                    expected: rule.expected(),
                });
            }
        }
        Ok(())
    }
}

/// What a numeric parameter of a campaign may be.
#[derive(Clone)]
enum Rule {
    /// A physical range and how it reads in a message.
    Range(std::ops::RangeInclusive<f64>, &'static str),
    Fraction,
    NonNegative,
    Cost,
}

impl Rule {
    fn allows(&self, v: f64) -> bool {
        match self {
            Rule::Range(range, _) => range.contains(&v),
            Rule::Fraction => (0.0..=1.0).contains(&v),
            Rule::NonNegative => v.is_finite() && v >= 0.0,
            Rule::Cost => v.is_finite() && v >= 1.0,
        }
    }
    fn expected(&self) -> &'static str {
        match self {
            Rule::Range(_, expected) => expected,
            Rule::Fraction => "a fraction between 0 and 1",
            Rule::NonNegative => "a finite non-negative number",
            Rule::Cost => "a cost multiplier ≥ 1",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The messages spell the ranges the constants hold.
    #[test]
    fn range_messages_match_the_constants() {
        for (range, text) in [
            (
                RoverParams::DRIVE_RATE_RANGE_M_PER_H,
                "1 ..= 1000 metres per hour",
            ),
            (RoverParams::STEP_RANGE_M, "0.25 ..= 10 metres"),
            (
                RoverParams::WAYPOINT_TOLERANCE_RANGE_M,
                "0.01 ..= 100 metres",
            ),
        ] {
            assert!(
                text.starts_with(&format!("{} ..= {} ", range.start(), range.end())),
                "{text}"
            );
        }
    }

    /// The shortest step at the fastest rate covers a whole sol within the loop bound, so
    /// [`crate::autonav::MAX_STEPS_PER_SOL`] never ends an in-range drive early.
    #[test]
    fn the_step_bound_holds_a_whole_sol_at_the_fastest_rate() {
        let metres =
            RoverParams::DRIVE_RATE_RANGE_M_PER_H.end() * f64::from(crate::time::SOL_S) / 3_600.0;
        let steps = metres / RoverParams::STEP_RANGE_M.start();
        assert!(steps < crate::autonav::MAX_STEPS_PER_SOL as f64, "{steps}");
    }
}
