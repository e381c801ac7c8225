//! Issue 26, finding 12 (first part): a disk that filled during the sweep's final step left
//! `runs.parquet` without `sols.parquet`. The output files are now removed when assembling
//! them fails, so the directory still reads as a running sweep, and `--resume` (with room
//! again) finishes it with the uninterrupted sweep's bytes. The full disk is a file-size limit
//! (`RLIMIT_FSIZE`, with `SIGXFSZ` ignored so the write fails with `EFBIG`) between the largest
//! chunk and the final `sols.parquet`.
#![cfg(unix)]

use std::os::unix::process::CommandExt as _;

use crate::common::killed_sweep::{Fixture, listing, resume, same_sweep};

#[test]
fn a_full_disk_while_assembling_leaves_no_half_output_set() {
    let f = Fixture::new(30, 1);
    let reference = f.complete("reference");
    let size = |name: &str| std::fs::metadata(reference.join(name)).expect("size").len();
    let (runs, sols, manifest) = (
        size("runs.parquet"),
        size("sols.parquet"),
        size("manifest.json"),
    );
    // Chunk files hold one run's rows: far below the final tables; the running manifest lists
    // 30 entries of ~250 bytes.
    let limit = runs.max(manifest).max(30 * 300) + 512;
    assert!(
        limit < sols,
        "the limit {limit} B must stop sols.parquet ({sols} B) only"
    );

    let dir = f.tmp.path().join("full");
    let mut cmd = resume(&f, &dir);
    // SAFETY: setrlimit and signal are async-signal-safe; nothing else runs before exec.
    unsafe {
        cmd.pre_exec(move || {
            let rl = libc::rlimit {
                rlim_cur: limit,
                rlim_max: limit,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &rl) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
            Ok(())
        });
    }
    let o = cmd.output().expect("runs");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("sols.parquet"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    let left = listing(&dir);
    assert_eq!(
        left,
        ["chunks", "manifest.json"],
        "a half-written output set"
    );
    // With room again, the resume finishes it.
    let o = resume(&f, &dir).output().expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    same_sweep(&dir, &reference).expect("the uninterrupted sweep's files");
}
