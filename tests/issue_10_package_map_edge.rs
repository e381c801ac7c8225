//! Issue 10: `solsim map package scenarios/crater-floor-passage.toml` (default options) panicked, exit 101:
//! `src/cmd_package.rs: range start index 495712 out of range for slice of length 495616`.
//!
//! The route starts 60 m from the map's south edge, so the 100 m corridor crosses it. A render
//! block is rendered in a square patch of the block plus a margin, shifted inwards where it
//! would leave the map; the inward snap of that shift had its tolerance the wrong way round, so
//! on a whole-metre map edge the patch moved one metre too far in. A block on the south (or
//! east) edge then reached one metre past its patch and cropping it indexed past the end of the
//! rendered buffer. On the north and west edges the same off-by-one did not panic: the crop
//! offset went to -1 m, saturated to 0, and the edge blocks were pasted one metre off their
//! place, so the package depended on the block size.
//!
//! Now the package comes out with tiles covering the part of the corridor that is on the map,
//! and it is the same whatever the render block size, at every edge.

use crate::common;

use common::{manifest, package, root, stderr};
use std::path::{Path, PathBuf};
use std::process::Output;

use maps::package::distance_to_route_m;
use maps::raster_io::{read_dem, read_png};
use maps::{GeoTransform, Raster};

fn f64_at(v: &serde_json::Value) -> f64 {
    v.as_f64().expect("a number")
}

fn geo_of(file: &serde_json::Value) -> GeoTransform {
    GeoTransform::new(
        f64_at(&file["origin_m"][0]),
        f64_at(&file["origin_m"][1]),
        f64_at(&file["resolution_m"]),
    )
}

/// Exit 0, no panic, and a manifest whose every PNG is on disk with the listed size.
fn assert_packaged(o: &Output, out: &Path) -> serde_json::Value {
    let err = stderr(o);
    assert!(!err.contains("panicked"), "panic: {err}");
    assert_eq!(o.status.code(), Some(0), "exit code; stderr: {err}");
    let m = manifest(out);
    let tiles = m["tiles"].as_array().expect("tiles");
    assert!(!tiles.is_empty(), "no tiles");
    for t in tiles {
        for f in [&t["appearance"], &t["dem"]] {
            let path = out.join(f["file"].as_str().expect("file"));
            let len = std::fs::metadata(&path).expect("tile on disk").len();
            assert_eq!(
                len,
                f["bytes"].as_u64().expect("bytes"),
                "{}",
                path.display()
            );
        }
    }
    m
}

#[test]
fn corridor_across_the_south_edge_is_packaged() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("pkg");
    // The reported command; 1 m appearance pixels only to keep the test short (the same blocks
    // are rendered at 25 cm either way).
    let scenario = root().join("scenarios/crater-floor-passage.toml");
    let o = package(&scenario, &out, &["--resolution-m", "1"]);
    let m = assert_packaged(&o, &out);

    // The crater-floor map is x, y ∈ [0, 1200] m; the route x ∈ [590, 600], y ∈ [60, 821].
    // The package is the corridor's bounding box clipped to the map: it ends at the south edge.
    let g = &m["georeference"];
    let (ox, oy) = (
        f64_at(&g["bbox_origin_m"][0]),
        f64_at(&g["bbox_origin_m"][1]),
    );
    let (w, h) = (f64_at(&g["bbox_size_m"][0]), f64_at(&g["bbox_size_m"][1]));
    assert_eq!([ox, oy, w, h], [490.0, 921.0, 210.0, 921.0]);
    assert_eq!(oy - h, 0.0, "the package reaches the map's south edge");

    // Every on-map DEM cell within 100 m of the route is kept (rendered), every other is no
    // data; near the edge the heights are the map's (fine detail and noise stay within a
    // metre or two of the map DEM).
    let route: Vec<[f64; 2]> = m["corridor"]["route"]
        .as_array()
        .expect("route")
        .iter()
        .map(|p| [f64_at(&p[0]), f64_at(&p[1])])
        .collect();
    let map_dem =
        read_dem(&root().join("maps/assets/crater-floor/dem.tif"), 0.0, None).expect("map DEM");
    let datum = f64_at(&m["dem"]["datum_m"]);
    let (mut kept, mut south_row_kept) = (0u64, 0);
    for t in m["tiles"].as_array().expect("tiles") {
        let df = &t["dem"];
        let dem: Raster<u16> =
            read_png(&out.join(df["file"].as_str().expect("file")), geo_of(df)).expect("decode");
        for row in 0..dem.height {
            for col in 0..dem.width {
                let (x, y) = dem.geo.center_of(col, row);
                let inside = distance_to_route_m([x, y], &route) <= 100.0;
                let cm = dem.get(col, row);
                assert_eq!(cm != 0, inside, "DEM cell at ({x}, {y}) m");
                if !inside {
                    continue;
                }
                kept += 1;
                if y < 1.0 {
                    south_row_kept += 1;
                }
                if y < 30.0 {
                    let h = datum + f64::from(cm) / 100.0;
                    let map_h = f64::from(map_dem.sample_bilinear(x, y).expect("on the map"));
                    assert!(
                        (h - map_h).abs() < 2.0,
                        "({x}, {y}): {h} m vs the map's {map_h} m"
                    );
                }
            }
        }
    }
    assert_eq!(kept, m["corridor"]["dem_px"].as_u64().expect("dem_px"));
    // The corridor is 200 m wide where it meets the edge, y = 60 − 100 m.
    assert!(
        south_row_kept > 150,
        "{south_row_kept} kept cells on the south edge"
    );
}

/// The bundled crater-floor-passage scenario with `route` instead of its own, a coarse planning grid and
/// no zones (its keep-in corridor does not reach the map's corners, and a start outside the
/// keep-in is refused: issue 13), written into `dir` (its map paths made absolute).
fn scenario_with_route(dir: &Path, route: [[f64; 2]; 2]) -> PathBuf {
    let scenarios = root().join("scenarios");
    let zones = dir.join("no-zones.geojson");
    std::fs::write(&zones, r#"{"type": "FeatureCollection", "features": []}"#).expect("zones");
    let text =
        std::fs::read_to_string(scenarios.join("crater-floor-passage.toml")).expect("scenario");
    let text: String = text
        .lines()
        .map(|line| match line.split_once(" = \"") {
            Some((key @ ("appearance" | "dem" | "terrain"), path)) => {
                format!("{key} = \"{}/{path}\n", scenarios.display())
            }
            Some(("zones", _)) => format!("zones = {:?}\n", zones.display().to_string()),
            _ if line.starts_with("waypoints = ") => format!("waypoints = {route:?}\n"),
            // The package does not use the planning grid: a coarse one loads faster.
            _ if line == "resolution_m = 1.0" => "resolution_m = 8.0\n".to_owned(),
            _ => format!("{line}\n"),
        })
        .collect();
    let path = dir.join("map-edge.toml");
    std::fs::write(&path, text).expect("write scenario");
    path
}

#[test]
fn edge_blocks_do_not_depend_on_the_block_size() {
    // Short routes into the south-east and the north-west corner of the 1200 m map: the
    // corridor leaves the map on two edges each.
    for (corner, route) in [
        ("south-east", [[1170.0, 30.0], [1100.0, 150.0]]),
        ("north-west", [[30.0, 1170.0], [150.0, 1100.0]]),
    ] {
        let dir = tempfile::tempdir().expect("tempdir");
        let sc = scenario_with_route(dir.path(), route);
        let mut pngs = Vec::new();
        for block_m in ["128", "48"] {
            let out = dir.path().join(format!("pkg-{block_m}"));
            let o = package(
                &sc,
                &out,
                &[
                    "--resolution-m",
                    "1",
                    "--corridor-m",
                    "50",
                    "--block-m",
                    block_m,
                ],
            );
            let m = assert_packaged(&o, &out);
            let files: Vec<Vec<u8>> = m["tiles"]
                .as_array()
                .expect("tiles")
                .iter()
                .flat_map(|t| [&t["appearance"], &t["dem"]])
                .map(|f| std::fs::read(out.join(f["file"].as_str().expect("file"))).expect("png"))
                .collect();
            pngs.push(files);
        }
        assert!(
            pngs[0] == pngs[1],
            "{corner}: the package changes with the render block size"
        );
    }
}
