//! `solsim compare SCENARIO --runs N` (issue 12, item 6): the one-run table unchanged, then each
//! strategy against ground over N seeded runs with intervals — the numbers `solsim sweep` gives
//! for the same scenario, seed and runs, whatever the thread count; bad `--runs` refused as
//! `sweep` refuses it.
//!
//! The rapid traverse: 8 runs of its five strategies take about 1 s (release, 2 cores), where
//! sols 383-386 take about 11 s.

use crate::common;

use std::path::Path;
use std::process::Output;

use common::{assert_bad_input, root, solsim, stderr};
use serde_json::Value;

const SCENARIO: &str = "scenarios/rapid-traverse-379-409.toml";
const NAME: &str = "rapid-traverse-379-409";

fn run(args: &[&str]) -> Output {
    solsim()
        .current_dir(root())
        .args(args)
        .output()
        .expect("runs solsim")
}

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "solsim failed: {}", stderr(o));
    String::from_utf8(o.stdout.clone()).expect("utf-8")
}

fn compare(extra: &[&str]) -> String {
    let mut args = vec!["compare", SCENARIO, "--no-files"];
    args.extend_from_slice(extra);
    ok(&run(&args))
}

fn json(text: &str) -> Value {
    serde_json::from_str(text).expect("JSON")
}

/// `+1.23` / `−0.40`, as the report prints a signed number.
fn signed(x: f64, decimals: usize) -> String {
    format!("{x:+.decimals$}").replace('-', "−")
}

#[test]
fn the_one_run_table_comes_first_then_the_section_with_intervals() {
    let plain = compare(&[]);
    let runs = compare(&["--runs", "8"]);
    // The verdict (the third line) adds the differences over the runs to each strategy's
    // one-run clause (issue 28); the rest of the one-run output is unchanged.
    let verdict = |text: &str| text.lines().nth(2).expect("a verdict line").to_string();
    let (one, over) = (verdict(&plain), verdict(&runs));
    let clauses: Vec<&str> = one.trim_end_matches('.').split("; ").collect();
    let mut rest = over.as_str();
    for clause in &clauses {
        let at = rest
            .find(clause)
            .unwrap_or_else(|| panic!("{clause:?} not in the --runs verdict:\n{over}"));
        rest = &rest[at + clause.len()..];
    }
    assert_eq!(
        over.matches(" — over 8 runs: ").count(),
        3,
        "onboard, extension and extension+onboard: {over}"
    );
    let without_verdict = |text: &str| text.replacen(&verdict(text), "", 1);
    let (plain, runs) = (without_verdict(&plain), without_verdict(&runs));
    assert!(
        runs.starts_with(&plain),
        "compare --runs must print the one-run output unchanged first:\n{runs}"
    );
    let section = &runs[plain.len()..];
    for s in [
        "Against ground over 8 runs (run indices 0..8 from seed",
        "[95 % bootstrap interval, 10000 resamples]",
        "[95 % Wilson interval]",
        "study segment (1402 m from sol 402): ground: covered in ",
        "  onboard:\n",
        "  extension+onboard:\n",
        "  replay:\n",
        "  extension:\n",
        "    study segment: ",
        "    drive sols: ",
        "    distance: ",
        "    drive time: ",
        "    peak r: ",
        "    distance from sol 402: ",
        "    NO_PATH: in ",
        "    any fault: in ",
        "    uplinks that needed a drive plan: ",
    ] {
        assert!(section.contains(s), "the section lacks {s:?}:\n{section}");
    }
    assert!(!section.contains("  ground:\n"), "{section}");
    // Units in the labels, no Rust debug formatting.
    for line in section.lines().filter(|l| l.contains("difference ")) {
        let unit = [" sols", " m ", " h ", "uplinks"]
            .iter()
            .any(|u| line.contains(u));
        assert!(unit, "no unit: {line}");
    }
    for debug in ["Some(", "None", "{ ", "PairedDifference", "Interval"] {
        assert!(!section.contains(debug), "{debug:?} in:\n{section}");
    }
}

/// The printed numbers and the JSON are the sweep's: `compare --runs 8 --json` carries
/// `solsim sweep --runs 8`'s `summary.json` as `over_runs`, and `--out` gets it byte for byte.
#[test]
fn the_numbers_are_those_of_solsim_sweep() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let swept = tmp.path().join("sweep");
    ok(&run(&[
        "sweep",
        SCENARIO,
        "--runs",
        "8",
        "--quiet",
        "--out",
        swept.to_str().expect("utf-8"),
    ]));
    let summary_bytes = std::fs::read(swept.join("summary.json")).expect("summary.json");
    let summary = json(std::str::from_utf8(&summary_bytes).expect("utf-8"));

    let doc = json(&compare(&["--runs", "8", "--json"]));
    assert_eq!(
        doc["over_runs"], summary,
        "compare --json against summary.json"
    );
    let one_run = json(&compare(&["--json"]));
    assert_eq!(
        doc["one_run"], one_run,
        "the one-run documents are unchanged"
    );

    // The text prints those numbers: onboard against ground, paired differences and rates.
    let text = compare(&["--runs", "8"]);
    let st = &summary["statistics"];
    let paired = |figure: &str| {
        st["paired"]
            .as_array()
            .expect("paired")
            .iter()
            .find(|p| p["strategy"] == "onboard" && p["figure"] == figure)
            .map(|p| p["difference"].clone())
            .expect("onboard has the figure")
    };
    let section = &text[text
        .find("Against ground over 8 runs")
        .expect("the section")..];
    let onboard = &section[section.find("  onboard:\n").expect("onboard lines")..];
    let onboard = &onboard[..=onboard.find("\n  extension:").expect("next strategy")];
    for (figure, scale, decimals, unit) in [
        ("distance_m", 1.0, 1, " m"),
        ("segment_distance_m", 1.0, 1, " m"),
        ("drive_sols", 1.0, 2, " sols"),
        ("drive_time_s", 1.0 / 3600.0, 2, " h"),
        ("max_uncertainty_m", 1.0, 2, " m"),
        ("drive_plan_uplinks", 1.0, 2, ""),
    ] {
        let d = paired(figure);
        let f = |k: &str| d[k].as_f64().expect("number") * scale;
        let want = format!(
            "difference {}{unit} [{}, {}]",
            signed(f("mean"), decimals),
            signed(d["interval"]["lo"].as_f64().expect("lo") * scale, decimals),
            signed(d["interval"]["hi"].as_f64().expect("hi") * scale, decimals)
        );
        assert!(
            onboard.contains(&want),
            "{figure}: {want:?} not in\n{onboard}"
        );
    }
    let rate = |strategy: &str, name: &str| {
        let r = st["strategies"]
            .as_array()
            .expect("strategies")
            .iter()
            .find(|s| s["strategy"] == strategy)
            .and_then(|s| s["rates"].as_array())
            .and_then(|rs| rs.iter().find(|r| r["name"] == name))
            .expect("rate")
            .clone();
        let p = |v: &Value| format!("{:.1}", 100.0 * v.as_f64().expect("number"));
        format!(
            "{} % [{}, {}]",
            p(&r["rate"]),
            p(&r["interval"]["lo"]),
            p(&r["interval"]["hi"])
        )
    };
    for want in [
        format!(
            "NO_PATH: in {} of runs against {}",
            rate("onboard", "no_path_rate"),
            rate("ground", "no_path_rate")
        ),
        format!(
            "any fault: in {} of runs against {}",
            rate("onboard", "fault_rate"),
            rate("ground", "fault_rate")
        ),
    ] {
        assert!(onboard.contains(&want), "{want:?} not in\n{onboard}");
    }

    // With files: the summary lands beside the per-strategy files, as sweep writes it.
    let out = tmp.path().join("compare");
    let printed = ok(&run(&[
        "compare",
        SCENARIO,
        "--runs",
        "8",
        "--out",
        out.to_str().expect("utf-8"),
    ]));
    assert!(
        printed.contains(&format!("{NAME}.over-runs.json")),
        "{printed}"
    );
    assert_eq!(
        std::fs::read(out.join(format!("{NAME}.over-runs.json"))).expect("written"),
        summary_bytes
    );
}

/// Determinism: one thread (by `--threads` or by `RAYON_NUM_THREADS`) and two print the same
/// bytes, text and JSON. A difference means some sum or the row order depends on how rayon split
/// the work.
#[test]
fn one_and_two_threads_print_the_same_bytes() {
    for extra in [&[][..], &["--json"][..]] {
        let mut args = vec!["--runs", "8"];
        args.extend_from_slice(extra);
        let two = compare(&[&args[..], &["--threads", "2"]].concat());
        let one = compare(&[&args[..], &["--threads", "1"]].concat());
        assert_eq!(one, two, "--threads 1 against 2 ({extra:?})");
        let mut cmd = solsim();
        cmd.current_dir(root())
            .env("RAYON_NUM_THREADS", "1")
            .args(["compare", SCENARIO, "--no-files"])
            .args(&args);
        let env_one = ok(&cmd.output().expect("runs"));
        assert_eq!(env_one, two, "RAYON_NUM_THREADS=1 against --threads 2");
    }
}

/// Run 0 of the sweep is the run of the table: its figures, the drive time and the uplinks that
/// needed a drive plan agree with what the one-run section prints (`sweep::rows` and
/// `report::against_ground` count them the same way).
#[test]
fn run_zero_is_the_one_run_table() {
    let scenario = study::Scenario::load_within(
        &root().join(SCENARIO),
        maps::MemoryBudget::new(maps::MemoryBudget::DEFAULT_BYTES),
    )
    .expect("loads");
    let outcomes = scenario.compare(&scenario.strategies(), scenario.seeds());
    let spec = sweep::SweepSpec::new(&scenario, 1);
    let rows = sweep::engine::run_in_memory(&scenario, &spec, 0..1);
    assert_eq!(rows.len(), outcomes.len());
    let section = outputs::against_ground::against_ground(&scenario, &outcomes);
    let ground = rows
        .iter()
        .find(|r| r.strategy == sim::Strategy::Ground)
        .expect("ground");
    for (row, o) in rows.iter().zip(&outcomes) {
        assert_eq!(row.strategy, o.strategy);
        assert_eq!(row.drive_sols, o.totals.drive_sols);
        assert_eq!(row.distance_m.to_bits(), o.totals.distance_m.to_bits());
        assert_eq!(row.max_uncertainty_m, o.totals.max_uncertainty_m);
        assert_eq!(row.no_path_faults, o.totals.no_path_faults);
        if row.strategy == sim::Strategy::Ground {
            continue;
        }
        let at = section
            .find(&format!("  {}:\n", row.strategy.name()))
            .expect("the strategy's lines");
        let lines = &section[at..];
        for want in [
            format!(
                "uplinks that needed a drive plan: {} against {}",
                row.drive_plan_uplinks, ground.drive_plan_uplinks
            ),
            format!(
                "drive time {:.1} h against {:.1} h",
                row.drive_time_s / 3600.0,
                ground.drive_time_s / 3600.0
            ),
        ] {
            assert!(lines.contains(&want), "{want:?} not in\n{lines}");
        }
    }
}

fn assert_refused(args: &[&str], must_contain: &[&str], out: &Path) {
    let mut all = vec!["compare", SCENARIO, "--out", out.to_str().expect("utf-8")];
    all.extend_from_slice(args);
    let o = run(&all);
    assert_bad_input(&o, must_contain);
    assert!(
        o.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert!(!out.exists(), "{} was created", out.display());
}

#[test]
fn bad_runs_are_refused_before_anything_runs() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    let range = format!(
        "--runs: expected a number of runs from 2 to {}",
        sweep::engine::MAX_RUNS
    );
    for runs in ["0", "1", "10000001", "99999999999"] {
        assert_refused(&["--runs", runs], &[&range, &format!("got {runs}")], &out);
    }
    // Within the run limit but not within the memory budget: 5 strategies × 5·10⁶ runs of rows.
    assert_refused(
        &["--runs", "5000000"],
        &[
            "--runs",
            "memory budget",
            "5000000 runs × 5 strategies need",
        ],
        &out,
    );
    // Not a number: clap's one line.
    for runs in ["two", "-3", "1e3", "99999999999999999999999"] {
        assert_refused(&[&format!("--runs={runs}")], &["--runs"], &out);
    }
    assert_refused(&["--runs", "8", "--threads", "0"], &["--threads"], &out);
    // An --out that holds other files: refused before the runs, and left alone.
    let busy = tmp.path().join("busy");
    std::fs::create_dir(&busy).expect("mkdir");
    std::fs::write(busy.join("notes.txt"), "mine").expect("write");
    let started = std::time::Instant::now();
    let o = run(&[
        "compare",
        SCENARIO,
        "--runs",
        "1000000",
        "--out",
        busy.to_str().expect("utf-8"),
    ]);
    assert_bad_input(&o, &["busy", "choose another --out"]);
    assert!(started.elapsed().as_secs() < 30, "the runs ran first");
    let left: Vec<_> = std::fs::read_dir(tmp.path())
        .expect("list")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(left, ["busy"], "nothing beside it");
    assert_eq!(
        std::fs::read_dir(&busy).expect("list").count(),
        1,
        "busy is left alone"
    );
}

#[test]
fn help_teaches_the_intervals() {
    let help = ok(&run(&["compare", "--help"]));
    for s in [
        "--runs <N>",
        "bootstrap interval",
        "middle 95 %",
        "Wilson",
        "excludes 0",
        "--threads",
    ] {
        assert!(help.contains(s), "compare --help lacks {s:?}:\n{help}");
    }
}
