//! Issue 28, item 6: `solsim completions zsh | head` panicked (exit 101, `BrokenPipe`) and
//! `solsim man | head` exited 2. Both write through the binary's one standard output, which
//! absorbs a closed pipe since issue 26 (`issue_26_broken_pipe.rs`, which covered `completions
//! bash` and a few commands); this file holds every shell's completions, the manual page, and
//! every other command that writes to standard output and was not covered: each ends quietly,
//! exit 0, whether its reader has gone before it starts or goes after the first line
//! (`| head -1`).

use std::io::{BufRead as _, BufReader, PipeReader};
use std::path::Path;
use std::process::{Output, Stdio};

use crate::common::{root, solsim, tiny};

/// Runs `args` from the repository with standard output a pipe whose reader has gone.
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

/// Runs `args` as `solsim ARGS | head -1` does: reads the first line, closes the pipe, waits.
fn head_1(args: &[&str]) -> (String, Output) {
    let mut child = solsim()
        .current_dir(root())
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    let mut first = String::new();
    BufReader::new(child.stdout.take().expect("stdout"))
        .read_line(&mut first)
        .expect("reads");
    // The reader is dropped here: the rest of the output meets a closed pipe.
    (first, child.wait_with_output().expect("waits"))
}

fn assert_quiet_success(what: &str, o: &Output) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{what}: stderr {err}");
    assert!(err.is_empty(), "{what}: stderr {err}");
}

#[test]
fn completions_of_every_shell_and_the_manual_page_end_quietly_in_a_closed_pipe() {
    for args in [
        &["completions", "bash"][..],
        &["completions", "zsh"],
        &["completions", "fish"],
        &["completions", "elvish"],
        &["completions", "powershell"],
        &["man"],
    ] {
        assert_quiet_success(
            &format!("{args:?} into a closed pipe"),
            &with_closed_stdout(args),
        );
    }
}

#[test]
fn completions_and_man_piped_to_head_end_quietly() {
    // zsh's script (about 70 KB) is larger than a pipe's 64 KiB buffer: once `head` has gone,
    // a write fails with EPIPE whatever the timing; the others may fit in the buffer.
    for (args, first) in [
        (&["completions", "zsh"][..], "#compdef solsim"),
        (&["completions", "bash"], "_solsim() {"),
        (&["completions", "fish"], ""),
        (&["man"], ".ie"),
    ] {
        let (line, o) = head_1(args);
        assert!(line.starts_with(first), "{args:?}: first line {line:?}");
        assert_quiet_success(&format!("{args:?} | head -1"), &o);
    }
}

/// Every other command that writes to standard output, each into a closed pipe: its files are
/// still written and its exit status is its work's.
#[test]
fn the_remaining_commands_end_quietly_in_a_closed_pipe() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let map = tiny::tiny_map(d);
    std::fs::write(d.join("zones.geojson"), tiny::NO_ZONES).expect("zones");
    // In a directory of its own: `regress` reads every *.toml there.
    std::fs::create_dir(d.join("scenarios")).expect("mkdir");
    let scenario = d.join("scenarios/tiny.toml");
    std::fs::write(
        &scenario,
        tiny::tiny_scenario(&map, &d.join("zones.geojson"), "tiny", ""),
    )
    .expect("scenario");
    let p = |path: &Path| path.to_str().expect("utf8").to_owned();
    let (scen, sweep_dir, s0, s1) = (
        p(&scenario),
        p(&d.join("sweep")),
        p(&d.join("s0")),
        p(&d.join("s1")),
    );
    let cases: Vec<Vec<String>> = [
        vec!["help", "sweep"],
        vec!["schema", "campaign"],
        vec!["man", "--out", &p(&d.join("man"))],
        vec![
            "map",
            "generate",
            &p(&d.join("tiny-recipe.toml")),
            "--out",
            &p(&d.join("map2")),
        ],
        vec!["sweep", &scen, "--runs", "2", "--out", &sweep_dir],
        vec![
            "sweep", &scen, "--runs", "2", "--shard", "0/2", "--out", &s0,
        ],
        vec![
            "sweep", &scen, "--runs", "2", "--shard", "1/2", "--out", &s1,
        ],
        vec!["sweep", "merge", &s0, &s1, "--out", &p(&d.join("merged"))],
        vec![
            "sweep",
            "slurm",
            &scen,
            "--runs",
            "2",
            "--shards",
            "2",
            "--out",
            &p(&d.join("slurm")),
        ],
        vec!["report", &sweep_dir, "--out", &p(&d.join("report"))],
        vec![
            "replay",
            "scenarios/crater-floor-passage.toml",
            "--no-files",
        ],
        vec![
            "whatif",
            &scen,
            &scen,
            "--strategy",
            "ground",
            "--runs",
            "2",
        ],
        vec!["regress", &p(&d.join("scenarios"))],
    ]
    .iter()
    .map(|c| c.iter().map(|s| (*s).to_owned()).collect())
    .collect();
    for args in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_quiet_success(&format!("{args:?}"), &with_closed_stdout(&args));
    }
    for written in [
        "man/solsim.1",
        "map2/dem.tif",
        "sweep/summary.json",
        "merged/manifest.json",
        "report/report.html",
    ] {
        assert!(d.join(written).is_file(), "{written} written");
    }
}
