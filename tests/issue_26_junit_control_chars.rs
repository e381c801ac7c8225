//! Issue 26, finding 9 (XML): a U+0001 in an `[[expect]] what` made the `solsim regress
//! --junit` report not well-formed XML (XML 1.0 forbids every C0 control character but tab,
//! line feed and carriage return, and U+FFFE / U+FFFF), so CI failed to read the report.
//!
//! Now the loader refuses such a `what`, and the JUnit writer never emits a character XML 1.0
//! forbids whatever its input: the report is parsed here by a real XML parser (python3's
//! xml.etree), and the names and messages it reads back are the input with every control
//! character escaped (`\u{1}`) but tab, line feed and carriage return, which survive.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{assert_bad_input, solsim, tiny};
use outputs::regress::{CaseResult, junit};
use study::expect::Mismatch;

/// Parses `file` with python3's xml.etree and returns, for each testcase, its `classname`,
/// `name`, and its failure's `message` and text (empty without a failure), as JSON.
fn parse_junit(file: &Path) -> Vec<[String; 4]> {
    let o = Command::new("python3")
        .arg("-c")
        .arg(
            "import json, sys, xml.etree.ElementTree as E\n\
             root = E.parse(sys.argv[1]).getroot()\n\
             out = []\n\
             for c in root.iter('testcase'):\n\
             \x20   f = c.find('failure')\n\
             \x20   out.append([c.get('classname'), c.get('name'),\n\
             \x20               '' if f is None else f.get('message'),\n\
             \x20               '' if f is None else (f.text or '')])\n\
             print(json.dumps(out))",
        )
        .arg(file)
        .output()
        .expect("python3 runs");
    assert!(
        o.status.success(),
        "{} is not well-formed XML: {}\n{}",
        file.display(),
        String::from_utf8_lossy(&o.stderr),
        String::from_utf8_lossy(&std::fs::read(file).unwrap_or_default())
    );
    serde_json::from_slice(&o.stdout).expect("json")
}

/// What the writer makes of `s`: every character XML 1.0 forbids, and every other control
/// character or bidi override, as its escape; tab, line feed, carriage return as they are.
fn escaped(s: &str) -> String {
    s.chars()
        .map(|c| match c {
            '\t' | '\n' | '\r' => c.to_string(),
            c if c.is_control()
                || matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}' | '\u{fffe}' | '\u{ffff}') =>
            {
                c.escape_default().to_string()
            }
            c => c.to_string(),
        })
        .collect()
}

#[test]
fn the_junit_writer_emits_only_what_xml_allows() {
    let hostile = "a\u{1}b\u{0}c\u{8}d\u{b}\u{c}e\u{1b}[2J\u{7f}\u{85}\u{fffe}\u{ffff}\u{202e}f\tg\nh\ri <&>\"' ]]> é🚀";
    let results = vec![
        CaseResult {
            scenario: PathBuf::from(format!("dir/{hostile}.toml")),
            case: "n/expect[0]".into(),
            what: hostile.to_owned(),
            mismatches: vec![Mismatch {
                check: format!("check {hostile}"),
                expected: format!("expected {hostile}"),
                got: format!("got {hostile}"),
            }],
            measured: vec![],
            seconds: 0.5,
        },
        CaseResult {
            scenario: PathBuf::from("plain.toml"),
            case: "p/expect[1]".into(),
            what: (0u32..0x20).filter_map(char::from_u32).collect(),
            mismatches: vec![],
            measured: vec![],
            seconds: 0.25,
        },
    ];
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("junit.xml");
    let xml = junit(&results);
    std::fs::write(&file, &xml).expect("write");
    let cases = parse_junit(&file);
    let body = format!("check {hostile}: expected expected {hostile}, got got {hostile}");
    assert_eq!(
        cases,
        vec![
            [
                escaped(&format!("dir/{hostile}.toml")),
                escaped(&format!("n/expect[0] {hostile}")),
                escaped(&body),
                escaped(&body),
            ],
            [
                "plain.toml".to_owned(),
                escaped(&format!("p/expect[1] {}", results[1].what)),
                String::new(),
                String::new(),
            ],
        ]
    );
    // Nothing XML 1.0 forbids, and no other control character, is in the document itself.
    let bad = xml.chars().find(|&c| {
        (c.is_control() && c != '\n') || matches!(c, '\u{fffe}' | '\u{ffff}' | '\u{202e}')
    });
    assert_eq!(bad, None, "{xml}");
}

/// The reported case end to end: a `what` holding U+0001 is refused before anything runs, and
/// no report (well-formed or not) is left behind.
#[test]
fn regress_refuses_a_what_xml_cannot_hold() {
    let dir = tempfile::tempdir().expect("tempdir");
    let map = tiny::tiny_map(dir.path());
    let zones = dir.path().join("zones.geojson");
    std::fs::write(&zones, tiny::NO_ZONES).expect("zones");
    let scenarios = dir.path().join("scenarios");
    std::fs::create_dir(&scenarios).expect("dir");
    let what = toml::Value::String("reaches the goal \u{1} soon".into());
    std::fs::write(
        scenarios.join("tiny.toml"),
        tiny::tiny_scenario(
            &map,
            &zones,
            "tiny",
            &format!("[[expect]]\nwhat = {what}\nstrategy = \"ground\"\nsols_to_goal = [0, 5]\n"),
        ),
    )
    .expect("scenario");
    let report = dir.path().join("junit.xml");
    let o = solsim()
        .arg("regress")
        .arg(&scenarios)
        .arg("--junit")
        .arg(&report)
        .output()
        .expect("runs");
    if report.exists() {
        parse_junit(&report);
    }
    assert_bad_input(
        &o,
        &[
            "expect[0].what: expected text without control characters",
            "\\u{1}",
        ],
    );
    assert!(
        !report.exists(),
        "a report was written for a refused scenario"
    );
}
