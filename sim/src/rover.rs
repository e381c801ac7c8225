//! The rover: how it drives, what it believes, what it does not know.
//!
//! - [`autonav`]: one sol's drive — plan on the grid, step, Visual Odometry, slip, faults.
//! - [`pose`]: the true pose and the rover's estimate, kept in different types.
//! - [`uncertainty`]: the disc `r = margin + k_vo·d_vo + k_novo·d_novo` and its resets.
//! - [`errors`]: what the estimate does not know (heading, VO scale and failures, slip, ground
//!   localization), calibrated and stress presets.
//! - [`physics`]: the rover in rapier on terramechanics soils; [`slip_profile`]: the
//!   slip-versus-slope tables it measures, which the traverse reads.

pub mod autonav;
pub mod errors;
pub mod physics;
pub mod pose;
pub mod slip_profile;
pub mod uncertainty;

pub use autonav::RoverSettings;
pub use uncertainty::UncertaintyModel;
