//! The physical range of every rate and length a study file holds that is not a simulator
//! setting: where the map lies, the route's and the targets' coordinates, the study segment,
//! a science target's reach, a campaign file's drives and cadences.
//!
//! The simulator's settings carry their own ranges beside their fields, and their own checks
//! (`RoverSettings::STEP_RANGE_M` and `RoverSettings::validate` in `sim::rover::autonav`, …): the
//! loaders run those and name the file's field. As there, a finite value outside its range
//! would run to nonsense, so the loaders refuse it, naming the field and the range; each range
//! carries its reason, and the README ("Input formats") lists them all. A range whose minimum
//! is 0 holds a tolerance, where 0 means "none".

use sim::PhysicalRange;

const METRES: &str = "metres";

/// `map.resolution_m_per_px`: a rover-mast DEM reaches 1 cm; MOLA's gridded DEM is 463 m.
pub const MAP_RESOLUTION_M_PER_PX: PhysicalRange =
    PhysicalRange::new(0.01, 1_000.0, "metres per pixel");
/// `map.dem_datum_m`: Mars spans about −8 km to +22 km.
pub const DEM_DATUM_M: PhysicalRange = PhysicalRange::new(-100_000.0, 100_000.0, METRES);
/// Map-metre coordinates (`route.waypoints`, `map.origin_m`, `science.targets.position_m`):
/// half the equatorial circumference of Mars is 10 660 km; a larger coordinate is off the
/// planet.
pub const COORDINATE_M: PhysicalRange = PhysicalRange::new(
    -maps::zone::MAX_COORDINATE_M,
    maps::zone::MAX_COORDINATE_M,
    "map metres",
);
/// `study_segment.distance_m`: less than 1 m is covered in one step; the longest is 10 km a
/// sol over the 10,000 sols a scenario may hold.
pub const STUDY_SEGMENT_M: PhysicalRange = PhysicalRange::new(1.0, 1e8, METRES);
/// `science.targets[].within_m`: how close the rover must truly be to observe; 10 cm is an
/// arm's placement, 1 km a remote sensor's longest reach.
pub const WITHIN_M: PhysicalRange = PhysicalRange::new(0.1, 1_000.0, METRES);
/// A drive's length in a campaign file (`drive.length_m`): 10 cm to 100 km (a drive lasts at
/// most 3 sols, checked with its rate).
pub const DRIVE_LENGTH_M: PhysicalRange = PhysicalRange::new(0.1, 100_000.0, METRES);
/// A state-based cadence (`every_m`): one instance per 1 m is already one per few steps;
/// 100 km is beyond any campaign's traverse.
pub const CADENCE_M: PhysicalRange = PhysicalRange::new(1.0, 100_000.0, METRES);
/// A state-based cadence's tolerance (`tolerance_m`): 0 (exactly at the distance) to 100 km.
pub const CADENCE_TOLERANCE_M: PhysicalRange = PhysicalRange::new(0.0, 100_000.0, METRES);
