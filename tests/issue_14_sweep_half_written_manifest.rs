//! Regression (found by CI on 2026-12-02): a sweep killed while writing its first manifest
//! left only `.manifest.json.tmp` in `--out`, and the resumed sweep refused the directory
//! ("holds .manifest.json.tmp and no sweep manifest", exit 2) instead of starting the sweep.
//! `tests/sweep_resume.rs` kills at random moments and hit that window only under load; this
//! test makes the state directly.

use crate::common;

use common::{root, solsim};

#[test]
fn a_half_written_first_manifest_is_resumed_not_refused() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("sweep");
    std::fs::create_dir(&out).expect("mkdir");
    // What `write_durably` leaves when killed between creating and renaming the file.
    std::fs::write(
        out.join(".manifest.json.tmp"),
        b"{\n  \"format\": \"solsim-sw",
    )
    .expect("write");
    for resume in [true, false] {
        let mut c = solsim();
        c.current_dir(root()).args([
            "sweep",
            "scenarios/crater-floor-717.toml",
            "--runs",
            "2",
            "--strategies",
            "ground",
            "--quiet",
            "--out",
        ]);
        c.arg(&out);
        if resume {
            c.arg("--resume");
        }
        let o = c.output().expect("run solsim");
        assert!(
            o.status.success(),
            "resume {resume}: {}",
            common::stderr(&o)
        );
        assert!(out.join("summary.json").is_file());
        assert!(!out.join(".manifest.json.tmp").exists());
        // Again from the same state, without --resume this time.
        std::fs::remove_dir_all(&out).expect("rm");
        std::fs::create_dir(&out).expect("mkdir");
        std::fs::write(out.join(".manifest.json.tmp"), b"{").expect("write");
    }
}
