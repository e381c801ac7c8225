//! A sweep directory is written by one process at a time.
//!
//! A sweep, a resume or a merge takes an exclusive lock on the directory it writes before it
//! looks inside; `solsim report` and a merge take a shared lock on the directories they read.
//! A second writer, or a reader of a directory being written, is refused at once with one line
//! naming the directory, rather than racing the first to `cannot rename into place`. The lock is
//! `flock(2)` on the directory's own descriptor: nothing is added to the directory, and the
//! kernel drops the lock when the process ends, however it ends (a SIGKILL leaves no stale lock
//! for `--resume` to clear).

use std::fs::File;
use std::path::Path;

use crate::error::SweepError;

/// A held lock on a directory; released when dropped (or when the process ends).
#[derive(Debug)]
pub struct DirLock {
    _dir: File,
}

/// Whether a lock excludes everyone else (a writer) or only writers (a reader).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LockKind {
    /// Writing the directory: no other reader or writer.
    Exclusive,
    /// Reading the directory: other readers, no writer.
    Shared,
}

impl DirLock {
    /// Takes the lock on `dir` without waiting. `option` names where the directory came from
    /// (`--out`, `DIR`) in the error.
    ///
    /// # Errors
    /// [`SweepError::Option`] when another process holds a conflicting lock;
    /// [`SweepError::Io`] when the directory cannot be opened.
    pub fn take(dir: &Path, kind: LockKind, option: &str) -> Result<Self, SweepError> {
        let file = File::open(dir)
            .map_err(|e| SweepError::io(dir, "cannot open the directory to lock it", e))?;
        #[cfg(unix)]
        {
            use std::os::fd::AsRawFd as _;
            let op = match kind {
                LockKind::Exclusive => libc::LOCK_EX,
                LockKind::Shared => libc::LOCK_SH,
            };
            // SAFETY: flock on a descriptor this function owns; no memory is passed.
            if unsafe { libc::flock(file.as_raw_fd(), op | libc::LOCK_NB) } != 0 {
                let e = std::io::Error::last_os_error();
                if e.raw_os_error() == Some(libc::EWOULDBLOCK) {
                    let (what, doing) = match kind {
                        LockKind::Exclusive => (
                            "a sweep directory no other solsim process is using",
                            "in use",
                        ),
                        LockKind::Shared => (
                            "a sweep directory no solsim process is writing",
                            "being written",
                        ),
                    };
                    return Err(SweepError::option(
                        option,
                        what,
                        format!(
                            "{} ({doing} by another solsim process: a sweep, resume, merge or report)",
                            dir.display()
                        ),
                    ));
                }
                return Err(SweepError::io(dir, "cannot lock the directory", e));
            }
        }
        Ok(Self { _dir: file })
    }
}
