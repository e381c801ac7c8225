//! The onboard global localization activity end to end, as the simulator runs it after a drive
//! (paper 000 §5-§7, Fig. 18-19).
//!
//! [`run_onboard`] takes the map the rover carries, where the rover truly is, where it believes
//! it is and how uncertain it is, and does what the flight system does:
//!
//! 1. **Imaging** — renders the post-drive orthomosaic and rover DEM at the *true* position, and
//!    the orbital appearance (25 cm) and DEM (1 m) tile around the *estimated* position, from a
//!    truth patch of the map ([`crate::synthetic`]). The truth and orbital seeds are fixed per
//!    scenario (one world, one orbital map); the rover seed changes every sol.
//! 2. **`MOB_WRITE_ONBD_INPUT_FILE`** — the pose file (prior, search radius, method) and the
//!    images and map tiles as [`HbsFile`]s with their checksums ([`encode_u8`], [`encode_f32`]).
//!    Each crosses the link at its flight size: the post-drive NavCam images
//!    ([`FLIGHT_NAVCAM_IMAGES_BYTES`], which the rendered orthomosaic and rover DEM stand in
//!    for), the orbital map chip and the input file at their own length — about 18 MB, 30 min
//!    at the flown 10 KB/s ([`FLIGHT_SIZE_LINK_BYTES`]).
//! 3. **The HBS activity** ([`crate::hbs::run_activity`]) — transfer, run, reboot, run, compare,
//!    with the matcher ([`localize`]) as the algorithm; the rover's validity check accepts only a
//!    well-formed result that passed the matcher's own checks with σ within the limit.
//! 4. **`MOB_APPLY_ONBD_LOCALIZATION`** — an [`OnboardRun`] with the applied position and σ, or
//!    why the localization was lost, and the activity's events and duration for the sol log.
//!
//! The search radius is the rover's uncertainty radius, kept within
//! [`OnboardSettings::min_search_radius_m`]..[`OnboardSettings::max_search_radius_m`]
//! (30 m by default, up to 100 m: paper 000 §4).
//!
//! Many runs on one map (a study's runs and strategies) share an [`OnboardCache`] through
//! [`run_onboard_with`]: the map's seed-independent terrain fields and the most recent renders,
//! which give the same results as rendering again.
//!
//! ## Timing
//! The HBS run time in the sol log is *not* this machine's wall clock (that would make outputs
//! differ run to run). It is [`OnboardSettings::hbs_slowdown`] × [`MEASURED_FLIGHT_SIZE_RUN_S`]
//! (one flight-size localization on the development machine, measured by `cargo bench --bench
//! localize`) × the run's work relative to flight size (search-window area). Link time is the
//! flight size of the input files ([`HbsFile::link_bytes`]) and the real size of the result
//! files at [`HbsSettings::link_bytes_per_s`]: at 10 KB/s a flight-size run's inputs take
//! [`FLIGHT_TRANSFER_S`], the paper's 30 minutes; a wider search sends a larger map chip.

use std::sync::Arc;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use maps::{GeoTransform, MapLayers, Raster};

use crate::benchmark_set::PATCH_MARGIN_M;
use crate::hbs::{ActivityLog, HbsFile, HbsSettings, LossReason, run_activity};
use crate::matcher::{MatchResult, MatchSettings, Method, OrbitalMap, RoverImages, localize};
use crate::synthetic::{
    ORTHO_RESOLUTION_M_PER_PX, ORTHO_SIZE_PX, OrbitalSettings, RoverImagingSettings,
    RoverObservation, SyntheticError, patch_grid, render_orbital_with, render_rover,
    truth_patch_on,
};

mod cache;
mod flight;

use cache::Rendered;
pub use cache::{DEFAULT_RECENT_RENDERS, OnboardCache};
use flight::FLIGHT_SEARCH_RADIUS_M;
pub use flight::{
    FLIGHT_LINK_BYTES_PER_S, FLIGHT_NAVCAM_IMAGES_BYTES, FLIGHT_RUN_S, FLIGHT_SIZE_INPUT_BYTES,
    FLIGHT_SIZE_LINK_BYTES, FLIGHT_SIZE_MAP_BYTES, FLIGHT_TRANSFER_S, MEASURED_FLIGHT_SIZE_RUN_S,
};

/// Settings of the onboard localization activity (plain struct; defaults on each field).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct OnboardSettings {
    /// Matcher settings; `search_radius_m` is replaced by the radius of each run and `method`
    /// chooses census, NCC or mutual information (default: [`MatchSettings::default`]).
    pub matcher: MatchSettings,
    /// Orbital products (default: [`OrbitalSettings::default`]).
    pub orbital: OrbitalSettings,
    /// Rover imaging (default: [`RoverImagingSettings::default`]).
    pub rover: RoverImagingSettings,
    /// The co-processor; `run_s` is replaced by the scaled run time of each run
    /// (default: [`HbsSettings::default`], no upsets).
    pub hbs: HbsSettings,
    /// Smallest search radius, metres (default: 30, paper 000 §4).
    pub min_search_radius_m: f64,
    /// Largest search radius, metres (default: 100, paper 000 §4).
    pub max_search_radius_m: f64,
    /// HBS seconds per second of this machine's run (default: [`FLIGHT_RUN_S`] ÷
    /// [`MEASURED_FLIGHT_SIZE_RUN_S`], so a flight-size run takes the paper's 32 s; the flight
    /// run also builds the orthomosaic from the stereo images, which solsim does not time).
    pub hbs_slowdown: f64,
}

impl Default for OnboardSettings {
    fn default() -> Self {
        Self {
            matcher: MatchSettings::default(),
            orbital: OrbitalSettings::default(),
            rover: RoverImagingSettings::default(),
            hbs: HbsSettings::default(),
            min_search_radius_m: FLIGHT_SEARCH_RADIUS_M,
            max_search_radius_m: 100.0,
            hbs_slowdown: FLIGHT_RUN_S / MEASURED_FLIGHT_SIZE_RUN_S,
        }
    }
}

/// What the simulator knows when the activity starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OnboardRequest {
    /// True rover position, map metres (renders the rover's images; never seen by the matcher).
    pub truth_m: [f64; 2],
    /// The rover's estimated position, map metres (the prior).
    pub prior_m: [f64; 2],
    /// The rover's position uncertainty radius, metres (sets the search radius).
    pub uncertainty_m: f64,
    /// Seed of the truth terrain (fixed per scenario).
    pub truth_seed: u64,
    /// Seed of the orbital map (fixed per scenario).
    pub orbital_seed: u64,
    /// Seed of this sol's rover imaging and of the HBS upset draws.
    pub sol_seed: u64,
}

/// What the activity produced.
#[derive(Clone, Debug, PartialEq)]
pub struct OnboardRun {
    /// Search radius used, metres.
    pub search_radius_m: f64,
    /// The matcher's result on the uncorrupted inputs (diagnostics; `None` if imaging or the
    /// matcher could not run).
    pub matched: Option<MatchResult>,
    /// The applied position and σ (`None` when lost).
    pub applied: Option<AppliedFix>,
    /// Why the localization was lost (`None` when applied).
    pub lost_reason: Option<LostReason>,
    /// The HBS activity log (steps, upsets, duration); empty when imaging failed.
    pub log: ActivityLog,
    /// Bytes of the simulated input files.
    pub input_bytes: usize,
    /// Bytes that crossed the link to the HBS, at flight size ([`HbsFile::link_bytes`]).
    pub link_bytes: usize,
}

/// Why an onboard localization was lost (a bad outcome, logged; the rover drives on).
///
/// Displayed (and serialised, as a string) as the sol log's sentence, e.g. `no imagery for the
/// search window: …` or `validity checks failed: REJECTED: ambiguous match: …`.
#[derive(Clone, Debug, PartialEq)]
pub enum LostReason {
    /// The post-drive imagery or the orbital tile could not be rendered for the search window
    /// (it leaves the map): nothing was sent to the co-processor.
    NoImagery(SyntheticError),
    /// The co-processor activity lost it: a checksum, a timeout, the two results differ, or
    /// the result failed the rover's validity checks.
    Hbs(LossReason),
}

impl std::fmt::Display for LostReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LostReason::NoImagery(e) => write!(f, "no imagery for the search window: {e}"),
            LostReason::Hbs(reason) => reason.fmt(f),
        }
    }
}

impl serde::Serialize for LostReason {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// A localization applied by `MOB_APPLY_ONBD_LOCALIZATION`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AppliedFix {
    /// Position the rover's estimate moves to, map metres.
    pub position_m: [f64; 2],
    /// The localizer's σ, metres.
    pub sigma_m: f64,
}

/// Serialise a u8 raster and its validity: `width`, `height` (u32 LE), the samples, one byte
/// per validity flag.
#[must_use]
pub fn encode_u8(r: &Raster<u8>, valid: &[bool]) -> Vec<u8> {
    let mut b = Vec::with_capacity(8 + 2 * r.data.len());
    b.extend_from_slice(&(r.width as u32).to_le_bytes());
    b.extend_from_slice(&(r.height as u32).to_le_bytes());
    b.extend_from_slice(&r.data);
    b.extend(valid.iter().map(|&v| u8::from(v)));
    b
}

/// Serialise an f32 raster and its validity: `width`, `height` (u32 LE), the samples (f32 LE),
/// one byte per validity flag.
#[must_use]
pub fn encode_f32(r: &Raster<f32>, valid: &[bool]) -> Vec<u8> {
    let mut b = Vec::with_capacity(8 + 5 * r.data.len());
    b.extend_from_slice(&(r.width as u32).to_le_bytes());
    b.extend_from_slice(&(r.height as u32).to_le_bytes());
    for v in &r.data {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b.extend(valid.iter().map(|&v| u8::from(v)));
    b
}

/// Width and height from an encoded header, and the sample count (`None` if the buffer is too
/// short or its length does not match `bytes_per_sample`).
fn header(b: &[u8], bytes_per_sample: usize) -> Option<(usize, usize)> {
    let word = |i: usize| {
        b.get(i..i + 4)
            .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]) as usize)
    };
    let (w, h) = (word(0)?, word(4)?);
    let n = w.checked_mul(h)?;
    (b.len() == 8 + n.checked_mul(bytes_per_sample + 1)?).then_some((w, h))
}

/// Read back an encoded raster of `bytes_per_sample`-byte samples; `None` if malformed.
fn decode<T>(
    b: &[u8],
    geo: GeoTransform,
    bytes_per_sample: usize,
    sample: impl Fn(&[u8]) -> T,
) -> Option<(Raster<T>, Vec<bool>)> {
    let (w, h) = header(b, bytes_per_sample)?;
    let n = w * h;
    let split = 8 + bytes_per_sample * n;
    let data = b[8..split]
        .chunks_exact(bytes_per_sample)
        .map(sample)
        .collect();
    let valid = b[split..].iter().map(|&v| v != 0).collect();
    Some((
        Raster {
            width: w,
            height: h,
            geo,
            data,
        },
        valid,
    ))
}

/// Read back what [`encode_u8`] wrote; `None` if the buffer is malformed (e.g. a corrupted
/// header).
#[must_use]
pub fn decode_u8(b: &[u8], geo: GeoTransform) -> Option<(Raster<u8>, Vec<bool>)> {
    decode(b, geo, 1, |c| c[0])
}

/// Read back what [`encode_f32`] wrote; `None` if the buffer is malformed.
#[must_use]
pub fn decode_f32(b: &[u8], geo: GeoTransform) -> Option<(Raster<f32>, Vec<bool>)> {
    decode(b, geo, 4, |c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
}

/// The pose file: prior position, search radius and method, one `key=value` per field.
fn pose_file(prior_m: [f64; 2], radius_m: f64, method: Method) -> Vec<u8> {
    format!(
        "prior_x_m={:?}\nprior_y_m={:?}\nsearch_radius_m={:?}\nmethod={}\n",
        prior_m[0],
        prior_m[1],
        radius_m,
        method.name()
    )
    .into_bytes()
}

/// Parse [`pose_file`]'s output.
fn parse_pose(b: &[u8]) -> Option<([f64; 2], f64, Method)> {
    let text = std::str::from_utf8(b).ok()?;
    let mut kv = text.lines().filter_map(|l| l.split_once('='));
    let mut num = |key: &str| {
        let (k, v) = kv.next()?;
        (k == key).then(|| v.parse::<f64>().ok())?
    };
    let (x, y, r) = (
        num("prior_x_m")?,
        num("prior_y_m")?,
        num("search_radius_m")?,
    );
    let (k, m) = kv.next()?;
    let method = (k == "method").then(|| Method::from_name(m))??;
    (x.is_finite() && y.is_finite() && r.is_finite() && r > 0.0).then_some(([x, y], r, method))
}

/// The result file the HBS writes: every number with full precision so the two runs compare
/// byte for byte, and the matcher's verdict.
fn result_file(m: &MatchResult) -> Vec<u8> {
    format!(
        "x_m={:?}\ny_m={:?}\nsigma_m={:?}\npeak_ratio={:?}\nvalid_fraction={:?}\nverdict={}\n",
        m.position_m[0],
        m.position_m[1],
        m.sigma_m,
        m.peak_ratio,
        m.valid_fraction,
        m.rejection
            .as_ref()
            .map_or_else(|| "ACCEPTED".to_string(), |r| format!("REJECTED: {r}"))
    )
    .into_bytes()
}

/// The rover's validity check of a result file (`MOB_APPLY_ONBD_LOCALIZATION`): well formed,
/// accepted by the matcher, finite, σ within `max_sigma_m`. Returns the fix.
fn check_result(b: &[u8], max_sigma_m: f64) -> Result<AppliedFix, String> {
    let text = std::str::from_utf8(b).map_err(|_| "result file is not text".to_string())?;
    let value = |key: &str| -> Result<&str, String> {
        text.lines()
            .filter_map(|l| l.split_once('='))
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v)
            .ok_or_else(|| format!("result file has no {key}: {}", text.trim()))
    };
    let verdict = value("verdict")?;
    if verdict != "ACCEPTED" {
        return Err(verdict.to_string());
    }
    let num = |key: &str| -> Result<f64, String> {
        value(key)?
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("result file field {key} is not a finite number"))
    };
    let fix = AppliedFix {
        position_m: [num("x_m")?, num("y_m")?],
        sigma_m: num("sigma_m")?,
    };
    if !(fix.sigma_m >= 0.0 && fix.sigma_m <= max_sigma_m) {
        return Err(format!("σ {} m outside 0..{max_sigma_m} m", fix.sigma_m));
    }
    Ok(fix)
}

/// Decode the HBS input files and run the matcher (the algorithm the HBS runs, twice).
fn hbs_algorithm(files: &[HbsFile], geos: &[GeoTransform; 4], params: &MatchSettings) -> Vec<u8> {
    let run = || -> Result<MatchResult, String> {
        let (prior, radius, method) = parse_pose(&files[0].bytes).ok_or("unreadable pose file")?;
        let (ortho, ortho_valid) =
            decode_u8(&files[1].bytes, geos[0]).ok_or("unreadable orthomosaic")?;
        let (rover_dem, rover_dem_valid) =
            decode_f32(&files[2].bytes, geos[1]).ok_or("unreadable rover DEM")?;
        let (appearance, _) = decode_u8(&files[3].bytes, geos[2]).ok_or("unreadable map tile")?;
        let (map_dem, _) = decode_f32(&files[4].bytes, geos[3]).ok_or("unreadable map DEM")?;
        if ortho_valid.len() != ortho.data.len() || rover_dem_valid.len() != rover_dem.data.len() {
            return Err("malformed validity mask".into());
        }
        let p = MatchSettings {
            search_radius_m: radius,
            method,
            ..*params
        };
        localize(
            &OrbitalMap {
                appearance: &appearance,
                dem: Some(&map_dem),
            },
            &RoverImages {
                ortho: &ortho,
                ortho_valid: &ortho_valid,
                dem: Some((&rover_dem, &rover_dem_valid)),
            },
            prior,
            &p,
        )
        .map_err(|e| e.to_string())
    };
    result_bytes(&run())
}

/// The result file of a matcher outcome (an error is a result file too, which the rover's
/// validity check refuses).
fn result_bytes(outcome: &Result<MatchResult, String>) -> Vec<u8> {
    match outcome {
        Ok(m) => result_file(m),
        Err(e) => format!("verdict=ERROR: {e}\n").into_bytes(),
    }
}

/// The imagery of one localization activity: the orbital products of a patch around the
/// prior and the rover's post-drive observation rendered at the truth.
#[derive(Clone, Debug)]
pub struct ActivityImagery {
    rendered: Arc<Rendered>,
    /// The rover's orthomosaic and DEM with their validity, rendered at the true position.
    pub rover: RoverObservation,
}

impl ActivityImagery {
    /// The orbital map of the patch: appearance and DEM as the orbiter sees them.
    #[must_use]
    pub fn orbital_map(&self) -> OrbitalMap<'_> {
        OrbitalMap::of(&self.rendered.orbital)
    }

    /// The rover's images as the matcher takes them.
    #[must_use]
    pub fn rover_images(&self) -> RoverImages<'_> {
        RoverImages::of(&self.rover)
    }
}

/// Render what one activity sees (as [`run_onboard_with`] does): a patch covering a search
/// window of `radius_m` around `req.prior_m` and the rover's view around `req.truth_m`, its
/// orbital products, and the rover's imagery at the truth drawn from `rover_seed`
/// ([`run_onboard_with`] takes it as the first draw of `req.sol_seed`'s stream).
///
/// # Errors
/// [`SyntheticError`] if the window or the rover's view leaves the map, or a setting is out
/// of range.
pub fn render_activity_imagery(
    layers: &MapLayers,
    cache: Option<&OnboardCache>,
    req: &OnboardRequest,
    s: &OnboardSettings,
    radius_m: f64,
    rover_seed: u64,
) -> Result<ActivityImagery, SyntheticError> {
    let half_ortho_m = 0.5 * ORTHO_SIZE_PX as f64 * ORTHO_RESOLUTION_M_PER_PX;
    let offset = (req.truth_m[0] - req.prior_m[0])
        .abs()
        .max((req.truth_m[1] - req.prior_m[1]).abs());
    let half_size_m = radius_m.max(offset) + half_ortho_m + PATCH_MARGIN_M;
    let rendered = match cache.filter(|c| c.serves(layers)) {
        Some(c) => c.render(
            layers,
            req.prior_m,
            half_size_m,
            req.truth_seed,
            req.orbital_seed,
            &s.orbital,
        ),
        None => patch_grid(layers, req.prior_m, half_size_m).and_then(|(geo, n)| {
            let patch = truth_patch_on(layers, geo, n, req.truth_seed, None, None);
            let orbital = render_orbital_with(&patch, &s.orbital, req.orbital_seed, None)?;
            Ok(Arc::new(Rendered { patch, orbital }))
        }),
    }?;
    let rover = render_rover(&rendered.patch, req.truth_m, &s.rover, rover_seed)?;
    Ok(ActivityImagery { rendered, rover })
}

/// Run one onboard localization activity on `layers` (the scenario's map).
///
/// Never panics on bad geometry: a search window off the map, or imaging that cannot be
/// rendered, is a lost localization with the reason.
#[must_use]
pub fn run_onboard(layers: &MapLayers, req: &OnboardRequest, s: &OnboardSettings) -> OnboardRun {
    run_onboard_with(layers, None, req, s)
}

/// [`run_onboard`] sharing `cache` with the other runs on `layers` (if it is that map's:
/// [`OnboardCache::serves`]): the same run, faster when many runs share one map.
#[must_use]
pub fn run_onboard_with(
    layers: &MapLayers,
    cache: Option<&OnboardCache>,
    req: &OnboardRequest,
    s: &OnboardSettings,
) -> OnboardRun {
    let radius_m = req
        .uncertainty_m
        .clamp(s.min_search_radius_m, s.max_search_radius_m);
    let mut run = OnboardRun {
        search_radius_m: radius_m,
        matched: None,
        applied: None,
        lost_reason: None,
        log: ActivityLog {
            events: Vec::new(),
            upsets: Vec::new(),
            duration_s: 0.0,
            outcome: Err(LossReason::Invalid {
                reason: "not run".into(),
            }),
        },
        input_bytes: 0,
        link_bytes: 0,
    };
    let params = MatchSettings {
        search_radius_m: radius_m,
        ..s.matcher
    };
    // One patch covers the search window around the prior and the rover's view around the truth.
    let mut sol_rng = ChaCha8Rng::seed_from_u64(req.sol_seed);
    let rover_seed = rand::RngExt::random::<u64>(&mut sol_rng);
    let imagery = match render_activity_imagery(layers, cache, req, s, radius_m, rover_seed) {
        Ok(v) => v,
        Err(e) => {
            run.lost_reason = Some(LostReason::NoImagery(e));
            return run;
        }
    };
    let (rendered, rover) = (&imagery.rendered, &imagery.rover);
    let orbital = &rendered.orbital;
    let geos = [
        rover.ortho.geo,
        rover.dem.geo,
        orbital.appearance.geo,
        orbital.dem.geo,
    ];
    let all_valid = |n: usize| vec![true; n];
    let inputs = vec![
        HbsFile::new(
            "onbd_input.txt",
            pose_file(req.prior_m, radius_m, params.method),
        ),
        // The orthomosaic and rover DEM stand in for the NavCam images they are built from,
        // which cross the link at their flight size.
        HbsFile::new("ortho.bin", encode_u8(&rover.ortho, &rover.valid))
            .with_link_bytes(FLIGHT_NAVCAM_IMAGES_BYTES),
        HbsFile::new("rover_dem.bin", encode_f32(&rover.dem, &rover.dem_valid)).with_link_bytes(0),
        HbsFile::new(
            "map_tile.bin",
            encode_u8(
                &orbital.appearance,
                &all_valid(orbital.appearance.data.len()),
            ),
        ),
        HbsFile::new(
            "map_dem.bin",
            encode_f32(&orbital.dem, &all_valid(orbital.dem.data.len())),
        ),
    ];
    run.input_bytes = inputs.iter().map(|f| f.bytes.len()).sum();
    run.link_bytes = inputs.iter().map(|f| f.link_bytes).sum();
    // The fault-free run, once. The matcher is deterministic, so an HBS run on intact inputs
    // returns exactly these bytes; only a run on inputs an upset changed is computed again.
    let fault_free = localize(
        &OrbitalMap::of(orbital),
        &RoverImages::of(rover),
        req.prior_m,
        &params,
    )
    .map_err(|e| e.to_string());
    let fault_free_bytes = result_bytes(&fault_free);
    debug_assert_eq!(
        hbs_algorithm(&inputs, &geos, &params),
        fault_free_bytes,
        "an HBS run on intact inputs must equal the fault-free run"
    );
    run.matched = fault_free.ok();
    let algorithm = |files: &[HbsFile]| {
        if files == inputs.as_slice() {
            fault_free_bytes.clone()
        } else {
            hbs_algorithm(files, &geos, &params)
        }
    };
    let window_px = (2.0 * radius_m) / ORTHO_RESOLUTION_M_PER_PX + ORTHO_SIZE_PX as f64;
    let flight_window_px =
        (2.0 * FLIGHT_SEARCH_RADIUS_M) / ORTHO_RESOLUTION_M_PER_PX + ORTHO_SIZE_PX as f64;
    let hbs = HbsSettings {
        run_s: s.hbs_slowdown * MEASURED_FLIGHT_SIZE_RUN_S * (window_px / flight_window_px).powi(2),
        ..s.hbs
    };
    let max_sigma_m = params.max_sigma_m;
    run.log = run_activity(&inputs, &hbs, &mut sol_rng, algorithm, |b| {
        check_result(b, max_sigma_m).map(|_| ())
    });
    // The activity applied the result only after the same check passed, so the second
    // `check_result` fails only if the two disagree; it is still a lost localization.
    match &run.log.outcome {
        Ok(bytes) => match check_result(bytes, max_sigma_m) {
            Ok(fix) => run.applied = Some(fix),
            Err(reason) => run.lost_reason = Some(LostReason::Hbs(LossReason::Invalid { reason })),
        },
        Err(reason) => run.lost_reason = Some(LostReason::Hbs(reason.clone())),
    }
    run
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::flight::FLIGHT_SIZE_POSE_BYTES;
    use super::*;
    use crate::benchmark_set::{BenchmarkMaps, TerrainKind};
    use crate::hbs::HbsStep;

    fn request(truth: [f64; 2], prior: [f64; 2], r: f64) -> OnboardRequest {
        OnboardRequest {
            truth_m: truth,
            prior_m: prior,
            uncertainty_m: r,
            truth_seed: 1,
            orbital_seed: 2,
            sol_seed: 3,
        }
    }

    #[test]
    fn encodings_round_trip_and_reject_corrupt_headers() {
        let geo = GeoTransform::new(0.0, 3.0, 1.0);
        let r = Raster {
            width: 2,
            height: 3,
            geo,
            data: vec![1u8, 2, 3, 4, 5, 6],
        };
        let valid = vec![true, false, true, true, false, true];
        let (back, v) = decode_u8(&encode_u8(&r, &valid), geo).unwrap();
        assert_eq!((back, v), (r.clone(), valid.clone()));
        let f = Raster {
            width: 2,
            height: 3,
            geo,
            data: vec![1.5f32, -2.0, 3.25, f32::NAN, 5.0, 6.0],
        };
        let (back, v) = decode_f32(&encode_f32(&f, &valid), geo).unwrap();
        assert_eq!(v, valid);
        assert_eq!(back.data[..3], f.data[..3]);
        assert!(back.data[3].is_nan());
        let mut bad = encode_u8(&r, &valid);
        bad[0] ^= 0x10;
        assert!(decode_u8(&bad, geo).is_none());
        assert!(decode_f32(&[1, 2, 3], geo).is_none());
    }

    #[test]
    fn pose_and_result_files_round_trip() {
        let b = pose_file([12.5, -3.0], 42.0, Method::Ncc);
        assert_eq!(parse_pose(&b), Some(([12.5, -3.0], 42.0, Method::Ncc)));
        assert_eq!(parse_pose(b"prior_x_m=1\nprior_y_m=x\n"), None);
        assert!(check_result(b"verdict=ERROR: boom\n", 1.5).is_err());
        assert!(check_result(b"x_m=1\ny_m=2\nsigma_m=9\nverdict=ACCEPTED\n", 1.5).is_err());
        let fix = check_result(b"x_m=1\ny_m=2\nsigma_m=0.2\nverdict=ACCEPTED\n", 1.5).unwrap();
        assert_eq!(fix.position_m, [1.0, 2.0]);
    }

    #[test]
    fn corrects_a_drifted_estimate_through_the_hbs() {
        let maps = BenchmarkMaps::generate(1);
        let layers = maps.get(TerrainKind::Rocky);
        let truth = [300.0, 310.0];
        let prior = [307.0, 301.0];
        let run = run_onboard(
            layers,
            &request(truth, prior, 14.0),
            &OnboardSettings::default(),
        );
        let fix = run.applied.expect("applied");
        let err = (fix.position_m[0] - truth[0]).hypot(fix.position_m[1] - truth[1]);
        assert!(err < 1.0, "error {err} m; {run:?}");
        assert_eq!(run.search_radius_m, 30.0);
        let steps: Vec<_> = run.log.events.iter().map(|e| e.step).collect();
        assert_eq!(steps.first(), Some(&HbsStep::WriteInputFile));
        assert_eq!(steps.last(), Some(&HbsStep::ApplyLocalization));
        // Flight-size run: the scaled run time is the paper's 32 s, twice, plus link and reboot.
        let link_s = run.link_bytes as f64 / 10_000.0;
        assert!(run.log.duration_s > 2.0 * FLIGHT_RUN_S + 120.0 + link_s - 1e-6);
        assert!(
            run.input_bytes.abs_diff(FLIGHT_SIZE_INPUT_BYTES) < 64,
            "{}",
            run.input_bytes
        );
        // The inputs cross the link in the paper's 30 minutes at 10 KB/s.
        // The map chip: everything but the pose file, the orthomosaic and the rover DEM.
        let pose_bytes = run.input_bytes - FLIGHT_SIZE_MAP_BYTES - 115_208 - 18_008;
        assert!(
            pose_bytes.abs_diff(FLIGHT_SIZE_POSE_BYTES) < 16,
            "{pose_bytes}"
        );
        assert!(
            run.link_bytes.abs_diff(FLIGHT_SIZE_LINK_BYTES) < 64,
            "{}",
            run.link_bytes
        );
        let transfer = run
            .log
            .events
            .iter()
            .find(|e| e.step == HbsStep::TransferToHbs);
        let transfer_s = transfer.map(|e| e.t_s).unwrap_or_default();
        assert!((transfer_s - FLIGHT_TRANSFER_S).abs() < 0.1, "{transfer_s}");
        // Same request, same run.
        let again = run_onboard(
            layers,
            &request(truth, prior, 14.0),
            &OnboardSettings::default(),
        );
        assert_eq!(again, run);
    }

    #[test]
    fn upsets_never_apply_a_result_other_than_the_fault_free_one() {
        let maps = BenchmarkMaps::generate(1);
        let layers = maps.get(TerrainKind::Rocky);
        let mut settings = OnboardSettings::default();
        settings.hbs.p_flip_memory = 1.0;
        settings.hbs.p_flip_storage = 0.5;
        for sol_seed in 0..6 {
            let req = OnboardRequest {
                sol_seed,
                ..request([300.0, 310.0], [304.0, 306.0], 10.0)
            };
            let run = run_onboard(layers, &req, &settings);
            assert!(!run.log.upsets.is_empty());
            if let Some(fix) = run.applied {
                let m = run.matched.as_ref().expect("fault-free result");
                assert_eq!(fix.position_m[0].to_bits(), m.position_m[0].to_bits());
                assert_eq!(fix.position_m[1].to_bits(), m.position_m[1].to_bits());
            } else {
                assert!(run.lost_reason.is_some());
            }
        }
    }

    #[test]
    fn off_map_window_is_a_lost_localization_not_a_panic() {
        let maps = BenchmarkMaps::generate(1);
        let layers = maps.get(TerrainKind::Plain);
        let run = run_onboard(
            layers,
            &request([5.0, 5.0], [8.0, 2.0], 10.0),
            &OnboardSettings::default(),
        );
        assert!(run.applied.is_none());
        let reason = run.lost_reason.expect("lost");
        assert!(
            matches!(
                reason,
                LostReason::NoImagery(SyntheticError::PatchOutsideMap { .. })
            ),
            "{reason:?}"
        );
        assert!(
            reason
                .to_string()
                .starts_with("no imagery for the search window: patch "),
            "{reason}"
        );
    }
}
