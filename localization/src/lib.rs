//! # localization — onboard global localization (paper 000 §4-§7)
//!
//! - [`census`]: the modified census transform (8 bits per pixel, per-bit validity) and the exact
//!   masked Hamming score of every offset in the search window.
//! - [`hbs`]: the Helicopter Base Station co-processor model — transfer over the 10 KB/s link,
//!   run, reboot, run again, byte-for-byte comparison, checksums at every stage, timeouts, and
//!   injected radiation upsets that must be caught and never applied.
//! - [`onboard`]: the whole activity as the simulator runs it after a drive — imaging at the
//!   true position, the matcher from the estimate, through the co-processor model.
#![warn(missing_docs)]

pub mod baselines;
pub mod benchmark_set;
pub mod census;
mod dem_score;
pub mod hbs;
pub mod matcher;
pub mod onboard;
pub mod synthetic;
