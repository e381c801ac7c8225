//! # localization — onboard global localization (paper 000 §4-§7) and the filters of papers 002 and 004
//!
//! - [`census`]: the modified census transform (8 bits per pixel, per-bit validity) and the exact
//!   masked Hamming score of every offset in the search window.
//! - [`hbs`]: the Helicopter Base Station co-processor model — transfer over the 10 KB/s link,
//!   run, reboot, run again, byte-for-byte comparison, checksums at every stage, timeouts, and
//!   injected radiation upsets that must be caught and never applied.
//! - [`upset_campaign`]: radiation upsets injected into seeded onboard localizations on the
//!   co-processor model, and what was caught, lost or (never) applied corrupted.
//! - [`onboard`]: the whole activity as the simulator runs it after a drive — imaging at the
//!   true position, the matcher from the estimate, through the co-processor model.
//! - [`raster_inputs`]: one localization on rasters a user supplies — the files and options
//!   read and checked, the result as a table or JSON (`solsim localize`).
//! - [`particle`]: the particle filter of paper 002 — odometry motion with the 5 %/50 % growth,
//!   census-score likelihoods of a sequence of panoramas, systematic or KLD resampling, the
//!   posterior as an ellipse; it resolves perceptual aliasing the single-shot matcher rejects.
//! - [`map_package`]: the onboard map package of a route — the orthoimage and DEM masked to a
//!   corridor, rendered seamlessly block by block, as PNG tiles with a manifest.
//! - [`ekf`]: the extended Kalman filter of paper 004 — IMU propagation (RK4) with biases,
//!   radio ranges to a two-body orbiter with Mars rotation, terrain-matching fixes; the four
//!   Table 1 cases (`examples/ekf_table1.rs`), checked against filterpy (`tests/ekf_filterpy.rs`).
#![warn(missing_docs)]

pub mod baselines;
pub mod benchmark_set;
pub mod census;
mod dem_score;
pub mod ekf;
pub mod hbs;
pub mod map_package;
pub mod matcher;
pub mod onboard;
pub mod particle;
pub mod raster_inputs;
pub mod synthetic;
pub mod upset_campaign;
