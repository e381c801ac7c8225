//! Issue 13, item 3: GIS outputs that land where they belong. The run GeoJSON had no CRS, so
//! GDAL and geopandas read its map metres as WGS 84 degrees (`ogrinfo` reported latitude 938°),
//! QGIS could not overlay it on the map's GeoTIFFs (which carried a local engineering CRS),
//! MMGIS, which expects longitude/latitude, put it nowhere, and it held the drive paths and
//! sol-end discs but not the route or the grown zones.
//!
//! Now the bundled maps lie in Jezero crater (the IAU 2015 Mars sphere in the Jezero
//! equirectangular projection, `maps::mars_crs`), their GeoTIFFs carry that CRS, and every run
//! writes each layer — route, zones, paths with sol ends, sol-end ellipses, faults, zones at
//! each fault's r — in Mars longitude/latitude (`.geojson`: each run's paths beside its JSON,
//! the other layers in `gis/`) and in the map's projected CRS (`gis/projected/`, `.geojson` +
//! `.prj`). Checked here with GDAL's own tools (gdal-bin), on
//! `solsim compare scenarios/crater-floor-passage.toml` and a `solsim map package` of it:
//!
//! - every layer and every bundled GeoTIFF reports a Mars CRS (a sphere of 3 396 190 m, not
//!   WGS 84); the projected layers, their `.prj` files and the GeoTIFFs report the same one;
//! - the longitude/latitude layers lie in Jezero (within 3 km of the anchor, the landing site)
//!   and inside the GeoTIFF's own extent as GDAL converts it to longitude/latitude;
//! - the projected layers lie inside the GeoTIFF's extent, and each longitude/latitude layer
//!   reprojected by `ogr2ogr` to the `.prj` (and to the GeoTIFF's CRS) lands within a millimetre
//!   of its projected twin;
//! - a package tile with its world file and PAM file reports the CRS and the extent the manifest
//!   gives it;
//! - without GDAL: the GIS files are the same bytes on a rerun, and a map without a Mars CRS is
//!   placed at the landing site, which its files say.
//!
//! Without gdal-bin the test prints `SKIPPED: gdal-bin not installed` and passes, except under
//! `CI`, where it fails (`.ci/run` installs gdal-bin).

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{package, root, solsim, stderr};
use serde_json::Value;

/// The Octavia E. Butler landing site, where `maps/assets/crater-floor` is centred.
const ANCHOR_LON_LAT: [f64; 2] = [77.4508, 18.4447];
/// "Within a few km": 3 km of latitude on the Mars sphere, degrees.
const NEAR_DEG: f64 = 3000.0 / 3_396_190.0 * 57.295_779_513_082_32;

/// Whether gdal-bin is here; without it the test fails naming `apt-get install gdal-bin`, unless
/// the run opted out of the external checks (then `false`, counted).
fn gdal_or_skip() -> bool {
    let found = Command::new("ogrinfo")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        common::external::unavailable(
            "the GDAL check of the GIS outputs",
            "gdal-bin is not installed (no ogrinfo on PATH)",
            "apt-get install gdal-bin",
        );
    }
    found
}

/// Runs a GDAL tool; its standard output, after checking it succeeded without an ERROR.
fn gdal(tool: &str, args: &[&str]) -> String {
    let o = Command::new(tool)
        .args(args)
        .output()
        .expect("a GDAL tool runs");
    let err = stderr(&o);
    assert!(
        o.status.success() && !err.contains("ERROR"),
        "{tool} {args:?}: {err}"
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

/// `gdalsrsinfo -o proj4` of a raster, vector or `.prj` file.
fn proj4(p: &Path) -> String {
    gdal("gdalsrsinfo", &["-o", "proj4", s(p)])
        .trim()
        .to_owned()
}

/// `(xmin, ymin, xmax, ymax)` from `ogrinfo -so -al`, or `None` for an empty layer.
fn extent(p: &Path) -> Option<[f64; 4]> {
    let text = gdal("ogrinfo", &["-ro", "-so", "-al", s(p)]);
    let count: u64 = text
        .lines()
        .find_map(|l| l.strip_prefix("Feature Count: "))
        .and_then(|n| n.trim().parse().ok())
        .unwrap_or_else(|| panic!("no feature count for {}:\n{text}", p.display()));
    if count == 0 {
        return None;
    }
    let line = text
        .lines()
        .find_map(|l| l.strip_prefix("Extent: "))
        .unwrap_or_else(|| panic!("no extent for {}:\n{text}", p.display()));
    let v: Vec<f64> = line
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter(|t| !t.is_empty() && *t != "-")
        .map(|t| t.parse().expect("a number"))
        .collect();
    assert_eq!(v.len(), 4, "{line}");
    Some([v[0], v[1], v[2], v[3]])
}

fn inside(inner: [f64; 4], outer: [f64; 4], slack: f64) -> bool {
    inner[0] >= outer[0] - slack
        && inner[1] >= outer[1] - slack
        && inner[2] <= outer[2] + slack
        && inner[3] <= outer[3] + slack
}

/// Every position of a GeoJSON file, in feature order.
fn positions(p: &Path) -> Vec<[f64; 2]> {
    fn walk(v: &Value, out: &mut Vec<[f64; 2]>) {
        match v.as_array() {
            Some(a) if a.len() >= 2 && a[0].is_number() => {
                out.push([a[0].as_f64().expect("x"), a[1].as_f64().expect("y")])
            }
            Some(a) => a.iter().for_each(|x| walk(x, out)),
            None => {}
        }
    }
    let doc: Value =
        serde_json::from_slice(&std::fs::read(p).expect("read GeoJSON")).expect("GeoJSON");
    let mut out = Vec::new();
    for f in doc["features"].as_array().expect("features") {
        walk(&f["geometry"]["coordinates"], &mut out);
    }
    out
}

/// The GeoTIFF's extent `(xmin, ymin, xmax, ymax)` in its own CRS, from `gdalinfo -json`.
fn raster_extent(tif: &Path) -> [f64; 4] {
    let info: Value = serde_json::from_str(&gdal("gdalinfo", &["-json", s(tif)])).expect("json");
    let c = &info["cornerCoordinates"];
    let at = |k: &str, i: usize| c[k][i].as_f64().expect("corner");
    [
        at("lowerLeft", 0),
        at("lowerLeft", 1),
        at("upperRight", 0),
        at("upperRight", 1),
    ]
}

/// Pixel positions `(column, row)` of `tif` in Mars longitude/latitude by GDAL alone:
/// `gdaltransform` from the file's own georeference to IAU_2015:49900 (PROJ's Mars sphere),
/// longitude first.
fn lonlat_by_gdal(tif: &Path, pixels: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut child = Command::new("gdaltransform")
        .args(["-t_srs", "IAU_2015:49900", "-output_xy", s(tif)])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("gdaltransform runs");
    {
        use std::io::Write as _;
        let mut stdin = child.stdin.take().expect("stdin");
        for p in pixels {
            writeln!(stdin, "{} {}", p[0], p[1]).expect("write");
        }
    }
    let o = child.wait_with_output().expect("output");
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    let out: Vec<[f64; 2]> = text
        .lines()
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|t| t.parse().expect("number"))
                .collect();
            [v[0], v[1]]
        })
        .collect();
    assert_eq!(out.len(), pixels.len(), "{text}");
    out
}

/// Reprojects `from` with `ogr2ogr -t_srs srs` and checks every position lands within
/// `tol_m` of the same position in `twin`.
fn assert_reprojects_onto(from: &Path, srs: &Path, twin: &Path, scratch: &Path, tol_m: f64) {
    let out = scratch.join(format!(
        "{}.reprojected.geojson",
        from.file_name().expect("name").to_string_lossy()
    ));
    let _ = std::fs::remove_file(&out);
    gdal(
        "ogr2ogr",
        &[
            "-f",
            "GeoJSON",
            "-t_srs",
            s(srs),
            "-lco",
            "COORDINATE_PRECISION=9",
            s(&out),
            s(from),
        ],
    );
    let (got, want) = (positions(&out), positions(twin));
    assert_eq!(got.len(), want.len(), "{}", from.display());
    let worst = got
        .iter()
        .zip(&want)
        .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
        .fold(0.0f64, f64::max);
    assert!(
        worst <= tol_m,
        "{} reprojected lies {worst} m from {}",
        from.display(),
        twin.display()
    );
}

const MARS_LONLAT: &str = "+proj=longlat +R=3396190 +no_defs";

/// Where a layer's longitude/latitude file is: each run's paths layer
/// (`<scenario>.<strategy>`) beside its JSON, every other layer in `gis/`.
fn lonlat_file(out: &std::path::Path, stem: &str) -> std::path::PathBuf {
    let paths_layer =
        stem.matches('.').count() == 1 && !stem.ends_with(".route") && !stem.ends_with(".zones");
    if paths_layer {
        out.join(format!("{stem}.geojson"))
    } else {
        out.join(format!("gis/{stem}.geojson"))
    }
}

#[test]
fn vectors_and_rasters_report_one_mars_crs_and_overlap() {
    if !gdal_or_skip() {
        return;
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("out");
    let o = solsim()
        .arg("compare")
        .arg(root().join("scenarios/crater-floor-passage.toml"))
        .arg("--out")
        .arg(&out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));

    // The bundled GeoTIFFs: a Mars sphere, equidistant cylindrical, one CRS for all layers.
    let map = root().join("maps/assets/crater-floor");
    let tif = map.join("appearance.tif");
    let map_proj4 = proj4(&tif);
    for want in ["+proj=eqc", "+lat_ts=18.4663", "+R=3396190", "+units=m"] {
        assert!(map_proj4.contains(want), "{want} not in {map_proj4}");
    }
    for name in ["appearance.tif", "dem.tif", "terrain.tif"] {
        let info: Value =
            serde_json::from_str(&gdal("gdalinfo", &["-json", s(&map.join(name))])).expect("json");
        let wkt = info["coordinateSystem"]["wkt"].as_str().expect("a CRS");
        assert!(
            wkt.contains("ELLIPSOID[\"Mars (2015) - Sphere\",3396190,0")
                && wkt.contains("Equidistant Cylindrical")
                && !wkt.contains("WGS"),
            "{name}: {wkt}"
        );
        assert_eq!(proj4(&map.join(name)), map_proj4, "{name}");
    }
    let rapid = proj4(&root().join("maps/assets/rapid-traverse/dem.tif"));
    assert!(
        rapid.contains("+proj=eqc") && rapid.contains("+R=3396190"),
        "{rapid}"
    );

    let tif_extent = raster_extent(&tif);
    // The 600 × 600 px map's south-west and north-east corners and centre, placed by GDAL
    // from the GeoTIFF alone.
    let by_gdal = lonlat_by_gdal(&tif, &[[0.0, 600.0], [600.0, 0.0], [300.0, 300.0]]);
    let tif_lonlat = [by_gdal[0][0], by_gdal[0][1], by_gdal[1][0], by_gdal[1][1]];
    // The map's centre is the anchor.
    let centre = by_gdal[2];
    assert!(
        (centre[0] - ANCHOR_LON_LAT[0]).abs() < 1e-7
            && (centre[1] - ANCHOR_LON_LAT[1]).abs() < 1e-7,
        "{centre:?}"
    );
    // The GeoTIFF's CRS as a file ogr2ogr can take.
    let tif_wkt = dir.path().join("map.wkt");
    std::fs::write(&tif_wkt, gdal("gdalsrsinfo", &["-o", "wkt2", s(&tif)])).expect("write");

    let mut stems: Vec<String> = vec![
        "crater-floor-passage.route".into(),
        "crater-floor-passage.zones".into(),
    ];
    for strategy in [
        "replay",
        "ground",
        "onboard",
        "extension",
        "extension+onboard",
    ] {
        let base = format!("crater-floor-passage.{strategy}");
        for layer in ["", ".ellipses", ".faults", ".fault-zones"] {
            stems.push(format!("{base}{layer}"));
        }
    }
    let (mut non_empty, mut faults) = (0, 0);
    for stem in &stems {
        let lonlat = lonlat_file(&out, stem);
        let projected = out.join(format!("gis/projected/{stem}.geojson"));
        let prj = out.join(format!("gis/projected/{stem}.prj"));
        // One Mars CRS: lon/lat on the Mars sphere; the projected layer, its .prj and the
        // GeoTIFFs the same equirectangular CRS.
        assert_eq!(proj4(&lonlat), MARS_LONLAT, "{stem}");
        let info = gdal("ogrinfo", &["-ro", "-so", "-al", s(&lonlat)]);
        assert!(
            info.contains("Mars (2015) - Sphere") && !info.contains("WGS"),
            "{stem}: {info}"
        );
        assert_eq!(proj4(&projected), map_proj4, "{stem}");
        assert_eq!(proj4(&prj), map_proj4, "{stem}");
        let Some(ll) = extent(&lonlat) else {
            assert!(extent(&projected).is_none(), "{stem}");
            continue;
        };
        non_empty += 1;
        faults += usize::from(stem.ends_with(".faults"));
        // In Jezero, near the anchor, and inside the GeoTIFF as GDAL places it.
        for (v, anchor) in [
            (ll[0], ANCHOR_LON_LAT[0]),
            (ll[2], ANCHOR_LON_LAT[0]),
            (ll[1], ANCHOR_LON_LAT[1]),
            (ll[3], ANCHOR_LON_LAT[1]),
        ] {
            assert!((v - anchor).abs() < NEAR_DEG, "{stem}: {ll:?}");
        }
        // (ogrinfo prints extents to 6 decimals: 1e-6° is 6 cm.)
        assert!(
            inside(ll, tif_lonlat, 1e-6),
            "{stem}: {ll:?} outside {tif_lonlat:?}"
        );
        let xy = extent(&projected).expect("the same features");
        assert!(
            inside(xy, tif_extent, 1e-6),
            "{stem}: {xy:?} outside {tif_extent:?}"
        );
        // Reprojected by GDAL, the lon/lat layer lands on its projected twin.
        assert_reprojects_onto(&lonlat, &prj, &projected, dir.path(), 1e-3);
    }
    assert!(non_empty >= 12, "{non_empty} non-empty layers");
    assert!(faults >= 1, "the replay's sol 385 NO_PATH is a fault");
    // And to the GeoTIFF's own CRS (from the file, not the .prj).
    for stem in [
        "crater-floor-passage.route",
        "crater-floor-passage.replay.fault-zones",
    ] {
        assert_reprojects_onto(
            &lonlat_file(&out, stem),
            &tif_wkt,
            &out.join(format!("gis/projected/{stem}.geojson")),
            dir.path(),
            1e-3,
        );
    }
    // The grown zones name their r.
    let zones: Value = serde_json::from_slice(
        &std::fs::read(out.join("gis/crater-floor-passage.replay.fault-zones.geojson"))
            .expect("read"),
    )
    .expect("json");
    let f = &zones["features"][0]["properties"];
    assert!(f["uncertainty_m"].as_f64().is_some_and(|r| r > 26.0), "{f}");
    assert!(f["offset_m"].as_f64().is_some_and(|d| d > 26.0), "{f}");
}

#[test]
fn a_package_tile_with_its_world_file_reports_the_crs_and_extent() {
    if !gdal_or_skip() {
        return;
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("pkg");
    let o = package(
        &root().join("scenarios/crater-floor-passage.toml"),
        &out,
        &[
            "--corridor-m",
            "20",
            "--tile-m",
            "256",
            "--resolution-m",
            "0.5",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let manifest = common::manifest(&out);
    let map_proj4 = proj4(&root().join("maps/assets/crater-floor/appearance.tif"));
    let tiles = manifest["tiles"].as_array().expect("tiles");
    assert!(!tiles.is_empty());
    for t in tiles {
        for layer in ["appearance", "dem"] {
            let f = &t[layer];
            let png: PathBuf = out.join(f["file"].as_str().expect("file"));
            assert!(out.join(f["world_file"].as_str().expect("pgw")).is_file());
            let info: Value =
                serde_json::from_str(&gdal("gdalinfo", &["-json", s(&png)])).expect("json");
            assert_eq!(proj4(&png), map_proj4, "{}", png.display());
            let gt: Vec<f64> = info["geoTransform"]
                .as_array()
                .expect("a geotransform from the world file")
                .iter()
                .map(|v| v.as_f64().expect("number"))
                .collect();
            let res = f["resolution_m"].as_f64().expect("res");
            let origin = [
                f["origin_m"][0].as_f64().expect("x"),
                f["origin_m"][1].as_f64().expect("y"),
            ];
            assert_eq!(
                gt,
                vec![origin[0], res, 0.0, origin[1], 0.0, -res],
                "{}",
                png.display()
            );
            assert!(
                inside(
                    raster_extent(&png),
                    raster_extent(&root().join("maps/assets/crater-floor/appearance.tif")),
                    0.0
                ),
                "{}",
                png.display()
            );
        }
    }
    let bbox = manifest["georeference"]["bbox_lonlat_deg"]
        .as_array()
        .expect("bbox");
    for (i, v) in bbox.iter().enumerate() {
        let v = v.as_f64().expect("degrees");
        assert!((v - ANCHOR_LON_LAT[i % 2]).abs() < NEAR_DEG, "{bbox:?}");
    }
}

/// Same scenario, same bytes: every GIS file of two runs is identical.
#[test]
fn gis_layers_are_the_same_bytes_on_a_rerun() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = |name: &str| {
        let out = dir.path().join(name);
        let o = solsim()
            .args(["run", "--strategy", "replay"])
            .arg(root().join("scenarios/crater-floor-passage.toml"))
            .arg("--out")
            .arg(&out)
            .output()
            .expect("runs");
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let (a, b) = (run("a"), run("b"));
    let mut n = 0;
    let mut names: Vec<std::path::PathBuf> = Vec::new();
    for sub in ["", "gis", "gis/projected"] {
        for e in std::fs::read_dir(a.join(sub)).expect("list") {
            names.push(std::path::Path::new(sub).join(e.expect("entry").file_name()));
        }
    }
    for name in names {
        let text = name.to_string_lossy();
        if text.ends_with(".geojson") || text.ends_with(".prj") {
            let bytes = std::fs::read(a.join(&name)).expect("read");
            assert_eq!(bytes, std::fs::read(b.join(&name)).expect("read"), "{text}");
            if text.ends_with(".geojson") {
                let v: Value = serde_json::from_slice(&bytes).expect("GeoJSON");
                assert_eq!(v["type"], "FeatureCollection", "{text}");
            }
            n += 1;
        }
    }
    // Route and zones, and the replay's four layers, each as .geojson (the replay's paths
    // beside its JSON, the others in gis/), and as gis/projected/*.geojson and *.prj.
    assert_eq!(n, 6 * 3, "GIS files written");
}

/// A map placed by the scenario (`map.origin_m` overrides the GeoTIFF's georeference, so it
/// has no Mars CRS) still gets longitude/latitude: map (0, 0) at the landing site, and the
/// files say so.
#[test]
fn a_map_without_a_mars_crs_is_placed_at_the_landing_site_and_says_so() {
    let (path, dir) = common::scenario_copy("crater-floor-passage.toml", |t| {
        common::replace_line(
            &t,
            "appearance = ",
            &format!(
                "{}\nresolution_m_per_px = 2.0\norigin_m = [0.0, 1200.0]",
                t.lines()
                    .find(|l| l.starts_with("appearance = "))
                    .expect("appearance")
            ),
        )
    });
    let out = dir.path().join("out");
    let o = solsim()
        .args(["run", "--strategy", "replay"])
        .arg(&path)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: Value = serde_json::from_slice(
        &std::fs::read(out.join("gis/crater-floor-passage.route.geojson")).expect("route"),
    )
    .expect("json");
    let note = doc["crs_note"].as_str().expect("note");
    assert!(
        note.contains("no Mars CRS") && note.contains("landing site"),
        "{note}"
    );
    // Route start (600, 60) m, 600 m east and 60 m north of the landing site.
    let start = &doc["features"][0]["geometry"]["coordinates"][0];
    let [lon, lat] = [0, 1].map(|i| start[i].as_f64().expect("degrees"));
    let dlon = 600.0 / (3_396_190.0 * 18.4663f64.to_radians().cos()) * 57.295_779_513_082_32;
    let dlat = 60.0 / 3_396_190.0 * 57.295_779_513_082_32;
    assert!((lon - (ANCHOR_LON_LAT[0] + dlon)).abs() < 1e-7, "{lon}");
    assert!((lat - (ANCHOR_LON_LAT[1] + dlat)).abs() < 1e-7, "{lat}");
}
