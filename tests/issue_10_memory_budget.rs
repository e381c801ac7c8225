//! Issue 10: sizes an input asks for were allocated before anything checked them —
//! `[grid] resolution_m = 0.05` in `scenarios/crater-floor-passage.toml` climbed to 6.4 GB and aborted
//! (exit 134, `memory allocation of 2304000000 bytes failed`), 0.01 aborted at once; a recipe
//! of 20 000 × 20 000 px reached 8 GB and aborted; a 2 MB PNG of 46 000 × 46 000 zeros
//! decoded to 4 GB before it was rejected. One memory budget per command (default 2 GiB,
//! `--memory-budget-mib`) is now checked from the fields and the raster headers before
//! allocating: exit 2, one line naming the field and the size it would need.

use crate::common;

use std::time::Duration;

use common::{assert_bad_input, output_within, root, scenario_copy, solsim};

/// Each refusal must come before any large allocation: fast.
const LIMIT: Duration = Duration::from_secs(30);

#[test]
fn a_grid_of_5_cm_cells_is_refused_by_the_budget() {
    for (cell, cells) in [("0.05", "576000000 cells"), ("0.01", "14400000000 cells")] {
        let (path, _d) = scenario_copy("crater-floor-passage.toml", |t| {
            t.replace("resolution_m = 1.0", &format!("resolution_m = {cell}"))
        });
        let o = output_within(solsim().arg("validate").arg(&path), LIMIT);
        assert_bad_input(
            &o,
            &[
                "grid.resolution_m",
                "fits the memory budget",
                "--memory-budget-mib",
                cells,
            ],
        );
    }
}

#[test]
fn the_budget_is_a_flag_and_counts_the_maps_and_the_grid() {
    let scenario = root().join("scenarios/crater-floor-passage.toml");
    let o = output_within(
        solsim()
            .args(["validate", "--memory-budget-mib", "16"])
            .arg(&scenario),
        LIMIT,
    );
    assert_bad_input(&o, &["grid.resolution_m", "(16 MiB; --memory-budget-mib)"]);
    let o = output_within(solsim().arg("validate").arg(&scenario), LIMIT);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
}

#[test]
fn a_20000_px_recipe_is_refused_by_the_budget() {
    let dir = tempfile::tempdir().expect("tempdir");
    let recipe = dir.path().join("recipe.toml");
    let text =
        std::fs::read_to_string(root().join("maps/assets/crater-floor/recipe.toml")).expect("read");
    let text = text
        .replace("width_px = 600", "width_px = 20000")
        .replace("height_px = 600", "height_px = 20000");
    std::fs::write(&recipe, text).expect("write");
    let o = output_within(
        solsim()
            .args(["map", "generate"])
            .arg(&recipe)
            .arg("--out")
            .arg(dir.path().join("map")),
        LIMIT,
    );
    assert_bad_input(
        &o,
        &[
            "terrain.width_px",
            "20000 × 20000 px",
            "needs 8.9 GiB",
            "memory budget",
        ],
    );
}

/// CRC-32 (IEEE) of a PNG chunk's type and data.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A PNG whose header claims `side × side` 8-bit gray pixels, with a few bytes of data: a
/// decoder that trusted the header would allocate `side²` bytes.
fn huge_png(side: u32) -> Vec<u8> {
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = |kind: &[u8], data: &[u8]| {
        png.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let mut body = kind.to_vec();
        body.extend_from_slice(data);
        png.extend_from_slice(&body);
        png.extend_from_slice(&crc32(&body).to_be_bytes());
    };
    let mut ihdr = side.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&side.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]); // 8-bit gray, deflate, no interlace
    chunk(b"IHDR", &ihdr);
    chunk(b"IDAT", &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]);
    chunk(b"IEND", &[]);
    png
}

#[test]
fn a_46000_px_png_map_layer_is_refused_from_its_header() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("appearance.png");
    std::fs::write(&png, huge_png(46_000)).expect("write");
    let (path, _d) = scenario_copy("crater-floor-passage.toml", |t| {
        common::with_png_appearance(&t, &png)
    });
    let o = output_within(solsim().arg("validate").arg(&path), LIMIT);
    assert_bad_input(
        &o,
        &[
            "map.appearance",
            "46000 × 46000 px would need 2.0 GiB",
            "memory budget",
        ],
    );
}

#[test]
fn a_46000_px_png_as_ortho_is_refused_from_its_header() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("ortho.png");
    std::fs::write(&png, huge_png(46_000)).expect("write");
    assert!(
        std::fs::metadata(&png).expect("size").len() < 200,
        "a tiny file"
    );
    let o = output_within(
        solsim()
            .args(["localize", "--map-appearance"])
            .arg(root().join("maps/assets/crater-floor/appearance.tif"))
            .arg("--ortho")
            .arg(&png)
            .args(["--prior", "600,300"]),
        LIMIT,
    );
    assert_bad_input(
        &o,
        &[
            "--ortho ",
            "ortho.png",
            "46000 × 46000 px would need",
            "memory budget",
        ],
    );
}
