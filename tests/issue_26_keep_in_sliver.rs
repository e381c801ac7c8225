//! Issue 26, finding 7: a keep-in sliver 1e-9 to 4 m wide along the route passed `validate`
//! with warnings ("the footprint overlaps a zone"), while every leg "closed at r = −1.65 m" and
//! every strategy drove 0 m. A waypoint whose footprint overlaps a zone was a warning that
//! also hid the legs to and from it from the "no path even at r = 0" check. AutoNav plans to
//! the waypoint's cell, which is closed there even at r = 0, so such a leg is the documented
//! error, with the overlap named as its cause: `validate` exits 2 and every other command
//! refuses the scenario.

use std::path::{Path, PathBuf};

use crate::common::{assert_bad_input, rebase, root, solsim, stderr};

/// `scenarios/crater-floor-passage.toml` with a straight route north along x = 600 and one keep-in of
/// `width_m` centred on it, in a new temporary directory.
fn sliver(dir: &Path, width_m: f64) -> PathBuf {
    let mut text = rebase(
        &std::fs::read_to_string(root().join("scenarios/crater-floor-passage.toml")).expect("read"),
    );
    let (x0, x1) = (600.0 - width_m / 2.0, 600.0 + width_m / 2.0);
    let zones = dir.join("sliver.geojson");
    std::fs::write(
        &zones,
        format!(
            r#"{{"type": "FeatureCollection", "features": [{{"type": "Feature",
                "properties": {{"name": "sliver", "kind": "keep_in"}},
                "geometry": {{"type": "Polygon", "coordinates":
                [[[{x0:?}, 50], [{x1:?}, 50], [{x1:?}, 780], [{x0:?}, 780], [{x0:?}, 50]]]}}}}]}}"#
        ),
    )
    .expect("zones");
    for (prefix, line) in [
        (
            "zones = ",
            format!("zones = {:?}", zones.display().to_string()),
        ),
        (
            "waypoints = ",
            "waypoints = [[600.0, 60.0], [600.0, 320.0], [600.0, 545.0], [600.0, 770.0]]".into(),
        ),
    ] {
        let start = text.find(prefix).expect("line");
        let end = start + text[start..].find('\n').expect("line end");
        text.replace_range(start..end, &line);
    }
    // The expectations are about the bundled route.
    text.truncate(text.find("[[expect]]").expect("expectations"));
    let path = dir.join("case.toml");
    std::fs::write(&path, text).expect("write");
    path
}

#[test]
fn a_keep_in_sliver_along_the_route_is_the_no_path_at_r_0_error() {
    let dir = tempfile::tempdir().expect("tempdir");
    for width_m in [1e-9, 1.0, 4.0] {
        let path = sliver(dir.path(), width_m);
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(
            o.status.code(),
            Some(2),
            "width {width_m}: {out}{}",
            stderr(&o)
        );
        for leg in ["[0..=1]", "[1..=2]", "[2..=3]"] {
            let line = out
                .lines()
                .find(|l| l.contains(&format!(": error: route.waypoints{leg}:")))
                .unwrap_or_else(|| panic!("width {width_m}: no error for leg {leg}:\n{out}"));
            assert!(
                line.contains("perfect position knowledge (r = 0)"),
                "{line}"
            );
            assert!(line.contains("closes at r = -"), "{line}");
            assert!(line.contains("the footprint overlaps a zone by"), "{line}");
            assert!(line.contains("NO_PATH"), "{line}");
        }
        assert!(
            out.contains("3 errors, 0 warnings"),
            "width {width_m}: {out}"
        );
        // Every other command refuses it, naming the first leg.
        let o = solsim()
            .arg("run")
            .arg(&path)
            .args(["--strategy", "ground", "--no-files"])
            .output()
            .expect("runs");
        assert_bad_input(&o, &["route.waypoints[0..=1]", "closes at r = -"]);
        assert!(o.stdout.is_empty());
    }
}

/// A keep-in corridor the 1.65 m footprint fits with room (8 m wide) is no finding:
/// the check is about the rover not fitting, not about a keep-in being narrow.
#[test]
fn a_keep_in_corridor_the_footprint_fits_is_fine() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = sliver(dir.path(), 8.0);
    let o = solsim().arg("validate").arg(&path).output().expect("runs");
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    assert!(out.contains(": ok"), "{out}");
}
