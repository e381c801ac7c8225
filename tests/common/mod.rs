//! Helpers shared by the CLI integration tests: run the built binary, read its output, and
//! check the bad-input contract (exit 2, exactly one `error:` line, no panic).
#![allow(dead_code)] // each test binary uses its own subset

use std::path::PathBuf;
use std::process::{Command, Output};

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
