//! Why the rasters and options of one localization cannot be used: one line naming the file or
//! option (by its command-line flag) and what was expected.

use maps::RasterError;

use crate::matcher::LocalizeError;

/// Bad input to one localization on user rasters.
#[derive(Debug, thiserror::Error)]
pub enum LocalizeInputError {
    /// An option's value is unusable: `--radius: expected …, got 0`.
    #[error("{input}: expected {expected}, got {got}")]
    Option {
        /// The option (`--radius`, `--map-origin`).
        input: String,
        /// What is allowed.
        expected: String,
        /// What was given.
        got: String,
    },
    /// A file (or an option and the files it concerns) holds something else than expected:
    /// `--ortho FILE: expected …, found …`.
    #[error("{input}: expected {expected}, found {found}")]
    Found {
        /// The option and its file, e.g. `--ortho ortho.png`, or the options at fault.
        input: String,
        /// What was expected.
        expected: String,
        /// What was found, and what to do about it.
        found: String,
    },
    /// A GeoTIFF's own georeference contradicts the options given with it.
    #[error("{input}: {conflict}: expected {expected}")]
    Contradiction {
        /// The option and its file.
        input: String,
        /// What contradicts what.
        conflict: String,
        /// What was expected (that they agree).
        expected: String,
    },
    /// An option given without the one it only works with.
    #[error("{input}: expected together with {partner}, which is missing")]
    WithoutPartner {
        /// The option(s) given.
        input: String,
        /// The option missing.
        partner: &'static str,
    },
    /// One of a pair of georeference options (origin, resolution) given without the other.
    #[error("{input}: expected together with {partner}, missing")]
    HalfPair {
        /// The option given.
        input: &'static str,
        /// The other of the pair.
        partner: &'static str,
    },
    /// A raster could not be read (or would not fit the memory budget).
    #[error("{input} {source}")]
    Raster {
        /// The option naming the raster.
        input: &'static str,
        /// Why (the message names the file).
        source: Box<RasterError>,
    },
    /// The matcher refused inputs the checks let through.
    #[error("{input}: {source}")]
    Match {
        /// The options (and file) at fault.
        input: String,
        /// The matcher's reason.
        source: LocalizeError,
    },
    /// No offset in the search window could be scored (valid rover DEM cells overlap valid
    /// map DEM cells nowhere).
    #[error(
        "--ortho / --rover-dem / --map-dem: expected some offset in the search window to be scorable, found none (do the valid rover DEM cells overlap valid map DEM cells?)"
    )]
    NothingScorable,
}
