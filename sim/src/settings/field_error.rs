//! [`FieldError`]: what a settings struct says when one of its fields is outside what it
//! allows — the field as the struct names it, what it expects (with its unit) and what it
//! holds. Each settings struct checks its own fields next to them (`RoverSettings::validate`,
//! `Calendar::validate`, …); a loader that read the settings from a file names the field as
//! the file does with [`FieldError::renamed`].

use std::fmt::Display;

/// A settings field outside what its struct allows, displayed as one line:
/// `FIELD: expected WHAT, got VALUE`.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{field}: expected {expected}, got {got}")]
pub struct FieldError {
    /// The field as the struct names it: a nested one joined with `.`
    /// (`errors.vo_failure.sand`), an element of a list with its index (`sols[3].window`).
    pub field: String,
    /// What the field may be, with its unit (`0.25 ..= 10 metres`).
    pub expected: String,
    /// What it holds (a number as `Display` writes it).
    pub got: String,
    /// A field of the same struct that `expected` names by its name (`mean_error_m` in "more
    /// than 1.05 × mean_error_m (0.36 m)"), so that a loader can name it as its file does.
    pub sibling: Option<&'static str>,
}

impl FieldError {
    /// `field` does not hold what it should: `expected`, with its unit; it holds `got`.
    #[must_use]
    pub fn new(field: impl Into<String>, expected: impl Into<String>, got: impl Display) -> Self {
        Self {
            field: field.into(),
            expected: expected.into(),
            got: got.to_string(),
            sibling: None,
        }
    }

    /// The same error, saying that `expected` names `sibling`, a field of the same struct.
    #[must_use]
    pub fn naming(mut self, sibling: &'static str) -> Self {
        self.sibling = Some(sibling);
        self
    }

    /// The error of a field of the struct held in `parent`: `within("errors")` turns
    /// `heading_sigma_deg` into `errors.heading_sigma_deg`.
    #[must_use]
    pub fn within(mut self, parent: &str) -> Self {
        self.field = format!("{parent}.{}", self.field);
        self
    }

    /// The error with its field named by `name` (a file's name for a path of struct fields,
    /// `rover.step_m` for `step_m`), and the sibling `expected` names renamed alike, by the
    /// last part of its new name (a key of the same table: `drive_start_lmst`).
    #[must_use]
    pub fn renamed(self, name: impl Fn(&str) -> String) -> Self {
        let expected = match self.sibling {
            None => self.expected,
            Some(sibling) => {
                let full = match self.field.rsplit_once('.') {
                    Some((parent, _)) => format!("{parent}.{sibling}"),
                    None => sibling.to_owned(),
                };
                let renamed = name(&full);
                let key = renamed.rsplit('.').next().unwrap_or(&renamed);
                self.expected.replacen(sibling, key, 1)
            }
        };
        Self {
            field: name(&self.field),
            expected,
            got: self.got,
            sibling: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_nested_error_is_renamed_with_the_sibling_it_names() {
        let e = FieldError::new("novo_m", "at most distance_m (183 m)", 200.5)
            .naming("distance_m")
            .within("historic")
            .within("sols[3]");
        assert_eq!(
            e.to_string(),
            "sols[3].historic.novo_m: expected at most distance_m (183 m), got 200.5"
        );
        let file = e.renamed(|f| f.replace("historic.", "historic_"));
        assert_eq!(
            file.to_string(),
            "sols[3].historic_novo_m: expected at most historic_distance_m (183 m), got 200.5"
        );
    }
}
