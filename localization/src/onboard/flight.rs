//! What one flight-size onboard localization takes and sends (30 m search radius): the run
//! time on the HBS, the files and what crosses the serial link, and how long that takes at
//! the flown rate — each figure with what it was measured or calibrated against.

/// One localization at flight size (240² orthomosaic, ±30 m at 25 cm, DEM, sub-pixel) on the
/// development machine, seconds: `cargo bench --bench localize` group B2, 1 thread (see
/// BENCHMARKS.md).
pub const MEASURED_FLIGHT_SIZE_RUN_S: f64 = 0.0182;

/// Flight-size localization on the HBS Snapdragon 801, seconds ("Phase 2 ran global
/// localization in only 32s", paper 000 §4).
pub const FLIGHT_RUN_S: f64 = 32.0;

/// Bytes of the simulated input files of a flight-size run (30 m radius): the pose file, the
/// orthomosaic and rover DEM with their masks, the orbital tile and DEM (the pose file's length
/// varies by a few bytes with its numbers) — checked by the test
/// `onboard::tests::corrects_a_drifted_estimate_through_the_hbs`. What crosses the link is
/// [`FLIGHT_SIZE_LINK_BYTES`].
pub const FLIGHT_SIZE_INPUT_BYTES: usize = 739_531;

/// The link rate the HBS flew with, bytes per second: "fixed at 10KB/s" (paper 000 §6).
pub const FLIGHT_LINK_BYTES_PER_S: f64 = 10_000.0;

/// The transfer of one onboard localization's inputs at [`FLIGHT_LINK_BYTES_PER_S`], seconds:
/// "although the transfer takes 30 minutes, the entire activity can be safely run in parallel
/// with other operations" (paper 000 §4).
pub const FLIGHT_TRANSFER_S: f64 = 1_800.0;

/// Bytes that cross the link to the HBS for a flight-size run (30 m radius): 30 minutes at
/// 10 KB/s, [`FLIGHT_TRANSFER_S`] × [`FLIGHT_LINK_BYTES_PER_S`].
pub const FLIGHT_SIZE_LINK_BYTES: usize = 18_000_000;

/// The orbital map chip of a flight-size run, bytes: the 25 cm appearance tile and the 1 m
/// DEM around the search window (`map_tile.bin`, `map_dem.bin`), at the simulator's
/// encoding. The paper gives no per-run size (its maps are masked to 100 m of the route and
/// JPEG-XL compressed, §5). A wider search window sends a larger chip. Checked by the test
/// `onboard::tests::corrects_a_drifted_estimate_through_the_hbs`.
pub const FLIGHT_SIZE_MAP_BYTES: usize = 606_224;

/// The input file (`onbd_input.txt`: prior, search radius, method) of a flight-size run,
/// bytes (a few more or less with its numbers).
pub(super) const FLIGHT_SIZE_POSE_BYTES: usize = 67;

/// The post-drive NavCam stereo images that cross the link, bytes. Paper 000 gives no size
/// ("Transfer input file and associated post-drive compressed images to HBS — time
/// consuming", Fig. 19): it is *calibrated to paper 000 §4's ~30 minutes at 10 KB/s* — what
/// [`FLIGHT_SIZE_LINK_BYTES`] leaves after the map chip and the input file, 17,393,709 bytes.
/// The HBS builds the orthomosaic and rover DEM from these images; the simulator renders
/// those directly (`ortho.bin`, `rover_dem.bin`), so they cross the link as the images.
pub const FLIGHT_NAVCAM_IMAGES_BYTES: usize =
    FLIGHT_SIZE_LINK_BYTES - FLIGHT_SIZE_MAP_BYTES - FLIGHT_SIZE_POSE_BYTES;

/// Search radius of the flight-size run, metres (paper 000 §4).
pub(super) const FLIGHT_SEARCH_RADIUS_M: f64 = 30.0;
