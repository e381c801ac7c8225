//! Reading TOML inputs: a regular file of at most [`MAX_TOML_BYTES`],
//! UTF-8, parsed into its raw (`deny_unknown_fields`) mirror, with its SHA-256 for provenance.

use std::path::Path;

use sha2::{Digest, Sha256};

use crate::error::ScenarioError;

/// Largest TOML input (scenario, campaign file, recipe), bytes: 1 MiB, some 150 times the
/// largest bundled scenario. The TOML parser holds about 150 times a file's size at its peak
/// (measured: 1.3–2.3 GB for 16 MiB of hostile TOML), so this keeps parsing near 150 MB.
pub const MAX_TOML_BYTES: u64 = 1 << 20;

/// Read a TOML file into its raw (`deny_unknown_fields`) structs, with the SHA-256 of its
/// bytes (hex) for provenance. Errors name the file, and the line and field for TOML errors.
///
/// # Errors
/// [`ScenarioError::Io`] for a file that cannot be read, is not a regular file, is too large
/// or is not UTF-8; [`ScenarioError::Syntax`] for TOML that does not match `T`.
pub fn read_toml<T: serde::de::DeserializeOwned>(
    path: &Path,
) -> Result<(T, String), ScenarioError> {
    let text = maps::input_file::read_text_file_capped(path, MAX_TOML_BYTES).map_err(|error| {
        ScenarioError::Io {
            path: path.to_path_buf(),
            error,
        }
    })?;
    let raw = parse_toml(path, &text)?;
    Ok((raw, sha256_hex(text.as_bytes())))
}

/// Parse TOML text (from `path`, named in errors) into its raw mirror.
///
/// # Errors
/// [`ScenarioError::Syntax`] for TOML that does not parse or does not match `T`.
pub fn parse_toml<T: serde::de::DeserializeOwned>(
    path: &Path,
    text: &str,
) -> Result<T, ScenarioError> {
    toml::from_str(text)
        .map_err(|e| ScenarioError::from_toml(path, text, &e, crate::error::toml_keys::<T>()))
}

/// SHA-256 of `bytes`, lower-case hex.
#[must_use]
pub fn sha256_hex(bytes: &[u8]) -> String {
    use std::fmt::Write as _;
    Sha256::digest(bytes)
        .iter()
        .fold(String::new(), |mut s, b| {
            let _ = write!(s, "{b:02x}");
            s
        })
}
