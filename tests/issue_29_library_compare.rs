//! Issue 29: the compare pipeline is a library. `outputs/examples/compare_out.rs` writes the
//! output directory of `solsim compare SCENARIO --out DIR --report` with the `study` and
//! `outputs` crates alone (no binary, no clap); its directory must equal the command's byte for
//! byte, file by file (the hidden output-set marker included), and it must print what the
//! command prints. A difference means the binary does something to its outputs that the
//! library does not (or the other way round).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::common::{root, solsim};

// The example itself, compiled into this test: the test runs exactly its code.
#[allow(dead_code)]
#[path = "../outputs/examples/compare_out.rs"]
mod compare_out;

/// Every file under `dir` (recursively, hidden files too) by its path relative to `dir`.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(base: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for entry in std::fs::read_dir(dir).expect("list") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                walk(base, &path, out);
            } else {
                let rel = path.strip_prefix(base).expect("under base").to_path_buf();
                out.insert(rel, std::fs::read(&path).expect("read"));
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

#[test]
fn the_library_writes_the_directory_compare_out_writes_byte_for_byte() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let scenario = root().join("scenarios/sol383-386.toml");
    let (by_cli, by_library) = (tmp.path().join("cli"), tmp.path().join("library"));

    let o = solsim()
        .arg("compare")
        .arg(&scenario)
        .arg("--out")
        .arg(&by_cli)
        .arg("--report")
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed = compare_out::compare_out(&scenario, &by_library).expect("the library writes");

    let (cli, library) = (files(&by_cli), files(&by_library));
    assert!(
        cli.len() > 30,
        "the command wrote {} files: {:?}",
        cli.len(),
        cli.keys()
    );
    assert!(cli.contains_key(Path::new("report.html")));
    assert!(cli.contains_key(Path::new(".solsim-output-set")));
    assert_eq!(
        cli.keys().collect::<Vec<_>>(),
        library.keys().collect::<Vec<_>>(),
        "the same file names"
    );
    for (name, bytes) in &cli {
        assert!(
            library[name] == *bytes,
            "{}: the library's file differs from the command's",
            name.display()
        );
    }
    let cli_printed = String::from_utf8(o.stdout).expect("UTF-8");
    assert_eq!(
        cli_printed.replace(&by_cli.display().to_string(), "DIR"),
        printed.replace(&by_library.display().to_string(), "DIR"),
        "the same text"
    );
}
