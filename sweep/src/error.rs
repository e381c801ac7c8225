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
    /// Two scenario files read again (to compare their settings) no longer parse.
    #[error("{} or {}: {message}", base.display(), variant.display())]
    Reread {
        /// The first file.
        base: PathBuf,
        /// The second file.
        variant: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// The two versions of a what-if study have different seeds, so their runs would not pair.
    #[error(
        "{}: seed {seed}: expected the base's seed ({base_seed}), so that run i of both sees the same world",
        variant.display()
    )]
    SeedMismatch {
        /// The variant's file.
        variant: PathBuf,
        /// Its seed.
        seed: u64,
        /// The base's seed.
        base_seed: u64,
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

    /// A [`SweepError::Io`] error: `what` failed on `path` (`cannot create`, `cannot list`,
    /// `cannot read` for an input that is missing, not a regular file or too large), with the
    /// cause's message.
    pub fn io(path: &std::path::Path, what: &str, e: impl std::fmt::Display) -> Self {
        SweepError::Io {
            path: path.to_path_buf(),
            what: what.into(),
            message: e.to_string(),
        }
    }
}
