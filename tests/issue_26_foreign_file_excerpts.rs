//! Issue 26, finding 10: error messages quoted files that are not solsim's. `solsim validate
//! /etc/shadow` printed the shadow file's first line (a password hash), `/proc/self/environ`
//! 120 characters of the environment, and `plan` (campaign file), `map generate` (recipe) and
//! `zones check --points` (CSV) did the same: whoever can choose the argument but not read the
//! file got its content in the error.
//!
//! Now an excerpt of a file is quoted only if the file read as the expected format far enough
//! to be solsim's: TOML whose text before the offending line parses and holds a key of the
//! format (`name`, `seed`, `terrain`, `sol` …); a CSV whose header names a points column; JSON
//! with a `type` member. Otherwise the error says where (line, column) and what was expected.
//! The files here are temporary stand-ins: a shadow-like line, NUL-separated `KEY=VALUE` bytes
//! as in `/proc/self/environ`, a `.env` file whose first line is valid TOML, and a JSON
//! string (a token file).

use crate::common;

use std::path::Path;
use std::process::Output;

use common::{assert_bad_input, root, solsim, stderr};

/// The secrets, one per stand-in; none may appear in any error.
const SECRETS: [&str; 5] = [
    "s3cr3tHASH",
    "TOKEN_VALUE_42",
    "hunter2",
    "dotenvsecret",
    "jsontok",
];

fn stand_ins(dir: &Path) -> Vec<(&'static str, std::path::PathBuf)> {
    let files: [(&str, &[u8]); 5] = [
        (
            "shadow",
            b"root:$6$s3cr3tHASH:19000:0:99999:7:::\ndaemon:*:19000:0:99999:7:::\n",
        ),
        (
            "environ",
            b"HOME=/root\0API_TOKEN=TOKEN_VALUE_42\0PATH=/usr/bin:/bin\0",
        ),
        // Valid TOML, none of solsim's keys: its message would quote the value.
        ("password.toml", b"password = \"hunter2\"\n"),
        // The first line is valid TOML, the second is not.
        ("dotenv", b"PRETTY_NAME=\"Debian\"\nSECRET=dotenvsecret\n"),
        ("token.json", b"\"jsontok\"\n"),
    ];
    files
        .into_iter()
        .map(|(name, bytes)| {
            let path = dir.join(name);
            std::fs::write(&path, bytes).expect("write");
            (name, path)
        })
        .collect()
}

fn assert_no_secret(o: &Output, what: &str) {
    let err = stderr(o);
    for s in SECRETS {
        assert!(!err.contains(s), "{what}: the error quotes {s:?}:\n{err}");
    }
    assert!(o.stdout.is_empty(), "{what}: output on stdout");
}

fn run(args: &[&std::ffi::OsStr]) -> Output {
    common::output_within(
        solsim().args(args).current_dir(root()),
        std::time::Duration::from_secs(60),
    )
}

#[test]
fn toml_errors_do_not_quote_foreign_files() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("out");
    for (name, path) in stand_ins(dir.path()) {
        let p = path.as_os_str();
        let commands: [(&str, Vec<&std::ffi::OsStr>, &str); 3] = [
            (
                "validate",
                vec!["validate".as_ref(), p],
                "`name`, `description`, `seed`, `map`",
            ),
            (
                "plan",
                vec!["plan".as_ref(), p],
                "`name`, `description`, `sol`, `activities`",
            ),
            (
                "map generate",
                vec![
                    "map".as_ref(),
                    "generate".as_ref(),
                    p,
                    "--out".as_ref(),
                    out.as_os_str(),
                ],
                "`terrain`, `dem_datum_m`, `georeference`",
            ),
        ];
        for (command, args, keys) in commands {
            let o = run(&args);
            let what = format!("{command} {name}");
            assert_no_secret(&o, &what);
            assert_bad_input(
                &o,
                &[
                    &format!("expected a TOML file with such keys as {keys}"),
                    "its text is not quoted",
                ],
            );
            assert!(stderr(&o).contains(", column "), "{what}: {}", stderr(&o));
        }
        assert!(!out.exists(), "map generate wrote {}", out.display());
    }
}

/// The rule still quotes solsim's own files: an error below a known key shows the line.
#[test]
fn toml_errors_still_quote_solsims_own_files() {
    let (scenario, _d) = common::scenario_copy("crater-floor-717.toml", |t| {
        t.replacen("seed = ", "seed = \"not a number\" # ", 1)
    });
    let o = run(&["validate".as_ref(), scenario.as_os_str()]);
    assert_bad_input(
        &o,
        &[
            "(`seed = \"not a number\"",
            "invalid type: string \"not a number\"",
        ],
    );
    let dir = tempfile::tempdir().expect("tempdir");
    let plan = dir.path().join("plan.toml");
    std::fs::write(&plan, "name = \"p\"\n[sol]\nstart_lmst = 9\n").expect("write");
    let o = run(&["plan".as_ref(), plan.as_os_str()]);
    assert_bad_input(&o, &["line 3", "(`start_lmst = 9`)"]);
}

#[test]
fn points_csv_errors_do_not_quote_foreign_files() {
    let dir = tempfile::tempdir().expect("tempdir");
    let zones = root().join("scenarios/crater-floor-717.zones.geojson");
    for (name, path) in stand_ins(dir.path()) {
        let o = run(&[
            "zones".as_ref(),
            "check".as_ref(),
            "--zones".as_ref(),
            zones.as_os_str(),
            "--points".as_ref(),
            path.as_os_str(),
        ]);
        assert_no_secret(&o, &format!("zones check --points {name}"));
        assert_bad_input(
            &o,
            &[
                "line 1: expected a header row naming the columns x_m, y_m and optionally name",
                "not quoted",
            ],
        );
    }
    // A header that names a points column: the file is a points CSV, its columns are quoted.
    let points = dir.path().join("p.csv");
    std::fs::write(&points, "x_m,y_m,z_m\n").expect("write");
    let o = run(&[
        "zones".as_ref(),
        "check".as_ref(),
        "--zones".as_ref(),
        zones.as_os_str(),
        "--points".as_ref(),
        points.as_os_str(),
    ]);
    assert_bad_input(&o, &["unknown column(s) \"z_m\""]);
}

#[test]
fn zones_errors_do_not_quote_foreign_files() {
    let dir = tempfile::tempdir().expect("tempdir");
    let points = dir.path().join("p.csv");
    std::fs::write(&points, "x_m,y_m\n1,2\n").expect("write");
    for (name, path) in stand_ins(dir.path()) {
        let o = run(&[
            "zones".as_ref(),
            "check".as_ref(),
            "--zones".as_ref(),
            path.as_os_str(),
            "--points".as_ref(),
            points.as_os_str(),
        ]);
        assert_no_secret(&o, &format!("zones check --zones {name}"));
        assert_bad_input(&o, &[name]);
    }
}
