//! Issue 26, finding 6: a path flipped between a regular file and a FIFO hung `validate` in
//! 39 of 300 tries: the file's type was checked on the path (`stat`) and the path opened after,
//! so a FIFO swapped in between blocked the open. The input gate now opens first, without
//! blocking (`O_NONBLOCK`), and checks the opened descriptor: under the same flipping, every
//! try ends at once, having read either the file or refused the FIFO.
#![cfg(unix)]

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use crate::common::killed_sweep::mkfifo;
use crate::common::{output_within, root, solsim};

const TRIES: usize = 300;

#[test]
fn a_path_flipped_between_a_file_and_a_fifo_never_hangs() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("flip.toml");
    // A regular file that fails fast after it is read (an unknown field), and a FIFO.
    let fifo = dir.path().join("fifo.toml");
    let stop = AtomicBool::new(false);
    let (mut read_file, mut refused_fifo) = (0, 0);
    std::thread::scope(|s| {
        s.spawn(|| {
            // Swap a regular file and a FIFO under `path` as fast as the kernel does it:
            // `renameat2(RENAME_EXCHANGE)` of two entries made once.
            std::fs::write(&path, "not_a_solsim_field = 1\n").expect("write");
            mkfifo(&fifo);
            let c = |p: &std::path::Path| {
                std::ffi::CString::new(p.as_os_str().as_encoded_bytes()).expect("path")
            };
            let (a, b) = (c(&path), c(&fifo));
            while !stop.load(Ordering::Relaxed) {
                // SAFETY: two valid NUL-terminated paths; nothing else is read.
                let r = unsafe {
                    libc::renameat2(
                        libc::AT_FDCWD,
                        a.as_ptr(),
                        libc::AT_FDCWD,
                        b.as_ptr(),
                        libc::RENAME_EXCHANGE,
                    )
                };
                assert_eq!(r, 0, "renameat2: {}", std::io::Error::last_os_error());
            }
        });
        // Stops the flipping however this thread leaves the scope (a failed try panics).
        struct Stop<'a>(&'a AtomicBool);
        impl Drop for Stop<'_> {
            fn drop(&mut self) {
                self.0.store(true, Ordering::Relaxed);
            }
        }
        let _stop = Stop(&stop);
        for _ in 0..TRIES {
            for args in [vec!["validate"], vec!["zones", "check", "--zones"]] {
                let mut cmd = solsim();
                cmd.args(&args).arg(&path);
                if args[0] == "zones" {
                    cmd.arg("--points")
                        .arg(root().join("peers/zones_fixtures/points.csv"));
                }
                let o = output_within(&mut cmd, Duration::from_secs(20));
                let err = String::from_utf8_lossy(&o.stderr);
                assert_eq!(o.status.code(), Some(2), "{err}");
                assert_eq!(err.trim_end().lines().count(), 1, "{err}");
                if err.contains("got a FIFO") {
                    refused_fifo += 1;
                } else {
                    read_file += 1;
                }
            }
        }
    });
    eprintln!(
        "{} tries on a flipping path: {read_file} read the file, {refused_fifo} refused the FIFO",
        2 * TRIES
    );
    assert!(
        read_file > 0 && refused_fifo > 0,
        "the path did not flip under the tries"
    );
}
