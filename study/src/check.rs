//! The field checks every file format shares (scenario, `[science]`, campaign files): each
//! returns a one-line [`ScenarioError`] naming the file and the TOML field, worded alike. A
//! simulator settings struct checks its own fields ([`FieldError`]); [`FieldCheck::setting`] names
//! the file's field for it.

use std::path::Path;

use planner::{MAX_TIERS, MAX_UTILITY};
use sim::settings::physical_range::check_fraction;
use sim::time::SolSeconds;
use sim::{FieldError, PhysicalRange};

use crate::error::ScenarioError;

pub(crate) struct FieldCheck<'a> {
    pub(crate) path: &'a Path,
}

impl FieldCheck<'_> {
    pub(crate) fn err(
        &self,
        field: &str,
        expected: impl Into<String>,
        got: impl std::fmt::Display,
    ) -> ScenarioError {
        ScenarioError::field(self.path, field, expected, got)
    }
    pub(crate) fn positive(&self, field: &str, v: f64, unit: &str) -> Result<f64, ScenarioError> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(field, format!("a positive number of {unit}"), v))
        }
    }
    pub(crate) fn non_negative(
        &self,
        field: &str,
        v: f64,
        unit: &str,
    ) -> Result<f64, ScenarioError> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(field, format!("a non-negative number of {unit}"), v))
        }
    }
    /// A simulator settings struct's error, its field already the file's (a TOML path).
    pub(crate) fn field_error(&self, e: FieldError) -> ScenarioError {
        ScenarioError::field(self.path, e.field, e.expected, e.got)
    }
    /// A simulator settings struct's error with its fields named as the file names them:
    /// `name` maps a path of the struct's fields onto the TOML path (`step_m` → `rover.step_m`).
    pub(crate) fn setting(&self, e: FieldError, name: impl Fn(&str) -> String) -> ScenarioError {
        self.field_error(e.renamed(name))
    }
    /// A value in `range` (a physical range: the loaders refuse absurd values that are finite
    /// but would run to nonsense).
    pub(crate) fn range(
        &self,
        range: PhysicalRange,
        field: &str,
        v: f64,
    ) -> Result<f64, ScenarioError> {
        range.check(field, v).map_err(|e| self.field_error(e))
    }
    /// A value in `lo ..= hi` `unit`: [`FieldCheck::range`] of a range given in place.
    pub(crate) fn in_range(
        &self,
        field: &str,
        v: f64,
        lo: f64,
        hi: f64,
        unit: &'static str,
    ) -> Result<f64, ScenarioError> {
        self.range(PhysicalRange::new(lo, hi, unit), field, v)
    }
    /// A value in `(0, hi]` `unit`.
    pub(crate) fn positive_at_most(
        &self,
        field: &str,
        v: f64,
        hi: f64,
        unit: &str,
    ) -> Result<f64, ScenarioError> {
        if v.is_finite() && v > 0.0 && v <= hi {
            Ok(v)
        } else {
            Err(self.err(
                field,
                format!("a positive number of {unit}, at most {hi}"),
                v,
            ))
        }
    }
    pub(crate) fn fraction(&self, field: &str, v: f64) -> Result<f64, ScenarioError> {
        check_fraction(field, v).map_err(|e| self.field_error(e))
    }
    pub(crate) fn lmst(&self, field: &str, v: &str) -> Result<SolSeconds, ScenarioError> {
        SolSeconds::parse_lmst(v).ok_or_else(|| {
            self.err(
                field,
                "a local mean solar time \"HH:MM\" between 00:00 and 24:00",
                format!("{v:?}"),
            )
        })
    }
    /// [`FieldCheck::lmst`] as the `planner` crate's seconds after local midnight (campaign files
    /// build planner problems).
    pub(crate) fn lmst_s(&self, field: &str, v: &str) -> Result<i64, ScenarioError> {
        self.lmst(field, v).map(SolSeconds::planner_s)
    }
    /// Minutes (SI) → whole seconds, > 0.
    pub(crate) fn minutes(&self, field: &str, v: f64) -> Result<i64, ScenarioError> {
        let m = self.positive(field, v, "minutes")?;
        let s = (m * 60.0).round();
        if (1.0..=259_200.0).contains(&s) {
            Ok(s as i64)
        } else {
            Err(self.err(field, "a duration between 1 s and 4320 min (72 h)", v))
        }
    }
    pub(crate) fn tier(&self, field: &str, v: Option<i64>) -> Result<u8, ScenarioError> {
        match v {
            None => Ok(1),
            Some(t) if (1..=MAX_TIERS as i64).contains(&t) => Ok(t as u8),
            Some(t) => Err(self.err(field, format!("a tier 1 ..= {MAX_TIERS}"), t)),
        }
    }
    pub(crate) fn utility(&self, field: &str, v: f64) -> Result<f64, ScenarioError> {
        if v.is_finite() && (0.0..=MAX_UTILITY).contains(&v) {
            Ok(v)
        } else {
            Err(self.err(field, format!("utility points 0 ..= {MAX_UTILITY}"), v))
        }
    }
    pub(crate) fn id(&self, field: &str, v: &str) -> Result<(), ScenarioError> {
        if v.trim().is_empty()
            || v.contains(['#', ' '])
            || maps::input_file::first_unsafe_char(v).is_some()
        {
            Err(self.err(
                field,
                "a non-empty id without spaces, '#' or control characters",
                format!("{v:?}"),
            ))
        } else {
            Ok(())
        }
    }
    /// Free text that is printed (a name, a description): refused when it holds a control
    /// character or a bidi override, which would drive the terminal that shows it.
    pub(crate) fn text(&self, field: &str, v: &str) -> Result<(), ScenarioError> {
        if maps::input_file::first_unsafe_char(v).is_some() {
            Err(self.err(field, "text without control characters", format!("{v:?}")))
        } else {
            Ok(())
        }
    }
}

pub(crate) use sim::time::lmst_of;
