//! Sweep directories for the hostile-input tests of issue 26: a complete sweep, and sweeps
//! interrupted after a given number of committed chunks, of the cheapest bundled scenario
//! (sols 717-719 under `ground`, one run per chunk), made in process and on a tmpfs when the
//! machine has one (`/dev/shm`: the sweep `fsync`s every chunk, which tmpfs makes free).

use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};

use std::process::Command;
use std::time::Duration;

use super::{output_within, root, solsim};

/// The scenario every fixture sweeps.
pub const SCENARIO: &str = "scenarios/crater-floor-717.toml";

/// A scenario and sweep spec, and a scratch directory for sweep directories.
pub struct Fixture {
    /// The loaded scenario.
    pub scenario: study::Scenario,
    /// `--runs RUNS --strategies ground --chunk-runs CHUNK`.
    pub spec: sweep::SweepSpec,
    /// Scratch space (removed on drop).
    pub tmp: tempfile::TempDir,
}

/// A scratch directory, on tmpfs where there is one.
pub fn scratch() -> tempfile::TempDir {
    let shm = Path::new("/dev/shm");
    if shm.is_dir() {
        tempfile::tempdir_in(shm).expect("tempdir in /dev/shm")
    } else {
        tempfile::tempdir().expect("tempdir")
    }
}

/// Generous for a command that answers in a second; a hang fails the test.
pub const LIMIT: Duration = Duration::from_secs(30);

/// What the progress callback panics with to interrupt a sweep.
struct Interrupt;

/// Keeps the panic hook from printing the interrupts (once per process; other panics print as
/// before).
fn quiet_interrupts() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let before = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !info.payload().is::<Interrupt>() {
                before(info);
            }
        }));
    });
}

impl Fixture {
    /// `runs` runs of `ground` in chunks of `chunk_runs`.
    pub fn new(runs: u64, chunk_runs: u64) -> Self {
        let scenario = study::Scenario::load_within(
            &root().join(SCENARIO),
            maps::MemoryBudget::new(maps::MemoryBudget::DEFAULT_BYTES),
        )
        .expect("the bundled scenario loads");
        let mut spec = sweep::SweepSpec::new(&scenario, runs);
        spec.strategies = vec![sim::Strategy::Ground];
        spec.baseline = Some(sim::Strategy::Ground);
        spec.chunk_runs = chunk_runs;
        Self {
            scenario,
            spec,
            tmp: scratch(),
        }
    }

    /// The command-line arguments of the same sweep (add `--out DIR`).
    pub fn cli_args(&self) -> Vec<String> {
        [
            "sweep",
            SCENARIO,
            "--runs",
            &self.spec.runs.to_string(),
            "--strategies",
            "ground",
            "--chunk-runs",
            &self.spec.chunk_runs.to_string(),
            "--quiet",
        ]
        .map(String::from)
        .to_vec()
    }

    /// Runs (or resumes, with `resume`) the sweep into `dir`.
    pub fn run(&self, dir: &Path, resume: bool) -> Result<sweep::SweepResult, sweep::SweepError> {
        sweep::run(&self.scenario, &self.spec, dir, resume, &|_, _| {})
    }

    /// A complete sweep in `tmp/name`.
    pub fn complete(&self, name: &str) -> PathBuf {
        let dir = self.tmp.path().join(name);
        self.run(&dir, false).expect("the sweep runs");
        settle(&dir);
        dir
    }

    /// A sweep in `tmp/name` interrupted once `committed` runs are committed, as a kill at that
    /// moment leaves it (the committer stops mid-sweep; with `committed` = all runs, before the
    /// output files are assembled). One worker thread, so the committed chunks are the first.
    pub fn killed(&self, name: &str, committed: u64) -> PathBuf {
        let dir = self.tmp.path().join(name);
        quiet_interrupts();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("pool");
        let outcome = std::panic::catch_unwind(AssertUnwindSafe(|| {
            pool.install(|| {
                sweep::run(&self.scenario, &self.spec, &dir, false, &|done, _| {
                    if done >= committed && done > 0 {
                        std::panic::panic_any(Interrupt);
                    }
                })
            })
        }));
        match outcome {
            Err(payload) if payload.is::<Interrupt>() => {
                settle(&dir);
                dir
            }
            Err(_) => panic!("the sweep panicked by itself"),
            Ok(r) => panic!("the sweep was not interrupted: {:?}", r.map(|r| r.runs_run)),
        }
    }
}

/// Waits until no process holds the lock an in-process sweep took on `dir`. The sweep has
/// released it, but a child another test forked while it was held shares the descriptor until
/// that child reaches `exec` (an instant, longer on a loaded machine): a `solsim` started on
/// `dir` meanwhile would be refused as "in use". util-linux `flock(1)` asks from outside.
fn settle(dir: &Path) {
    for _ in 0..1000 {
        let free = Command::new("flock")
            .args(["--nonblock", "--exclusive"])
            .arg(dir)
            .arg("true")
            .status()
            .expect("util-linux flock runs");
        if free.success() {
            return;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    panic!("{} stayed locked for 10 s after its sweep", dir.display());
}

/// Copies the files (and `chunks/`) of a sweep directory.
pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("mkdir");
    for e in std::fs::read_dir(from).expect("list") {
        let e = e.expect("entry");
        let target = to.join(e.file_name());
        if e.file_type().expect("type").is_dir() {
            copy_dir(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).expect("copy");
        }
    }
}

/// The names in a directory, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `Ok` when `dir` holds exactly the files of the complete sweep `reference`, byte for byte.
pub fn same_sweep(dir: &Path, reference: &Path) -> Result<(), String> {
    let (got, want) = (listing(dir), listing(reference));
    if got != want {
        return Err(format!("files {got:?}, expected {want:?}"));
    }
    for name in want {
        if std::fs::read(dir.join(&name)).ok() != std::fs::read(reference.join(&name)).ok() {
            return Err(format!("{name} differs from the uninterrupted sweep's"));
        }
    }
    Ok(())
}

/// Makes a FIFO at `path`.
pub fn mkfifo(path: &Path) {
    let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).expect("path");
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0, "mkfifo");
}

/// Exit 2 and one `error:` line holding every string of `must`.
pub fn refused(cmd: &mut Command, must: &[&str]) -> String {
    let o = output_within(cmd, LIMIT);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(!err.contains("panicked"), "{err}");
    for m in must {
        assert!(err.contains(m), "stderr lacks {m:?}: {err}");
    }
    err
}

/// `solsim sweep --resume` of the fixture's sweep into `dir`.
pub fn resume(f: &Fixture, dir: &Path) -> Command {
    let mut c = solsim();
    c.current_dir(root())
        .args(f.cli_args())
        .arg("--resume")
        .arg("--out")
        .arg(dir);
    c
}
