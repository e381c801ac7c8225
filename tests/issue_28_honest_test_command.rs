//! Issue 28: the README's test command said ok without checking. `cargo test --workspace` ended
//! "661 passed, 0 failed" on a machine without Chromium, GDAL or `peers/.venv`, while 17 external
//! checks had returned early with a SKIPPED line only `--nocapture` showed.
//!
//! Now a check whose tool is missing fails, naming the install command, unless the run opted out
//! with `scripts/test.sh --skip-external`; then it is written to a ledger and the script's last
//! lines count the checks that did not run, by what was missing.

use crate::common;

use std::os::unix::fs::symlink;
use std::path::Path;
use std::process::{Command, Output};

use common::{root, stderr};

/// A test of this binary that needs groff (and nothing else from `PATH`).
const GROFF_CHECK: &str = "completions_man::man_pages_cover_every_command_and_format_cleanly";

/// Runs [`GROFF_CHECK`] in this test binary with an empty `PATH`, opted out into `ledger` or not.
fn groff_check_without_groff(ledger: Option<&Path>) -> Output {
    let empty = tempfile::tempdir().expect("tempdir");
    let mut cmd = Command::new(std::env::current_exe().expect("this test binary"));
    cmd.args(["--exact", GROFF_CHECK, "--test-threads", "1", "--nocapture"])
        .env("PATH", empty.path())
        .env_remove(common::external::OPT_OUT);
    if let Some(ledger) = ledger {
        cmd.env(common::external::OPT_OUT, ledger);
    }
    cmd.output().expect("runs the test binary")
}

#[test]
fn a_check_without_its_tool_fails_naming_the_install_command() {
    let o = groff_check_without_groff(None);
    let out = format!("{}{}", String::from_utf8_lossy(&o.stdout), stderr(&o));
    assert!(!o.status.success(), "passed without groff:\n{out}");
    assert!(out.contains("1 failed"), "{out}");
    for needle in [
        "formatting the manual pages with groff cannot run",
        "apt-get install groff-base",
        "scripts/test.sh --skip-external",
    ] {
        assert!(out.contains(needle), "{needle:?} not in:\n{out}");
    }
}

#[test]
fn an_opted_out_check_passes_and_is_written_to_the_ledger() {
    let dir = tempfile::tempdir().expect("tempdir");
    let ledger = dir.path().join("skipped.tsv");
    let o = groff_check_without_groff(Some(&ledger));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}\n{}", stderr(&o));
    assert!(out.contains("1 passed"), "{out}");
    let lines = std::fs::read_to_string(&ledger).expect("the ledger was written");
    let fields: Vec<Vec<&str>> = lines.lines().map(|l| l.split('\t').collect()).collect();
    assert_eq!(fields.len(), 1, "one check not run: {lines:?}");
    assert_eq!(fields[0][0], "formatting the manual pages with groff");
    assert!(fields[0][1].starts_with("groff does not run"), "{lines:?}");
    assert_eq!(fields[0][2], "apt-get install groff-base");
    assert!(stderr(&o).contains("SKIPPED (opted out)"), "{}", stderr(&o));
}

/// A `PATH` holding only `programs` (symlinks to the real ones) and the executable `extra` scripts.
fn bare_path(programs: &[&str], extra: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("tempdir");
    for p in programs {
        let real = ["/usr/bin", "/bin"]
            .iter()
            .map(|d| Path::new(d).join(p))
            .find(|c| c.exists())
            .unwrap_or_else(|| panic!("{p} is not in /usr/bin or /bin"));
        symlink(real, dir.path().join(p)).expect("symlink");
    }
    for (name, body) in extra {
        use std::os::unix::fs::PermissionsExt;
        let path = dir.path().join(name);
        std::fs::write(&path, body).expect("write");
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).expect("chmod");
    }
    dir
}

/// `bash scripts/test.sh ARGS` with `PATH` = `path` only.
fn test_script(path: &Path, args: &[&str]) -> Output {
    Command::new("/bin/bash")
        .arg(root().join("scripts/test.sh"))
        .args(args)
        .env("PATH", path)
        .env_remove(common::external::OPT_OUT)
        .output()
        .expect("runs scripts/test.sh")
}

/// The coreutils and text tools the script itself uses.
const SCRIPT_TOOLS: &[&str] = &[
    "dirname", "id", "mkdir", "mktemp", "wc", "cut", "sort", "uniq", "sed", "awk", "cat",
];

#[test]
fn the_test_command_stops_before_building_naming_what_is_missing() {
    // No chromium, ogrinfo, groff, script, apt-get or python3; a cargo that must not be reached.
    let path = bare_path(
        SCRIPT_TOOLS,
        &[("cargo", "#!/bin/sh\necho cargo was run >&2\nexit 7\n")],
    );
    let o = test_script(path.path(), &[]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(!err.contains("cargo was run"), "it built anyway: {err}");
    for needle in [
        "the external checks cannot run here",
        "sudo apt-get install -y chromium gdal-bin groff-base util-linux",
        "python3 python3-venv",
        "scripts/test.sh --skip-external",
    ] {
        assert!(err.contains(needle), "{needle:?} not in:\n{err}");
    }
}

#[test]
fn with_the_opt_out_the_last_lines_count_the_checks_not_run() {
    // A stand-in cargo that "runs" three opted-out checks, as the tests would, and fails or not.
    for (exit, expected_status) in [(0, Some(0)), (101, Some(101))] {
        let cargo = format!(
            "#!/bin/bash\n\
             printf 'browser check of a.html\\tchromium is not on PATH\\tapt-get install chromium\\n' >> \"$SOLSIM_SKIP_EXTERNAL\"\n\
             printf 'browser check of b.html\\tchromium is not on PATH\\tapt-get install chromium\\n' >> \"$SOLSIM_SKIP_EXTERNAL\"\n\
             printf 'the GDAL check\\tgdal-bin is not installed\\tapt-get install gdal-bin\\n' >> \"$SOLSIM_SKIP_EXTERNAL\"\n\
             echo \"cargo $*\"\n\
             exit {exit}\n"
        );
        let path = bare_path(SCRIPT_TOOLS, &[("cargo", &cargo)]);
        let o = test_script(path.path(), &["--skip-external", "--", "--no-run"]);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(o.status.code(), expected_status, "{out}\n{}", stderr(&o));
        assert!(out.contains("cargo test --workspace --no-run"), "{out}");
        let tail: Vec<&str> = out.lines().rev().take(4).collect::<Vec<_>>();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        assert_eq!(
            tail[0], "external checks: 3 did not run (--skip-external), by what was missing:",
            "{out}"
        );
        assert_eq!(
            tail[1],
            "  2 chromium is not on PATH  (install: apt-get install chromium)"
        );
        assert_eq!(
            tail[2],
            "  1 gdal-bin is not installed  (install: apt-get install gdal-bin)"
        );
        assert!(
            tail[3].starts_with("  each check: ")
                && tail[3].contains("/target/skipped-external-checks."),
            "{out}"
        );
    }
}
