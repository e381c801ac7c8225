//! `solsim plan` end to end on the bundled paper 003 scenario
//! (`scenarios/plans/self-reliant-campaign.toml`): the plan is proven optimal or reports an honest
//! gap, holds both relay passes at their fixed times, puts every tau instance within ±20 min
//! of its due time and every survey at its driven distance (75 m ± 10 m cadence), and the
//! independent validator finds nothing; the table and the JSON say the same; two runs are
//! byte-identical. Bad campaign files get exit 2 and exactly one `error:` line naming the file
//! and the field. No timing assertions.

use crate::common;

use common::solsim;
use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;
use sim::time::SolSeconds;

const SCENARIO: &str = "self-reliant-campaign.toml";

fn scenario() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join("plans")
        .join(SCENARIO)
}

fn plan(path: &Path, extra: &[&str]) -> Output {
    solsim()
        .arg("plan")
        .arg(path)
        .args(extra)
        .output()
        .expect("runs")
}

fn stdout(o: &Output) -> String {
    assert!(
        o.status.success(),
        "exit {:?}: {}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout.clone()).expect("utf8")
}

fn plan_json() -> Value {
    serde_json::from_str(&stdout(&plan(&scenario(), &["--json"]))).expect("JSON")
}

fn lmst_s(text: &str) -> i64 {
    SolSeconds::parse_lmst(text).expect("LMST").planner_s()
}

fn steps(doc: &Value) -> &Vec<Value> {
    doc["steps"].as_array().expect("steps")
}

fn str_of<'a>(v: &'a Value, key: &str) -> &'a str {
    v[key].as_str().unwrap_or_default()
}

#[test]
fn bundled_campaign_is_planned_with_an_honest_status_and_no_violations() {
    let doc = plan_json();
    let tiers = doc["tiers"].as_array().expect("tiers");
    assert!(!tiers.is_empty());
    let status = str_of(&doc, "status");
    match status {
        "optimal" => {
            assert_eq!(doc["proven_optimal"], true);
            for t in tiers {
                assert_eq!(t["utility"], t["best_bound"], "{t}");
                assert_eq!(t["gap"].as_f64(), Some(0.0), "{t}");
            }
        }
        "feasible" => {
            assert_eq!(doc["proven_optimal"], false);
            assert!(str_of(&doc, "status_text").starts_with("FEASIBLE gap"));
            for t in tiers {
                assert!(t["gap"].as_f64().expect("gap") >= 0.0, "{t}");
            }
        }
        other => panic!("the bundled campaign must be planned, got {other}"),
    }
    assert_eq!(
        doc["validator"]["violations"].as_array().map(Vec::len),
        Some(0),
        "{}",
        doc["validator"]
    );
    // Both relay passes, mandatory, at their fixed starts.
    for (id, at) in [("relay-mro-am", "11:50"), ("relay-odyssey-pm", "16:20")] {
        let s = steps(&doc)
            .iter()
            .find(|s| str_of(s, "activity") == id)
            .unwrap_or_else(|| panic!("{id} missing"));
        assert_eq!(s["start_s"].as_i64(), Some(lmst_s(at)), "{s}");
        assert_eq!(s["mandatory"], true);
    }
    // Each relay pass frees data: stored data drops across it.
    let mut prev_data = doc["sol"]["initial_data_mb"].as_f64().expect("data");
    for s in steps(&doc) {
        let data = s["data_mb"].as_f64().expect("data");
        if str_of(s, "activity").starts_with("relay-") {
            assert!(data < prev_data, "{s}");
        }
        assert!(data <= doc["sol"]["data_capacity_mb"].as_f64().expect("cap"));
        assert!(s["energy_wh"].as_f64().expect("energy") >= 0.0);
        prev_data = data;
    }
    // The heating precedes the first drive segment and the distant target follows the drive.
    let pos = |id: &str| {
        steps(&doc)
            .iter()
            .position(|s| str_of(s, "activity") == id)
            .unwrap_or_else(|| panic!("{id} missing"))
    };
    assert!(pos("heat-mobility") < pos("drive-to-b"));
    let last_drive = steps(&doc)
        .iter()
        .rposition(|s| str_of(s, "activity") == "drive-to-b")
        .expect("drive");
    assert!(last_drive < pos("mastcam-distant"));
}

#[test]
fn tau_instances_land_within_twenty_minutes_of_their_due_times() {
    let doc = plan_json();
    let first_due = lmst_s("09:30");
    let mut n = 0;
    for s in steps(&doc)
        .iter()
        .filter(|s| str_of(s, "campaign") == "tau")
    {
        let k: i64 = str_of(s, "activity")
            .strip_prefix("tau-")
            .and_then(|k| k.parse().ok())
            .expect("tau-k");
        let due = first_due + k * 180 * 60;
        let start = s["start_s"].as_i64().expect("start");
        assert!((start - due).abs() <= 20 * 60, "{s} due at {due} s");
        n += 1;
    }
    assert!(n >= 2, "expected tau instances in the plan");
}

#[test]
fn surveys_run_at_their_driven_distances_between_drive_segments() {
    let doc = plan_json();
    let mut n = 0;
    for s in steps(&doc)
        .iter()
        .filter(|s| str_of(s, "campaign") == "survey")
    {
        let k: f64 = str_of(s, "activity")
            .strip_prefix("survey-")
            .and_then(|k| k.parse().ok())
            .expect("survey-k");
        let driven = s["driven_at_start_m"].as_f64().expect("driven");
        assert!((driven - 75.0 * k).abs() <= 10.0 + 1e-6, "{s}");
        n += 1;
    }
    assert!(n >= 2, "expected surveys in the plan");
    // The drive is split at 75 m and 150 m so surveys 1 and 2 interleave with it.
    let segs: Vec<(u64, u64)> = steps(&doc)
        .iter()
        .filter_map(|s| {
            let g = &s["segment"];
            Some((g["k"].as_u64()?, g["n"].as_u64()?))
        })
        .collect();
    assert_eq!(segs, [(1, 3), (2, 3), (3, 3)]);
}

#[test]
fn table_and_json_agree() {
    let doc = plan_json();
    let table = stdout(&plan(&scenario(), &[]));
    let rows: Vec<Vec<&str>> = table
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|w| {
            w.len() > 3 && w[0].len() == 5 && w[0].as_bytes()[2] == b':' && w[1].contains(':')
        })
        .collect();
    assert_eq!(rows.len(), steps(&doc).len(), "{table}");
    for (row, s) in rows.iter().zip(steps(&doc)) {
        assert_eq!(row[0], str_of(s, "start_lmst"));
        assert_eq!(row[1], str_of(s, "end_lmst"));
        assert_eq!(row[2], str_of(s, "activity"));
        let campaign = s["campaign"].as_str().unwrap_or("-");
        assert!(row.contains(&campaign), "{row:?} vs {s}");
        let energy = format!("{:.1}", s["energy_wh"].as_f64().expect("energy"));
        let data = format!("{:.1}", s["data_mb"].as_f64().expect("data"));
        assert_eq!(row[row.len() - 2], energy, "{row:?}");
        assert_eq!(row[row.len() - 1], data, "{row:?}");
    }
    assert!(table.contains(&format!("status: {}", str_of(&doc, "status_text"))));
    assert!(table.contains("validator: 0 violations"));
    for c in doc["campaigns"].as_array().expect("campaigns") {
        let line = table
            .lines()
            .find(|l| l.starts_with(&format!("{} ", str_of(c, "id"))))
            .unwrap_or_else(|| panic!("campaign {c} not in the table"));
        let want = format!(
            "{:.2}/{:.2}",
            c["utility"].as_f64().expect("u"),
            c["max_utility"].as_f64().expect("m")
        );
        assert!(line.contains(&want), "{line} vs {want}");
    }
}

#[test]
fn two_runs_are_byte_identical() {
    for extra in [&[][..], &["--json"][..]] {
        let a = plan(&scenario(), extra);
        let b = plan(&scenario(), extra);
        assert_eq!(stdout(&a), stdout(&b), "{extra:?}");
    }
}

#[test]
fn a_tiny_node_budget_reports_an_honest_status() {
    let doc: Value = serde_json::from_str(&stdout(&plan(&scenario(), &["--json", "--nodes", "3"])))
        .expect("JSON");
    let status = str_of(&doc, "status");
    assert!(
        ["optimal", "feasible", "no_plan_found"].contains(&status),
        "{status}"
    );
    assert!(doc["search"]["nodes_expanded"].as_u64().expect("nodes") <= 3);
    if status == "feasible" {
        assert!(str_of(&doc, "status_text").starts_with("FEASIBLE gap"));
        assert!(
            doc["tiers"]
                .as_array()
                .expect("tiers")
                .iter()
                .any(|t| t["gap"].as_f64().expect("gap") > 0.0)
        );
        assert_eq!(
            doc["validator"]["violations"].as_array().map(Vec::len),
            Some(0)
        );
    }
}

// --- Bad input: exit 2, one `error:` line naming the file and the field.

fn plan_modified(edit: impl Fn(String) -> String) -> (Output, PathBuf, tempfile::TempDir) {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = std::fs::read_to_string(scenario()).expect("read");
    let edited = edit(text.clone());
    assert_ne!(edited, text, "the edit must change the file");
    let path = dir.path().join("case.toml");
    std::fs::write(&path, edited).expect("write");
    let o = plan(&path, &[]);
    (o, path, dir)
}

fn assert_bad_input(o: &Output, path: &Path, must_contain: &[&str]) {
    let mut all = vec![path.to_str().expect("utf8")];
    all.extend_from_slice(must_contain);
    common::assert_bad_input(o, &all);
}

#[test]
fn unknown_activity_in_preconditions() {
    let (o, path, _d) = plan_modified(|t| {
        t.replace(
            "preconditions = [\"heat-mobility\"]",
            "preconditions = [\"heat-mobilty\"]",
        )
    });
    assert_bad_input(
        &o,
        &path,
        &["activities[3].preconditions[0]", "heat-mobilty"],
    );
}

#[test]
fn negative_duration() {
    let (o, path, _d) = plan_modified(|t| t.replace("duration_min = 30", "duration_min = -30"));
    assert_bad_input(
        &o,
        &path,
        &["activities[2].duration_min", "positive", "-30"],
    );
}

#[test]
fn latest_start_before_earliest_start() {
    let (o, path, _d) = plan_modified(|t| {
        t.replace(
            "latest_start_lmst = \"12:00\"\n# Wheel",
            "latest_start_lmst = \"09:00\"\n# Wheel",
        )
        .replace(
            "earliest_start_lmst = \"09:00\"\nlatest_start_lmst = \"09:00\"\n# Wheel",
            "earliest_start_lmst = \"10:00\"\nlatest_start_lmst = \"09:00\"\n# Wheel",
        )
    });
    assert_bad_input(&o, &path, &["activities[2].latest_start_lmst", "\"09:00\""]);
}

#[test]
fn window_outside_the_sol() {
    // Starts before the sol window opens.
    let (o, path, _d) = plan_modified(|t| {
        t.replace(
            "earliest_start_lmst = \"09:00\"\nlatest_start_lmst = \"12:00\"",
            "earliest_start_lmst = \"08:00\"\nlatest_start_lmst = \"12:00\"",
        )
    });
    assert_bad_input(
        &o,
        &path,
        &["activities[2].earliest_start_lmst", "sol window"],
    );
    // Cannot end before the sol window closes (20 min from 16:50 runs past 17:00).
    let (o, path, _d) = plan_modified(|t| {
        t.replace(
            "latest_start_lmst = \"16:30\"",
            "latest_start_lmst = \"16:50\"",
        )
    });
    assert_bad_input(&o, &path, &["activities[5].latest_start_lmst", "17:00"]);
}

#[test]
fn bad_lmst_string() {
    let (o, path, _d) = plan_modified(|t| {
        t.replacen(
            "earliest_start_lmst = \"11:50\"",
            "earliest_start_lmst = \"11:75\"",
            1,
        )
    });
    assert_bad_input(
        &o,
        &path,
        &["activities[0].earliest_start_lmst", "HH:MM", "11:75"],
    );
    let (o, path, _d) =
        plan_modified(|t| t.replace("start_lmst = \"09:00\"\nend", "start_lmst = \"nine\"\nend"));
    assert_bad_input(&o, &path, &["sol.start_lmst", "nine"]);
}

#[test]
fn unknown_field() {
    let (o, path, _d) = plan_modified(|t| t.replace("power_w = 80.0", "power_watts = 80.0"));
    assert_bad_input(&o, &path, &["power_watts", "unknown field"]);
}

#[test]
fn nan_is_rejected() {
    let (o, path, _d) =
        plan_modified(|t| t.replace("net_recharge_w = 40.0", "net_recharge_w = nan"));
    assert_bad_input(&o, &path, &["sol.net_recharge_w", "NaN"]);
}

#[test]
fn unknown_campaign() {
    let (o, path, _d) = plan_modified(|t| {
        t.replace("members = [\"mastcam-near\", \"mastcam-distant\"]\n", "")
            .replace(
                "id = \"mastcam-near\"\n",
                "id = \"mastcam-near\"\ncampaign = \"outcropz\"\n",
            )
    });
    assert_bad_input(&o, &path, &["activities[4].campaign", "outcropz"]);
}

#[test]
fn planner_errors_name_the_activity() {
    // A precondition cycle is found by the planner; the message still names file and field.
    let (o, path, _d) = plan_modified(|t| {
        t.replace(
            "power_w = 80.0\n",
            "power_w = 80.0\npreconditions = [\"drive-to-b\"]\n",
        )
    });
    assert_bad_input(&o, &path, &["activities[", "cycle"]);
}

#[test]
fn documented_defaults_match_the_code() {
    use solsim::cmd_plan::DEFAULT_NODE_BUDGET;
    use study::campaign_file::{DEFAULT_MAX_SEGMENTS, DEFAULT_MIN_SEGMENT_MIN};
    let readme =
        std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("README.md"))
            .expect("README");
    let section = readme
        .split("## Planning a sol (`solsim plan`)")
        .nth(1)
        .expect("README section");
    assert!(section.contains(&format!("(default: {DEFAULT_NODE_BUDGET})")));
    assert!(section.contains(&format!(
        "(default: {DEFAULT_MIN_SEGMENT_MIN}, {DEFAULT_MAX_SEGMENTS})"
    )));
    let help = solsim().args(["plan", "--help"]).output().expect("runs");
    let help = stdout(&help);
    assert!(
        help.contains(&format!("[default: {DEFAULT_NODE_BUDGET}]")),
        "{help}"
    );
    assert!(
        help.contains(&format!("(default {DEFAULT_NODE_BUDGET} nodes)")),
        "{help}"
    );
}

// --- The HBS link timeline (issue 12, item 3).

/// The bundled file with a 30 min transfer to the co-processor on the HBS link, fixed to start
/// at 16:00, and a co-processor run after it; `extra` is added to the transfer.
fn with_link_transfer(extra: &str) -> String {
    let text = std::fs::read_to_string(scenario()).expect("read");
    let at = text.find("[[campaigns]]").expect("campaigns");
    let link = [
        "[[activities]]",
        "id = \"hbs-transfer\"",
        "duration_min = 30",
        "earliest_start_lmst = \"16:00\"",
        "latest_start_lmst = \"16:00\"",
        "power_w = 15.0",
        "mandatory = true",
        "timeline = \"hbs_link\"",
        extra,
        "[[activities]]",
        "id = \"hbs-run\"",
        "duration_min = 1",
        "power_w = 15.0",
        "mandatory = true",
        "timeline = \"hbs_link\"",
        "preconditions = [\"hbs-transfer\"]",
        "",
    ]
    .join("\n");
    format!("{}{link}\n{}", &text[..at], &text[at..])
}

fn plan_text(text: &str, extra: &[&str]) -> (Output, PathBuf, tempfile::TempDir) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("case.toml");
    std::fs::write(&path, text).expect("write");
    let o = plan(&path, extra);
    (o, path, dir)
}

#[test]
fn a_transfer_on_the_hbs_link_runs_across_the_relay_pass() {
    let (o, _path, _d) = plan_text(&with_link_transfer(""), &["--json"]);
    let doc: Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    assert_eq!(
        doc["validator"]["violations"],
        serde_json::json!([]),
        "{doc}"
    );
    let step = |id: &str| {
        steps(&doc)
            .iter()
            .find(|s| str_of(s, "activity") == id)
            .unwrap_or_else(|| panic!("{id} not planned"))
            .clone()
    };
    let (transfer, run, pass) = (
        step("hbs-transfer"),
        step("hbs-run"),
        step("relay-odyssey-pm"),
    );
    assert_eq!(str_of(&transfer, "timeline"), "hbs_link");
    assert!(pass.get("timeline").is_none(), "main is left out: {pass}");
    let s = |v: &Value, k: &str| v[k].as_i64().expect("seconds");
    assert_eq!(s(&transfer, "start_s"), lmst_s("16:00"));
    assert!(
        s(&pass, "start_s") < s(&transfer, "end_s"),
        "the pass runs during the transfer"
    );
    assert_eq!(s(&run, "start_s"), s(&transfer, "end_s"));
    // The table marks the link rows.
    let (o, _path, _d) = plan_text(&with_link_transfer(""), &[]);
    let table = stdout(&o);
    assert!(table.contains("hbs-transfer [hbs_link] *"), "{table}");
    assert!(
        table.contains("[hbs_link] runs in parallel with the main timeline"),
        "{table}"
    );
    assert!(table.contains("validator: 0 violations"), "{table}");
}

#[test]
fn a_bad_timeline_is_refused_with_its_field() {
    let text = with_link_transfer("").replacen("timeline = \"hbs_link\"", "timeline = \"hbs\"", 1);
    let (o, path, _d) = plan_text(&text, &[]);
    assert_bad_input(
        &o,
        &path,
        &["activities[6].timeline", "hbs_link", "\"hbs\""],
    );
    // A link activity makes no data: the planner's error names the field.
    let (o, path, _d) = plan_text(&with_link_transfer("data_mb = 5.0"), &[]);
    assert_bad_input(&o, &path, &["activities[6].data_mb", "hbs_link"]);
}
