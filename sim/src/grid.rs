//! The grid AutoNav plans on, and the grid algorithms.
//!
//! - [`planning_grid`]: per-cell clearance to the zones, slope hazards, terrain class
//!   ([`PlanningGrid`]).
//! - [`edt`]: the exact Euclidean distance transform the clearances come from.
//! - [`astar`]: A* on the 8-connected grid, the paths AutoNav drives.
//! - [`widest_path`]: the bottleneck (maximin) path, the largest uncertainty at which a passage
//!   is still open.

pub mod astar;
pub mod edt;
pub mod planning_grid;
pub mod widest_path;

pub use planning_grid::PlanningGrid;
