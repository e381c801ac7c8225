//! Issue 28: `solsim regress scenarios/` ran 27 s without a word. On a terminal it now draws a
//! progress bar on standard error over every `[[expect]]` entry, with the scenario and the
//! stage beside it, as `sweep` and `compare --runs` do (`src/progress.rs`); piped, or with
//! `--quiet`, standard error stays empty.

use crate::common;

use common::{rebase, root, solsim, stderr};

/// A directory with one scenario of three checks of one run.
fn three_checks() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("tempdir");
    let text =
        std::fs::read_to_string(root().join("scenarios/crater-floor-717.toml")).expect("read");
    std::fs::write(dir.path().join("a.toml"), rebase(&text)).expect("write");
    dir
}

#[test]
fn regress_draws_a_bar_on_a_terminal_only() {
    let dir = three_checks();
    let path = dir.path().to_str().expect("utf-8");
    if let Some(tty) = common::on_a_terminal(&["regress", path]) {
        assert!(
            tty.contains("regress ") && tty.contains("/3 checks"),
            "{tty}"
        );
        assert!(tty.contains("3 passed, 0 failed"), "the report too: {tty}");
    }
    if let Some(tty) = common::on_a_terminal(&["regress", path, "--quiet"]) {
        assert!(!tty.contains("/3 checks"), "--quiet draws no bar: {tty}");
        assert!(tty.contains("3 passed, 0 failed"), "{tty}");
    }
    let o = solsim()
        .arg("regress")
        .arg(dir.path())
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "", "nothing on a piped stderr");
}
