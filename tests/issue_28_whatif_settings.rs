//! Issue 28: `solsim whatif BASE VARIANT` never said which setting differs between the two
//! runs, so its differences could not be read without a `diff` of the files. It now names every
//! setting whose value differs, with both values (a map file compared by contents, not by its
//! path), and says so when none does; `--json` lists them as `differences`.

use crate::common;

use common::{rebase, root, run_ok};

const BASE: &str = "scenarios/dune-crossing.toml";

#[test]
fn whatif_names_the_setting_that_differs() {
    let text = run_ok(
        &[
            "whatif",
            BASE,
            "scenarios/dune-crossing-slip-unaware.toml",
            "--runs",
            "2",
        ],
        &[],
    );
    assert_eq!(
        text.lines().nth(1),
        Some("  the setting that differs: rover.slip_aware_routing: true → false"),
        "{text}"
    );
    let json = run_ok(
        &[
            "whatif",
            BASE,
            "scenarios/dune-crossing-slip-unaware.toml",
            "--runs",
            "2",
            "--json",
        ],
        &[],
    );
    let w: serde_json::Value = serde_json::from_str(&json).expect("JSON");
    assert_eq!(
        w["differences"],
        serde_json::json!([{"field": "rover.slip_aware_routing", "base": "true", "variant": "false"}])
    );
}

#[test]
fn whatif_says_when_nothing_differs_and_reads_map_files_by_contents() {
    let text = run_ok(&["whatif", BASE, BASE, "--runs", "2"], &[]);
    assert!(
        text.lines()
            .nth(1)
            .is_some_and(|l| l.starts_with("  no setting differs")),
        "{text}"
    );
    // A copy elsewhere names the same map files by other paths: not a difference; its name is
    // not a setting; the setting it changes is.
    let dir = tempfile::tempdir().expect("tempdir");
    let copy = dir.path().join("copy.toml");
    let original = std::fs::read_to_string(root().join(BASE)).expect("read");
    let edited = rebase(&original)
        .replace("name = \"dune-crossing\"", "name = \"copy\"")
        .replace("slip_aware_routing = true", "slip_aware_routing = false");
    assert_ne!(edited, rebase(&original), "the edit applies");
    std::fs::write(&copy, edited).expect("write");
    let out = run_ok(&["whatif", BASE, "--runs", "2"], &[copy.as_path()]);
    assert_eq!(
        out.lines().nth(1),
        Some("  the setting that differs: rover.slip_aware_routing: true → false"),
        "the map paths differ, their contents do not:\n{out}"
    );
}

#[test]
fn setting_differences_flatten_tables_and_arrays_of_tables() {
    let base = "name = \"a\"\nseed = 1\n[rover]\nx = 1\n[[sols]]\nsol = 1\nnote = \"n\"\n\
                [[sols]]\nsol = 2\n[[expect]]\nwhat = \"w\"\n";
    let variant = "name = \"b\"\nseed = 1\n[rover]\nx = 2\ny = [1, 2]\n[[sols]]\nsol = 1\n\
                   note = \"other\"\n[[sols]]\nsol = 3\n";
    let d = sweep::setting_diff::setting_differences(base, variant).expect("TOML");
    let shown: Vec<String> = d.iter().map(ToString::to_string).collect();
    assert_eq!(
        shown,
        [
            "rover.x: 1 → 2",
            "rover.y: (not set: default) → [1, 2]",
            "sols[1].sol: 2 → 3",
        ]
    );
}
