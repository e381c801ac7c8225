//! `solsim localize` end to end on rasters written to disk: a synthetic post-drive scene
//! (orbital orthoimage and DEM, rover orthomosaic, masks and DEM from
//! `localization::synthetic`) is written as GeoTIFF and PNG, localized from a prior several
//! metres off, and compared with the truth and with a direct call of
//! `localization::matcher::localize` on the same rasters. Bad input — missing files, wrong
//! pixel types, masks of the wrong size, no valid pixels, mismatched resolutions, a prior off
//! the map, a search window leaving it, NaN and out-of-range flags — gets exit code 2 and one
//! `error:` line naming the file or flag, never a panic. The README's example is run as printed.

use crate::common;

use common::{assert_bad_input, root, solsim, stderr};
use std::path::PathBuf;
use std::process::Output;
use std::sync::OnceLock;

use localization::matcher::{MatchSettings, OrbitalMap, RoverImages, localize};
use localization::synthetic::{
    OrbitalProducts, OrbitalSettings, RoverImagingSettings, RoverObservation, render_orbital,
    render_rover, truth_patch,
};
use maps::raster_io::{write_dem, write_geotiff, write_raster};
use maps::{GeoTransform, MapLayers, Raster};

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Search radius used by the tests, metres (small, so the scene renders quickly).
const RADIUS_M: f64 = 15.0;

/// One synthetic scene, rendered once and written to disk for every test.
struct Scene {
    dir: PathBuf,
    truth_m: [f64; 2],
    prior_m: [f64; 2],
    orbital: OrbitalProducts,
    rover: RoverObservation,
}

impl Scene {
    fn file(&self, name: &str) -> String {
        self.dir.join(name).to_str().expect("utf8").to_owned()
    }

    fn prior(&self) -> String {
        format!("{},{}", self.prior_m[0], self.prior_m[1])
    }

    /// The arguments of a good run on the GeoTIFF map and the PNG orthomosaic.
    fn good_args(&self) -> Vec<String> {
        [
            "localize",
            "--map-appearance",
            &self.file("map.tif"),
            "--map-dem",
            &self.file("map-dem.tif"),
            "--ortho",
            &self.file("ortho.png"),
            "--ortho-valid",
            &self.file("ortho-valid.png"),
            "--rover-dem",
            &self.file("rover-dem.tif"),
            "--rover-dem-valid",
            &self.file("rover-dem-valid.png"),
            "--prior",
            &self.prior(),
            "--radius",
            &RADIUS_M.to_string(),
        ]
        .map(str::to_owned)
        .to_vec()
    }
}

fn mask(geo: GeoTransform, w: usize, h: usize, valid: &[bool]) -> Raster<u8> {
    Raster {
        width: w,
        height: h,
        geo,
        data: valid.iter().map(|&v| if v { 255 } else { 0 }).collect(),
    }
}

fn scene() -> &'static Scene {
    static SCENE: OnceLock<Scene> = OnceLock::new();
    SCENE.get_or_init(|| {
        let a = root().join("maps/assets/crater-floor");
        let layers = MapLayers::load(
            &a.join("appearance.tif"),
            &a.join("dem.tif"),
            &a.join("terrain.tif"),
            0.0,
            None,
        )
        .expect("bundled map");
        let truth_m = [700.0, 520.0];
        let prior_m = [truth_m[0] + 4.5, truth_m[1] - 3.25];
        // The patch covers the search window around the prior plus half the orthomosaic.
        let patch = truth_patch(&layers, prior_m, RADIUS_M + 30.0 + 4.0, 21).expect("patch");
        let orbital = render_orbital(&patch, &OrbitalSettings::default(), 22).expect("orbital");
        let rover =
            render_rover(&patch, truth_m, &RoverImagingSettings::default(), 23).expect("rover");

        // Rendering is deterministic and every writer renames atomically, so concurrent test
        // runs sharing this directory write identical files.
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("localize_cli");
        std::fs::create_dir_all(&dir).expect("mkdir");
        let w = |name: &str| dir.join(name);
        write_geotiff(&w("map.tif"), &orbital.appearance, None).expect("map.tif");
        write_raster(&w("map.png"), &orbital.appearance).expect("map.png");
        write_geotiff(&w("map-dem.tif"), &orbital.dem, None).expect("map-dem.tif");
        write_dem(&w("map-dem-cm.png"), &orbital.dem, 0.0).expect("map-dem-cm.png");
        write_raster(&w("ortho.png"), &rover.ortho).expect("ortho.png");
        let (ow, oh) = (rover.ortho.width, rover.ortho.height);
        write_raster(
            &w("ortho-valid.png"),
            &mask(rover.ortho.geo, ow, oh, &rover.valid),
        )
        .expect("ortho-valid.png");
        write_geotiff(&w("rover-dem.tif"), &rover.dem, None).expect("rover-dem.tif");
        let (dw, dh) = (rover.dem.width, rover.dem.height);
        write_raster(
            &w("rover-dem-valid.png"),
            &mask(rover.dem.geo, dw, dh, &rover.dem_valid),
        )
        .expect("rover-dem-valid.png");
        let mut holes = rover.dem.clone();
        for (h, &v) in holes.data.iter_mut().zip(&rover.dem_valid) {
            if !v {
                *h = f32::NAN;
            }
        }
        write_geotiff(&w("rover-dem-nan.tif"), &holes, None).expect("rover-dem-nan.tif");
        // Bad files.
        let g = rover.ortho.geo;
        write_raster(&w("flat-ortho.png"), &Raster::filled(ow, oh, g, 128u8)).expect("flat");
        write_raster(&w("small-mask.png"), &Raster::filled(10, 10, g, 255u8)).expect("small");
        write_raster(&w("empty-mask.png"), &Raster::filled(ow, oh, g, 0u8)).expect("empty");
        write_raster(&w("ortho-u16.png"), &Raster::filled(ow, oh, g, 300u16)).expect("u16");
        Scene {
            dir,
            truth_m,
            prior_m,
            orbital,
            rover,
        }
    })
}

/// The "E x m, N y m" position of the table, and the verdict line.
fn parse_table(text: &str) -> ([f64; 2], String) {
    let line = |key: &str| {
        text.lines()
            .find_map(|l| l.trim_start().strip_prefix(key).map(str::trim))
            .unwrap_or_else(|| panic!("no {key} line in:\n{text}"))
            .to_owned()
    };
    let pos = line("position");
    let nums: Vec<f64> = pos
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter_map(|t| t.parse().ok())
        .collect();
    assert_eq!(nums.len(), 2, "position line {pos:?}");
    ([nums[0], nums[1]], line("verdict"))
}

fn error_m(s: &Scene, p: [f64; 2]) -> f64 {
    (p[0] - s.truth_m[0]).hypot(p[1] - s.truth_m[1])
}

#[test]
fn localizes_png_map_with_flags_and_cm_dem_within_a_metre() {
    let s = scene();
    let geo = s.orbital.appearance.geo;
    let dgeo = s.orbital.dem.geo;
    let o = solsim()
        .args([
            "localize",
            "--map-appearance",
            &s.file("map.png"),
            "--map-origin",
            &format!("{},{}", geo.origin_m[0], geo.origin_m[1]),
            "--map-resolution",
            &geo.resolution_m_per_px.to_string(),
            "--map-dem",
            &s.file("map-dem-cm.png"),
            "--map-dem-origin",
            &format!("{},{}", dgeo.origin_m[0], dgeo.origin_m[1]),
            "--map-dem-resolution",
            &dgeo.resolution_m_per_px.to_string(),
            "--ortho",
            &s.file("ortho.png"),
            "--ortho-valid",
            &s.file("ortho-valid.png"),
            "--rover-dem",
            &s.file("rover-dem.tif"),
            "--rover-dem-valid",
            &s.file("rover-dem-valid.png"),
            "--prior",
            &s.prior(),
            "--radius",
            &RADIUS_M.to_string(),
        ])
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let (pos, verdict) = parse_table(&text);
    assert!(
        error_m(s, pos) < 1.0,
        "{pos:?} vs truth {:?}\n{text}",
        s.truth_m
    );
    assert_eq!(verdict, "ACCEPTED", "{text}");
    assert!(text.contains("appearance + DEM"), "{text}");
    for field in [
        "correction",
        "sigma",
        "best score",
        "peak ratio",
        "valid fraction",
    ] {
        assert!(text.contains(field), "no {field}:\n{text}");
    }
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
}

#[test]
fn json_equals_the_library_call_on_the_same_rasters() {
    let s = scene();
    let o = solsim()
        .args(s.good_args())
        .arg("--json")
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("JSON");

    let direct = localize(
        &OrbitalMap {
            appearance: &s.orbital.appearance,
            dem: Some(&s.orbital.dem),
        },
        &RoverImages {
            ortho: &s.rover.ortho,
            ortho_valid: &s.rover.valid,
            dem: Some((&s.rover.dem, &s.rover.dem_valid)),
        },
        s.prior_m,
        &MatchSettings {
            search_radius_m: RADIUS_M,
            ..MatchSettings::default()
        },
    )
    .expect("localizes");
    let want = serde_json::to_value(&direct).expect("serializes");
    let got = &doc["result"];
    // The same numbers: equal to the last bit, up to the JSON text round trip.
    let same = |a: &serde_json::Value, b: &serde_json::Value| match (a.as_f64(), b.as_f64()) {
        (Some(x), Some(y)) => (x - y).abs() <= 4.0 * f64::EPSILON * x.abs().max(1.0),
        _ => a == b,
    };
    let obj = want.as_object().expect("object");
    assert_eq!(obj.len(), got.as_object().expect("object").len(), "{got}");
    for (k, v) in obj {
        let g = &got[k];
        let ok = match (v.as_array(), g.as_array()) {
            (Some(a), Some(b)) => a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same(x, y)),
            _ => same(v, g),
        };
        assert!(ok, "{k}: CLI {g} vs library {v}");
    }
    assert!(error_m(s, direct.position_m) < 1.0, "{direct:?}");
    assert_eq!(doc["accepted"], serde_json::json!(true), "{doc}");
    assert_eq!(doc["verdict"], "ACCEPTED");
    assert_eq!(doc["dem_used"], serde_json::json!(true));
    assert_eq!(doc["inputs"]["params"]["method"], "census");
}

#[test]
fn a_rejected_match_is_a_result_with_exit_0() {
    let s = scene();
    // A featureless orthomosaic and no DEM term (the DEM alone would still localize the scene).
    let mut args = without(without(s.good_args(), "--rover-dem"), "--rover-dem-valid");
    let i = args.iter().position(|a| a == "--ortho").expect("flag") + 1;
    args[i] = s.file("flat-ortho.png");
    let o = solsim().args(args).output().expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (_, verdict) = parse_table(&stdout(&o));
    assert!(verdict.starts_with("REJECTED: "), "{verdict}");
}

/// Runs `args` with `--json` and returns the document.
fn json_of(args: &[String]) -> serde_json::Value {
    let o = solsim().args(args).arg("--json").output().expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_str(&stdout(&o)).expect("JSON")
}

/// Removes `flag` and its value from `args`.
fn without(mut args: Vec<String>, flag: &str) -> Vec<String> {
    let i = args.iter().position(|a| a == flag).expect("flag");
    args.drain(i..i + 2);
    args
}

#[test]
fn documented_defaults_for_masks_hold() {
    let s = scene();
    let good = json_of(&s.good_args());
    // Without --ortho-valid, 0 is no data: the synthetic orthomosaic holds 0 where invalid.
    let doc = json_of(&without(s.good_args(), "--ortho-valid"));
    let vf = doc["result"]["valid_fraction"].as_f64().expect("number");
    assert!(
        (vf - s.rover.valid_fraction()).abs() < 0.01,
        "{vf} vs {}",
        s.rover.valid_fraction()
    );
    // Without --rover-dem-valid, NaN cells are the holes: the same result as the mask gives.
    let mut args = without(s.good_args(), "--rover-dem-valid");
    let i = args.iter().position(|a| a == "--rover-dem").expect("flag") + 1;
    args[i] = s.file("rover-dem-nan.tif");
    assert_eq!(json_of(&args)["result"], good["result"]);
}

#[test]
fn a_one_sided_dem_warns_and_matches_on_appearance() {
    let s = scene();
    let o = solsim()
        .args(without(s.good_args(), "--rover-dem"))
        .output();
    // --rover-dem-valid without --rover-dem is bad input ...
    assert_bad_input(&o.expect("runs"), &["--rover-dem-valid", "--rover-dem"]);
    // ... the map DEM alone is a warning.
    let args = without(without(s.good_args(), "--rover-dem-valid"), "--rover-dem");
    let o = solsim().args(args).output().expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("warning: "), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("appearance only"), "{text}");
    let (pos, _) = parse_table(&text);
    assert!(error_m(s, pos) < 1.0, "{pos:?}\n{text}");
}

#[test]
fn flags_contradicting_a_geotiff_are_rejected() {
    let s = scene();
    let o = run_with("--map-origin", "0,0");
    // Only one of the pair given.
    assert_bad_input(&o, &["--map-resolution", "--map-origin"]);
    let mut args = s.good_args();
    args.extend(["--map-origin", "0,0", "--map-resolution", "0.25"].map(str::to_owned));
    let o = solsim().args(args).output().expect("runs");
    assert_bad_input(&o, &[&s.file("map.tif"), "contradicts", "--map-origin 0,0"]);
}

// ---- bad input --------------------------------------------------------------------------

/// Runs the good arguments with `flag`'s value replaced (or the flag added).
fn run_with(flag: &str, value: &str) -> Output {
    let mut args = scene().good_args();
    match args.iter().position(|a| a == flag) {
        Some(i) => args[i + 1] = value.to_owned(),
        None => args.extend([flag.to_owned(), value.to_owned()]),
    }
    solsim().args(args).output().expect("runs")
}

#[test]
fn missing_file_names_the_file() {
    let missing = scene().file("no-such-ortho.tif");
    assert_bad_input(&run_with("--ortho", &missing), &["--ortho", &missing]);
    let missing = scene().file("no-such-dem.tif");
    assert_bad_input(&run_with("--map-dem", &missing), &["--map-dem", &missing]);
}

#[test]
fn wrong_pixel_type_names_the_file_and_the_expected_type() {
    let s = scene();
    let dem = s.file("map-dem.tif");
    assert_bad_input(
        &run_with("--map-appearance", &dem),
        &[&dem, "8-bit unsigned", "32-bit float"],
    );
    let u16 = s.file("ortho-u16.png");
    assert_bad_input(&run_with("--ortho", &u16), &[&u16, "8-bit unsigned"]);
    let u8 = s.file("map.tif");
    assert_bad_input(
        &run_with("--map-dem", &u8),
        &[&u8, "16-bit unsigned (cm) or 32-bit float (m) DEM"],
    );
}

#[test]
fn mask_of_another_size_is_rejected() {
    let small = scene().file("small-mask.png");
    assert_bad_input(
        &run_with("--ortho-valid", &small),
        &[&small, "expected 240x240 px", "found 10x10 px"],
    );
    assert_bad_input(
        &run_with("--rover-dem-valid", &small),
        &[&small, "expected 60x60 px", "found 10x10 px"],
    );
}

#[test]
fn no_valid_pixels_is_rejected() {
    let empty = scene().file("empty-mask.png");
    assert_bad_input(
        &run_with("--ortho-valid", &empty),
        &[&empty, "at least one valid"],
    );
}

#[test]
fn ortho_resolution_must_equal_the_maps() {
    let s = scene();
    assert_bad_input(
        &run_with("--ortho-resolution", "0.5"),
        &[&s.file("ortho.png"), "0.25 m/px", "0.5 m/px"],
    );
    assert_bad_input(
        &run_with("--rover-dem-resolution", "2"),
        &[&s.file("rover-dem.tif"), "1 m/px", "contradicts"],
    );
}

#[test]
fn png_map_without_georeference_flags_is_rejected() {
    let png = scene().file("map.png");
    assert_bad_input(
        &run_with("--map-appearance", &png),
        &[&png, "--map-origin", "--map-resolution"],
    );
}

#[test]
fn prior_off_the_map_is_rejected() {
    let s = scene();
    assert_bad_input(
        &run_with("--prior", "5000,520"),
        &[
            "--prior 5000,520",
            &s.file("map.tif"),
            "on the orbital orthoimage",
        ],
    );
}

#[test]
fn search_window_leaving_the_map_says_which_side_and_by_how_much() {
    let s = scene();
    let (x0, _, _, y1) = s.orbital.appearance.extent_m();
    // 5 m inside the north-west corner: the window reaches 45 m beyond the west and north edges.
    let o = run_with("--prior", &format!("{},{}", x0 + 5.0, y1 - 5.0));
    assert_bad_input(
        &o,
        &[
            &s.file("map.tif"),
            "search window",
            "40.00 m on the west",
            "40.00 m on the north",
        ],
    );
    let o = run_with("--radius", "40");
    assert_bad_input(&o, &["--radius 40", "on the", &s.file("map.tif")]);
}

#[test]
fn nan_and_out_of_range_flags_are_rejected() {
    assert_bad_input(&run_with("--prior", "nan,520"), &["--prior", "finite"]);
    assert_bad_input(&run_with("--radius", "NaN"), &["--radius", "(0, 100]"]);
    assert_bad_input(&run_with("--radius", "0"), &["--radius", "(0, 100]"]);
    assert_bad_input(&run_with("--radius", "100.5"), &["--radius", "(0, 100]"]);
    assert_bad_input(&run_with("--latitude", "inf"), &["--latitude"]);
    assert_bad_input(
        &run_with("--map-resolution", "-1"),
        &["--map-resolution", "positive"],
    );
    assert_bad_input(&run_with("--method", "sad"), &["--method", "census"]);
}

/// Pixels 285..315 of `r` in both axes, placed as `gdal_translate -srcwin 285 285 30 30` places
/// them.
fn srcwin<T: Copy>(r: &Raster<T>) -> Raster<T> {
    r.try_crop(285, 285, 30, 30)
        .expect("the README's window lies on the map")
}

/// The README's example, command for command: `gdal_translate -srcwin 285 285 30 30` crops of
/// the bundled crater-floor map (2 m pixels) as the rover's orthomosaic and DEM, here cropped
/// in Rust with the same georeference GDAL gives them.
#[test]
fn readme_example_runs_as_printed() {
    let a = root().join("maps/assets/crater-floor");
    let layers = MapLayers::load(
        &a.join("appearance.tif"),
        &a.join("dem.tif"),
        &a.join("terrain.tif"),
        0.0,
        None,
    )
    .expect("bundled map");
    let dir = tempfile::tempdir().expect("tempdir");
    write_geotiff(
        &dir.path().join("ortho.tif"),
        &srcwin(&layers.appearance),
        None,
    )
    .expect("ortho");
    write_dem(&dir.path().join("rover-dem.tif"), &srcwin(&layers.dem), 0.0).expect("rover DEM");
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let cmd = readme
        .split("```sh\n")
        .filter_map(|b| b.split("```").next())
        .find(|b| b.contains("solsim localize ") && !b.contains("gdal_translate"))
        .expect("README has a `solsim localize` example block");
    let map_dir = format!("{}/", a.display());
    let words: Vec<String> = cmd
        .replace("\\\n", " ")
        .split_whitespace()
        .map(|w| w.replace("my-map/", &map_dir))
        .collect();
    assert_eq!(words[0], "solsim", "{cmd}");
    let o = solsim()
        .current_dir(dir.path())
        .args(&words[1..])
        .output()
        .expect("runs");
    assert!(o.status.success(), "{cmd}\n{}", stderr(&o));
    let (pos, verdict) = parse_table(&stdout(&o));
    assert!(
        (pos[0] - 600.0).hypot(pos[1] - 600.0) < 0.5,
        "{pos:?}\n{}",
        stdout(&o)
    );
    assert!(stdout(&o).contains("appearance + DEM"), "{}", stdout(&o));
    assert_eq!(verdict, "ACCEPTED");
}
