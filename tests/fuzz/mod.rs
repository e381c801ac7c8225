//! A small seeded mutation fuzzer for solsim's parsers, run by `cargo test`.
//!
//! Each [`Target`] is a parser behind a closure that returns `Ok(())` for an accepted input and
//! `Err(kind)` for a rejected one. [`Fuzzer::run`] feeds it its seeds, then mutants of a growing
//! pool ([`mutate::Mutator`]): a mutant that is accepted, or rejected with a kind not seen
//! before, joins the pool, so the fuzzer works its way past the syntax errors into the
//! validation behind them. Everything is drawn from one seeded `ChaCha8Rng` per target, so a run
//! is reproducible from (`SOLSIM_FUZZ_SEED`, target name, input number).
//!
//! Per input it checks: no panic (caught with `catch_unwind`, default hook silenced), time under
//! the target's limit (a watchdog ends the process on a true hang, after saving the input), peak
//! heap under the target's limit and no single allocation over
//! [`memory::MAX_SINGLE_ALLOC_BYTES`] (a counting allocator; the process's address space is
//! capped too). A failing input is saved in the fuzzer's temporary directory (kept) and shown,
//! truncated, in the test failure.
//!
//! Environment:
//! - `SOLSIM_FUZZ_SEED` (u64, default [`DEFAULT_SEED`]): another run of mutants;
//! - `SOLSIM_FUZZ_SCALE` (default 1): multiplies every input count (10 for a long local run);
//! - `SOLSIM_FUZZ_MAX_LEN=<bytes>`: overrides every target's longest mutant (CI keeps them short
//!   to run 20 000 inputs per parser in its budget);
//! - `SOLSIM_FUZZ_ONLY=<target>`: runs one target;
//! - `SOLSIM_FUZZ_DUMP=<n>`: saves input number `n` of each target and keeps the scratch
//!   directory (to reproduce an input named in a report);
//! - `SOLSIM_FUZZ_KINDS=1`: lists the rejection kinds of each target;
//! - `SOLSIM_FUZZ_SAVE_EACH=1`: writes every input to `current-input` in the scratch directory
//!   before running it, so an input that kills the process (a stack overflow) can be recovered.

pub mod kinds;
pub mod memory;
pub mod mutate;
pub mod rasters;
pub mod seeds;

use std::collections::BTreeMap;
use std::ffi::CString;
use std::io::Write as _;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub use mutate::Format;

#[global_allocator]
static ALLOCATOR: memory::Counting = memory::Counting;

/// Base seed of a run (each target's stream mixes in its name).
pub const DEFAULT_SEED: u64 = 0x5017_5133_0010_0008;

/// Time after which a still-running input is a hang: the watchdog saves it and ends the process.
const HANG_LIMIT: Duration = Duration::from_secs(20);

/// Inputs added to a target's pool at most, and the largest input kept there.
const MAX_POOL: usize = 1024;
const MAX_POOL_INPUT_BYTES: usize = 32 << 10;

/// Failures described in full per target (the rest are counted).
const MAX_REPORTED_FAILURES: usize = 5;

/// A parser under test: `Ok(())` for an accepted input, `Err(kind)` for a rejected one.
pub type Parser<'a> = Box<dyn FnMut(&[u8]) -> Result<(), String> + 'a>;

/// One parser under test.
pub struct Target<'a> {
    /// Short name, used in the report and in saved file names.
    pub name: &'static str,
    /// Input format, for the structure-aware mutations.
    pub format: Format,
    /// Inputs to run (seeds included), before `SOLSIM_FUZZ_SCALE`.
    pub inputs: usize,
    /// Starting inputs, run first as they are.
    pub seeds: Vec<Vec<u8>>,
    /// Tokens worth inserting.
    pub dict: Vec<Vec<u8>>,
    /// Longest mutant, bytes.
    pub max_len: usize,
    /// Value-level mutations only (see [`mutate::Mutator::gentle`]).
    pub gentle: bool,
    /// Longest time one input may take.
    pub time_limit: Duration,
    /// Most heap one input may hold at once above what was live before it, bytes.
    pub memory_limit_bytes: usize,
    /// The parser: `Ok(())` accepted, `Err(kind)` rejected (kinds are counted).
    pub run: Parser<'a>,
}

/// What one target's run did.
#[derive(Debug, Default)]
pub struct Stats {
    /// Target name.
    pub name: &'static str,
    /// Inputs run.
    pub inputs: usize,
    /// Inputs the parser accepted.
    pub accepted: usize,
    /// Inputs the parser rejected with an error.
    pub rejected: usize,
    /// Rejections by kind.
    pub kinds: BTreeMap<String, usize>,
    /// Inputs that panicked.
    pub panics: usize,
    /// Inputs over the time limit.
    pub slow: usize,
    /// Inputs over the memory limits.
    pub over_memory: usize,
    /// Slowest input.
    pub max_time: Duration,
    /// All inputs.
    pub total_time: Duration,
    /// The slowest input's number.
    pub max_time_input: usize,
    /// Largest peak heap of one input, bytes.
    pub max_peak_bytes: usize,
    /// The number of the input with the largest peak heap.
    pub max_peak_input: usize,
    /// Longest input, bytes.
    pub max_input_bytes: usize,
    /// Pool size at the end.
    pub pool: usize,
}

/// The input being run, for the watchdog and the allocator's refusal path.
struct Current {
    target: &'static str,
    index: usize,
    started: Option<Instant>,
    input: Vec<u8>,
}

static CURRENT: Mutex<Current> = Mutex::new(Current {
    target: "",
    index: 0,
    started: None,
    input: Vec::new(),
});
/// Where the allocator's refusal path saves the current input (a C string: it cannot allocate).
static REFUSAL_DUMP_PATH: OnceLock<CString> = OnceLock::new();
static IN_INPUT: AtomicBool = AtomicBool::new(false);
static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);
static STOP_WATCHDOG: AtomicBool = AtomicBool::new(false);

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Called by the allocator before it refuses a huge request: saves the current input and says
/// so on stderr, allocating nothing (the process may abort right after).
pub(crate) fn dump_current_input_raw(size: usize) {
    let Ok(current) = CURRENT.try_lock() else {
        return;
    };
    let mut msg = [0u8; 512];
    let mut w = &mut msg[..];
    let _ = write!(
        w,
        "\nfuzz_parsers: {} input #{} requested {size} bytes in one allocation (refused)",
        current.target, current.index
    );
    if let Some(path) = REFUSAL_DUMP_PATH.get() {
        // SAFETY: a NUL-terminated path and a live buffer of the given length.
        unsafe {
            let fd = libc::open(
                path.as_ptr(),
                libc::O_WRONLY | libc::O_CREAT | libc::O_TRUNC,
                0o644,
            );
            if fd >= 0 {
                let _ = libc::write(fd, current.input.as_ptr().cast(), current.input.len());
                libc::close(fd);
            }
        }
        let _ = write!(w, "; input saved to {}", path.to_str().unwrap_or("<path>"));
    }
    let _ = writeln!(w);
    let len = 512 - w.len();
    // SAFETY: writing a live stack buffer to stderr.
    unsafe {
        let _ = libc::write(2, msg.as_ptr().cast(), len);
    }
}

/// A text input shown in a failure: escaped, at most 1500 bytes.
pub fn preview(input: &[u8], text: bool) -> String {
    const MAX: usize = 1500;
    let shown = &input[..input.len().min(MAX)];
    let more = if input.len() > MAX {
        format!(" … ({} bytes in all)", input.len())
    } else {
        String::new()
    };
    if text {
        format!("{:?}{more}", String::from_utf8_lossy(shown))
    } else {
        let hex: Vec<String> = shown.iter().take(256).map(|b| format!("{b:02x}")).collect();
        format!(
            "hex {}{}",
            hex.join(""),
            if input.len() > 256 { " …" } else { "" }
        )
    }
}

fn fnv1a(s: &str) -> u64 {
    s.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Runs targets, collects their statistics and failures, and reports them.
pub struct Fuzzer {
    /// Scratch directory: parser input files and saved failures (kept when the test fails).
    pub dir: tempfile::TempDir,
    seed: u64,
    scale: f64,
    save_each: bool,
    keep: bool,
    failures: Vec<String>,
    stats: Vec<Stats>,
    started: Instant,
    watchdog: Option<std::thread::JoinHandle<()>>,
}

impl Fuzzer {
    /// Caps the address space, silences the panic hook during inputs, starts the watchdog.
    pub fn new() -> Self {
        memory::limit_address_space();
        let dir = tempfile::Builder::new()
            .prefix("solsim-fuzz-")
            .tempdir()
            .expect("temporary directory");
        let dump = dir.path().join("refused-allocation-input");
        let _ = REFUSAL_DUMP_PATH
            .set(CString::new(dump.to_string_lossy().into_owned()).expect("temp path without NUL"));
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if IN_INPUT.load(Ordering::SeqCst) {
                lock(&LAST_PANIC).get_or_insert_with(|| info.to_string());
            } else {
                previous(info);
            }
        }));
        let hang_dir = dir.path().to_path_buf();
        STOP_WATCHDOG.store(false, Ordering::SeqCst);
        let watchdog = std::thread::spawn(move || watchdog(&hang_dir));
        let seed = std::env::var("SOLSIM_FUZZ_SEED")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(DEFAULT_SEED);
        let scale = std::env::var("SOLSIM_FUZZ_SCALE")
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .filter(|s| s.is_finite() && *s > 0.0)
            .unwrap_or(1.0);
        let save_each = std::env::var("SOLSIM_FUZZ_SAVE_EACH").is_ok_and(|v| v == "1");
        let fuzzer = Self {
            dir,
            seed,
            scale,
            save_each,
            keep: false,
            failures: Vec::new(),
            stats: Vec::new(),
            started: Instant::now(),
            watchdog: Some(watchdog),
        };
        log(&format!(
            "fuzz_parsers: seed {seed:#x}, scale {scale}, scratch {}",
            fuzzer.dir.path().display()
        ));
        fuzzer
    }

    /// Runs one target to its input count and prints its line of the report.
    pub fn run(&mut self, mut target: Target<'_>) {
        if std::env::var("SOLSIM_FUZZ_ONLY").is_ok_and(|only| only != target.name) {
            return;
        }
        let dump_index: Option<usize> = std::env::var("SOLSIM_FUZZ_DUMP")
            .ok()
            .and_then(|v| v.parse().ok());
        let inputs = ((target.inputs as f64 * self.scale).round() as usize).max(target.seeds.len());
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed ^ fnv1a(target.name));
        let max_len = std::env::var("SOLSIM_FUZZ_MAX_LEN")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(target.max_len);
        let mutator = mutate::Mutator {
            format: target.format,
            dict: &target.dict,
            max_len,
            gentle: target.gentle,
        };
        let mut pool = target.seeds.clone();
        let mut stats = Stats {
            name: target.name,
            ..Stats::default()
        };
        let mut failures = 0usize;
        let started = Instant::now();
        for index in 0..inputs {
            let (input, ops) = if index < target.seeds.len() {
                (target.seeds[index].clone(), vec!["seed"])
            } else {
                let base = &pool[rng.random_range(0..pool.len())];
                mutator.mutate(&mut rng, base, &pool)
            };
            {
                let mut c = lock(&CURRENT);
                c.target = target.name;
                c.index = index;
                c.input.clear();
                c.input.extend_from_slice(&input);
                c.started = Some(Instant::now());
            }
            if dump_index == Some(index) {
                let saved = self
                    .dir
                    .path()
                    .join(format!("{}-{index}.input", target.name));
                std::fs::write(&saved, &input).expect("save input");
                log(&format!(
                    "fuzz_parsers: saved {} (mutations {ops:?})",
                    saved.display()
                ));
                self.keep = true;
            }
            if self.save_each {
                std::fs::write(self.dir.path().join("current-input"), &input).expect("save input");
            }
            *lock(&LAST_PANIC) = None;
            IN_INPUT.store(true, Ordering::SeqCst);
            let baseline = memory::start_input();
            let t0 = Instant::now();
            let result = catch_unwind(AssertUnwindSafe(|| (target.run)(&input)));
            let elapsed = t0.elapsed();
            let (peak, huge) = memory::finish_input(baseline);
            IN_INPUT.store(false, Ordering::SeqCst);
            lock(&CURRENT).started = None;

            stats.inputs += 1;
            stats.total_time += elapsed;
            if elapsed > stats.max_time {
                stats.max_time = elapsed;
                stats.max_time_input = index;
            }
            if peak > stats.max_peak_bytes {
                stats.max_peak_bytes = peak;
                stats.max_peak_input = index;
            }
            stats.max_input_bytes = stats.max_input_bytes.max(input.len());
            let mut problems = Vec::new();
            match result {
                Ok(Ok(())) => {
                    stats.accepted += 1;
                    if index >= target.seeds.len()
                        && input.len() <= MAX_POOL_INPUT_BYTES
                        && pool.len() < MAX_POOL
                        && rng.random_ratio(1, 8)
                    {
                        pool.push(input.clone());
                    }
                }
                Ok(Err(kind)) => {
                    stats.rejected += 1;
                    let n = stats.kinds.entry(kind).or_insert(0);
                    *n += 1;
                    if *n == 1 && input.len() <= MAX_POOL_INPUT_BYTES && pool.len() < MAX_POOL {
                        pool.push(input.clone());
                    }
                }
                Err(payload) => {
                    stats.panics += 1;
                    let message = lock(&LAST_PANIC).take().unwrap_or_else(|| {
                        payload
                            .downcast_ref::<&str>()
                            .map(|s| (*s).to_owned())
                            .or_else(|| payload.downcast_ref::<String>().cloned())
                            .unwrap_or_else(|| "<non-string panic payload>".to_owned())
                    });
                    problems.push(format!("panicked: {message}"));
                }
            }
            if elapsed > target.time_limit {
                stats.slow += 1;
                problems.push(format!(
                    "took {elapsed:.2?} (limit {:?})",
                    target.time_limit
                ));
            }
            if let Some(bytes) = huge {
                stats.over_memory += 1;
                problems.push(format!("requested {bytes} bytes in one allocation"));
            } else if peak > target.memory_limit_bytes {
                stats.over_memory += 1;
                problems.push(format!(
                    "held {peak} bytes at once (limit {})",
                    target.memory_limit_bytes
                ));
            }
            if !problems.is_empty() {
                failures += 1;
                if failures <= MAX_REPORTED_FAILURES {
                    let saved = self
                        .dir
                        .path()
                        .join(format!("{}-{index}.input", target.name));
                    let _ = std::fs::write(&saved, &input);
                    let message = format!(
                        "{} input #{index} (mutations {ops:?}, {} bytes, saved to {}): {}\n  input: {}",
                        target.name,
                        input.len(),
                        saved.display(),
                        problems.join("; "),
                        preview(&input, target.format.is_text()),
                    );
                    log(&format!("fuzz_parsers: FAILURE {message}"));
                    self.failures.push(message);
                }
            }
        }
        stats.pool = pool.len();
        let wall = started.elapsed();
        log(&format!(
            "fuzz_parsers: {:<16} inputs {:>6}  accepted {:>6}  rejected {:>6}  kinds {:>4}  panics {}  slow {}  over-memory {}  max {:>6.1} ms (#{})  total {:>5.1} s  peak heap {:>5.1} MiB (#{})  max input {} B  pool {}",
            stats.name,
            stats.inputs,
            stats.accepted,
            stats.rejected,
            stats.kinds.len(),
            stats.panics,
            stats.slow,
            stats.over_memory,
            stats.max_time.as_secs_f64() * 1e3,
            stats.max_time_input,
            wall.as_secs_f64(),
            stats.max_peak_bytes as f64 / f64::from(1 << 20),
            stats.max_peak_input,
            stats.max_input_bytes,
            stats.pool,
        ));
        if std::env::var("SOLSIM_FUZZ_KINDS").is_ok_and(|v| v == "1") {
            for (kind, n) in &stats.kinds {
                log(&format!("fuzz_parsers:   {:>6} × {kind}", n));
            }
        }
        self.stats.push(stats);
    }

    /// Stops the watchdog, restores the panic hook, prints the totals, and fails the test with
    /// every failure found (keeping the scratch directory).
    pub fn finish(mut self) -> Vec<Stats> {
        STOP_WATCHDOG.store(true, Ordering::SeqCst);
        if let Some(w) = self.watchdog.take() {
            let _ = w.join();
        }
        drop(std::panic::take_hook());
        let total: usize = self.stats.iter().map(|s| s.inputs).sum();
        log(&format!(
            "fuzz_parsers: {} targets, {total} inputs in {:.1} s, {} failures",
            self.stats.len(),
            self.started.elapsed().as_secs_f64(),
            self.failures.len()
        ));
        if self.keep && self.failures.is_empty() {
            let kept = self.dir.keep();
            log(&format!(
                "fuzz_parsers: scratch directory kept: {}",
                kept.display()
            ));
            return std::mem::take(&mut self.stats);
        }
        if !self.failures.is_empty() {
            let kept = self.dir.keep();
            panic!(
                "{} fuzz failure(s); inputs kept in {}:\n{}",
                self.failures.len(),
                kept.display(),
                self.failures.join("\n")
            );
        }
        std::mem::take(&mut self.stats)
    }
}

/// Ends the process on an input running past [`HANG_LIMIT`], after saving and showing it.
fn watchdog(dir: &std::path::Path) {
    while !STOP_WATCHDOG.load(Ordering::SeqCst) {
        std::thread::sleep(Duration::from_millis(100));
        let c = lock(&CURRENT);
        if let Some(started) = c.started
            && started.elapsed() > HANG_LIMIT
        {
            let saved: PathBuf = dir.join(format!("hang-{}-{}.input", c.target, c.index));
            let _ = std::fs::write(&saved, &c.input);
            let kept = dir.to_path_buf();
            log(&format!(
                "fuzz_parsers: HANG {} input #{} still running after {HANG_LIMIT:?}; saved to {} (directory kept: {})\n  input: {}",
                c.target,
                c.index,
                saved.display(),
                kept.display(),
                preview(
                    &c.input,
                    !c.input.starts_with(b"\x89PNG")
                        && !c.input.starts_with(b"II")
                        && !c.input.starts_with(b"MM")
                ),
            ));
            std::process::exit(101);
        }
    }
}

/// One line on the real stderr, past libtest's capture, so it shows in the CI log even when the
/// test passes.
pub fn log(line: &str) {
    let mut err = std::io::stderr().lock();
    let _ = writeln!(err, "{line}");
}
