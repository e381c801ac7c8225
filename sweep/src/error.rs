//! Why a sweep could not run, resume or merge: one line naming the file or option, the field
//! and what was expected.

use std::path::PathBuf;

/// A sweep error, displayed as one line.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// A file or directory could not be read or written.
    #[error("{}: {what}: {message}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// What was being done (`cannot create`, `cannot read`, …).
        what: String,
        /// The operating system's or the decoder's message.
        message: String,
    },
    /// A sweep file (manifest, table) holds something other than what this sweep expects.
    #[error("{}: {field}: expected {expected}, got {got}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// The field.
        field: String,
        /// What was expected.
        expected: String,
        /// What the file holds.
        got: String,
    },
    /// An option's value cannot be used.
    #[error("{option}: expected {expected}, got {got}")]
    Option {
        /// The option, e.g. `--shard`.
        option: String,
        /// What is allowed.
        expected: String,
        /// What was given.
        got: String,
    },
    /// The scenario could not be loaded.
    #[error(transparent)]
    Scenario(#[from] study::ScenarioError),
}

impl SweepError {
    /// A [`SweepError::Option`] error.
    pub fn option(
        option: impl Into<String>,
        expected: impl Into<String>,
        got: impl std::fmt::Display,
    ) -> Self {
        SweepError::Option {
            option: option.into(),
            expected: expected.into(),
            got: got.to_string(),
        }
    }

    /// A [`SweepError::Format`] error.
    pub fn format(
        path: impl Into<PathBuf>,
        field: impl Into<String>,
        expected: impl Into<String>,
        got: impl std::fmt::Display,
    ) -> Self {
        SweepError::Format {
            path: path.into(),
            field: field.into(),
            expected: expected.into(),
            got: got.to_string(),
        }
    }
}
