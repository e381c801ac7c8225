//! The physical range of every rate and length a scenario or campaign file holds.
//!
//! A finite value outside its range would run to nonsense — a drive rate of 5e-324 m/h made
//! the step time infinite and the drive time NaN, and the rover drove 523 m in a sol; a step
//! of 5e-324 m drove 0 m — so the loaders refuse it, naming the field and the range. Each
//! range is generous against the rover it bounds and carries its reason; the README
//! ("Input formats") lists them. A range whose minimum is 0 holds a margin, an error or a
//! buffer, where 0 means "none".

use crate::check::Check;
use crate::error::ScenarioError;
use sim::autonav::RoverParams;

/// A closed interval of physical values with their unit, as the loaders check it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicalRange {
    /// Smallest value allowed.
    pub min: f64,
    /// Largest value allowed.
    pub max: f64,
    /// The unit, as messages spell it (`metres per hour`).
    pub unit: &'static str,
}

impl PhysicalRange {
    const fn new(min: f64, max: f64, unit: &'static str) -> Self {
        Self { min, max, unit }
    }

    const fn of(range: std::ops::RangeInclusive<f64>, unit: &'static str) -> Self {
        Self::new(*range.start(), *range.end(), unit)
    }

    /// Whether `v` is a finite value inside the range.
    #[must_use]
    pub fn contains(&self, v: f64) -> bool {
        v.is_finite() && (self.min..=self.max).contains(&v)
    }

    /// `v` if it is inside the range; otherwise the one-line error naming `field`, the range
    /// and `v`.
    pub(crate) fn check(&self, c: &Check<'_>, field: &str, v: f64) -> Result<f64, ScenarioError> {
        c.in_range(field, v, self.min, self.max, self.unit)
    }
}

const METRES: &str = "metres";

/// `rover.drive_rate_m_per_h`: Perseverance's AutoNav drives on the order of 100 m/h (the
/// record's 91.9 m/h) with a top speed near 150 m/h; 1000 leaves room for what-if studies,
/// and below 1 m/h a four-hour window drives under 4 m ([`RoverParams::DRIVE_RATE_RANGE_M_PER_H`]).
pub const DRIVE_RATE_M_PER_H: PhysicalRange =
    PhysicalRange::of(RoverParams::DRIVE_RATE_RANGE_M_PER_H, "metres per hour");
/// `rover.step_m`: below 0.25 m the simulator's step bound could end a whole-sol drive at the
/// fastest rate; above 10 m the rover drives several body lengths between path checks
/// ([`RoverParams::STEP_RANGE_M`]).
pub const STEP_M: PhysicalRange = PhysicalRange::of(RoverParams::STEP_RANGE_M, METRES);
/// `rover.waypoint_tolerance_m`: 1 cm is below any orbital map's precision; beyond 100 m a
/// waypoint no longer marks a place ([`RoverParams::WAYPOINT_TOLERANCE_RANGE_M`]).
pub const WAYPOINT_TOLERANCE_M: PhysicalRange =
    PhysicalRange::of(RoverParams::WAYPOINT_TOLERANCE_RANGE_M, METRES);
/// `rover.footprint_radius_m`: Perseverance's is about 1.65 m; 0 plans for the rover's centre
/// alone; beyond 10 m no rover fits a passage.
pub const FOOTPRINT_RADIUS_M: PhysicalRange = PhysicalRange::new(0.0, 10.0, METRES);
/// Margins, buffers, uncertainties and localization errors that may be 0 (`edge_buffer_m`,
/// `initial_margin_m`, `operator_margin_m`, `passage_margin_m`, `reported_sigma_m`,
/// `ground_localization_sigma_m`): beyond 1 km no passage of a rover's route survives.
pub const MARGIN_M: PhysicalRange = PhysicalRange::new(0.0, 1_000.0, METRES);
/// A localizer's typical error (`mean_error_m`, `p99_error_m`): 1 cm is below any orbital
/// map's pixel (HiRISE: 25 cm), 1 km is no localization.
pub const LOCALIZATION_ERROR_M: PhysicalRange = PhysicalRange::new(0.01, 1_000.0, METRES);
/// `onboard_localization.range_sigma_m`: radio-range noise; paper 004 Table 1 has 0.25 to
/// 10 m. Below 1 cm the EKF's measurement covariance is numerically singular.
pub const RANGE_SIGMA_M: PhysicalRange = PhysicalRange::new(0.01, 100.0, METRES);
/// `onboard_localization.image_resolution_m`: an orbital image's pixel, 1 cm to 100 m
/// (HiRISE 0.25 m, CTX 6 m).
pub const IMAGE_RESOLUTION_M: PhysicalRange = PhysicalRange::new(0.01, 100.0, "metres per pixel");
/// `grid.resolution_m`: finer than 1 cm no map has data (and the grid's memory is budgeted);
/// coarser than 50 m a cell cannot represent a passage.
pub const GRID_RESOLUTION_M: PhysicalRange = PhysicalRange::new(0.01, 50.0, METRES);
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
/// `uncertainty.k_vo`, `uncertainty.k_novo`: uncertainty growth per metre driven; 1 m/m is
/// already knowing nothing of the distance.
pub const GROWTH_M_PER_M: PhysicalRange = PhysicalRange::new(0.0, 1.0, "metres per metre");
/// `sols[].historic_distance_m`, `historic_novo_m`: the longest Mars drives are well under
/// 1 km a sol.
pub const SOL_DRIVE_M: PhysicalRange = PhysicalRange::new(0.0, 10_000.0, METRES);
/// `study_segment.distance_m`: less than 1 m is covered in one step; the longest is 10 km a
/// sol over the 10,000 sols a scenario may hold.
pub const STUDY_SEGMENT_M: PhysicalRange = PhysicalRange::new(1.0, 1e8, METRES);
/// `onboard_localization.hbs_slowdown`: co-processor seconds per second of the development
/// machine's run. The flown chain is 1758.2 (a flight-size run takes 32 s, paper 000); 1 is a
/// co-processor as fast as a desktop; at 100,000 a run takes half an hour.
pub const HBS_SLOWDOWN: PhysicalRange = PhysicalRange::new(1.0, 100_000.0, "seconds per second");
/// `onboard_localization.hbs_link_rate_kb_per_s`: 10 KB/s flown, 40 possible (paper 000 §6).
/// Below 1 KB/s the flight-size inputs take over five hours, beyond a sol's activities; above
/// 1000 it is not this serial link.
pub const HBS_LINK_RATE_KB_PER_S: PhysicalRange = PhysicalRange::new(
    1.0,
    1_000.0,
    "KB/s (1 KB = 1000 bytes; 10 flown, 40 after an RCE flight-software update)",
);
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

/// `calendar.relay_latency_h`, `calendar.shift_hours`: a delay or a shift within the day,
/// hours.
pub const CALENDAR_HOURS: PhysicalRange = PhysicalRange::new(0.0, 24.0, "hours");
/// `calendar.light_time_min`: Earth-Mars one-way light time is 3-22 minutes.
pub const LIGHT_TIME_MIN: PhysicalRange = PhysicalRange::new(0.0, 30.0, "minutes");
