//! Errors in scenario files: every one names the file, the field and what was expected.

use std::path::PathBuf;

/// Why a scenario could not be loaded. Displayed as one line:
/// `FILE: FIELD: expected WHAT, got VALUE`.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read: missing, not a regular file (a FIFO, a device), larger
    /// than [`maps::input_file::MAX_TEXT_FILE_BYTES`], or not UTF-8.
    #[error("{}: {error}", path.display())]
    Io {
        /// The scenario file.
        path: PathBuf,
        /// Why (part of the message, so not also a `source`).
        error: maps::input_file::InputFileError,
    },
    /// The TOML did not parse or did not match the scenario format.
    #[error("{}: line {line}, column {column} (`{text}`): {message}", path.display())]
    Syntax {
        /// The scenario file.
        path: PathBuf,
        /// 1-based line of the offending text.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The offending line, trimmed.
        text: String,
        /// What the parser expected.
        message: String,
    },
    /// A field has a value outside what is allowed.
    #[error("{}: {field}: expected {expected}, got {got}", path.display())]
    Field {
        /// The scenario file.
        path: PathBuf,
        /// TOML path of the field, e.g. `sols[3].historic_distance_m`.
        field: String,
        /// What is allowed.
        expected: String,
        /// What the file holds.
        got: String,
    },
    /// A map raster referenced by the scenario could not be loaded.
    #[error("{}: {field}: {source}", path.display())]
    Map {
        /// The scenario file.
        path: PathBuf,
        /// The field naming the raster.
        field: String,
        /// What went wrong with the raster.
        source: Box<maps::RasterError>,
    },
    /// The campaign built from a valid file failed the simulator's own checks (a bug in the
    /// loader if it ever shows: every field is checked before).
    #[error("{}: {source}", path.display())]
    Campaign {
        /// The scenario file.
        path: PathBuf,
        /// What the simulator refused.
        source: sim::CampaignError,
    },
    /// The zones file referenced by the scenario could not be loaded.
    #[error("{}: map.zones: {source}", path.display())]
    Zones {
        /// The scenario file.
        path: PathBuf,
        /// What went wrong with the zones.
        source: Box<maps::ZoneError>,
    },
}

impl ScenarioError {
    /// A [`ScenarioError::Field`] error.
    pub fn field(
        path: &std::path::Path,
        field: impl Into<String>,
        expected: impl Into<String>,
        got: impl std::fmt::Display,
    ) -> Self {
        ScenarioError::Field {
            path: path.to_path_buf(),
            field: excerpt(&field.into(), MAX_EXCERPT_CHARS),
            // An expectation may quote another field's value (`at most battery_capacity_wh =
            // 1e300 Wh`): numbers print readably there too.
            expected: readable_numbers(&Into::<String>::into(expected)),
            got: excerpt(&readable_value(&got.to_string()), MAX_EXCERPT_CHARS),
        }
    }

    /// Turn a TOML parse error into a one-line [`ScenarioError::Syntax`].
    #[must_use]
    pub fn from_toml(path: &std::path::Path, text: &str, err: &toml::de::Error) -> Self {
        let offset = err.span().map_or(0, |s| s.start).min(text.len());
        let before = &text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = text[line_start..offset].chars().count() + 1;
        let line_text = excerpt(
            text[line_start..].lines().next().unwrap_or("").trim(),
            MAX_EXCERPT_CHARS,
        );
        let message = excerpt(
            &readable_numbers(
                err.message()
                    .lines()
                    .next()
                    .unwrap_or("invalid TOML")
                    .trim(),
            ),
            MAX_EXCERPT_CHARS,
        );
        ScenarioError::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            text: line_text,
            message,
        }
    }
}

/// Longest excerpt of a file (an offending line, a value, a field) quoted in a message,
/// characters: a message stays one readable line whatever the input holds.
pub const MAX_EXCERPT_CHARS: usize = 120;

pub use maps::input_file::excerpt;

/// A number as a person reads it: `1e300` rather than 301 digits, `1.5e-9` rather than a run
/// of zeros, an integer as its digits (`2147483647`, not `2.147483647e9`); anything that is not
/// a plain number is returned unchanged.
#[must_use]
pub fn readable_value(text: &str) -> String {
    let plain = !text.is_empty()
        && text
            .chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '-' | '.' | '+' | 'e' | 'E'));
    if !plain {
        return text.to_string();
    }
    let digits = text.trim_start_matches(['-', '+']);
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        return readable_integer(text);
    }
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v != 0.0 && (v.abs() >= 1e15 || v.abs() < 1e-4) => {
            format!("{v:e}")
        }
        _ => text.to_string(),
    }
}

/// An integer's digits (optionally signed) as a person reads them: as they are (`2147483647`,
/// an exact `u64`), unless they are a float's exact spelling of 1e9 or more that scientific
/// notation says shorter (`1e9`, and `1e300` rather than 301 digits).
fn readable_integer(text: &str) -> String {
    let unsigned = text.trim_start_matches('+');
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v.abs() >= 1e9 && format!("{v}") == unsigned => {
            let scientific = format!("{v:e}");
            if scientific.len() < unsigned.len() {
                scientific
            } else {
                text.to_string()
            }
        }
        _ => text.to_string(),
    }
}

/// `text` with every run of more than 15 digits that spells a float in full (a number no one
/// reads: `1e300` spelled out by a parser or a `{}` format) rewritten as `1e300`. Integers a
/// person wrote, up to `u64::MAX`, stay as they are.
#[must_use]
pub fn readable_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        out.push_str(&rest[..start]);
        let run = &rest[start..];
        let end = run
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(run.len());
        let number = &run[..end];
        let digits = number.chars().filter(char::is_ascii_digit).count();
        let integer = number.trim_end_matches('.');
        match number.parse::<f64>() {
            Ok(_) if digits > 15 && !integer.contains('.') => {
                out.push_str(&readable_integer(integer));
                out.push_str(&number[integer.len()..]);
            }
            Ok(v) if digits > 15 => out.push_str(&format!("{v:e}")),
            _ => out.push_str(number),
        }
        rest = &run[end..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn excerpts_are_capped_on_character_boundaries() {
        assert_eq!(excerpt("short", 80), "short");
        let long = "é".repeat(1000);
        let e = excerpt(&long, 80);
        assert_eq!(e.chars().count(), 80);
        assert!(e.ends_with('…'));
    }

    #[test]
    fn long_digit_runs_are_shortened() {
        let spelled = format!("floating point `{}`, expected u64", 1e300_f64);
        assert_eq!(
            readable_numbers(&spelled),
            "floating point `1e300`, expected u64"
        );
        assert_eq!(readable_numbers("line 12, column 3"), "line 12, column 3");
        assert_eq!(
            readable_numbers("got 18446744073709551615."),
            "got 18446744073709551615."
        );
        assert_eq!(
            readable_numbers(&format!("length_m = {} m", 1e300_f64)),
            "length_m = 1e300 m"
        );
    }

    #[test]
    fn numbers_print_readably() {
        assert_eq!(readable_value(&1e300_f64.to_string()), "1e300");
        assert_eq!(readable_value(&(-2.5e-9_f64).to_string()), "-2.5e-9");
        assert_eq!(readable_value("0.05"), "0.05");
        assert_eq!(readable_value("123456"), "123456");
        assert_eq!(readable_value("2147483647"), "2147483647");
        assert_eq!(readable_value("-2147483648"), "-2147483648");
        assert_eq!(
            readable_value("18446744073709551615"),
            "18446744073709551615"
        );
        assert_eq!(readable_value(&1e20_f64.to_string()), "1e20");
        assert_eq!(readable_value(&(-1e300_f64).to_string()), "-1e300");
        assert_eq!(readable_value("2147483647.5"), "2147483647.5");
        assert_eq!(readable_value("1000000000"), "1e9");
        assert_eq!(readable_value("4294967296"), "4294967296");
        assert_eq!(readable_value("9007199254740992"), "9007199254740992");
        assert_eq!(readable_value("1.5e300"), "1.5e300");
        assert_eq!(readable_value("\"abc\""), "\"abc\"");
        assert_eq!(readable_value("NaN"), "NaN");
    }
}
