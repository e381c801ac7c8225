//! A sweep killed (SIGKILL) at random moments and resumed with `--resume` finishes with no run
//! lost or duplicated and files byte-identical to an uninterrupted sweep.

use crate::common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

use common::{root, solsim};
use rand::{RngExt as _, SeedableRng as _};

const ARGS: [&str; 8] = [
    "sweep",
    "scenarios/rapid-traverse-379-409.toml",
    "--runs",
    "60",
    "--strategies",
    "ground,extension+onboard",
    "--chunk-runs",
    "3",
];

fn sweep_cmd(out: &Path) -> Command {
    let mut c = solsim();
    c.current_dir(root())
        .args(ARGS)
        .args(["--quiet", "--resume", "--out"])
        .arg(out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    c
}

#[test]
fn killed_at_random_moments_then_resumed_equals_an_uninterrupted_sweep() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let reference = tmp.path().join("reference");
    let start = Instant::now();
    let o = sweep_cmd(&reference).output().expect("run solsim");
    assert!(o.status.success(), "{}", common::stderr(&o));
    let full = start.elapsed();

    let out = tmp.path().join("killed");
    // Kill moments spread over the whole sweep, up to its end (assembly of the files
    // included), from a seeded generator so a failure can be replayed.
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let mut kills = 0;
    for _ in 0..12 {
        let mut child = sweep_cmd(&out).spawn().expect("spawn solsim");
        let at = full.mul_f64(rng.random_range(0.0..1.1));
        std::thread::sleep(at);
        if child.try_wait().expect("wait").is_none() {
            child.kill().expect("SIGKILL");
            kills += 1;
        }
        let o = child.wait_with_output().expect("wait");
        if o.status.success() {
            break;
        }
        // Whatever the kill left must be resumable: never an error.
        assert!(
            o.status.code().is_none(),
            "an interrupted run exited with {}: {}",
            o.status,
            common::stderr(&o)
        );
    }
    assert!(
        kills >= 3,
        "only {kills} kills landed; the test proves nothing"
    );
    eprintln!(
        "sweep killed {kills} times (uninterrupted sweep: {:.2} s), then resumed",
        full.as_secs_f64()
    );
    let o = sweep_cmd(&out).output().expect("run solsim");
    assert!(o.status.success(), "{}", common::stderr(&o));
    for f in [
        "runs.parquet",
        "sols.parquet",
        "summary.json",
        "manifest.json",
    ] {
        assert!(
            std::fs::read(reference.join(f)).expect("read")
                == std::fs::read(out.join(f)).expect("read"),
            "{f} differs after {kills} kills and a resume"
        );
    }
    // No chunk or temporary file left behind.
    let mut left: Vec<String> = std::fs::read_dir(&out)
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(
        left,
        [
            "manifest.json",
            "runs.parquet",
            "sols.parquet",
            "summary.json"
        ]
    );
}
