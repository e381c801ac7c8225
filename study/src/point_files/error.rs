//! Why a file of points (a points CSV, a track) cannot be used.

use std::path::PathBuf;

use maps::input_file::InputFileError;

/// Why a file of points cannot be used, as one line naming the file.
#[derive(Debug, thiserror::Error)]
pub enum PointFileError {
    /// The file could not be read (missing, not a regular file, too large, not UTF-8).
    #[error("{}: {what}: {error}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What the file is (`points file`, `track file`).
        what: &'static str,
        /// Why (part of the message, so not also a `source`).
        error: InputFileError,
    },
    /// A field, line, column or feature holds something else than expected.
    #[error("{file}: {field}: expected {expected}, got {got}")]
    Field {
        /// The file, as displayed.
        file: String,
        /// Where: `line 3, column lat`, `features[2].geometry.type`.
        field: String,
        /// What was expected.
        expected: String,
        /// What the file holds (quoted only where the file reads as the expected format).
        got: String,
    },
    /// The file as a whole is not what was expected (too few points, not JSON).
    #[error("{file}: expected {expected}, got {got}")]
    Whole {
        /// The file, as displayed.
        file: String,
        /// What was expected.
        expected: String,
        /// What the file holds.
        got: String,
    },
    /// The file has no line but blank ones.
    #[error("{file}: empty file; expected {expected}")]
    Empty {
        /// The file, as displayed.
        file: String,
        /// What its first line should be.
        expected: &'static str,
    },
    /// A CSV line that does not split into fields.
    #[error("{file}: line {line}: {error}")]
    CsvSyntax {
        /// The file, as displayed.
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong: an unterminated quoted field, text after a quoted field.
        error: &'static str,
    },
    /// A CSV header naming a column twice.
    #[error("{file}: line {line}: column {column} appears twice")]
    DuplicateColumn {
        /// The file, as displayed.
        file: String,
        /// 1-based line number of the header.
        line: usize,
        /// The column.
        column: String,
    },
    /// A CSV header naming columns the format does not have.
    #[error("{file}: line {line}: unknown column(s) {columns}; expected {expected}")]
    UnknownColumns {
        /// The file, as displayed.
        file: String,
        /// 1-based line number of the header.
        line: usize,
        /// The unknown columns, quoted and comma-separated.
        columns: String,
        /// What the header should name.
        expected: &'static str,
    },
    /// A CSV header without a column the format needs.
    #[error("{file}: line {line}: missing column {column}; expected {expected}")]
    MissingColumn {
        /// The file, as displayed.
        file: String,
        /// 1-based line number of the header.
        line: usize,
        /// The column missing.
        column: &'static str,
        /// What the header should name.
        expected: &'static str,
    },
}

impl PointFileError {
    /// A [`PointFileError::Field`] error.
    pub fn field(
        file: &str,
        field: impl Into<String>,
        expected: impl Into<String>,
        got: impl std::fmt::Display,
    ) -> Self {
        PointFileError::Field {
            file: file.to_owned(),
            field: field.into(),
            expected: expected.into(),
            got: got.to_string(),
        }
    }

    /// A [`PointFileError::Whole`] error.
    pub fn whole(file: &str, expected: impl Into<String>, got: impl std::fmt::Display) -> Self {
        PointFileError::Whole {
            file: file.to_owned(),
            expected: expected.into(),
            got: got.to_string(),
        }
    }
}
