//! Issue 28: on the README's own traverse, `compare` said onboard localization "gains 2 drive
//! sols (1101, 1105) but loses 2 (1108, 1109)": the two it "lost" were sols after onboard had
//! reached the goal, two sols before ground. Not driving after the goal is not a loss: lost sols
//! are now only those before the strategy reached its goal, and the verdict says how much sooner
//! it got there.

use crate::common::{root, solsim};

const TRACK: &str = "scenarios/tracks/jezero-example.geojson";

#[test]
fn a_strategy_at_its_goal_loses_no_sol_and_the_verdict_says_it_got_there_sooner() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scenario = dir.path().join("own.toml");
    let o = solsim()
        .args(["route", "import"])
        .arg(root().join(TRACK))
        .arg("--out")
        .arg(&scenario)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    let o = solsim()
        .args(["compare", "--no-files", "--json"])
        .arg(&scenario)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let outcomes = json["outcomes"]
        .as_array()
        .or_else(|| json.as_array())
        .expect("outcomes");
    let by = |name: &str| {
        outcomes
            .iter()
            .find(|o| o["strategy"] == name)
            .unwrap_or_else(|| panic!("{name} in {json}"))
    };
    let goal = |o: &serde_json::Value| o["totals"]["sols_to_goal"].as_u64();
    let ground = by("ground");
    let first_sol = ground["sols"][0]["sol"].as_u64().expect("first sol");
    let drove = |o: &serde_json::Value| -> Vec<u64> {
        o["sols"]
            .as_array()
            .expect("sols")
            .iter()
            .filter(|s| s["drove"] == true)
            .map(|s| s["sol"].as_u64().expect("sol"))
            .collect()
    };

    let text = solsim()
        .args(["compare", "--no-files"])
        .arg(&scenario)
        .output()
        .expect("runs");
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout).into_owned();
    let mut sooner = 0;
    for name in ["onboard", "extension", "extension+onboard"] {
        let o = by(name);
        let (Some(mine), Some(theirs)) = (goal(o), goal(ground)) else {
            continue;
        };
        if mine >= theirs {
            continue;
        }
        sooner += 1;
        let goal_sol = first_sol + mine - 1;
        let after_goal: Vec<u64> = drove(ground)
            .into_iter()
            .filter(|s| *s > goal_sol && !drove(o).contains(s))
            .collect();
        assert!(
            !after_goal.is_empty(),
            "ground drives on after {name}'s goal"
        );
        // Its "drive sols" line: none of those sols is called lost.
        let block = text
            .split(&format!("\n  {name}:\n"))
            .nth(1)
            .unwrap_or_else(|| panic!("{name}'s lines in:\n{text}"));
        let line = block
            .lines()
            .find(|l| l.trim_start().starts_with("drive sols:"))
            .expect("drive sols line");
        let lost = line.split("lost ").nth(1).expect("lost part");
        for s in &after_goal {
            assert!(
                !lost.split([',', ' ']).any(|w| w == s.to_string()),
                "{name} reached the goal on sol {goal_sol}, yet sol {s} is called lost: {line}"
            );
        }
        let verdict = text
            .lines()
            .find(|l| l.starts_with("Verdict"))
            .expect("verdict");
        let n = theirs - mine;
        let said = format!(
            "reaches the goal {n} sol{} sooner (in {mine} sols against {theirs})",
            if n == 1 { "" } else { "s" }
        );
        assert!(verdict.contains(&said), "{said:?} not in {verdict}");
    }
    assert!(
        sooner > 0,
        "no strategy reached the goal before ground:\n{text}"
    );
}
