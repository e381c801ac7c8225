//! Issue 26: the fuzzer extended to sweep directories, which the parser fuzzer never reached.
//! Seeded hostile edits of the files of killed, complete and shard sweep directories — a file
//! (or `chunks/`) replaced by a FIFO, a link to `/dev/zero`, a link to a good copy outside, a
//! directory, an empty, cut, sparse-huge or bit-flipped file — then `--resume`, the report's
//! reader and `sweep merge` in process. Each must end within the watchdog's limit, without a
//! panic, with the uninterrupted sweep's bytes (or rows) or one printable error line, and
//! leave a directory outside the sweep untouched.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use rand::{RngExt as _, SeedableRng as _};
use rand_chacha::ChaCha8Rng;

use crate::common::killed_sweep::{Fixture, copy_dir, listing, mkfifo, same_sweep};

/// A case still running after this is a hang: the watchdog says which and ends the process.
const HANG: Duration = Duration::from_secs(60);

/// Every file under `dir`, relative, `chunks/` itself included.
fn entries(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for name in listing(dir) {
        let p = PathBuf::from(&name);
        if dir.join(&p).is_dir() {
            out.push(p.clone());
            for inner in listing(&dir.join(&p)) {
                out.push(p.join(inner));
            }
        } else {
            out.push(p);
        }
    }
    out
}

/// Replaces `dir/rel` by something hostile; returns what.
fn hostile(rng: &mut ChaCha8Rng, dir: &Path, rel: &Path, outside: &Path) -> String {
    let path = dir.join(rel);
    let is_dir = path.is_dir();
    // A good copy of it outside the directory, for the link cases.
    let copy = outside.join(format!("copy-{}", rng.random::<u32>()));
    if is_dir {
        copy_dir(&path, &copy);
    } else {
        std::fs::copy(&path, &copy).expect("copy");
    }
    let remove = |p: &Path| {
        if p.is_dir() {
            std::fs::remove_dir_all(p).expect("rm -r");
        } else {
            std::fs::remove_file(p).expect("rm");
        }
    };
    let kind = rng.random_range(0..8);
    match kind {
        0 => {
            remove(&path);
            mkfifo(&path);
        }
        1 => {
            remove(&path);
            std::os::unix::fs::symlink("/dev/zero", &path).expect("ln");
        }
        2 => {
            remove(&path);
            std::os::unix::fs::symlink(&copy, &path).expect("ln");
        }
        3 => {
            remove(&path);
            std::fs::create_dir(&path).expect("mkdir");
        }
        _ if is_dir => {
            remove(&path);
            std::fs::write(&path, b"").expect("write");
        }
        4 => std::fs::write(&path, b"").expect("write"),
        5 => {
            let len = std::fs::metadata(&path).expect("len").len();
            let f = std::fs::OpenOptions::new()
                .write(true)
                .open(&path)
                .expect("open");
            f.set_len(len / 2).expect("cut");
        }
        6 => {
            // Sparse, past the cap on files read inside a sweep directory.
            let f = std::fs::OpenOptions::new()
                .write(true)
                .open(&path)
                .expect("open");
            f.set_len(sweep::parquet_io::MAX_TABLE_BYTES + 1)
                .expect("sparse");
        }
        _ => {
            let mut bytes = std::fs::read(&path).expect("read");
            if !bytes.is_empty() {
                let at = rng.random_range(0..bytes.len());
                bytes[at] ^= 1 << rng.random_range(0..8);
            }
            std::fs::write(&path, bytes).expect("write");
        }
    }
    let what = [
        "FIFO",
        "link to /dev/zero",
        "link to a copy outside",
        "directory",
        "empty",
        "cut in half",
        "sparse past the cap",
        "one bit flipped",
    ];
    format!("{} made {}", rel.display(), what[kind])
}

/// One printable line.
fn one_line(case: usize, what: &str, e: &dyn std::fmt::Display) {
    let line = e.to_string();
    assert!(
        !line.contains('\n') && !line.contains('\u{1b}') && !line.contains('\0'),
        "case {case} ({what}): not one printable line: {line:?}"
    );
}

#[test]
fn hostile_sweep_directories_end_right_or_refused() {
    let cases: usize = std::env::var("SOLSIM_SWEEP_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000);
    let budget = maps::MemoryBudget::new(maps::MemoryBudget::DEFAULT_BYTES);
    let mut f = Fixture::new(6, 2);
    let reference = f.complete("reference");
    let killed = f.killed("killed", 4);
    let summary_ref = sweep::engine::read_complete(&reference, budget)
        .expect("reads")
        .summary;
    let summary_ref = serde_json::to_string(&summary_ref).expect("json");
    let mut shards = Vec::new();
    for k in 0..2 {
        f.spec.shard = Some(sweep::Shard { index: k, count: 2 });
        shards.push(f.complete(&format!("shard-{k}")));
    }
    f.spec.shard = None;
    let merged_ref = f.tmp.path().join("merged-reference");
    sweep::merge(&shards, &merged_ref).expect("merges");

    let outside = f.tmp.path().join("outside");
    std::fs::create_dir(&outside).expect("mkdir");
    std::fs::write(outside.join("precious.txt"), "keep me").expect("write");

    let started = AtomicU64::new(u64::MAX);
    let epoch = Instant::now();
    let mut rng = ChaCha8Rng::seed_from_u64(0x26_0003);
    let (mut right, mut refused) = (0, 0);
    std::thread::scope(|s| {
        let watchdog_done = &started;
        s.spawn(move || {
            loop {
                let at = watchdog_done.load(Ordering::Relaxed);
                if at == u64::MAX - 1 {
                    return;
                }
                if at != u64::MAX && epoch.elapsed().as_secs() > at + HANG.as_secs() {
                    eprintln!("case starting at {at} s still running after {HANG:?}: a hang");
                    std::process::abort();
                }
                std::thread::sleep(Duration::from_millis(200));
            }
        });
        for case in 0..cases {
            let dir = f.tmp.path().join(format!("case-{case}"));
            let op = rng.random_range(0..3);
            let source: &Path = match op {
                0 => &killed,
                1 => &reference,
                _ => &shards[rng.random_range(0..2)],
            };
            copy_dir(source, &dir);
            let files = entries(&dir);
            let rel = files[rng.random_range(0..files.len())].clone();
            let what = hostile(&mut rng, &dir, &rel, &outside);
            let before = listing(&outside);
            started.store(epoch.elapsed().as_secs(), Ordering::Relaxed);
            let outcome =
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| -> Result<(), String> {
                    match op {
                        0 => match f.run(&dir, true) {
                            Ok(_) => same_sweep(&dir, &reference).map(|()| true),
                            Err(e) => {
                                one_line(case, &what, &e);
                                Ok(false)
                            }
                        },
                        1 => match sweep::engine::read_complete(&dir, budget) {
                            Ok(done) => {
                                let got = serde_json::to_string(&done.summary).expect("json");
                                if got == summary_ref {
                                    Ok(true)
                                } else {
                                    Err("other statistics".into())
                                }
                            }
                            Err(e) => {
                                one_line(case, &what, &e);
                                Ok(false)
                            }
                        },
                        _ => {
                            let other = if dir.ends_with("shard-0") {
                                &shards[1]
                            } else {
                                &shards[0]
                            };
                            let pair = [dir.clone(), other.clone()];
                            let out = f.tmp.path().join(format!("merged-{case}"));
                            let r = match sweep::merge(&pair, &out) {
                                Ok(_) => same_sweep(&out, &merged_ref).map(|()| true),
                                Err(e) => {
                                    one_line(case, &what, &e);
                                    Ok(false)
                                }
                            };
                            let _ = std::fs::remove_dir_all(&out);
                            r
                        }
                    }
                    .map(|ok| if ok { right += 1 } else { refused += 1 })
                }));
            started.store(u64::MAX, Ordering::Relaxed);
            match outcome {
                Err(_) => panic!("case {case} ({what}): panicked"),
                Ok(Err(e)) => panic!("case {case} ({what}): ended complete but wrong: {e}"),
                Ok(Ok(())) => {}
            }
            assert_eq!(
                listing(&outside),
                before,
                "case {case} ({what}): outside touched"
            );
            let _ = std::fs::remove_dir_all(&dir);
        }
        started.store(u64::MAX - 1, Ordering::Relaxed);
    });
    assert_eq!(
        std::fs::read_to_string(outside.join("precious.txt")).expect("kept"),
        "keep me"
    );
    eprintln!("{cases} hostile sweep directories: {right} ended right, {refused} refused");
    assert!(right > 0 && refused > 0, "{right} / {refused}");
}
