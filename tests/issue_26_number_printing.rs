//! Issue 26, finding 12: one error printed 1e300 as 301 digits, and integers printed as
//! `2.147483647e9`. `readable_value` turned every number of 1e9 or more into scientific
//! notation, integers included; a value quoted in an error's *expected* part
//! (`at most sol.battery_capacity_wh = …`) and the command line's own messages
//! (`--footprint-radius-m`) printed f64s with `{}`, every digit spelled out. Integers now print
//! as their digits and a float's full spelling as `1e300`, in every message: the scenario and
//! campaign-file loaders, and the one line the binary prints for any error.

use std::path::Path;

use crate::common::{assert_bad_input, root, scenario_copy, solsim};

#[test]
fn an_integer_prints_as_its_digits() {
    let (path, _d) = scenario_copy("crater-floor-passage.toml", |t| {
        t.replace("sol = 384", "sol = 2147483647")
    });
    let o = solsim().arg("validate").arg(&path).output().expect("runs");
    assert_bad_input(
        &o,
        &["sols[1].sol: expected sol 384 (sols are consecutive), got 2147483647"],
    );
    // The largest u32 and a value past it (a TOML integer a u32 field cannot hold).
    for (sol, want) in [
        ("4294967295", "got 4294967295"),
        ("18446744073709551615", "18446744073709551615"),
    ] {
        let (path, _d) = scenario_copy("crater-floor-passage.toml", |t| {
            t.replace("sol = 384", &format!("sol = {sol}"))
        });
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        assert_bad_input(&o, &[want]);
        // After the file's path: a temporary directory's random name may hold "e9" itself
        // (CI saw `/tmp/.tmpD7e9in/`).
        let err = crate::common::stderr(&o);
        let message = err.rsplit("case.toml: ").next().unwrap_or(&err);
        assert!(!message.contains("e9"), "{err}");
    }
}

#[test]
fn a_huge_value_quoted_in_what_is_expected_prints_as_1e300() {
    let path = root().join("scenarios/plans/self-reliant-campaign.toml");
    let text = std::fs::read_to_string(&path).expect("read");
    let text = replace_value(&text, "battery_capacity_wh", "1e300");
    let text = replace_value(&text, "initial_energy_wh", "2e300");
    let e = study::CampaignFile::from_toml_str(&path, &text)
        .expect_err("more energy than capacity")
        .to_string();
    assert!(
        e.ends_with(
            "sol.initial_energy_wh: expected at most sol.battery_capacity_wh = 1e300 Wh, got 2e300"
        ),
        "{e}"
    );
}

#[test]
fn a_command_line_value_prints_readably() {
    let o = solsim()
        .args(["zones", "check", "--zones"])
        .arg(root().join("peers/zones_fixtures/zones.geojson"))
        .arg("--points")
        .arg(root().join("peers/zones_fixtures/points.csv"))
        .arg("--footprint-radius-m=-1e300")
        .output()
        .expect("runs");
    assert_bad_input(
        &o,
        &["--footprint-radius-m: expected 0 ..= 10 metres, got -1e300"],
    );
}

/// Every number of the bundled scenario and campaign files, set to a huge float and to large
/// integers: no error spells a number in more than 20 digits, and no integer written as one
/// comes back in scientific notation.
#[test]
fn no_error_spells_out_a_huge_number_or_an_integer_in_scientific_notation() {
    let scenario = |path: &Path, text: &str| {
        study::scenario::ScenarioSpec::from_toml_str(path, text)
            .map(drop)
            .map_err(|e| e.to_string())
    };
    let plan = |path: &Path, text: &str| {
        study::CampaignFile::from_toml_str(path, text)
            .map(drop)
            .map_err(|e| e.to_string())
    };
    let mut errors = 0;
    for (file, load) in [
        (
            "scenarios/crater-floor-passage.toml",
            &scenario as &dyn Fn(&Path, &str) -> _,
        ),
        ("scenarios/self-reliant-campaign.toml", &scenario),
        ("scenarios/plans/self-reliant-campaign.toml", &plan),
    ] {
        let path = root().join(file);
        let text = std::fs::read_to_string(&path).expect("read");
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let Some((key, value)) = line.split_once(" = ") else {
                continue;
            };
            if value.parse::<f64>().is_err() || key.starts_with('#') {
                continue;
            }
            for v in [
                "1e300",
                "-1e300",
                "2147483647",
                "4294967296",
                "9007199254740993",
            ] {
                let mut edited = lines.clone();
                let new = format!("{key} = {v}");
                edited[i] = &new;
                let Err(e) = load(&path, &edited.join("\n")) else {
                    continue;
                };
                errors += 1;
                let longest = e
                    .split(|c: char| !c.is_ascii_digit())
                    .map(str::len)
                    .max()
                    .unwrap_or(0);
                assert!(longest <= 20, "{file}:{} {key} = {v}: {e}", i + 1);
                if !v.contains('e') {
                    assert!(!e.contains("e9") && !e.contains("e15"), "{key} = {v}: {e}");
                }
            }
        }
    }
    assert!(errors > 100, "{errors} errors");
}

fn replace_value(text: &str, key: &str, value: &str) -> String {
    let start = text.find(&format!("{key} = ")).expect("key");
    let end = start + text[start..].find('\n').expect("line end");
    format!("{}{key} = {value}{}", &text[..start], &text[end..])
}
