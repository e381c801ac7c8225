//! The onboard position-uncertainty disc (paper 000 §2, §7).
//!
//! Perseverance models its position uncertainty as a disc whose radius grows with odometry:
//! `r = margin + k_vo·d_vo + k_novo·d_novo`, where `d_vo` is the distance driven while Visual
//! Odometry measured the motion and `d_novo` the distance driven without it. Ground localization
//! resets the odometers and the margin to zero. Onboard localization resets the odometers and sets
//! the margin to the localizer's own uncertainty plus an operator margin — the flight software
//! adds it as a margin term rather than changing how the odometers reset (000 §7).

use crate::settings::field_error::FieldError;
use crate::settings::physical_range::{MARGIN_M, PhysicalRange};

/// Growth rates of the uncertainty disc (plain settings struct).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct UncertaintyModel {
    /// Growth per metre driven with VO, metres per metre (default: 0.05 — 5 % of distance;
    /// range [`UncertaintyModel::GROWTH_RANGE_M_PER_M`]).
    pub k_vo: f64,
    /// Growth per metre driven without VO, metres per metre (default: 0.50 — 50 % of
    /// distance; range [`UncertaintyModel::GROWTH_RANGE_M_PER_M`]).
    pub k_novo: f64,
    /// Radius at the start of the scenario, metres (default: 0; range
    /// [`crate::settings::physical_range::MARGIN_M`]).
    pub initial_margin_m: f64,
}

impl UncertaintyModel {
    /// The growth rates a disc may have, metres per metre driven: 1 m/m is already knowing
    /// nothing of the distance.
    pub const GROWTH_RANGE_M_PER_M: PhysicalRange =
        PhysicalRange::new(0.0, 1.0, "metres per metre");

    /// Checks each rate and the margin against its range.
    ///
    /// # Errors
    /// A [`FieldError`] naming the first field outside its range.
    pub fn validate(&self) -> Result<(), FieldError> {
        Self::GROWTH_RANGE_M_PER_M.check("k_vo", self.k_vo)?;
        Self::GROWTH_RANGE_M_PER_M.check("k_novo", self.k_novo)?;
        MARGIN_M.check("initial_margin_m", self.initial_margin_m)?;
        Ok(())
    }
}

impl Default for UncertaintyModel {
    fn default() -> Self {
        Self {
            k_vo: 0.05,
            k_novo: 0.50,
            initial_margin_m: 0.0,
        }
    }
}

/// The rover's odometers and margin since the last localization.
#[derive(Clone, Copy, Debug, PartialEq, Default, serde::Serialize)]
pub struct UncertaintyState {
    /// Constant term, metres: 0 after ground localization, localizer σ + operator margin after
    /// an onboard localization.
    pub margin_m: f64,
    /// Metres driven with VO since the last localization.
    pub d_vo_m: f64,
    /// Metres driven without VO since the last localization.
    pub d_novo_m: f64,
}

impl UncertaintyState {
    /// The disc radius in metres under `model`.
    #[must_use]
    pub fn radius_m(&self, model: &UncertaintyModel) -> f64 {
        self.margin_m + model.k_vo * self.d_vo_m + model.k_novo * self.d_novo_m
    }

    /// Record `distance_m` of driving, of which a fraction `novo_fraction` (0..=1) without VO.
    pub fn drive(&mut self, distance_m: f64, novo_fraction: f64) {
        let novo = distance_m * novo_fraction.clamp(0.0, 1.0);
        self.d_novo_m += novo;
        self.d_vo_m += distance_m - novo;
    }

    /// Ground localization: odometers and margin to zero.
    pub fn reset_ground(&mut self) {
        *self = Self::default();
    }

    /// Onboard localization accepted: odometers to zero, margin = localizer σ + operator margin.
    pub fn reset_onboard(&mut self, localizer_sigma_m: f64, operator_margin_m: f64) {
        *self = Self {
            margin_m: localizer_sigma_m + operator_margin_m,
            d_vo_m: 0.0,
            d_novo_m: 0.0,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_papers() {
        let m = UncertaintyModel::default();
        assert_eq!((m.k_vo, m.k_novo, m.initial_margin_m), (0.05, 0.50, 0.0));
    }

    #[test]
    fn sol_717_719_figure() {
        // Paper 000 Fig. 2: 655.8 m over three sols, 0 → 32.92 m. With 5 % per VO metre that
        // needs 0.289 m without VO: 0.05·655.511 + 0.5·0.289 = 32.920.
        let m = UncertaintyModel::default();
        let mut s = UncertaintyState::default();
        s.drive(655.8, 0.289 / 655.8);
        assert!((s.radius_m(&m) - 32.92).abs() < 1e-3);
    }

    #[test]
    fn resets() {
        let m = UncertaintyModel::default();
        let mut s = UncertaintyState::default();
        s.drive(100.0, 0.5);
        assert!((s.radius_m(&m) - 27.5).abs() < 1e-12);
        s.reset_onboard(0.93, 1.0);
        assert!((s.radius_m(&m) - 1.93).abs() < 1e-12);
        s.reset_ground();
        assert_eq!(s.radius_m(&m), 0.0);
    }
}
