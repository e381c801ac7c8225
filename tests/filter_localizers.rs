//! The particle filter (paper 002) and the EKF (paper 004) as the simulator's onboard
//! localizer (`[onboard_localization] localizer = "particle" | "ekf"`): the bundled scenarios
//! run through `compare` byte-identically on one and two threads; the filter's ellipse reaches
//! the sol log, the CSV and the GeoJSON; bad settings are refused naming the field.

use crate::common;

use std::path::Path;

use common::{assert_bad_input, replace_line, root, scenario_copy, solsim};

const SCENARIOS: [(&str, &str); 2] = [
    ("sol717-719-particle.toml", "particle"),
    ("sol717-719-ekf.toml", "ekf"),
];

fn compare_into(scenario: &str, out: &Path, threads: &str) -> String {
    let o = solsim()
        .current_dir(root())
        .args([
            "compare",
            &format!("scenarios/{scenario}"),
            "--threads",
            threads,
            "--out",
        ])
        .arg(out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", common::stderr(&o));
    String::from_utf8(o.stdout).expect("utf-8")
}

/// Every file under `dir`, relative path → bytes.
fn files(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    let mut out = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("list") {
            let p = e.expect("entry").path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p
                    .strip_prefix(dir)
                    .expect("as documented")
                    .to_string_lossy()
                    .into_owned();
                out.insert(rel, std::fs::read(&p).expect("read"));
            }
        }
    }
    out
}

#[test]
fn one_and_two_threads_write_the_same_bytes() {
    for (scenario, _) in SCENARIOS {
        let tmp = tempfile::tempdir().expect("tempdir");
        let (a, b) = (tmp.path().join("one"), tmp.path().join("two"));
        let one = compare_into(scenario, &a, "1");
        let two = compare_into(scenario, &b, "2");
        let strip = |s: &str, dir: &Path| s.replace(&dir.display().to_string(), "OUT");
        assert_eq!(strip(&one, &a), strip(&two, &b), "{scenario}: printed text");
        let (fa, fb) = (files(&a), files(&b));
        assert!(fa.len() > 20, "{scenario}: {} files", fa.len());
        assert_eq!(
            fa.keys().collect::<Vec<_>>(),
            fb.keys().collect::<Vec<_>>(),
            "{scenario}"
        );
        for (name, bytes) in &fa {
            assert!(
                bytes == &fb[name],
                "{scenario}: {name} differs between 1 and 2 threads"
            );
        }
        // Sweeps too: the over-runs statistics.
        let runs = |threads: &str| {
            let o = solsim()
                .current_dir(root())
                .args([
                    "compare",
                    &format!("scenarios/{scenario}"),
                    "--no-files",
                    "--json",
                ])
                .args(["--runs", "6", "--threads", threads])
                .output()
                .expect("runs");
            assert!(o.status.success(), "{}", common::stderr(&o));
            o.stdout
        };
        assert!(runs("1") == runs("2"), "{scenario}: --runs 6 differs");
    }
}

#[test]
fn the_ellipse_reaches_the_sol_log_csv_and_geojson() {
    for (scenario, localizer) in SCENARIOS {
        let tmp = tempfile::tempdir().expect("tempdir");
        let out = tmp.path().join("run");
        compare_into(scenario, &out, "2");
        let stem = scenario.trim_end_matches(".toml");
        let doc: serde_json::Value = serde_json::from_slice(
            &std::fs::read(out.join(format!("{stem}.onboard.json"))).expect("onboard JSON"),
        )
        .expect("JSON");
        let margin = 1.0; // the default operator margin, metres
        let mut applied = 0;
        for sol in doc["sols"].as_array().expect("sols") {
            let l = &sol["onboard_localization"];
            if l.is_null() {
                continue;
            }
            assert_eq!(l["localizer"], localizer);
            if l["applied"] == true {
                applied += 1;
                let e = &l["ellipse"];
                let (a, b) = (
                    e["semi_major_m"].as_f64().expect("a number"),
                    e["semi_minor_m"].as_f64().expect("a number"),
                );
                let disc = e["disc_radius_m"].as_f64().expect("a number");
                assert!(b > 0.0 && b <= a, "{e}");
                // The disc is 3 × the 1σ semi-major axis, the σ the margin is made of.
                assert!((disc - 3.0 * a).abs() < 1e-12, "{e}");
                assert_eq!(l["sigma_m"].as_f64(), Some(disc));
                let after = l["uncertainty_after_m"].as_f64().expect("a number");
                assert!((after - (disc + margin)).abs() < 1e-9, "{l}");
                let mmgis = e["mmgis_angle_deg"].as_f64().expect("a number");
                let az = e["azimuth_deg"].as_f64().expect("a number");
                assert!(((az - 90.0).rem_euclid(180.0) - mmgis).abs() < 1e-9);
            }
        }
        assert!(applied >= 2, "{scenario}: {applied} fixes applied");
        let csv = std::fs::read_to_string(out.join(format!("{stem}.onboard.sols.csv")))
            .expect("as documented");
        let header: Vec<&str> = csv
            .lines()
            .next()
            .expect("as documented")
            .split(',')
            .collect();
        let col = |name: &str| header.iter().position(|h| *h == name).expect(name);
        let (major, angle) = (col("onboard_semi_major_m"), col("onboard_mmgis_angle_deg"));
        let filled = csv
            .lines()
            .skip(1)
            .filter(|l| {
                let cells: Vec<&str> = l.split(',').collect();
                !cells[major].is_empty() && !cells[angle].is_empty()
            })
            .count();
        assert!(filled >= applied, "{csv}");
        let geo: serde_json::Value = serde_json::from_slice(
            &std::fs::read(out.join(format!("{stem}.onboard.geojson"))).expect("GeoJSON"),
        )
        .expect("JSON");
        let fixes = geo["features"]
            .as_array()
            .expect("as documented")
            .iter()
            .filter(|f| f["properties"]["kind"] == "localization")
            .inspect(|f| {
                let p = &f["properties"];
                for key in ["semi_major_m", "semi_minor_m", "angle_deg", "disc_radius_m"] {
                    assert!(p[key].as_f64().is_some(), "{key}: {p}");
                }
            })
            .count();
        assert!(fixes >= applied, "{scenario}: {fixes} localization points");
        let ellipses = std::fs::read_to_string(
            out.join("gis")
                .join(format!("{stem}.onboard.ellipses.geojson")),
        )
        .expect("ellipses layer");
        assert!(ellipses.contains("localization_3sigma"), "{scenario}");
    }
}

#[test]
fn bad_settings_are_refused_naming_the_field() {
    let cases: [(&str, &str, &str, &[&str]); 10] = [
        (
            "sol717-719-particle.toml",
            "particle_count",
            "particle_count = 5",
            &["onboard_localization.particle_count", "100 ..= 100000"],
        ),
        (
            "sol717-719-particle.toml",
            "resampling",
            "resampling = \"stratified\"",
            &["onboard_localization.resampling", "\"kld\""],
        ),
        (
            "sol717-719-particle.toml",
            "particle_count",
            "range_sigma_m = 1.0",
            &["onboard_localization.range_sigma_m", "ekf"],
        ),
        (
            "sol717-719-particle.toml",
            "localizer",
            "localizer = \"kalman\"",
            &["onboard_localization.localizer", "\"particle\" or \"ekf\""],
        ),
        (
            "sol717-719-ekf.toml",
            "range_sigma_m",
            "range_sigma_m = -1.0",
            &["onboard_localization.range_sigma_m"],
        ),
        (
            "sol717-719-ekf.toml",
            "range_sigma_m",
            "range_sigma_m = nan",
            &["onboard_localization.range_sigma_m"],
        ),
        (
            "sol717-719-ekf.toml",
            "pass_duration_s",
            "pass_duration_s = 10",
            &["onboard_localization.pass_duration_s", "60 ..= 3600"],
        ),
        (
            "sol717-719-ekf.toml",
            "elevation_mask_deg",
            "elevation_mask_deg = 95.0",
            &["onboard_localization.elevation_mask_deg"],
        ),
        (
            "sol717-719-ekf.toml",
            "pass_duration_s",
            "particle_count = 1000",
            &["onboard_localization.particle_count", "particle"],
        ),
        (
            "sol717-719-ekf.toml",
            "pass_duration_s",
            "hbs_slowdown = 2.0",
            &[
                "onboard_localization.hbs_slowdown",
                "census, ncc, mi, particle",
            ],
        ),
    ];
    for (base, prefix, line, must) in cases {
        let (path, _dir) = scenario_copy(base, |t| replace_line(&t, prefix, line));
        for cmd in ["validate", "compare"] {
            let o = solsim()
                .current_dir(root())
                .args([cmd])
                .arg(&path)
                .args(if cmd == "compare" {
                    &["--no-files"][..]
                } else {
                    &[][..]
                })
                .output()
                .expect("runs");
            assert_bad_input(&o, must);
        }
    }
}
