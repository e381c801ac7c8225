//! Helpers shared by the CLI integration tests: run the built binary, read its output, and
//! check the bad-input contract (exit 2, exactly one `error:` line, no panic).
#![allow(dead_code)] // each test binary uses its own subset

pub mod browser;
pub mod external;
pub mod killed_sweep;
pub mod tiny;

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The `solsim` binary built for these tests.
pub fn solsim() -> Command {
    Command::new(env!("CARGO_BIN_EXE_solsim"))
}

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit code 2, one line starting `error: `, no panic, and every string of `must_contain` in it.
pub fn assert_bad_input(o: &Output, must_contain: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "exit code; stderr: {err}");
    assert!(!err.contains("panicked"), "panic: {err}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one line expected:\n{err}"
    );
    assert!(err.starts_with("error: "), "{err}");
    for s in must_contain {
        assert!(err.contains(s), "stderr lacks {s:?}:\n{err}");
    }
}

/// Point the relative map and zone paths of a bundled scenario at the repository, so a copy in a
/// temporary directory still finds them.
pub fn rebase(text: &str) -> String {
    let scen = root().join("scenarios");
    text.replace("\"../maps/", &format!("\"{}/maps/", root().display()))
        .replace("zones = \"", &format!("zones = \"{}/", scen.display()))
}

/// A copy of bundled scenario `base` (a file in `scenarios/`) edited by `edit`, written as
/// `case.toml` in a new temporary directory (kept alive by the returned guard).
pub fn scenario_copy(base: &str, edit: impl Fn(String) -> String) -> (PathBuf, tempfile::TempDir) {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = rebase(&std::fs::read_to_string(root().join("scenarios").join(base)).expect("read"));
    let path = dir.path().join("case.toml");
    std::fs::write(&path, edit(text)).expect("write");
    (path, dir)
}

/// `solsim validate` on a copy of `scenarios/crater-floor-717.toml` edited by `edit`.
pub fn validate_edited_sol717(edit: impl Fn(String) -> String) -> Output {
    let (path, _d) = scenario_copy("crater-floor-717.toml", edit);
    solsim().arg("validate").arg(&path).output().expect("runs")
}

/// Runs `cmd` with no standard input and returns its output, killing it and failing the test
/// if it has not finished within `limit` (a hang is a bug, not a slow test).
pub fn output_within(cmd: &mut Command, limit: Duration) -> Output {
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    let start = Instant::now();
    loop {
        if child.try_wait().expect("waits").is_some() {
            return child.wait_with_output().expect("output");
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let o = child.wait_with_output().expect("output");
            panic!(
                "still running after {limit:?} (killed); stderr: {}",
                stderr(&o)
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// `text` with its line starting `prefix` replaced by `new` (the line must exist).
pub fn replace_line(text: &str, prefix: &str, new: &str) -> String {
    let line = text
        .lines()
        .find(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("no line starting {prefix:?}"))
        .to_string();
    text.replace(&line, new)
}

/// A scenario's `[map]` with `png` as its appearance layer, placed as the bundled crater-floor
/// map (2 m pixels from the north-west corner (0, 1200)).
pub fn with_png_appearance(text: &str, png: &std::path::Path) -> String {
    replace_line(
        text,
        "appearance = ",
        &format!(
            "appearance = \"{}\"\nresolution_m_per_px = 2.0\norigin_m = [0.0, 1200.0]",
            png.display()
        ),
    )
}

/// Runs `solsim map package SCENARIO --out OUT EXTRA…`.
pub fn package(scenario: &std::path::Path, out: &std::path::Path, extra: &[&str]) -> Output {
    solsim()
        .args(["map", "package"])
        .arg(scenario)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}

/// A map package's manifest.json.
pub fn manifest(out: &std::path::Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(out.join("manifest.json")).expect("manifest"))
        .expect("json")
}

/// `peers/.venv`'s Python, or `None` when it does not exist and the run opted out of the
/// external checks (`check` is what then does not run); otherwise its absence fails the test,
/// naming `python3 peers/setup_venv.py` ([`external::unavailable`]).
pub fn peers_python(check: &str) -> Option<PathBuf> {
    external::peers_python(&root(), check)
}

/// What `solsim ARGS`, run from the repository, writes to a pseudo-terminal (stdout and stderr
/// both), through util-linux's `script`; it must exit 0. Without `script` the test fails naming
/// `apt-get install util-linux`, unless the run opted out of the external checks: then `None`,
/// counted ([`external::unavailable`]).
pub fn on_a_terminal(args: &[&str]) -> Option<String> {
    let line = std::iter::once(env!("CARGO_BIN_EXE_solsim"))
        .chain(args.iter().copied())
        .map(|a| format!("'{a}'"))
        .collect::<Vec<_>>()
        .join(" ");
    match Command::new("script")
        .args(["-qefc", &line, "/dev/null"])
        .current_dir(root())
        .output()
    {
        Ok(o) => {
            assert!(o.status.success(), "{line}: {}", stderr(&o));
            Some(String::from_utf8_lossy(&o.stdout).into_owned())
        }
        Err(e) => {
            external::unavailable(
                "a progress bar drawn on a terminal",
                &format!("util-linux's `script` does not run ({e})"),
                "apt-get install util-linux",
            );
            None
        }
    }
}

/// Runs solsim from the repository with `args` then `paths`, asserts exit 0, returns stdout.
pub fn run_ok(args: &[&str], paths: &[&std::path::Path]) -> String {
    let o = solsim()
        .current_dir(root())
        .args(args)
        .args(paths)
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A sweep of the rapid traverse over `runs` runs into `out` (quiet).
pub fn sweep_rapid_traverse(runs: u32, out: &std::path::Path) {
    run_ok(
        &[
            "sweep",
            "scenarios/rapid-traverse-379-409.toml",
            "--runs",
            &runs.to_string(),
            "-q",
            "--out",
        ],
        &[out],
    );
}

/// `solsim report DIR --out OUT EXTRA…` from the repository root.
pub fn report(dir: &std::path::Path, out: &std::path::Path, extra: &[&str]) -> Output {
    solsim()
        .current_dir(root())
        .arg("report")
        .arg(dir)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .expect("runs")
}
