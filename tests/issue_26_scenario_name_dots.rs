//! Issue 26, finding 12: scenario names `.` and `..` were accepted, and `compare` failed only at
//! write time (the output directory `solsim-out/<name>/` is the output root itself or its
//! parent), leaving an empty directory behind. A name must be usable as a directory name: not
//! empty, not `.` or `..`, no `/` or `\`, no control characters or bidi overrides, at most 100
//! characters. Anything else is refused when the scenario loads, before anything is written.

use crate::common::{assert_bad_input, scenario_copy, solsim};

fn with_name(name: &str) -> (std::path::PathBuf, tempfile::TempDir) {
    let name = toml::Value::from(name).to_string();
    scenario_copy("crater-floor-passage.toml", move |t| {
        t.replace("name = \"crater-floor-passage\"", &format!("name = {name}"))
    })
}

#[test]
fn names_that_are_no_directory_are_refused_before_anything_is_written() {
    for name in [
        ".",
        "..",
        " .. ",
        "",
        "   ",
        "a/b",
        "../up",
        "a\\b",
        "tab\there",
        "nul\u{0}",
        "esc\u{1b}[2J",
        "bidi\u{202e}txt",
        &"x".repeat(101),
    ] {
        let (path, dir) = with_name(name);
        // The default output directory, `solsim-out/<name>/`, under the working directory.
        let out = dir.path().join("solsim-out");
        let o = solsim()
            .current_dir(dir.path())
            .arg("compare")
            .arg(&path)
            .output()
            .expect("runs");
        assert_bad_input(
            &o,
            &["case.toml: name: expected a name usable as a directory name"],
        );
        assert!(!out.exists(), "{name:?}: {} was created", out.display());
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        assert_bad_input(&o, &["name: expected", "not \".\" or \"..\""]);
    }
}

#[test]
fn ordinary_names_still_load() {
    for name in [
        "crater-floor-passage",
        "a.b",
        "...",
        ".hidden",
        "x y",
        &"x".repeat(100),
        "Jezero crater é",
    ] {
        let (path, _dir) = with_name(name);
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        assert_eq!(
            o.status.code(),
            Some(0),
            "{name:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}
