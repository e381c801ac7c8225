//! Issue 26, finding 9 (terminal): an `[[expect]] what`, a zone's name and a point's name
//! reached the terminal with raw escape sequences (`ESC ]0;…BEL` retitles the terminal,
//! `ESC [2J` clears it): `solsim regress` printed `what` as written, `solsim zones check`
//! printed point names as written, and zone names were accepted whatever they held.
//!
//! Now the loaders refuse names and `what` holding control characters (one error line naming
//! the field, expected "text without control characters", got the escaped value) — so do
//! campaign files for activity ids and names, which `solsim plan` printed raw too — and
//! whatever reaches the terminal is escaped again: the error line as a whole (a path that holds
//! ESC), the regress report and the zones table. No byte 0x1b ever reaches stdout or stderr.

use crate::common;

use std::path::Path;
use std::process::Output;
use std::time::Duration;

use common::{assert_bad_input, output_within, solsim, tiny};

/// Retitles the terminal, then clears it.
const ESC: &str = "\u{1b}]0;pwned\u{7}\u{1b}[2J";

fn assert_no_escape(o: &Output) {
    for (stream, bytes) in [("stdout", &o.stdout), ("stderr", &o.stderr)] {
        assert!(
            !bytes.iter().any(|&b| b == 0x1b || b == 0x07),
            "raw ESC or BEL on {stream}: {:?}",
            String::from_utf8_lossy(bytes)
        );
    }
}

fn run(cmd: &mut std::process::Command) -> Output {
    output_within(cmd, Duration::from_secs(120))
}

/// A tiny scenario with `zones` as its zones file and `extra` TOML, in `dir`.
fn scenario(dir: &Path, zones: &str, extra: &str) -> std::path::PathBuf {
    let map = tiny::tiny_map(dir);
    let zones_path = dir.join("zones.geojson");
    std::fs::write(&zones_path, zones).expect("zones");
    let path = dir.join("s").join("tiny.toml");
    std::fs::create_dir_all(path.parent().expect("parent")).expect("dir");
    std::fs::write(&path, tiny::tiny_scenario(&map, &zones_path, "tiny", extra)).expect("write");
    path
}

#[test]
fn an_expectation_whose_what_holds_esc_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let what = toml::Value::String(format!("reaches the goal {ESC}"));
    let path = scenario(
        dir.path(),
        tiny::NO_ZONES,
        &format!("[[expect]]\nwhat = {what}\nstrategy = \"ground\"\nsols_to_goal = [0, 5]\n"),
    );
    let o = run(solsim().arg("regress").arg(path.parent().expect("dir")));
    assert_no_escape(&o);
    assert_bad_input(
        &o,
        &[
            "expect[0].what: expected text without control characters",
            "\\u{1b}]0;pwned\\u{7}\\u{1b}[2J",
        ],
    );
    let o = run(solsim().arg("validate").arg(&path));
    assert_no_escape(&o);
    assert_bad_input(
        &o,
        &["expect[0].what: expected text without control characters"],
    );
}

#[test]
fn a_zone_whose_name_holds_esc_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let name = serde_json::to_string(&format!("crater{ESC}")).expect("json");
    let zones = format!(
        r#"{{"type": "FeatureCollection", "features": [{{"type": "Feature",
            "properties": {{"kind": "keep_out", "name": {name}}},
            "geometry": {{"type": "Polygon", "coordinates": [[[18, 10], [22, 10], [22, 30], [18, 30], [18, 10]]]}}}}]}}"#
    );
    let path = scenario(dir.path(), &zones, "");
    let expected = [
        "features[0].properties.name: expected text without control characters",
        "crater\\u{1b}]0;pwned\\u{7}\\u{1b}[2J",
    ];
    for args in [&["validate"][..], &["run", "--strategy", "ground"]] {
        let o = run(solsim().args(args).arg(&path).current_dir(dir.path()));
        assert_no_escape(&o);
        assert_bad_input(&o, &expected);
    }
    let points = dir.path().join("points.csv");
    std::fs::write(&points, "x_m,y_m\n1,2\n").expect("points");
    let o = run(solsim()
        .args(["zones", "check", "--zones"])
        .arg(dir.path().join("zones.geojson"))
        .arg("--points")
        .arg(&points));
    assert_no_escape(&o);
    assert_bad_input(&o, &expected);
}

#[test]
fn a_point_whose_name_holds_esc_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let zones = dir.path().join("zones.geojson");
    std::fs::write(&zones, tiny::NO_ZONES).expect("zones");
    let points = dir.path().join("points.csv");
    std::fs::write(&points, format!("name,x_m,y_m\nok,1,2\n\"a{ESC}\",3,4\n")).expect("points");
    for json in [false, true] {
        let mut cmd = solsim();
        cmd.args(["zones", "check", "--zones"])
            .arg(&zones)
            .arg("--points")
            .arg(&points);
        if json {
            cmd.arg("--json");
        }
        let o = run(&mut cmd);
        assert_no_escape(&o);
        assert_bad_input(
            &o,
            &[
                "line 3, column name: expected text without control characters",
                "a\\u{1b}]0;pwned\\u{7}\\u{1b}[2J",
            ],
        );
    }
}

/// The second defence: an error line quoting a path that holds ESC is escaped as a whole.
#[test]
fn an_error_quoting_a_path_with_esc_is_escaped() {
    let dir = tempfile::tempdir().expect("tempdir");
    let missing = dir.path().join(format!("no{ESC}.toml"));
    let o = run(solsim().arg("validate").arg(&missing));
    assert_no_escape(&o);
    assert_bad_input(&o, &["no\\u{1b}]0;pwned\\u{7}\\u{1b}[2J.toml"]);
}

/// The same for a campaign file's activity ids and names, which `solsim plan` prints in its
/// table.
#[test]
fn a_campaign_activity_whose_id_or_name_holds_esc_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text =
        std::fs::read_to_string(common::root().join("scenarios/plans/self-reliant-campaign.toml"))
            .expect("read");
    for (from, to, expected) in [
        (
            "id = \"relay-mro-am\"",
            "id = \"relay\\u001b]0;pwned\\u0007\"",
            "activities[0].id: expected a non-empty id without spaces, '#' or control characters",
        ),
        (
            "name = \"UHF relay pass, MRO (morning)\"",
            "name = \"UHF \\u001b[2J relay\"",
            "activities[0].name: expected text without control characters",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let path = dir.path().join("plan.toml");
        std::fs::write(&path, text.replacen(from, to, 1)).expect("write");
        let o = run(solsim().arg("plan").arg(&path));
        assert_no_escape(&o);
        assert_bad_input(&o, &[expected, "\\u{1b}"]);
    }
}
