//! Issue 26, finding 3: special files inside sweep directories. A FIFO as `runs.parquet`
//! (`solsim report`), as a shard's `sols.parquet` (`sweep merge`) or as a committed chunk
//! (`--resume`) blocked until killed; a link to `/dev/zero` was read until 8.4 GB (`report`)
//! or 4.2 GB (`--resume`). Every file read inside a sweep directory now goes through the input
//! gate (type checked on the opened descriptor, no link followed, size capped): each case ends
//! at once, with one error line or, for a chunk that is run again, the sweep's own files.
#![cfg(unix)]

use std::path::Path;
use std::process::Command;

use crate::common::killed_sweep::{Fixture, LIMIT, copy_dir, listing, mkfifo, refused, resume};
use crate::common::{output_within, root, solsim};

fn replace_with_fifo(path: &Path) {
    std::fs::remove_file(path).expect("remove");
    mkfifo(path);
}

fn replace_with_link(path: &Path, to: &Path) {
    std::fs::remove_file(path).expect("remove");
    std::os::unix::fs::symlink(to, path).expect("symlink");
}

fn report(dir: &Path, out: &Path) -> Command {
    let mut c = solsim();
    c.current_dir(root())
        .arg("report")
        .arg(dir)
        .arg("--out")
        .arg(out);
    c
}

#[test]
fn report_refuses_a_fifo_or_a_device_link_as_runs_parquet() {
    let f = Fixture::new(6, 2);
    let done = f.complete("done");
    let fifo = f.tmp.path().join("fifo");
    copy_dir(&done, &fifo);
    replace_with_fifo(&fifo.join("runs.parquet"));
    refused(
        &mut report(&fifo, &f.tmp.path().join("r1")),
        &["runs.parquet", "FIFO"],
    );
    let zero = f.tmp.path().join("zero");
    copy_dir(&done, &zero);
    replace_with_link(&zero.join("runs.parquet"), Path::new("/dev/zero"));
    refused(
        &mut report(&zero, &f.tmp.path().join("r2")),
        &["runs.parquet", "symbolic link"],
    );
    // The manifest itself, as a FIFO.
    let m = f.tmp.path().join("manifest-fifo");
    copy_dir(&done, &m);
    replace_with_fifo(&m.join("manifest.json"));
    refused(
        &mut report(&m, &f.tmp.path().join("r3")),
        &["manifest.json", "FIFO"],
    );
}

#[test]
fn merge_refuses_a_fifo_as_a_shards_sols_parquet() {
    let mut f = Fixture::new(6, 2);
    let mut shards = Vec::new();
    for k in 0..2 {
        f.spec.shard = Some(sweep::Shard { index: k, count: 2 });
        shards.push(f.complete(&format!("shard-{k}")));
    }
    replace_with_fifo(&shards[1].join("sols.parquet"));
    let out = f.tmp.path().join("merged");
    refused(
        solsim()
            .args(["sweep", "merge"])
            .args(&shards)
            .arg("--out")
            .arg(&out),
        &["sols.parquet", "FIFO"],
    );
}

#[test]
fn resume_refuses_a_fifo_or_a_device_link_as_a_committed_chunk() {
    let f = Fixture::new(6, 2);
    let killed = f.killed("killed", 4);
    let chunk = "chunks/sols-0000000000-0000000002.parquet";
    for (name, make) in [
        ("fifo", &(|p: &Path| replace_with_fifo(p)) as &dyn Fn(&Path)),
        ("zero", &|p: &Path| {
            replace_with_link(p, Path::new("/dev/zero"))
        }),
    ] {
        let dir = f.tmp.path().join(name);
        copy_dir(&killed, &dir);
        make(&dir.join(chunk));
        // A listed chunk that cannot be read as its entry says is run again: the resume ends
        // at once, with the uninterrupted sweep's files, and never reads the FIFO or device.
        let o = output_within(&mut resume(&f, &dir), LIMIT);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert_eq!(
            listing(&dir),
            [
                "manifest.json",
                "runs.parquet",
                "sols.parquet",
                "summary.json"
            ]
        );
    }
}
