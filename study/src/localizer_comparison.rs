//! Every onboard localizer on the same benchmark cases (`solsim localize-bench --methods all`):
//! the statistical model, the census, NCC and MI matchers, the particle filter (paper 002) and
//! the EKF (paper 004), side by side — accuracy of what each applies, rejections, run time, and
//! what each needs.
//!
//! Per case ([`benchmark_cases`] on [`BenchmarkMaps`]), from the case's own draws
//! ([`case_draws`]): a true position, a prior up to [`MAX_PRIOR_OFFSET_M`] from it, and the
//! rendered imagery. Each localizer gets:
//!
//! | localizer | input | accepted when |
//! |---|---|---|
//! | `statistical` | nothing: a draw of the flight statistics (paper 000 §4), seeded by the case | not in its `failure_rate` |
//! | `census`, `ncc`, `mi` | the imagery, the prior, a 30 m search window | the matcher's validity checks pass |
//! | `particle` | the imagery; particles from the disc of radius [`MAX_PRIOR_OFFSET_M`] around the prior (3σ) | one mode, and a 3σ disc smaller than the prior's |
//! | `ekf` | the prior with the same disc; one orbiter pass of ranges (1 m), IMU, zero-velocity updates | a 3σ disc smaller than the prior's |
//!
//! The imagery is rendered once per case and shared by the four image localizers, so their
//! errors compare case by case; the matchers' figures equal `localize-bench`'s per-method
//! tables. Run time is the localizer's own call per case (rendering excluded), timed on the
//! thread that ran it, cases in parallel on the rayon pool.
//!
//! This module sits in `study` because the statistical model is the simulator's
//! ([`sim::localizers`]); the others are [`localization`]'s.
//!
//! [`benchmark_cases`]: localization::benchmark_set::benchmark_cases
//! [`BenchmarkMaps`]: localization::benchmark_set::BenchmarkMaps
//! [`case_draws`]: localization::benchmark_set::case_draws
//! [`MAX_PRIOR_OFFSET_M`]: localization::benchmark_set::MAX_PRIOR_OFFSET_M

mod candidate;
mod report;
mod run;

pub use candidate::Candidate;
pub use report::{accuracy_table, table};
pub use run::{BenchmarkRun, Comparison, ComparisonRow, compare};
