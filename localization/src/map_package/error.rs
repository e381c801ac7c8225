//! Why a map package could not be made: one line naming the option or the scenario file.

use std::path::PathBuf;

use maps::RasterError;
use maps::package::PackageError;

use crate::synthetic::SyntheticError;

/// Why a map package could not be made.
#[derive(Debug, thiserror::Error)]
pub enum MapPackageError {
    /// An option is out of range (`--corridor-m`, `--tile-m`).
    #[error("{option}: expected {expected}, got {got}")]
    Option {
        /// The option, as on the command line.
        option: &'static str,
        /// What is allowed.
        expected: String,
        /// What was given.
        got: String,
    },
    /// The corridor of the scenario's route cannot be laid out on its map.
    #[error("{}: {source}", file.display())]
    Layout {
        /// The scenario file.
        file: PathBuf,
        /// Why.
        source: Box<PackageError>,
    },
    /// A tile could not be assembled (a block of the wrong size, a height the 16-bit
    /// centimetre format cannot hold).
    #[error(transparent)]
    Tile(Box<PackageError>),
    /// A block could not be rendered.
    #[error(transparent)]
    Render(#[from] SyntheticError),
    /// A tile could not be encoded as PNG.
    #[error(transparent)]
    Raster(Box<RasterError>),
}

impl From<PackageError> for MapPackageError {
    fn from(e: PackageError) -> Self {
        MapPackageError::Tile(Box::new(e))
    }
}

impl From<RasterError> for MapPackageError {
    fn from(e: RasterError) -> Self {
        MapPackageError::Raster(Box::new(e))
    }
}
