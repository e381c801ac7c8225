//! Issue 28, item 6: a misspelt field in a scenario got serde's `unknown field`, `expected one
//! of …` list in declaration order, cut at 120 characters — for `[rover]
//! drive_rate_m_per_hr` before the right name showed — and no "did you mean". A misspelt key
//! in any TOML solsim reads (scenario sections, the calendar, sols, expectations, `plan`
//! campaign files, `map generate` recipes), a misspelt `kind` in a zones file and a misspelt
//! key in a sweep's manifest.json now name the closest known one first, and the list of known
//! names is whole.

use std::path::Path;
use std::process::Output;

use crate::common::{assert_bad_input, root, scenario_copy, solsim, stderr, tiny};

/// `solsim validate` on a copy of bundled scenario `base` with `from` replaced by `to`.
fn validate_with(base: &str, from: &str, to: &str) -> Output {
    let (path, _dir) = scenario_copy(base, |t| {
        assert!(t.contains(from), "{base} holds {from:?}");
        t.replacen(from, to, 1)
    });
    solsim().arg("validate").arg(&path).output().expect("runs")
}

#[test]
fn misspelt_scenario_fields_name_the_closest_one_in_every_section() {
    for (base, from, to, typo, right) in [
        // The case: the list was cut before `drive_rate_m_per_h` showed.
        (
            "crater-floor-passage.toml",
            "drive_rate_m_per_h = 100.0",
            "drive_rate_m_per_hr = 100.0",
            "drive_rate_m_per_hr",
            "drive_rate_m_per_h",
        ),
        // Top level: two letters swapped.
        (
            "crater-floor-passage.toml",
            "seed = 385",
            "sede = 385",
            "sede",
            "seed",
        ),
        // [operations]
        (
            "crater-floor-passage.toml",
            "drive_start_lmst = \"11:30\"",
            "drive_start_lmts = \"11:30\"",
            "drive_start_lmts",
            "drive_start_lmst",
        ),
        // [onboard_localization]: case.
        (
            "crater-floor-passage.toml",
            "localizer = \"census\"",
            "Localizer = \"census\"",
            "Localizer",
            "localizer",
        ),
        // [grid]
        (
            "crater-floor-passage.toml",
            "max_slope_deg = 25.0",
            "max_slop_deg = 25.0",
            "max_slop_deg",
            "max_slope_deg",
        ),
        // [calendar]
        (
            "sol717-719.toml",
            "mission = \"mars2020\"",
            "misson = \"mars2020\"",
            "misson",
            "mission",
        ),
        // [[sols]]: the unit left off.
        (
            "sol717-719.toml",
            "historic_distance_m = 224.71",
            "historic_distance = 224.71",
            "historic_distance",
            "historic_distance_m",
        ),
        // [[expect]]
        (
            "crater-floor-717.toml",
            "strategy = \"replay\"",
            "stratgey = \"replay\"",
            "stratgey",
            "strategy",
        ),
    ] {
        let o = validate_with(base, from, to);
        assert_bad_input(
            &o,
            &[
                &format!("unknown field `{typo}` (did you mean `{right}`?)"),
                "case.toml: line ",
            ],
        );
    }
}

/// The suggestion comes before the list, and the list is not cut: its last name shows.
#[test]
fn the_list_of_known_fields_is_whole() {
    let o = validate_with(
        "crater-floor-passage.toml",
        "drive_rate_m_per_h = 100.0",
        "drive_rate_m_per_hr = 100.0",
    );
    let err = stderr(&o);
    let hint = err.find("did you mean").expect("a suggestion");
    let list = err.find("expected one of").expect("the list");
    assert!(hint < list, "{err}");
    // The last field of [rover], far past 120 characters of the message.
    assert!(err.contains("`max_tilt_deg`"), "{err}");
    assert!(!err.contains('…'), "{err}");
}

/// Nothing close: no guess, but still the whole list.
#[test]
fn a_name_far_from_every_field_gets_no_guess() {
    let o = validate_with(
        "crater-floor-passage.toml",
        "step_m = 2.0",
        "step_m = 2.0\ncolour = \"red\"",
    );
    assert_bad_input(
        &o,
        &["unknown field `colour`, expected one of", "`max_tilt_deg`"],
    );
    assert!(!stderr(&o).contains("did you mean"), "{}", stderr(&o));
}

#[test]
fn campaign_files_and_recipes_suggest_too() {
    let dir = tempfile::tempdir().expect("tempdir");
    let campaign = dir.path().join("campaign.toml");
    let text = std::fs::read_to_string(root().join("scenarios/plans/self-reliant-campaign.toml"))
        .expect("read")
        .replacen("battery_capacity_wh = ", "battery_capacity_w = ", 1);
    std::fs::write(&campaign, text).expect("write");
    let o = solsim().arg("plan").arg(&campaign).output().expect("runs");
    assert_bad_input(
        &o,
        &["unknown field `battery_capacity_w` (did you mean `battery_capacity_wh`?)"],
    );

    let recipe = dir.path().join("recipe.toml");
    let text = std::fs::read_to_string(root().join("maps/assets/crater-floor/recipe.toml"))
        .expect("read")
        .replacen("relief_m = ", "releif_m = ", 1);
    std::fs::write(&recipe, text).expect("write");
    let o = solsim()
        .args(["map", "generate"])
        .arg(&recipe)
        .arg("--out")
        .arg(dir.path().join("map"))
        .output()
        .expect("runs");
    assert_bad_input(&o, &["unknown field `releif_m` (did you mean `relief_m`?)"]);
}

#[test]
fn a_zone_with_a_misspelt_kind_names_it() {
    let dir = tempfile::tempdir().expect("tempdir");
    let zones = dir.path().join("zones.geojson");
    let text = std::fs::read_to_string(root().join("peers/zones_fixtures/zones.geojson"))
        .expect("read")
        .replacen("\"kind\": \"keep_out\"", "\"knd\": \"keep_out\"", 1);
    std::fs::write(&zones, text).expect("write");
    let o = solsim()
        .current_dir(root())
        .args(["zones", "check", "--zones"])
        .arg(&zones)
        .args(["--points", "peers/zones_fixtures/points.csv"])
        .output()
        .expect("runs");
    assert_bad_input(
        &o,
        &[
            "features[0]",
            "properties.kind: missing (the properties have `knd`: did you mean `kind`?)",
        ],
    );
}

/// A sweep's manifest.json with a key misspelt by hand: `sweep --resume` names the closest.
#[test]
fn a_misspelt_manifest_key_names_the_closest() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let map = tiny::tiny_map(d);
    std::fs::write(d.join("zones.geojson"), tiny::NO_ZONES).expect("zones");
    let scenario = d.join("tiny.toml");
    std::fs::write(
        &scenario,
        tiny::tiny_scenario(&map, &d.join("zones.geojson"), "tiny", ""),
    )
    .expect("scenario");
    let out = d.join("sweep");
    let sweep = |extra: &[&str]| {
        solsim()
            .arg("sweep")
            .arg(&scenario)
            .args(["--runs", "2", "-q", "--out"])
            .arg(&out)
            .args(extra)
            .output()
            .expect("runs")
    };
    let o = sweep(&[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let manifest = out.join("manifest.json");
    let text = std::fs::read_to_string(&manifest).expect("manifest");
    assert!(text.contains("\"strategies\":"), "{text}");
    std::fs::write(
        &manifest,
        text.replacen("\"strategies\":", "\"strategis\":", 1),
    )
    .expect("write");
    let o = sweep(&["--resume"]);
    assert_bad_input(
        &o,
        &[
            &Path::new("sweep")
                .join("manifest.json")
                .display()
                .to_string(),
            "unknown field `strategis` (did you mean `strategies`?)",
        ],
    );
}
