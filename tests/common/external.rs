//! External checks: the tests that compare solsim with a tool it does not build (Chromium, GDAL,
//! groff, util-linux's `script`, the Python peers in `peers/.venv`, a Slurm cluster run as root).
//!
//! A missing tool fails the test, naming what is missing and the command that installs it. The
//! one way round is the explicit opt-out of `scripts/test.sh --skip-external`, which sets
//! `SOLSIM_SKIP_EXTERNAL` to a ledger file: each check that then cannot run is written there (and
//! said on stderr), and the script's last lines count them by reason. No check passes without
//! having run unless it was opted out and counted.
//!
//! This file uses only `std`, so the member crates' tests include it with `#[path]`.

use std::io::Write;

/// The opt-out variable: the path of the ledger the skipped checks are appended to.
pub const OPT_OUT: &str = "SOLSIM_SKIP_EXTERNAL";

/// Call when `check` cannot run because `missing` is absent; `install` is the one command that
/// provides it.
///
/// Panics (the test fails) unless the run opted out with `scripts/test.sh --skip-external`; then it
/// appends `check`, `missing` and `install` to the ledger and returns, and the caller skips.
pub fn unavailable(check: &str, missing: &str, install: &str) {
    let Some(ledger) = std::env::var_os(OPT_OUT).filter(|v| !v.is_empty()) else {
        panic!(
            "{check} cannot run: {missing}. Install it with `{install}`, or run the suite with \
             `scripts/test.sh --skip-external` to opt out of the external checks (they are then \
             counted as not run)"
        );
    };
    let line = format!(
        "{}\t{}\t{}\n",
        one_line(check),
        one_line(missing),
        one_line(install)
    );
    // One short write with O_APPEND: lines from parallel tests and processes do not interleave.
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&ledger)
        .unwrap_or_else(|e| {
            panic!(
                "{OPT_OUT}={}: cannot append to the skipped-checks ledger: {e}",
                std::path::Path::new(&ledger).display()
            )
        });
    file.write_all(line.as_bytes())
        .unwrap_or_else(|e| panic!("{OPT_OUT}: writing the skipped-checks ledger: {e}"));
    eprintln!("SKIPPED (opted out) {check}: {missing} ({install})");
}

/// `peers/.venv`'s Python under `root`, or `None` after [`unavailable`] when it does not exist.
pub fn peers_python(root: &std::path::Path, check: &str) -> Option<std::path::PathBuf> {
    let python = root.join("peers/.venv/bin/python");
    if python.exists() {
        return Some(python);
    }
    unavailable(check, "peers/.venv does not exist", PEERS_INSTALL);
    None
}

/// The command that creates `peers/.venv` with every peer package (what `scripts/test.sh` runs).
pub const PEERS_INSTALL: &str = "python3 peers/setup_venv.py";

fn one_line(s: &str) -> String {
    s.replace(['\t', '\n', '\r'], " ")
}
