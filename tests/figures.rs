//! Figures (issue 13, item 1): `solsim compare` writes beside its other files
//! `<scenario>.uncertainty.svg`, the uncertainty radius against sol per strategy (paper 000
//! Fig. 2 and 5), `<scenario>.metres.svg`, metres per sol, and per strategy
//! `<scenario>.<strategy>.map.svg` (zones, keep-outs grown by the r of the closest pass, route,
//! path, sol-end discs, faults; Fig. 3-4), `<scenario>.<strategy>.passages.svg` (the same zoomed
//! at each passage), `<scenario>.<strategy>.fault-sol<N>.map.svg` (a fault at its r) and
//! `<scenario>.<strategy>.plans.svg` (each sol's plan as a Gantt chart with the HBS chain). Every SVG is well-formed XML (Python's
//! `xml.etree.ElementTree` parses it), shows what it claims from the run's own JSON, and is
//! the same byte for byte on a second run.

use crate::common;

use common::{root, solsim, stderr};

fn compare_svg(scenario: &str, out: &std::path::Path) -> String {
    compare_svg_with(scenario, out, &[])
}

fn compare_svg_with(scenario: &str, out: &std::path::Path, extra: &[&str]) -> String {
    let o = solsim()
        .current_dir(root())
        .args(["compare", scenario, "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let name = std::path::Path::new(scenario)
        .file_stem()
        .and_then(|s| s.to_str())
        .expect("name");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("SVG figures"), "{stdout}");
    std::fs::read_to_string(out.join(format!("{name}.uncertainty.svg"))).expect("the figure")
}

#[test]
fn compare_writes_the_uncertainty_figure() {
    let dir = tempfile::tempdir().expect("tempdir");
    let svg = compare_svg("scenarios/crater-floor-passage.toml", &dir.path().join("a"));
    // Well-formed: parsed by an independent XML parser.
    let parsed = std::process::Command::new("python3")
        .args([
            "-c",
            "import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); \
             print(r.tag, len(list(r.iter())))",
        ])
        .arg(dir.path().join("a/crater-floor-passage.uncertainty.svg"))
        .output()
        .expect("python3 runs");
    assert!(
        parsed.status.success(),
        "not well-formed XML: {}",
        stderr(&parsed)
    );
    assert!(
        String::from_utf8_lossy(&parsed.stdout).starts_with("{http://www.w3.org/2000/svg}svg"),
        "{}",
        String::from_utf8_lossy(&parsed.stdout)
    );
    // plotters writes each text on its own line inside <text>.
    let text = |t: &str| svg.contains(&format!("\n{t}\n</text>"));
    for strategy in [
        "replay",
        "ground",
        "onboard",
        "extension",
        "extension+onboard",
    ] {
        assert!(text(strategy), "{strategy} not in the legend");
    }
    assert!(text("uncertainty radius r (m)") && text("sol"), "axes");
    // One label per sol, each once, in the middle of its sol (none past the last sol).
    assert!(
        !svg.contains("\n388\n</text>"),
        "no label for a sol that is not there"
    );
    for sol in 383..=387 {
        assert_eq!(
            svg.matches(&format!("\n{sol}\n</text>")).count(),
            1,
            "sol {sol}"
        );
    }
    // One line per strategy, plus the legend's five swatches (tests/issue_28_strategy_lines_distinct.rs
    // checks their dashes and markers).
    assert!(svg.matches("<polyline").count() >= 10, "{svg}");
    // The replay faults NO_PATH on sol 385: a red cross (two red strokes).
    assert!(svg.contains("#FF0000"), "the fault marker");
    // Deterministic.
    let again = compare_svg("scenarios/crater-floor-passage.toml", &dir.path().join("b"));
    assert_eq!(svg, again);
}

/// Parses every `*.svg` in `dir` with Python's ElementTree; returns their names.
fn all_svgs_parse(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".svg"))
        .collect();
    names.sort();
    for n in &names {
        let parsed = std::process::Command::new("python3")
            .args([
                "-c",
                "import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])",
            ])
            .arg(dir.join(n))
            .output()
            .expect("python3 runs");
        assert!(parsed.status.success(), "{n}: {}", stderr(&parsed));
    }
    names
}

fn run_doc(dir: &std::path::Path, name: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join(name)).expect("run JSON")).expect("JSON")
}

#[test]
fn compare_writes_maps_metres_and_plan_figures_from_the_run() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("a");
    compare_svg("scenarios/crater-floor-passage.toml", &out);
    let names = all_svgs_parse(&out);
    for strategy in [
        "replay",
        "ground",
        "onboard",
        "extension",
        "extension+onboard",
    ] {
        for kind in ["map", "passages", "plans"] {
            let n = format!("crater-floor-passage.{strategy}.{kind}.svg");
            assert!(names.contains(&n), "{n} in {names:?}");
        }
    }
    assert!(names.contains(&"crater-floor-passage.metres.svg".to_string()));
    let read = |n: &str| std::fs::read_to_string(out.join(n)).expect("figure");
    let text = |svg: &str, t: &str| svg.contains(&format!("\n{t}\n</text>"));

    // The replay's fault zoom grows the keep-outs by its fault's r (from its JSON) plus the
    // footprint, and marks the NO_PATH on sol 385; its whole map grows each keep-out by the r
    // of the closest pass instead (tests/issue_28_keep_outs_at_the_moment.rs).
    let replay = run_doc(&out, "crater-floor-passage.replay.json");
    let fault = replay["sols"]
        .as_array()
        .expect("sols")
        .iter()
        .find_map(|s| s["fault"].as_object().cloned())
        .expect("the replay faults");
    let r = fault["uncertainty_m"].as_f64().expect("r");
    let zoom = read("crater-floor-passage.replay.fault-sol385.map.svg");
    assert!(
        zoom.contains(&format!("keep-outs grown by r = {r:.2} m")),
        "the zoom's title names the fault's r {r:.2}"
    );
    assert!(
        text(&zoom, "NO_PATH sol 385"),
        "the fault is labelled on the zoom"
    );
    let map = read("crater-floor-passage.replay.map.svg");
    assert!(
        map.contains("each keep-out grown by the r at the closest pass"),
        "the map's title says how the keep-outs are grown"
    );
    assert!(text(&map, "NO_PATH sol 385"), "the fault is labelled");
    for legend in ["keep-out", "route and waypoints", "fault"] {
        assert!(text(&map, legend), "legend {legend}");
    }
    // Drive sols' ends are labelled with their sol where there is room (the first always);
    // no label names a sol that did not drive.
    let drove: Vec<u64> = replay["sols"]
        .as_array()
        .expect("sols")
        .iter()
        .filter(|s| s["drove"].as_bool() == Some(true))
        .map(|s| s["sol"].as_u64().expect("sol"))
        .collect();
    assert!(
        text(&map, &drove[0].to_string()),
        "first drive sol labelled"
    );
    for sol in 380..400u64 {
        if text(&map, &sol.to_string()) {
            assert!(drove.contains(&sol), "sol {sol} labelled but did not drive");
        }
    }
    // Ground never faults here: no fault in its legend. Its passages are drawn at the r of
    // each pass, none above its largest end-of-sol r, and the map names no single r.
    let ground_map = read("crater-floor-passage.ground.map.svg");
    assert!(!text(&ground_map, "fault"), "no fault legend for ground");
    assert!(
        !ground_map.contains("grown by r = "),
        "no single r on the map"
    );
    let ground = run_doc(&out, "crater-floor-passage.ground.json");
    let max_r = ground["sols"]
        .as_array()
        .expect("sols")
        .iter()
        .filter_map(|s| s["end_uncertainty_m"].as_f64())
        .fold(0.0, f64::max);
    let passages = read("crater-floor-passage.ground.passages.svg");
    let rs: Vec<f64> = passages
        .split(" at r = ")
        .skip(1)
        .flat_map(|t| {
            let t = t.split(" m\n").next().expect("r");
            t.split('-')
                .map(|x| x.parse::<f64>().expect("r in a caption"))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(!rs.is_empty(), "a passage panel with its r");
    for r in rs {
        assert!(
            (0.0..=max_r + 0.005).contains(&r),
            "{r} against largest {max_r}"
        );
    }

    // The onboard plans: a row per planned sol and an HBS row under each sol that ran the
    // co-processor chain.
    let onboard = run_doc(&out, "crater-floor-passage.onboard.json");
    let plans = read("crater-floor-passage.onboard.plans.svg");
    for s in onboard["sols"].as_array().expect("sols") {
        let Some(plan) = s["activity_plan"].as_object() else {
            continue;
        };
        let sol = s["sol"].as_u64().expect("sol");
        let rows = plan["timeline"].as_array().expect("timeline");
        if rows.is_empty() {
            continue;
        }
        assert!(text(&plans, &format!("sol {sol}")), "sol {sol} row");
        let hbs = rows
            .iter()
            .any(|t| t["timeline"].as_str() == Some("hbs_link"));
        assert_eq!(
            text(&plans, &format!("{sol} HBS")),
            hbs,
            "sol {sol} HBS row"
        );
    }
    assert!(
        text(&plans, "HBS: image transfer") && text(&plans, "HBS: reboot") && text(&plans, "drive")
    );

    // Metres per sol: one bar per drive sol per strategy (plotters draws each as a <rect> in
    // the strategy's colour; ground is the second colour, #1F77B4).
    let metres = read("crater-floor-passage.metres.svg");
    let ground_drives = ground["sols"]
        .as_array()
        .expect("sols")
        .iter()
        .filter(|s| s["drove"].as_bool() == Some(true))
        .count();
    let ground_rects = metres
        .split("<rect")
        .skip(1)
        .filter(|r| {
            r.split("/>")
                .next()
                .is_some_and(|a| a.contains("fill=\"#1F77B4\""))
        })
        .count();
    // The drive sols' bars and the legend swatch.
    assert_eq!(ground_rects, ground_drives + 1, "ground bars");
}

#[test]
fn the_map_grows_the_keep_outs_at_the_asked_r() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("a");
    compare_svg_with(
        "scenarios/crater-floor-passage.toml",
        &out,
        &["--map-r-m", "10"],
    );
    let map =
        std::fs::read_to_string(out.join("crater-floor-passage.onboard.map.svg")).expect("map");
    assert!(map.contains("keep-outs grown by r = 10.00 m"), "asked r");
    for bad in ["-1", "nan", "1e9"] {
        let o = solsim()
            .current_dir(root())
            .args([
                "compare",
                "scenarios/crater-floor-passage.toml",
                "--no-files",
            ])
            .arg(format!("--map-r-m={bad}"))
            .output()
            .expect("runs");
        common::assert_bad_input(&o, &["--map-r-m", "metres"]);
    }
}
