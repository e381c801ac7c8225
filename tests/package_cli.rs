//! `solsim map package` end to end on a short route over the bundled rapid-traverse map: the
//! files decode, the MD5s and sizes in the manifest are those on disk, the printed total is the
//! bytes on disk, pixels outside the corridor are masked, the DEM round-trips to the centimetre,
//! blocks join without seams, and bad input is one `error:` line with exit code 2.

use crate::common;

use common::{manifest, package, root, solsim, stderr};
use std::path::{Path, PathBuf};
use std::process::Output;

use localization::hbs::HbsFile;
use localization::map_package::{RenderSettings, render_block};
use maps::package::{BlockRequest, distance_to_route_m};
use maps::raster_io::read_png;
use maps::{GeoTransform, Raster};
use study::map_package::SeededRenderSettings as _;

/// The route of the test scenario: 67 m on a diagonal, in the middle of the map.
const ROUTE: [[f64; 2]; 3] = [[1000.0, 1000.0], [1040.0, 1030.0], [1060.0, 1020.0]];
const SEED: u64 = 4242;

/// A small scenario on the rapid-traverse map with [`ROUTE`], written into `dir`.
fn scenario(dir: &Path) -> PathBuf {
    let map = root().join("maps/assets/rapid-traverse");
    let zones = root().join("scenarios/rapid-traverse-379-409.zones.geojson");
    let text = format!(
        r#"name = "package-test"
seed = {SEED}

[map]
appearance = "{}"
dem = "{}"
terrain = "{}"
zones = "{}"

[grid]
resolution_m = 8.0

[route]
waypoints = {ROUTE:?}

[[sols]]
sol = 1
"#,
        map.join("appearance.tif").display(),
        map.join("dem.tif").display(),
        map.join("terrain.tif").display(),
        zones.display()
    );
    let path = dir.join("package-test.toml");
    std::fs::write(&path, text).expect("write scenario");
    path
}

fn geo_of(file: &serde_json::Value) -> GeoTransform {
    let o = &file["origin_m"];
    GeoTransform::new(
        o[0].as_f64().expect("x"),
        o[1].as_f64().expect("y"),
        file["resolution_m"].as_f64().expect("res"),
    )
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Checks a file entry of the manifest against the disk: size, MD5, pixel size.
fn check_file(out: &Path, f: &serde_json::Value) -> PathBuf {
    let path = out.join(f["file"].as_str().expect("file"));
    let bytes = std::fs::read(&path).expect("tile file");
    assert_eq!(bytes.len() as u64, f["bytes"].as_u64().expect("bytes"));
    let md5 = hex(&HbsFile::new("tile", bytes).md5);
    assert_eq!(md5, f["md5"].as_str().expect("md5"), "{}", path.display());
    path
}

#[test]
fn package_decodes_masks_and_round_trips_the_dem() {
    let dir = tempfile::tempdir().expect("tempdir");
    let sc = scenario(dir.path());
    let out = dir.path().join("pkg");
    let o = package(&sc, &out, &["--corridor-m", "15", "--tile-m", "32"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    for s in [
        "corridor:",
        "km²",
        "appearance px",
        "DEM px",
        "manifest.json",
        "MB",
    ] {
        assert!(text.contains(s), "output lacks {s}:\n{text}");
    }

    // The printed total is the bytes on disk (every file in the directory).
    let printed: u64 = text
        .lines()
        .find_map(|l| l.strip_prefix("total: "))
        .and_then(|l| l.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no total line:\n{text}"));
    let on_disk: u64 = std::fs::read_dir(&out)
        .expect("dir")
        .map(|e| e.expect("entry").metadata().expect("meta").len())
        .sum();
    assert_eq!(printed, on_disk);

    let m = manifest(&out);
    let half_width = m["corridor"]["half_width_m"].as_f64().expect("hw");
    assert_eq!(half_width, 15.0);
    let datum = m["dem"]["datum_m"].as_f64().expect("datum");
    let tiles = m["tiles"].as_array().expect("tiles");
    assert!(tiles.len() >= 4, "{} tiles", tiles.len());
    let scenario = study::Scenario::load(&sc).expect("scenario");
    let layers = &*scenario.layers;
    let settings = RenderSettings::for_seed(SEED);
    let (mut app_kept, mut dem_kept) = (0, 0);
    for t in tiles {
        // Appearance: decodes, masked outside the corridor, non-zero inside.
        let af = &t["appearance"];
        let app: Raster<u8> = read_png(&check_file(&out, af), geo_of(af)).expect("decode");
        assert_eq!(
            [app.width as u64, app.height as u64],
            [
                af["size_px"][0].as_u64().expect("w"),
                af["size_px"][1].as_u64().expect("h")
            ]
        );
        let mut kept = 0;
        for row in 0..app.height {
            for col in 0..app.width {
                let (x, y) = app.geo.center_of(col, row);
                let inside = distance_to_route_m([x, y], &ROUTE) <= half_width;
                assert_eq!(app.get(col, row) != 0, inside, "appearance ({col}, {row})");
                kept += usize::from(inside);
            }
        }
        assert_eq!(kept as u64, af["kept_px"].as_u64().expect("kept"));
        app_kept += kept;

        // DEM: decodes, masked, and within half a centimetre of the rendered heights; the
        // appearance equals the tile rendered as one block (whatever the CLI's blocks were).
        let df = &t["dem"];
        let dem: Raster<u16> = read_png(&check_file(&out, df), geo_of(df)).expect("decode");
        let req = BlockRequest {
            origin_m: dem.geo.origin_m,
            size_m: [dem.width, dem.height],
        };
        let (truth_app, truth_dem) = render_block(layers, &req, &settings).expect("render");
        for row in 0..dem.height {
            for col in 0..dem.width {
                let (x, y) = dem.geo.center_of(col, row);
                let inside = distance_to_route_m([x, y], &ROUTE) <= half_width;
                let cm = dem.get(col, row);
                assert_eq!(cm != 0, inside, "DEM ({col}, {row})");
                if inside {
                    dem_kept += 1;
                    let h = datum + f64::from(cm) / 100.0;
                    let want = f64::from(truth_dem.get(col, row));
                    assert!((h - want).abs() <= 0.005 + 1e-4, "{h} vs {want}");
                }
            }
        }
        for (i, (&got, &want)) in app.data.iter().zip(&truth_app.data).enumerate() {
            if got != 0 {
                assert_eq!(got, want.max(1), "appearance pixel {i}");
            }
        }
    }
    assert_eq!(
        app_kept as u64,
        m["corridor"]["appearance_px"].as_u64().expect("n")
    );
    assert_eq!(
        dem_kept as u64,
        m["corridor"]["dem_px"].as_u64().expect("n")
    );
    // A 67 m route with a 15 m corridor: about 67 × 30 + π 15² m².
    let area = m["corridor"]["area_km2"].as_f64().expect("area") * 1e6;
    assert!(
        (area - (67.1 * 30.0 + std::f64::consts::PI * 225.0)).abs() < 150.0,
        "{area}"
    );
}

#[test]
fn blocks_join_without_seams() {
    // One 64 m block against the same ground rendered as four 32 m blocks: bit for bit.
    let dir = tempfile::tempdir().expect("tempdir");
    let loaded = study::Scenario::load(&scenario(dir.path())).expect("scenario");
    let layers = &*loaded.layers;
    let s = RenderSettings::for_seed(SEED);
    let whole = BlockRequest {
        origin_m: [3000.0, 1010.0],
        size_m: [64, 64],
    };
    let (app, dem) = render_block(layers, &whole, &s).expect("render");
    for (dx, dy) in [(0usize, 0usize), (32, 0), (0, 32), (32, 32)] {
        let part = BlockRequest {
            origin_m: [3000.0 + dx as f64, 1010.0 - dy as f64],
            size_m: [32, 32],
        };
        let (a, d) = render_block(layers, &part, &s).expect("render");
        for row in 0..a.height {
            for col in 0..a.width {
                assert_eq!(
                    a.get(col, row),
                    app.get(col + 4 * dx, row + 4 * dy),
                    "appearance ({col}, {row}) of block +{dx}+{dy}"
                );
            }
        }
        for row in 0..d.height {
            for col in 0..d.width {
                assert_eq!(
                    d.get(col, row).to_bits(),
                    dem.get(col + dx, row + dy).to_bits(),
                    "DEM ({col}, {row}) of block +{dx}+{dy}"
                );
            }
        }
    }
}

#[test]
fn package_does_not_depend_on_threads_or_tiles() {
    let dir = tempfile::tempdir().expect("tempdir");
    let sc = scenario(dir.path());
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    let one = solsim()
        .env("RAYON_NUM_THREADS", "1")
        .args(["map", "package"])
        .arg(&sc)
        .arg("--out")
        .arg(&a)
        .args(["--corridor-m", "10", "--resolution-m", "0.5"])
        .output()
        .expect("runs");
    assert!(one.status.success(), "{}", stderr(&one));
    let two = package(&sc, &b, &["--corridor-m", "10", "--resolution-m", "0.5"]);
    assert!(two.status.success(), "{}", stderr(&two));
    let (ma, mb) = (manifest(&a), manifest(&b));
    assert_eq!(ma["tiles"], mb["tiles"]);
    let f = &ma["tiles"][0]["appearance"];
    assert_eq!(f["resolution_m"].as_f64(), Some(0.5));
}

/// Runs a bad invocation: exit 2 and exactly one `error:` line containing `needle`.
fn assert_bad(o: &Output, needle: &str) {
    assert_eq!(o.status.code(), Some(2), "{}", stderr(o));
    let err = stderr(o);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(lines[0].starts_with("error: "), "{err}");
    assert!(lines[0].contains(needle), "{err} lacks {needle}");
}

#[test]
fn bad_input_is_one_error_line_and_exit_2() {
    let dir = tempfile::tempdir().expect("tempdir");
    let sc = scenario(dir.path());
    let out = dir.path().join("pkg");

    let missing = dir.path().join("no-such-scenario.toml");
    assert_bad(&package(&missing, &out, &[]), "no-such-scenario.toml");
    assert_bad(&package(&sc, &out, &["--corridor-m", "0"]), "--corridor-m");
    assert_bad(&package(&sc, &out, &["--corridor-m=-5"]), "--corridor-m");
    assert_bad(
        &package(&sc, &out, &["--resolution-m", "0.3"]),
        "--resolution-m",
    );

    // --out under a regular file cannot be created.
    let file = dir.path().join("a-file");
    std::fs::write(&file, b"x").expect("write");
    let unwritable = file.join("pkg");
    assert_bad(&package(&sc, &unwritable, &[]), "a-file/pkg");
}
