//! Issue 28: a drive the planners shortened before a passage showed a blank note in the `run`
//! table — only the JSON said `shortened_for_passage` — and no drive said why it ended. Each
//! drive sol now says it in the note column (reached goal, fault, shortened for passage, time
//! limit, the record's distance, the sol plan), from the sol record's `drive_end`, which the
//! JSON carries in the same words.

use crate::common;

use common::run_ok;

/// The rows of `solsim run SCENARIO --strategy S`: (sol, note), and the JSON's sols.
fn table_and_json(scenario: &str, strategy: &str) -> (Vec<(u32, String)>, serde_json::Value) {
    let text = run_ok(
        &["run", scenario, "--strategy", strategy, "--no-files"],
        &[],
    );
    let header = text.lines().nth(1).expect("header");
    let note_at = header.find("note").expect("note column");
    let rows = text
        .lines()
        .skip(2)
        .take_while(|l| !l.starts_with("totals:"))
        .map(|l| {
            let sol = l[..5].trim().parse().expect("sol");
            // The fault cell may run past its column: the note follows two spaces after it.
            let note = l.get(note_at..).unwrap_or("").trim().to_string();
            (sol, note)
        })
        .collect();
    let json = run_ok(
        &[
            "run",
            scenario,
            "--strategy",
            strategy,
            "--no-files",
            "--json",
        ],
        &[],
    );
    (rows, serde_json::from_str(&json).expect("JSON"))
}

fn sol(json: &serde_json::Value, n: u32) -> &serde_json::Value {
    json["sols"]
        .as_array()
        .and_then(|s| s.iter().find(|r| r["sol"] == n))
        .unwrap_or_else(|| panic!("sol {n}"))
}

/// Every drive sol's note holds its `drive_end`; every sol without a drive has none.
fn notes_match_json(rows: &[(u32, String)], json: &serde_json::Value) {
    for (n, note) in rows {
        let r = sol(json, *n);
        match r["drive_end"].as_str() {
            Some(end) => {
                assert_eq!(r["drove"], true, "sol {n}");
                assert!(
                    note.contains(end),
                    "sol {n}: {end:?} not in the note {note:?}"
                );
            }
            None => {
                assert_eq!(r["drove"], false, "sol {n} drove without a drive_end");
                assert!(note.contains("skipped: "), "sol {n}: {note:?}");
            }
        }
    }
}

#[test]
fn a_drive_shortened_for_a_passage_says_so_in_the_table() {
    let (rows, json) = table_and_json("scenarios/rapid-traverse-379-409.toml", "extension");
    notes_match_json(&rows, &json);
    let note = |n: u32| &rows.iter().find(|(s, _)| *s == n).expect("sol").1;
    assert_eq!(
        note(405),
        "shortened for passage: predicted r 42.9 m would close the passage to waypoint 44 \
         (clearance 17.6 m)"
    );
    assert!(sol(&json, 405)["shortened_for_passage"].is_object());
    assert_eq!(
        note(404),
        "time limit: drive window ends at 14:40 LMST",
        "a full drive names its window"
    );
    assert!(
        note(402).starts_with("ground-localized; time limit"),
        "{}",
        note(402)
    );
}

#[test]
fn faults_the_record_and_the_goal_end_drives_too() {
    let (rows, json) = table_and_json("scenarios/sol383-386.toml", "replay");
    notes_match_json(&rows, &json);
    assert_eq!(rows[0], (383, "drove the record's distance".to_string()));
    assert_eq!(rows[2], (385, "fault: NO_PATH".to_string()));
    let (rows, json) = table_and_json("scenarios/crater-floor-717.toml", "ground");
    notes_match_json(&rows, &json);
    assert_eq!(rows[2], (719, "reached goal".to_string()));
    // Science stretches the sol plan of 384 until its last drive segment no longer fits.
    let (rows, json) = table_and_json("scenarios/self-reliant-campaign.toml", "extension");
    notes_match_json(&rows, &json);
    assert!(
        rows.iter().any(|(n, note)| *n == 384
            && note == "sol plan cut the drive: segments after 4 of 5 no longer fit"),
        "{rows:?}"
    );
    // No drive of the bundled runs falls through to the step cap.
    for (scenario, strategy) in [
        ("scenarios/self-reliant-campaign.toml", "ground"),
        ("scenarios/conjunction.toml", "extension+onboard"),
    ] {
        let (rows, json) = table_and_json(scenario, strategy);
        notes_match_json(&rows, &json);
        assert!(
            !rows.iter().any(|(_, note)| note.contains("step limit")),
            "{scenario} {strategy}: {rows:?}"
        );
    }
}
