//! Issue 10: special files given where a scenario, zones, points or recipe file is expected
//! hung until killed (`solsim run FIFO`, `zones check --zones FIFO`, `--points /dev/urandom`,
//! `map generate /dev/urandom`), and `run /dev/zero` read 4 GB. Every input path must be a
//! regular file, checked before it is opened, and read with a size cap: each case ends at once
//! with exit 2 and one `error:` line naming the file.
#![cfg(unix)]

use crate::common;

use std::time::Duration;

use common::{assert_bad_input, output_within, root, solsim};

/// Generous for a command that should answer in milliseconds; a hang fails the test.
const LIMIT: Duration = Duration::from_secs(20);

fn fifo(dir: &tempfile::TempDir) -> String {
    let path = dir.path().join("pipe.toml");
    let status = std::process::Command::new("mkfifo")
        .arg(&path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success());
    path.display().to_string()
}

#[test]
fn a_fifo_as_the_scenario_is_refused_without_blocking() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pipe = fifo(&dir);
    for args in [
        vec!["run", &pipe, "--no-files"],
        vec!["compare", &pipe, "--no-files"],
        vec!["validate", &pipe],
    ] {
        let o = output_within(solsim().args(&args), LIMIT);
        assert_bad_input(&o, &[&pipe, "expected a regular file, got a FIFO"]);
    }
}

#[test]
fn a_fifo_as_the_zones_file_is_refused_without_blocking() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pipe = fifo(&dir);
    let points = root().join("peers/zones_fixtures/points.csv");
    let o = output_within(
        solsim()
            .args(["zones", "check", "--zones", &pipe, "--points"])
            .arg(&points),
        LIMIT,
    );
    assert_bad_input(&o, &[&pipe, "expected a regular file, got a FIFO"]);
}

#[test]
fn devices_as_points_recipe_or_scenario_are_refused() {
    let zones = root().join("peers/zones_fixtures/zones.geojson");
    let o = output_within(
        solsim()
            .args(["zones", "check", "--zones"])
            .arg(&zones)
            .args(["--points", "/dev/urandom"]),
        LIMIT,
    );
    assert_bad_input(
        &o,
        &["/dev/urandom", "points file", "got a character device"],
    );
    let out = tempfile::tempdir().expect("tempdir");
    let o = output_within(
        solsim()
            .args(["map", "generate", "/dev/urandom", "--out"])
            .arg(out.path()),
        LIMIT,
    );
    assert_bad_input(&o, &["/dev/urandom", "got a character device"]);
    let o = output_within(solsim().args(["run", "/dev/zero", "--no-files"]), LIMIT);
    assert_bad_input(&o, &["/dev/zero", "got a character device"]);
}

#[test]
fn a_directory_or_a_huge_file_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let o = output_within(solsim().arg("validate").arg(dir.path()), LIMIT);
    assert_bad_input(&o, &["expected a regular file, got a directory"]);
    // 17 MiB of comment lines: over the 1 MiB cap on TOML inputs, refused from its size.
    let big = dir.path().join("big.toml");
    std::fs::write(&big, "#\n".repeat(17 << 19)).expect("write");
    let o = output_within(solsim().arg("validate").arg(&big), LIMIT);
    assert_bad_input(
        &o,
        &["big.toml", "expected at most 1 MiB of text, got 17 MiB"],
    );
}

#[test]
fn a_fifo_as_a_map_layer_is_refused_without_blocking() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pipe = dir.path().join("dem.tif");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&pipe)
            .status()
            .expect("mkfifo")
            .success()
    );
    let (path, _d) = common::scenario_copy("crater-floor-passage.toml", |t| {
        let dem = t
            .lines()
            .find(|l| l.starts_with("dem = "))
            .expect("dem line")
            .to_string();
        t.replace(&dem, &format!("dem = \"{}\"", pipe.display()))
    });
    let o = output_within(solsim().arg("validate").arg(&path), LIMIT);
    assert_bad_input(&o, &["map.dem", "an existing regular file", "FIFO"]);
}
