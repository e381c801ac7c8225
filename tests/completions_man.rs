//! Shell integration (issue 13, item 6): `solsim completions SHELL` prints a completion script
//! the shell accepts, naming every command; `solsim man` prints the manual page and `--out`
//! writes one page per command, each of which groff formats without a warning.

use crate::common;

use common::{solsim, stderr};

const COMMANDS: [&str; 10] = [
    "compare",
    "init",
    "route",
    "run",
    "sweep",
    "validate",
    "regress",
    "plan",
    "completions",
    "man",
];

fn stdout_of(args: &[&str]) -> String {
    let o = solsim().args(args).output().expect("runs");
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    String::from_utf8(o.stdout).expect("UTF-8")
}

#[test]
fn bash_completion_is_valid_bash_and_names_every_command() {
    let script = stdout_of(&["completions", "bash"]);
    for c in COMMANDS {
        assert!(script.contains(c), "{c} missing from the bash completion");
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("solsim.bash");
    std::fs::write(&path, &script).expect("write");
    let o = std::process::Command::new("bash")
        .arg("-n")
        .arg(&path)
        .output()
        .expect("bash runs");
    assert!(o.status.success(), "bash -n: {}", stderr(&o));
}

#[test]
fn every_shell_gets_a_script_and_an_unknown_one_is_refused() {
    for shell in ["zsh", "fish", "elvish", "powershell"] {
        assert!(
            stdout_of(&["completions", shell]).contains("solsim"),
            "{shell}"
        );
    }
    let o = solsim()
        .args(["completions", "tcsh"])
        .output()
        .expect("runs");
    common::assert_bad_input(&o, &["tcsh"]);
}

/// Whether groff runs; without it the test fails naming `apt-get install groff-base`, unless the
/// run opted out of the external checks (then `false`, counted once).
fn groff_here() -> bool {
    match std::process::Command::new("groff")
        .arg("--version")
        .output()
    {
        Ok(o) if o.status.success() => true,
        outcome => {
            let why = match outcome {
                Ok(o) => format!("`groff --version` exits with {}", o.status),
                Err(e) => e.to_string(),
            };
            common::external::unavailable(
                "formatting the manual pages with groff",
                &format!("groff does not run ({why})"),
                "apt-get install groff-base",
            );
            false
        }
    }
}

/// groff's warnings for a page (UTF-8 through preconv, as `man` reads it).
fn groff_warnings(page: &std::path::Path) -> String {
    let o = std::process::Command::new("groff")
        .args(["-k", "-man", "-Tutf8", "-ww", "-z"])
        .arg(page)
        .output()
        .unwrap_or_else(|e| panic!("groff on {}: {e}", page.display()));
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn man_pages_cover_every_command_and_format_cleanly() {
    let top = stdout_of(&["man"]);
    assert!(
        top.starts_with(".ie") || top.contains(".TH solsim 1"),
        "{top}"
    );
    for c in COMMANDS {
        assert!(top.contains(c), "{c} missing from solsim(1)");
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let out = stdout_of(&["man", "--out", dir.path().to_str().expect("path")]);
    assert!(out.starts_with("wrote "), "{out}");
    let mut pages: Vec<String> = std::fs::read_dir(dir.path())
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    pages.sort();
    for c in COMMANDS {
        assert!(pages.contains(&format!("solsim-{c}.1")), "{c}: {pages:?}");
    }
    assert!(
        pages.contains(&"solsim-sweep-merge.1".to_string()),
        "{pages:?}"
    );
    assert!(
        pages.iter().all(|p| p.ends_with(".1")),
        "no temporary left: {pages:?}"
    );
    let groff = groff_here();
    for p in &pages {
        let text = std::fs::read_to_string(dir.path().join(p)).expect("page");
        assert!(
            text.contains(&format!(".TH {} 1", p.trim_end_matches(".1"))),
            "{p}"
        );
        if groff {
            let w = groff_warnings(&dir.path().join(p));
            assert!(w.is_empty(), "{p}: {w}");
        }
    }
}
