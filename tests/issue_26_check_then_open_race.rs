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
    let file = dir.path().join("file.toml");
    let fifo = dir.path().join("fifo.toml");
    let stop = AtomicBool::new(false);
    let (mut read_file, mut refused_fifo) = (0, 0);
    std::thread::scope(|s| {
        s.spawn(|| {
            // Swap the two in under `path` as fast as renames go.
            let mut n = 0_u64;
            while !stop.load(Ordering::Relaxed) {
                std::fs::write(&file, "not_a_solsim_field = 1\n").expect("write");
                std::fs::rename(&file, &path).expect("rename");
                mkfifo(&fifo);
                std::fs::rename(&fifo, &path).expect("rename");
                n += 1;
            }
            assert!(n > 0);
        });
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
        stop.store(true, Ordering::Relaxed);
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
