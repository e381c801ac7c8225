//! Issue 10: output sets were not atomic as a set — a kill during `compare --out DIR` over an
//! earlier run's files left old and new results mixed (10 of 10 tries), and `.NAME.tmp-PID`
//! files that nothing removed. Now the set is written aside and swapped into place whole: after
//! a SIGKILL at any moment DIR holds the earlier set or the new one, complete, and the next
//! run removes what the killed one left beside it.
#![cfg(unix)]

use crate::common;

use std::path::Path;
use std::time::Instant;

use common::{scenario_copy, solsim};

/// The seeds in the provenance of every JSON file of the set, and how many files it has.
fn seeds_and_count(dir: &Path) -> (Vec<u64>, usize) {
    let mut seeds = Vec::new();
    let mut count = 0;
    for entry in std::fs::read_dir(dir).expect("list") {
        let path = entry.expect("entry").path();
        count += 1;
        if path.extension().is_some_and(|e| e == "json") {
            let doc: serde_json::Value =
                serde_json::from_slice(&std::fs::read(&path).expect("read")).expect("whole JSON");
            seeds.push(doc["provenance"]["seed"].as_u64().expect("seed"));
        }
    }
    (seeds, count)
}

#[test]
fn a_kill_at_any_moment_leaves_the_old_set_or_the_new_one() {
    let (old, _a) = scenario_copy("crater-floor-717.toml", |t| t);
    let seed_line = |t: &str| {
        t.lines()
            .find(|l| l.starts_with("seed = "))
            .expect("seed")
            .to_string()
    };
    let (new, _b) = scenario_copy("crater-floor-717.toml", |t| {
        let line = seed_line(&t);
        t.replace(&line, "seed = 987654321")
    });
    let root = tempfile::tempdir().expect("tempdir");
    let out = root.path().join("set");
    let run = |scenario: &Path| {
        solsim()
            .arg("compare")
            .arg(scenario)
            .arg("--out")
            .arg(&out)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("spawns")
    };
    let start = Instant::now();
    assert!(run(&old).wait().expect("waits").success());
    let full_run = start.elapsed();
    let (old_seeds, full_count) = seeds_and_count(&out);
    assert!(old_seeds.len() >= 4, "{old_seeds:?}");
    let old_seed = old_seeds[0];
    let mut outcomes = [0, 0];
    for i in 0..10u32 {
        let mut child = run(if i % 2 == 0 { &new } else { &old });
        // Spread the kills over the whole run, from start-up to past the final rename.
        std::thread::sleep(full_run.mul_f64(1.3 * f64::from(i) / 9.0));
        let _ = child.kill();
        let _ = child.wait();
        let (seeds, count) = seeds_and_count(&out);
        assert_eq!(count, full_count, "try {i}: a partial set: {count} files");
        assert!(
            seeds.iter().all(|&s| s == seeds[0]),
            "try {i}: old and new files mixed: {seeds:?}"
        );
        outcomes[usize::from(seeds[0] != old_seed)] += 1;
    }
    // A completed run removes what the killed ones left beside the set.
    assert!(run(&new).wait().expect("waits").success());
    let left: Vec<String> = std::fs::read_dir(root.path())
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left, ["set"], "stale temporaries left: {left:?}");
    assert_eq!(seeds_and_count(&out).0[0], 987_654_321);
    eprintln!("kills leaving the old set / the new set: {outcomes:?} of 10");
}

#[test]
fn a_directory_with_other_files_is_not_replaced() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("notes.txt"), b"mine").expect("write");
    let o = solsim()
        .arg("run")
        .arg(common::root().join("scenarios/crater-floor-717.toml"))
        .arg("--out")
        .arg(dir.path())
        .output()
        .expect("runs");
    common::assert_bad_input(
        &o,
        &["expected a new or empty directory", "choose another --out"],
    );
    assert_eq!(
        std::fs::read(dir.path().join("notes.txt")).expect("kept"),
        b"mine"
    );
}
