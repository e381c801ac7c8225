//! Issue 27: the `ground` baseline, "today's practice", skipped sols the team drove (399 and 401
//! of the rapid traverse, 214 m and 180 m in the public record) because the calendar was typed
//! in. On the calendar computed from Mars time it drives every sol the record drove and skips
//! only 403 and 406, for paper 000 §8's reasons.

use crate::common::{root, solsim};

#[test]
fn ground_drives_every_sol_the_team_drove() {
    let o = solsim()
        .args(["record", "baseline", "--runs", "20", "--json"])
        .arg(root().join("scenarios/rapid-traverse-379-409.toml"))
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let b: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let rows = b["rows"].as_array().expect("rows");
    let mut record_sols = 0;
    for r in rows {
        if r["record_m"].as_f64() > Some(0.0) {
            record_sols += 1;
            assert_eq!(r["ground_drove_share"].as_f64(), Some(1.0), "{r}");
        }
    }
    assert_eq!(record_sols, 24);
    let skipped: Vec<u64> = rows
        .iter()
        .filter(|r| r["record_m"].as_f64() == Some(0.0) && r["calendar_rule"].is_string())
        .filter(|r| {
            let rule = r["calendar_rule"].as_str().unwrap_or("");
            !rule.contains("no drive in the calendar")
        })
        .map(|r| r["sol"].as_u64().expect("sol"))
        .collect();
    assert_eq!(
        skipped,
        [403, 406],
        "the sols the calendar alone makes ground skip"
    );
    for sol in [399, 401] {
        let r = rows.iter().find(|r| r["sol"] == sol).expect("row");
        assert_eq!(r["agreement"], "both", "{r}");
    }
}
