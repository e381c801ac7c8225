//! Errors in scenario files: every one names the file, the field and what was expected.

use std::path::PathBuf;

/// Why a scenario could not be loaded. Displayed as one line:
/// `FILE: FIELD: expected WHAT, got VALUE`.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{path}: cannot read the file: {source}")]
    Io {
        /// The scenario file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The TOML did not parse or did not match the scenario format.
    #[error("{path}: line {line}, column {column} (`{text}`): {message}")]
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
    #[error("{path}: {field}: expected {expected}, got {got}")]
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
    #[error("{path}: {field}: {source}")]
    Map {
        /// The scenario file.
        path: PathBuf,
        /// The field naming the raster.
        field: String,
        /// What went wrong with the raster.
        source: Box<maps::RasterError>,
    },
    /// The zones file referenced by the scenario could not be loaded.
    #[error("{path}: map.zones: {source}")]
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
            field: field.into(),
            expected: expected.into(),
            got: got.to_string(),
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
        let line_text = text[line_start..]
            .lines()
            .next()
            .unwrap_or("")
            .trim()
            .to_string();
        let message = err
            .message()
            .lines()
            .next()
            .unwrap_or("invalid TOML")
            .trim()
            .to_string();
        ScenarioError::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            text: line_text,
            message,
        }
    }
}
