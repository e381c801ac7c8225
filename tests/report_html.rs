//! `solsim report` and `compare --report` (issue 13, item 2): one self-contained report.html —
//! inline SVG figures, no script, nothing loaded from anywhere — for a compare directory and
//! for a sweep directory; the report of a directory equals the one compare wrote with the run;
//! a directory whose files the scenario no longer gives is refused. (The page in a real
//! browser: tests/report_browser.rs.)

use crate::common;

use std::path::Path;

use common::{assert_bad_input, run_ok, solsim, stderr};

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).expect("readable")
}

/// What every report must be: a whole HTML page with nothing fetched from anywhere.
fn assert_self_contained(html: &str) {
    assert!(html.starts_with("<!DOCTYPE html>"), "doctype");
    assert!(html.trim_end().ends_with("</html>"), "whole page");
    for banned in [
        "<script", "<link", "<img", "<iframe", "src=", "@import", "url(",
    ] {
        assert!(!html.contains(banned), "{banned} in the report");
    }
    // The only URLs are the SVG namespace declarations.
    for (at, _) in html.match_indices("http") {
        let rest = &html[at..];
        assert!(
            rest.starts_with("http://www.w3.org/2000/svg")
                || rest.starts_with("http://www.w3.org/1999/xlink"),
            "a URL in the report: {}",
            &rest[..rest.len().min(60)]
        );
    }
}

#[test]
fn compare_report_and_report_of_the_directory_are_the_same_page() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = dir.path().join("run");
    let stdout = run_ok(
        &[
            "compare",
            "scenarios/crater-floor-passage.toml",
            "--report",
            "--out",
        ],
        &[&run],
    );
    assert!(stdout.contains("report.html"), "{stdout}");
    let html = read(&run.join("report.html"));
    assert_self_contained(&html);
    for id in ["compare", "verdict", "figures", "sol-logs"] {
        assert!(html.contains(&format!("id=\"{id}\"")), "section {id}");
    }
    // Every figure compare wrote is in the page, inline.
    let svgs: Vec<String> = std::fs::read_dir(&run)
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".svg"))
        .collect();
    // Uncertainty and metres; per strategy a map, its passages and the plans; the replay's
    // sol-385 zoom.
    assert_eq!(svgs.len(), 18, "{svgs:?}");
    assert_eq!(html.matches("<figure").count(), svgs.len());
    assert_eq!(html.matches("<svg").count(), svgs.len());
    for n in &svgs {
        assert!(html.contains(&format!("<figure id=\"{n}\">")), "{n}");
    }
    // The compare table and the sol logs: a row per strategy, a log per strategy.
    for strategy in [
        "replay",
        "ground",
        "onboard",
        "extension",
        "extension+onboard",
    ] {
        assert!(
            html.contains(&format!("<tr><td>{strategy}</td>")),
            "{strategy} row"
        );
        assert!(
            html.contains(&format!("id=\"sols-{strategy}\"")),
            "{strategy} log"
        );
    }
    // The replay's NO_PATH on sol 385 is in its sol log (the log under its heading, a row per
    // sol starting with the sol).
    let replay_log = html
        .split("id=\"sols-replay\"")
        .nth(1)
        .and_then(|t| t.split("<h3").next())
        .expect("the replay's log");
    assert!(replay_log.contains("<tr><td>385</td>"), "sol 385 row");
    assert!(
        replay_log.contains("NO_PATH after "),
        "the fault in the log"
    );

    // `solsim report` on the directory gives the same page, byte for byte (the run is
    // regenerated from the scenario and checked against the directory first).
    let again = dir.path().join("report");
    let stdout = run_ok(&["report"], &[&run, Path::new("--out"), &again]);
    assert!(stdout.contains("18 figures inline"), "{stdout}");
    assert_eq!(read(&again.join("report.html")), html);
}

#[test]
fn report_refuses_a_directory_the_scenario_no_longer_gives() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = dir.path().join("run");
    run_ok(
        &["compare", "scenarios/crater-floor-passage.toml", "--out"],
        &[&run],
    );
    let out = dir.path().join("report");
    let report = |d: &Path, extra: &[&str]| common::report(d, &out, extra);
    // An edited sol log.
    let ground = run.join("crater-floor-passage.ground.json");
    let text = read(&ground);
    let edited = text.replacen("\"distance_m\": ", "\"distance_m\": 1", 1);
    assert_ne!(edited, text);
    std::fs::write(&ground, &edited).expect("write");
    assert_bad_input(
        &report(&run, &[]),
        &["crater-floor-passage.ground.json", "edited"],
    );
    std::fs::write(&ground, &text).expect("write");
    // The scenario given with --scenario is not the one the run used.
    let (copy, _keep) = common::scenario_copy("crater-floor-passage.toml", |t| {
        t.replacen("seed = ", "seed = 1", 1)
    });
    let o = report(&run, &["--scenario", copy.to_str().expect("utf-8")]);
    assert_bad_input(&o, &["SHA-256", "edited since the run"]);
    // Not a run directory at all.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).expect("mkdir");
    assert_bad_input(&report(&empty, &[]), &["empty", "found neither"]);
    assert_bad_input(&report(&dir.path().join("missing"), &[]), &["missing"]);
    // Two documents for one strategy, and a JSON that is not a run document.
    let twin = dir.path().join("twin");
    std::fs::create_dir(&twin).expect("mkdir");
    std::fs::copy(&ground, twin.join("a.json")).expect("copy");
    std::fs::copy(&ground, twin.join("b.json")).expect("copy");
    assert_bad_input(&report(&twin, &[]), &["b.json", "second for ground"]);
    std::fs::write(twin.join("b.json"), "[1, 2]").expect("write");
    assert_bad_input(&report(&twin, &[]), &["b.json", "JSON object"]);
    // Nothing was written by the refused runs.
    assert!(!out.exists());
    // And it works again on the restored directory.
    let o = report(&run, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(out.join("report.html").is_file());
}

#[test]
fn a_compare_over_runs_is_reported_with_its_statistics() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = dir.path().join("run");
    run_ok(
        &[
            "compare",
            "scenarios/rapid-traverse-379-409.toml",
            "--runs",
            "20",
            "--report",
            "--out",
        ],
        &[&run],
    );
    let html = read(&run.join("report.html"));
    assert_self_contained(&html);
    assert!(html.contains("id=\"over-runs\""), "over-runs section");
    assert!(html.contains("Over 20 seeded worlds"));
    assert!(html.contains("no_path_rate"), "rates table");
    let again = dir.path().join("report");
    run_ok(&["report"], &[&run, Path::new("--out"), &again]);
    assert_eq!(read(&again.join("report.html")), html);
}

#[test]
fn a_sweep_directory_is_reported_and_a_changed_one_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let sweep = dir.path().join("sweep");
    common::sweep_rapid_traverse(30, &sweep);
    let out = dir.path().join("report");
    let stdout = run_ok(&["report"], &[&sweep, Path::new("--out"), &out]);
    assert!(
        stdout.contains("sweep of 30 runs; 2 figures inline"),
        "{stdout}"
    );
    let html = read(&out.join("report.html"));
    assert_self_contained(&html);
    assert!(html.contains("rapid-traverse-379-409 — sweep of 30 runs"));
    for id in [
        "rapid-traverse-379-409.sols-cdf.svg",
        "rapid-traverse-379-409.rates.svg",
    ] {
        assert!(html.contains(&format!("<figure id=\"{id}\">")), "{id}");
    }
    // The rates come from the rows: the summary's numbers are in the page.
    let summary: serde_json::Value =
        serde_json::from_str(&read(&sweep.join("summary.json"))).expect("JSON");
    for st in summary["statistics"]["strategies"]
        .as_array()
        .expect("strategies")
    {
        let name = st["strategy"].as_str().expect("name");
        let rate = &st["rates"][0];
        let row = format!(
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td>",
            name,
            rate["name"].as_str().expect("rate name"),
            rate["count"],
            rate["runs"]
        );
        assert!(html.contains(&row), "{row}");
    }
    // The CDF names every strategy with its run count.
    assert!(html.contains("sols to cover the study segment"));
    for s in ["ground", "onboard", "extension", "extension+onboard"] {
        assert!(
            html.contains(&format!("\n{s} (")) || html.contains(&format!("\n{s}: ")),
            "{s} in the CDF legend"
        );
    }
    // The rates figure names its groups (as text in the SVG, not only in the table).
    for rate in ["no_path_rate", "fault_rate", "goal_reached_rate"] {
        assert!(
            html.contains(&format!("\n{rate}\n</text>")),
            "{rate} in the figure"
        );
    }
    // Deterministic.
    let out2 = dir.path().join("report2");
    run_ok(&["report"], &[&sweep, Path::new("--out"), &out2]);
    assert_eq!(read(&out2.join("report.html")), html);

    // summary.json edited: refused, naming the file.
    let path = sweep.join("summary.json");
    let text = read(&path);
    std::fs::write(&path, text.replacen("\"runs\": 30", "\"runs\": 31", 1)).expect("write");
    let o = solsim()
        .arg("report")
        .arg(&sweep)
        .arg("--out")
        .arg(dir.path().join("report3"))
        .output()
        .expect("runs");
    assert_bad_input(&o, &["summary.json", "changed file"]);
}

#[test]
fn a_shard_is_reported_as_the_shard() {
    let dir = tempfile::tempdir().expect("tempdir");
    let shard = dir.path().join("shard");
    run_ok(
        &[
            "sweep",
            "scenarios/rapid-traverse-379-409.toml",
            "--runs",
            "20",
            "--shard",
            "1/2",
            "-q",
            "--out",
        ],
        &[&shard],
    );
    let out = dir.path().join("report");
    let stdout = run_ok(&["report"], &[&shard, Path::new("--out"), &out]);
    assert!(
        stdout.contains("shard 1 of 2 (runs 10..20 of a sweep of 20)"),
        "{stdout}"
    );
    let html = read(&out.join("report.html"));
    assert!(html.contains("rates over 10 runs"), "the shard's 10 runs");
}
