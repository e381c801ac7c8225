//! One onboard global localization (paper 000 §5) on rasters a user supplies — an orbital
//! orthoimage (and DEM) and the rover's orthomosaic (and DEM) — around a prior position: the
//! inputs read and checked, and the result as a table or a JSON document (`solsim localize`).
//!
//! Reading is two-stage: every file and option of a [`LocalizeRequest`] is checked by [`load`]
//! and turned into one [`LocalizeInputError`] line naming the file or option (by its
//! command-line flag) and what was expected; only then does
//! [`localize`](crate::matcher::localize) run ([`LocalizeInputs::localize`]). A match rejected
//! by its validity checks is a result, not an error.
//!
//! Conventions: map metres, x east, y north; a raster's origin is the north-west corner of
//! pixel (0, 0) and row 0 is the north edge; the rover is at the centre of its orthomosaic; the
//! orthomosaic has the orbital appearance's resolution.

mod error;
mod inputs;
mod load;
mod read;
mod report;

pub use error::LocalizeInputError;
pub use inputs::{
    DEFAULT_RADIUS_M, DEFAULT_ROVER_DEM_RESOLUTION_M_PER_PX, LocalizeInputs, LocalizeRequest,
    MAX_RADIUS_M,
};
pub use load::load;
pub use report::{json_doc, table, verdict, warnings};
