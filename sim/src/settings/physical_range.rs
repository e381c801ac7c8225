//! [`PhysicalRange`]: the closed interval of values a physical setting may take, with its
//! unit, and the checks every settings struct shares ([`check_fraction`], [`MARGIN_M`]).
//!
//! A finite value outside its range would run to nonsense — a drive rate of 5e-324 m/h made
//! the step time infinite and the drive time NaN, and the rover drove 523 m in a sol; a step
//! of 5e-324 m drove 0 m — so the settings refuse it, naming the field and the range. Each
//! range is generous against the rover it bounds and carries its reason where it is defined,
//! beside the field. A range whose minimum is 0 holds a margin, an error or a buffer, where 0
//! means "none".

use super::field_error::FieldError;

/// A closed interval of physical values with their unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicalRange {
    /// Smallest value allowed.
    pub min: f64,
    /// Largest value allowed.
    pub max: f64,
    /// The unit, as messages spell it (`metres per hour`).
    pub unit: &'static str,
}

impl PhysicalRange {
    /// `min ..= max` `unit`.
    #[must_use]
    pub const fn new(min: f64, max: f64, unit: &'static str) -> Self {
        Self { min, max, unit }
    }

    /// Whether `v` is a finite value inside the range.
    #[must_use]
    pub fn contains(&self, v: f64) -> bool {
        v.is_finite() && (self.min..=self.max).contains(&v)
    }

    /// The range as messages write it: `0.25 ..= 10 metres`.
    #[must_use]
    pub fn expected(&self) -> String {
        format!("{} ..= {} {}", self.min, self.max, self.unit)
    }

    /// `v` if it is inside the range.
    ///
    /// # Errors
    /// A [`FieldError`] naming `field`, the range and `v`.
    pub fn check(&self, field: &str, v: f64) -> Result<f64, FieldError> {
        if self.contains(v) {
            Ok(v)
        } else {
            Err(FieldError::new(field, self.expected(), v))
        }
    }
}

/// Margins, buffers, uncertainties and localization errors that may be 0 (an edge buffer, the
/// initial and operator margins, the planners' passage margin, a localizer's reported σ, the
/// ground localization's σ): beyond 1 km no passage of a rover's route survives.
pub const MARGIN_M: PhysicalRange = PhysicalRange::new(0.0, 1_000.0, "metres");

/// `v` if it is a fraction (a probability, a share): 0 ..= 1.
///
/// # Errors
/// A [`FieldError`] naming `field` and `v`.
pub fn check_fraction(field: &str, v: f64) -> Result<f64, FieldError> {
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(FieldError::new(field, "a fraction between 0 and 1", v))
    }
}
