//! Regression (issue 13 review): `solsim report D --out D` exited 0 and left only
//! report.html — the run's files were replaced with the output set. `--out` must now be a
//! directory of its own: not the reported one, nor one holding other files.

use crate::common;

use std::path::Path;

use common::{assert_bad_input, root, run_ok, solsim};

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).expect("readable")
}

#[test]
fn report_out_never_replaces_the_run() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = dir.path().join("run");
    run_ok(
        &["compare", "scenarios/crater-floor-passage.toml", "--out"],
        &[&run],
    );
    let twin = dir.path().join("twin");
    std::fs::create_dir(&twin).expect("mkdir");
    std::fs::write(twin.join("notes.txt"), "mine").expect("write");
    // --out may not be the run directory (replacing it would lose the run), nor any directory
    // holding other files.
    let o = solsim()
        .current_dir(root())
        .arg("report")
        .arg(&run)
        .arg("--out")
        .arg(&run)
        .output()
        .expect("runs");
    assert_bad_input(&o, &["--out", "directory reported on"]);
    let o = solsim()
        .current_dir(root())
        .arg("report")
        .arg(&run)
        .arg("--out")
        .arg(&twin)
        .output()
        .expect("runs");
    assert_bad_input(&o, &["--out", "other files"]);
    assert!(
        run.join("crater-floor-passage.ground.json").is_file(),
        "the run is intact"
    );
    assert_eq!(read(&twin.join("notes.txt")), "mine");
}
