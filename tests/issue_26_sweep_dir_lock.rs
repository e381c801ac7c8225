//! Issue 26, finding 11: nothing stopped two sweeps, or two resumes, writing one directory at
//! once; the loser died with `cannot rename into place` or `cannot create .tmp`, and the files
//! stayed right only by luck of timing. A sweep, resume or merge now takes an exclusive lock
//! on the directory it writes (`report` and a merge's shards a shared one): a second process is
//! refused at once with one line, and the directory ends as one process wrote it.
#![cfg(unix)]

use std::path::Path;
use std::process::{Child, Command, Stdio};

use crate::common::killed_sweep::{Fixture, copy_dir, refused, resume, same_sweep};
use crate::common::{root, solsim};

/// Another process holding the writer's lock on `dir` until dropped: util-linux `flock(1)`,
/// which takes the same `flock(2)` lock solsim does. (A lock held by this test process would
/// leak, for an instant, into every child another test forks meanwhile.)
struct Holder(Child);

impl Holder {
    fn new(dir: &Path) -> Self {
        let mut child = Command::new("flock")
            .args(["--exclusive", "--nonblock", "--no-fork"])
            .arg(dir)
            .args(["sh", "-c", "echo held; exec sleep 600"])
            .stdout(Stdio::piped())
            .spawn()
            .expect("util-linux flock runs");
        let mut line = String::new();
        std::io::BufRead::read_line(
            &mut std::io::BufReader::new(child.stdout.as_mut().expect("stdout")),
            &mut line,
        )
        .expect("read");
        assert_eq!(line, "held\n", "flock did not take the lock");
        Self(child)
    }
}

impl Drop for Holder {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn a_directory_being_written_is_refused_to_every_other_command() {
    let mut f = Fixture::new(4, 2);
    let reference = f.complete("reference");
    let killed = f.killed("killed", 2);
    // Another process writing `killed`.
    let held = Holder::new(&killed);
    refused(
        &mut resume(&f, &killed),
        &["--out", "in use by another solsim process"],
    );
    refused(
        solsim()
            .arg("report")
            .arg(&killed)
            .arg("--out")
            .arg(f.tmp.path().join("report")),
        &["being written by another solsim process"],
    );
    drop(held);
    // Released, the same resume finishes the sweep.
    assert!(resume(&f, &killed).status().expect("runs").success());
    same_sweep(&killed, &reference).expect("the uninterrupted sweep's files");

    // A merge into a directory another process holds, and of a shard being written.
    let mut shards = Vec::new();
    for k in 0..2 {
        f.spec.shard = Some(sweep::Shard { index: k, count: 2 });
        shards.push(f.complete(&format!("shard-{k}")));
    }
    let out = f.tmp.path().join("merged");
    std::fs::create_dir(&out).expect("mkdir");
    let merge = || {
        let mut c = solsim();
        c.args(["sweep", "merge"])
            .args(&shards)
            .arg("--out")
            .arg(&out);
        c
    };
    let held = Holder::new(&out);
    refused(&mut merge(), &["--out", "in use"]);
    drop(held);
    let held = Holder::new(&shards[1]);
    refused(&mut merge(), &["being written"]);
    drop(held);
    assert!(merge().arg("--quiet").status().expect("runs").success());
}

/// Two resumes of one killed sweep started together, six times: each ends with exit 0 or is
/// refused with the lock's one line, and the directory holds the uninterrupted sweep's files.
#[test]
fn two_resumes_at_once_leave_one_sweep() {
    let f = Fixture::new(6, 1);
    let reference = f.complete("reference");
    let killed = f.killed("killed", 2);
    let mut refusals = 0;
    for trial in 0..6 {
        let dir = f.tmp.path().join(format!("trial-{trial}"));
        copy_dir(&killed, &dir);
        let children: Vec<_> = (0..2)
            .map(|_| {
                resume(&f, &dir)
                    .current_dir(root())
                    .stdout(Stdio::null())
                    .stderr(Stdio::piped())
                    .spawn()
                    .expect("spawn")
            })
            .collect();
        for child in children {
            let o = child.wait_with_output().expect("wait");
            let err = String::from_utf8_lossy(&o.stderr);
            if !o.status.success() {
                assert_eq!(o.status.code(), Some(2), "{err}");
                assert!(err.contains("in use by another solsim process"), "{err}");
                assert_eq!(err.trim_end().lines().count(), 1, "{err}");
                refusals += 1;
            }
        }
        same_sweep(&dir, &reference).unwrap_or_else(|e| panic!("trial {trial}: {e}"));
    }
    eprintln!("6 trials of two resumes at once: {refusals} refused by the lock");
}
