//! The rover's true position and its own estimate, kept in different types so the simulator
//! cannot hand the truth to code that stands for the rover (planning, AutoNav).

use nalgebra::Vector2;

/// Where the rover really is, in map metres (x east, y north). Only the simulator's world model
/// (terrain under the wheels, slip, localization) may read it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TruePose {
    /// Map position, metres.
    pub position_m: Vector2<f64>,
}

/// Where the rover believes it is, in map metres. Everything the rover decides uses this.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EstimatedPose {
    /// Map position, metres.
    pub position_m: Vector2<f64>,
}

/// Distance between the truth and the estimate, metres.
#[must_use]
pub fn estimate_error_m(truth: &TruePose, estimate: &EstimatedPose) -> f64 {
    (truth.position_m - estimate.position_m).norm()
}
