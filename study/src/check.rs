//! The field checks every file format shares (scenario, `[science]`, campaign files): each
//! returns a one-line [`ScenarioError`] naming the file and the TOML field, worded alike.

use std::path::Path;

use planner::{MAX_TIERS, MAX_UTILITY};
use sim::time::SolSeconds;

use crate::error::ScenarioError;

pub(crate) struct Check<'a> {
    pub(crate) path: &'a Path,
}

impl Check<'_> {
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
    /// A value in `lo ..= hi` `unit` (a physical range: the loaders refuse absurd values that
    /// are finite but would run to nonsense).
    pub(crate) fn in_range(
        &self,
        field: &str,
        v: f64,
        lo: f64,
        hi: f64,
        unit: &str,
    ) -> Result<f64, ScenarioError> {
        if v.is_finite() && (lo..=hi).contains(&v) {
            Ok(v)
        } else {
            Err(self.err(field, format!("{lo} ..= {hi} {unit}"), v))
        }
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
        if (0.0..=1.0).contains(&v) {
            Ok(v)
        } else {
            Err(self.err(field, "a fraction between 0 and 1", v))
        }
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
    /// [`Check::lmst`] as the `planner` crate's seconds after local midnight (campaign files
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
