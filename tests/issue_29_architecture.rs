//! Issue 29: the architecture's rules hold, and every document the code cites is in the
//! repository.
//!
//! - `scripts/architecture_check.py` (ARCHITECTURE.md, "Rules"): no import circle between the
//!   files of a crate, no source file over 600 lines (tests not counted), the binary crate under
//!   3000 lines. The script is run here, and checked to catch what it must catch.
//! - Nothing cites the notes that lived outside the repository (`DESIGN.md`, `PERFORMANCE.md`,
//!   `ECOSYSTEM.md`, `SLURM.md`, `STYLE.md`, `../shared/`), and every `docs/design.md, "…"`
//!   citation names a section that exists.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{external, root};

fn python3() -> Option<&'static str> {
    Command::new("python3")
        .arg("--version")
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|_| "python3")
}

pub(crate) fn architecture_check(dir: &Path, crates: &[&str]) -> std::process::Output {
    Command::new("python3")
        .arg(root().join("scripts/architecture_check.py"))
        .args(crates)
        .env("SOLSIM_ROOT", dir)
        .output()
        .expect("runs python3")
}

#[test]
fn the_workspace_keeps_the_architecture_rules() {
    if python3().is_none() {
        external::unavailable(
            "the architecture check",
            "python3 is not on PATH",
            "apt-get install python3",
        );
        return;
    }
    let o = architecture_check(&root(), &[]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{out}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(out.contains("0 breach(es)"), "{out}");
}

/// A copy of a crate with a circle, a long file and a fat binary: the script names each.
/// A planted workspace for the check (one crate, `a`), or `None` when python3 is missing
/// (counted by the external-check gate).
pub(crate) fn planted_tree() -> Option<tempfile::TempDir> {
    if python3().is_none() {
        external::unavailable(
            "the architecture check",
            "python3 is not on PATH",
            "apt-get install python3",
        );
        return None;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    plant(dir.path(), "Cargo.toml", "[workspace]\nmembers = [\"a\"]\n");
    Some(dir)
}

/// Writes `text` at `p` under the planted tree `d`, making its folders.
pub(crate) fn plant(d: &Path, p: &str, text: &str) {
    let path = d.join(p);
    std::fs::create_dir_all(path.parent().expect("parent")).expect("mkdir");
    std::fs::write(path, text).expect("write");
}

#[test]
fn the_check_catches_a_circle_a_long_file_and_a_fat_binary() {
    let Some(dir) = planted_tree() else { return };
    let d = dir.path();
    let write = |p: &str, text: &str| plant(d, p, text);
    write("a/src/lib.rs", "mod x;\nmod y;\nmod long;\n");
    write("a/src/x.rs", "use crate::y::Y;\npub struct X;\n");
    // `super::x::X` from y: a circle x -> y -> x.
    write("a/src/y.rs", "pub struct Y;\nfn f(_: super::x::X) {}\n");
    let long: String = (0..601).map(|i| format!("// line {i}\n")).collect();
    let test_tail: String = (0..900).map(|i| format!("// test {i}\n")).collect();
    write(
        "a/src/long.rs",
        &format!("{long}#[cfg(test)]\nmod tests {{\n{test_tail}}}\n"),
    );
    let fat: String = (0..3000).map(|i| format!("// {i}\n")).collect();
    write("src/main.rs", &fat);
    let o = architecture_check(d, &["a"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(out.contains("a: import circle between x.rs, y.rs"), "{out}");
    // Lines after #[cfg(test)] are not counted: 601, not 1503.
    assert!(out.contains("a/src/long.rs: 601 lines"), "{out}");
    assert!(out.contains("src/main.rs: 3000 lines"), "{out}");
    assert!(out.contains("src/ (the binary crate): 3000 lines"), "{out}");
}

/// Text files of the repository, without build outputs, the venv or git's own files.
fn repository_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let path = e.path();
            let name = e.file_name().to_string_lossy().into_owned();
            if name.starts_with('.') || name == "target" || name == "solsim-out" {
                continue;
            }
            if path.is_dir() {
                walk(&path, out);
            } else if ["rs", "toml", "md", "sh", "py", "txt"]
                .iter()
                .any(|ext| name.ends_with(&format!(".{ext}")))
            {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(&root(), &mut out);
    out.sort();
    out
}

#[test]
fn every_document_the_code_cites_is_in_the_repository() {
    let outside = [
        "DESIGN.md",
        "PERFORMANCE.md",
        "ECOSYSTEM.md",
        "SLURM.md",
        "STYLE.md",
        "../shared/",
    ];
    let design = std::fs::read_to_string(root().join("docs/design.md")).expect("docs/design.md");
    let sections: Vec<&str> = design
        .lines()
        .filter_map(|l| l.strip_prefix("## "))
        .collect();
    let this_file = root().join("tests/issue_29_architecture.rs");
    let mut found = Vec::new();
    let mut cited = 0;
    for path in repository_files() {
        if path == this_file {
            continue;
        }
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let rel = path
            .strip_prefix(root())
            .unwrap_or(&path)
            .display()
            .to_string();
        for (i, line) in text.lines().enumerate() {
            for name in outside {
                if line.contains(name) && !line.contains(&format!("docs/{}", name.to_lowercase())) {
                    found.push(format!("{rel}:{}: cites {name}: {line}", i + 1));
                }
            }
        }
        // `docs/design.md, "Section"` (a citation may wrap after the comma).
        let flat = text
            .replace("\n//! ", " ")
            .replace("\n/// ", " ")
            .replace("\n# ", " ");
        for (at, _) in flat.match_indices("docs/design.md, \"") {
            let rest = &flat[at + "docs/design.md, \"".len()..];
            let Some(end) = rest.find('"') else { continue };
            let section = rest[..end].split_whitespace().collect::<Vec<_>>().join(" ");
            cited += 1;
            if !sections.contains(&section.as_str()) {
                found.push(format!(
                    "{rel}: cites docs/design.md, \"{section}\", which has no such section"
                ));
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
    // The citations the design notes exist for are found (the scan is not blind).
    assert!(cited >= 6, "only {cited} citations of docs/design.md found");
}
