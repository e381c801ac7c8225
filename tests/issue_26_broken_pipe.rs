//! Issue 26, finding 12: a closed pipe printed `error: Broken pipe` with exit 2
//! (`solsim compare scenarios/crater-floor-passage.toml | head -1`, `solsim validate … | head -c1`), and
//! `solsim completions bash` panicked (exit 101). Rust ignores SIGPIPE, so a reader that goes
//! away is an `EPIPE` write error; the binary's standard output now absorbs it once for every
//! command: the rest of the output is discarded, the command finishes its work and exits with
//! the status that work gives, saying nothing.
//!
//! Each command runs with its standard output the write end of a pipe whose read end is closed
//! before the command starts, so its first write fails, whatever the timing.

use std::io::PipeReader;
use std::process::Output;

use crate::common::{root, solsim};

/// Runs `args` with standard output a pipe nobody reads.
fn with_closed_stdout(args: &[&str]) -> Output {
    let (reader, writer) = std::io::pipe().expect("pipe");
    drop::<PipeReader>(reader);
    solsim()
        .current_dir(root())
        .args(args)
        .stdout(writer)
        .output()
        .expect("runs")
}

fn assert_quiet_success(args: &[&str]) {
    let o = with_closed_stdout(args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{args:?}: stderr {}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        o.stderr.is_empty(),
        "{args:?}: stderr {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn a_closed_pipe_ends_each_command_quietly_with_success() {
    for args in [
        &["validate", "scenarios/crater-floor-passage.toml"][..],
        &["validate", "scenarios/crater-floor-passage.toml", "--json"],
        &[
            "run",
            "scenarios/crater-floor-passage.toml",
            "--strategy",
            "ground",
            "--no-files",
        ],
        &["schema", "scenario"],
        &["completions", "bash"],
        &["--help"],
        &["--version"],
        &[
            "zones",
            "check",
            "--zones",
            "peers/zones_fixtures/zones.geojson",
            "--points",
            "peers/zones_fixtures/points.csv",
        ],
    ] {
        assert_quiet_success(args);
    }
}

/// `compare` still writes its files when nobody reads its table.
#[test]
fn compare_into_a_closed_pipe_still_writes_its_files() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("out");
    let out_arg = out.to_str().expect("utf8");
    assert_quiet_success(&[
        "compare",
        "scenarios/crater-floor-passage.toml",
        "--out",
        out_arg,
    ]);
    assert!(
        out.join("crater-floor-passage.ground.json").is_file(),
        "files written"
    );
}

/// The status is still the work's: a scenario with an error still exits 2 (its findings go
/// to a closed pipe, and nothing else is printed).
#[test]
fn a_closed_pipe_keeps_the_exit_status_of_the_work() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = std::fs::read_to_string(root().join("scenarios/crater-floor-passage.toml"))
        .expect("read")
        .replace("drive_rate_m_per_h = 100.0", "drive_rate_m_per_h = -1.0");
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, crate::common::rebase(&text)).expect("write");
    let o = with_closed_stdout(&["validate", path.to_str().expect("utf8")]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("rover.drive_rate_m_per_h"), "{err}");
    assert!(!err.contains("Broken pipe"), "{err}");
}
