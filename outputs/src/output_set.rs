//! Output sets written as a whole: a reader of the output directory sees the earlier run's
//! files or this run's, never a mix, and never half a file.
//!
//! A run writes its files into a staging directory beside the target (`.NAME.staging-PID`),
//! then puts it in place with one atomic step: on Linux `renameat2(RENAME_EXCHANGE)` swaps the
//! staging directory with the earlier set, which is then removed; where the target does not
//! exist yet a plain `rename` is atomic. A run killed at any moment leaves either the old set
//! or the new one at the target, and at worst a staging or retired directory beside it, which
//! the next run into the same place removes (its process is gone).
//!
//! Because the whole directory is replaced, the target must be one solsim wrote: a new or
//! empty directory, or one holding the [`MARKER_FILE`] every set carries. A directory with
//! other files is refused rather than swapped away.

use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// The file that marks a directory as a solsim output set (so replacing it is safe).
pub const MARKER_FILE: &str = ".solsim-output-set";

/// Why an output set could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputSetError {
    /// The target holds files solsim did not write.
    #[error(
        "{}: expected a new or empty directory or an earlier solsim output (with {MARKER_FILE}); it holds other files, so it is left alone — choose another --out",
        dir.display()
    )]
    NotAnOutputSet {
        /// The target directory.
        dir: PathBuf,
    },
    /// The target exists and is not a directory.
    #[error("{}: expected a directory, found a file", dir.display())]
    NotADirectory {
        /// The target.
        dir: PathBuf,
    },
    /// The file system refused (full disk, permissions …); the earlier set is untouched.
    #[error("{}: {error}", path.display())]
    Io {
        /// The file or directory concerned.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> OutputSetError + '_ {
    move |error| OutputSetError::Io {
        path: path.to_path_buf(),
        error,
    }
}

/// An output set being written: files go to a staging directory until [`OutputSet::commit`].
/// Dropped without a commit, it removes the staging directory and leaves the target as it was.
#[derive(Debug)]
pub struct OutputSet {
    target: PathBuf,
    staging: PathBuf,
    committed: bool,
}

impl OutputSet {
    /// Checks that `target` may be replaced (new, an empty directory, or an earlier output set)
    /// without touching anything: lets a long command refuse an unusable `--out` before it
    /// runs. [`OutputSet::begin`] checks again.
    ///
    /// # Errors
    /// [`OutputSetError::NotAnOutputSet`], [`OutputSetError::NotADirectory`], or
    /// [`OutputSetError::Io`] when `target` cannot be inspected.
    pub fn check(target: &Path) -> Result<(), OutputSetError> {
        check_replaceable(target)
    }

    /// Starts a set for `target`, after checking it may be replaced and removing what killed
    /// runs into the same place left behind.
    ///
    /// # Errors
    /// [`OutputSetError`].
    pub fn begin(target: &Path) -> Result<Self, OutputSetError> {
        check_replaceable(target)?;
        let parent = parent_of(target);
        fs::create_dir_all(&parent).map_err(io(&parent))?;
        remove_stale(target);
        let staging = sibling(target, "staging", std::process::id());
        if staging.exists() {
            fs::remove_dir_all(&staging).map_err(io(&staging))?;
        }
        fs::create_dir(&staging).map_err(io(&staging))?;
        let set = OutputSet {
            target: target.to_path_buf(),
            staging,
            committed: false,
        };
        // Empty: a set's bytes on disk are its outputs'.
        set.write(MARKER_FILE, b"")?;
        Ok(set)
    }

    /// Writes `name` into the set: a file name, or a relative path such as `gis/a.geojson`
    /// whose folders are made as needed.
    ///
    /// # Errors
    /// [`OutputSetError::Io`].
    ///
    /// # Panics
    /// If `name` is absolute or climbs out of the set (`..`): names are the program's own.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, OutputSetError> {
        let path = self.staged(name);
        if let Some(folder) = path.parent()
            && folder != self.staging
        {
            fs::create_dir_all(folder).map_err(io(folder))?;
        }
        let mut f = fs::File::create(&path).map_err(io(&path))?;
        f.write_all(bytes).map_err(io(&path))?;
        f.sync_all().map_err(io(&path))?;
        Ok(self.target.join(name))
    }

    /// Where a writer of its own (a GeoTIFF writer, say) puts `name` inside the set: the staging
    /// path, its folders made. The file must be complete before [`OutputSet::commit`].
    ///
    /// # Errors
    /// [`OutputSetError::Io`].
    ///
    /// # Panics
    /// As [`OutputSet::write`].
    pub fn staging_path(&self, name: &str) -> Result<PathBuf, OutputSetError> {
        let path = self.staged(name);
        fs::create_dir_all(&path).map_err(io(&path))?;
        Ok(path)
    }

    /// `name` inside the staging directory.
    ///
    /// # Panics
    /// If `name` is absolute or climbs out of the set (`..`): names are the program's own.
    fn staged(&self, name: &str) -> PathBuf {
        let relative = Path::new(name);
        assert!(
            relative
                .components()
                .all(|c| matches!(c, std::path::Component::Normal(_))),
            "output name {name:?} must be a relative path inside the set"
        );
        self.staging.join(relative)
    }

    /// Puts the set in place of the earlier one, atomically.
    ///
    /// # Errors
    /// [`OutputSetError::Io`]; the earlier set is then still in place.
    pub fn commit(mut self) -> Result<(), OutputSetError> {
        sync_dir(&self.staging);
        let retired = if self.target.exists() {
            let retired = sibling(&self.target, "retired", std::process::id());
            swap_into_place(&self.staging, &self.target, &retired)?;
            Some(retired)
        } else {
            fs::rename(&self.staging, &self.target).map_err(io(&self.target))?;
            None
        };
        self.committed = true;
        sync_dir(&parent_of(&self.target));
        if let Some(retired) = retired {
            // The earlier set, now beside the target: removing it is housekeeping only.
            let _ = fs::remove_dir_all(retired);
        }
        Ok(())
    }
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.staging);
        }
    }
}

/// `target` may be replaced: missing, an empty directory, or an earlier output set.
fn check_replaceable(target: &Path) -> Result<(), OutputSetError> {
    let meta = match fs::symlink_metadata(target) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(io(target)(e)),
        Ok(m) => m,
    };
    if !meta.is_dir() {
        return Err(OutputSetError::NotADirectory {
            dir: target.to_path_buf(),
        });
    }
    if target.join(MARKER_FILE).is_file() {
        return Ok(());
    }
    let mut entries = fs::read_dir(target).map_err(io(target))?;
    if entries.next().is_none() {
        Ok(())
    } else {
        Err(OutputSetError::NotAnOutputSet {
            dir: target.to_path_buf(),
        })
    }
}

fn parent_of(target: &Path) -> PathBuf {
    match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn file_name_of(target: &Path) -> String {
    target
        .file_name()
        .map_or_else(|| "out".to_string(), |n| n.to_string_lossy().into_owned())
}

/// `.NAME.KIND-PID` beside `target`.
fn sibling(target: &Path, kind: &str, pid: u32) -> PathBuf {
    parent_of(target).join(format!(".{}.{kind}-{pid}", file_name_of(target)))
}

/// Removes staging and retired directories beside `target` whose process is gone, and puts a
/// retired set back if a run was killed between the two renames of the fallback swap.
fn remove_stale(target: &Path) {
    let parent = parent_of(target);
    let prefix = format!(".{}.", file_name_of(target));
    let Ok(entries) = fs::read_dir(&parent) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = name.strip_prefix(&prefix) else {
            continue;
        };
        let Some((kind, pid)) = rest.split_once('-') else {
            continue;
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        if !matches!(kind, "staging" | "retired") || process_alive(pid) {
            continue;
        }
        let path = entry.path();
        if kind == "retired" && !target.exists() {
            let _ = fs::rename(&path, target);
        } else {
            let _ = fs::remove_dir_all(&path);
        }
    }
}

/// Whether process `pid` still runs (Linux: `/proc/PID`; elsewhere assumed gone unless it is
/// this one).
fn process_alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    if Path::new("/proc/self").exists() {
        Path::new("/proc").join(pid.to_string()).exists()
    } else {
        false
    }
}

/// Exchanges `staging` and `target` in one step where the system can; otherwise renames the
/// target aside to `retired` and the staging directory into place (a kill between the two is
/// repaired by [`remove_stale`] on the next run).
fn swap_into_place(staging: &Path, target: &Path, retired: &Path) -> Result<(), OutputSetError> {
    #[cfg(target_os = "linux")]
    {
        if exchange(staging, target).is_ok() {
            // `staging` now names the earlier set.
            return fs::rename(staging, retired).map_err(io(retired));
        }
    }
    fs::rename(target, retired).map_err(io(target))?;
    if let Err(e) = fs::rename(staging, target) {
        let _ = fs::rename(retired, target);
        return Err(io(target)(e));
    }
    Ok(())
}

#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt as _;
    let ca = CString::new(a.as_os_str().as_bytes())?;
    let cb = CString::new(b.as_os_str().as_bytes())?;
    // SAFETY: both are valid NUL-terminated paths; renameat2 reads them and nothing else.
    let rc = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            ca.as_ptr(),
            libc::AT_FDCWD,
            cb.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if rc == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

/// Flushes a directory's entries to disk (best effort).
fn sync_dir(dir: &Path) {
    if let Ok(f) = fs::File::open(dir) {
        let _ = f.sync_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_replaces_the_earlier_one_whole() {
        let root = tempfile::tempdir().expect("tempdir");
        let out = root.path().join("out");
        let set = OutputSet::begin(&out).expect("begin");
        set.write("a.json", b"1").expect("write");
        set.write("b.csv", b"1").expect("write");
        set.commit().expect("commit");
        let set = OutputSet::begin(&out).expect("begin again");
        set.write("a.json", b"2").expect("write");
        set.commit().expect("commit");
        let mut names: Vec<String> = fs::read_dir(&out)
            .expect("list")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(names, [MARKER_FILE, "a.json"]);
        assert_eq!(fs::read(out.join("a.json")).expect("read"), b"2");
        // Nothing left beside it.
        assert_eq!(fs::read_dir(root.path()).expect("list").count(), 1);
    }

    #[test]
    fn an_uncommitted_set_leaves_the_earlier_one_and_no_staging() {
        let root = tempfile::tempdir().expect("tempdir");
        let out = root.path().join("out");
        let set = OutputSet::begin(&out).expect("begin");
        set.write("a.json", b"old").expect("write");
        set.commit().expect("commit");
        {
            let set = OutputSet::begin(&out).expect("begin");
            set.write("a.json", b"new").expect("write");
        }
        assert_eq!(fs::read(out.join("a.json")).expect("read"), b"old");
        assert_eq!(fs::read_dir(root.path()).expect("list").count(), 1);
    }

    #[test]
    fn a_directory_of_other_files_is_refused_and_stale_staging_removed() {
        let root = tempfile::tempdir().expect("tempdir");
        let mine = root.path().join("notes");
        fs::create_dir(&mine).expect("mkdir");
        fs::write(mine.join("thesis.tex"), b"x").expect("write");
        let e = OutputSet::begin(&mine).expect_err("refused");
        assert!(matches!(e, OutputSetError::NotAnOutputSet { .. }), "{e}");
        // A staging directory of a process that no longer exists.
        let out = root.path().join("out");
        let stale = root.path().join(".out.staging-4294967");
        fs::create_dir(&stale).expect("mkdir");
        OutputSet::begin(&out)
            .expect("begin")
            .commit()
            .expect("commit");
        assert!(!stale.exists());
    }
}
