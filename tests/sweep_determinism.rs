//! A sweep's files depend only on the scenario, the seed, the runs and the strategies: not on
//! the thread count, the chunk size, or how the run indices were cut into shards and merged.

use crate::common;

use std::path::Path;

use common::{root, solsim};

const FILES: [&str; 4] = [
    "runs.parquet",
    "sols.parquet",
    "summary.json",
    "manifest.json",
];

fn sweep(out: &Path, extra: &[&str]) {
    let o = solsim()
        .current_dir(root())
        .args([
            "sweep",
            "scenarios/rapid-traverse-379-409.toml",
            "--runs",
            "24",
            "--strategies",
            "ground,onboard,extension+onboard",
            "--quiet",
            "--out",
        ])
        .arg(out)
        .args(extra)
        .output()
        .expect("run solsim");
    assert!(
        o.status.success(),
        "solsim sweep {extra:?} failed: {}",
        common::stderr(&o)
    );
}

fn assert_same(a: &Path, b: &Path) {
    for f in FILES {
        let (x, y) = (
            std::fs::read(a.join(f)).expect("read"),
            std::fs::read(b.join(f)).expect("read"),
        );
        assert!(
            x == y,
            "{f} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn one_and_two_threads_and_any_chunk_size_write_identical_files() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let one = tmp.path().join("one");
    let two = tmp.path().join("two");
    let chunky = tmp.path().join("chunky");
    sweep(&one, &["--threads", "1"]);
    sweep(&two, &["--threads", "2"]);
    sweep(&chunky, &["--threads", "2", "--chunk-runs", "7"]);
    assert_same(&one, &two);
    assert_same(&one, &chunky);
    // Not vacuous: another seed gives other files.
    let other = tmp.path().join("other");
    sweep(&other, &["--seed", "7"]);
    assert_ne!(
        std::fs::read(one.join("runs.parquet")).expect("read"),
        std::fs::read(other.join("runs.parquet")).expect("read")
    );
}

#[test]
fn shards_merged_equal_one_sweep() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let whole = tmp.path().join("whole");
    sweep(&whole, &[]);
    for n in [3_u64, 5] {
        let mut dirs = Vec::new();
        // Shards run in reverse order, and merged in a scrambled order.
        for k in (0..n).rev() {
            let d = tmp.path().join(format!("n{n}-shard-{k}"));
            sweep(&d, &["--shard", &format!("{k}/{n}"), "--threads", "1"]);
            dirs.push(d);
        }
        dirs.swap(0, 1);
        let merged = tmp.path().join(format!("merged-{n}"));
        let o = solsim()
            .args(["sweep", "merge", "--quiet", "--out"])
            .arg(&merged)
            .args(&dirs)
            .output()
            .expect("run solsim");
        assert!(o.status.success(), "merge failed: {}", common::stderr(&o));
        assert_same(&whole, &merged);
    }
}
