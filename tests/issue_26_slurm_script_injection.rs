//! Issue 26, finding 1: `solsim sweep slurm` wrote the scenario path and `--out` into a bash
//! script whose job scripts were here-documents ending at a line `SOLSIM_JOB`, and the raw path
//! into a comment. A scenario at `$'D/scen\nSOLSIM_JOB\ntouch D/pwned\n: <<\'SOLSIM_JOB\'\n.toml'`
//! closed the here-document early, so `bash s.sh` ran `touch D/pwned`.
//!
//! Now every path and name that reaches the script is refused when it holds a control
//! character or is not UTF-8 (one error line naming the argument, exit 2), and the script is
//! safe regardless: the job scripts are written by `printf '%s\n'` of single-quoted lines whose
//! values are single-quoted again, so no byte of a path can become code. Slurm's own reading
//! of `--output` is respected too: `%` in the directory is passed as `%%` (checked on a real
//! cluster: the logs land in `OUT/slurm`), and an `--out` holding a backslash, which Slurm
//! cannot name log files in (the job fails to launch), is refused.
//!
//! The canary test generates 1,000 seeded hostile scenario paths, `--out` directories,
//! `--solsim` paths and scenario names (newlines, `SOLSIM_JOB`, `EOF`, quotes, `'\''`, `$()`,
//! backticks, `;`, `&`, `|`, globs, a leading `-`, spaces, escape sequences, bidi overrides,
//! non-UTF-8 bytes, long components), each payload touching `$CANARY`. Every accepted script
//! is run by bash under a fake `sbatch` that records its arguments, then the job scripts it
//! wrote are run with a fake `solsim` that records its argv: the canary must never exist, and
//! the jobs must run exactly the scenario and `--out` asked for, byte for byte.
//! Cost: some 41 % of the cases are accepted and run (8 processes each: solsim, the submit
//! script, two sbatch, the shard and merge jobs and their two solsims). 1,000 cases took
//! 22-30 s on 2 cores shared with other builds (load average 7-9), on a tiny 40 × 40 px map
//! generated once (a bundled scenario costs 0.25-3 s per `solsim sweep slurm` to load), in a
//! tmpfs where there is one (on a busy disk, creating and removing the 10,000 small files
//! cost another 20-25 s).
#![cfg(unix)]

use crate::common;

use std::ffi::{OsStr, OsString};
use std::os::unix::ffi::{OsStrExt as _, OsStringExt as _};
use std::os::unix::fs::PermissionsExt as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use common::{output_within, stderr, tiny};
use rand::{RngExt as _, SeedableRng as _};
use rand_chacha::ChaCha8Rng;

/// How long one command may take (a hang is a bug).
const LIMIT: Duration = Duration::from_secs(60);
/// Cases of the canary test.
const CASES: u64 = 1_000;

/// A tiny map, a scenario over it and the fake `sbatch` and `solsim`, shared by every case.
struct Kit {
    dir: tempfile::TempDir,
}

impl Kit {
    fn new() -> Kit {
        // Some ten thousand small files: in memory where the machine has a tmpfs (on a busy
        // disk, creating and removing them took 20-25 s of the test's time).
        let shm = Path::new("/dev/shm");
        let dir = if shm.is_dir() {
            tempfile::tempdir_in(shm)
        } else {
            tempfile::tempdir()
        }
        .expect("tempdir");
        let d = dir.path();
        tiny::tiny_map(d);
        std::fs::write(d.join("zones.geojson"), tiny::NO_ZONES).expect("zones");
        std::fs::create_dir(d.join("bin")).expect("bin");
        // Records each call's arguments in $SBATCH_RECORD.N and prints a job id as
        // `sbatch --parsable` does (with a cluster name after `;`).
        executable(
            &d.join("bin/sbatch"),
            "#!/bin/sh\nn=0\nwhile [ -e \"$SBATCH_RECORD.$n\" ]; do n=$((n+1)); done\n\
             printf '%s\\0' \"$@\" > \"$SBATCH_RECORD.$n\"\necho \"424$n;cluster\"\n",
        );
        // Records how it was called ($0) and its arguments.
        executable(
            &d.join("fake-solsim"),
            "#!/bin/sh\nprintf '%s\\0' \"$0\" \"$@\" > \"$SOLSIM_RECORD\"\n",
        );
        Kit { dir }
    }

    fn path(&self) -> &Path {
        self.dir.path()
    }

    /// The scenario text named `name`, over the kit's map.
    fn scenario(&self, name: &str) -> String {
        let d = self.path();
        tiny::tiny_scenario(&d.join("map"), &d.join("zones.geojson"), name, "")
    }
}

fn executable(path: &Path, text: &str) {
    std::fs::write(path, text).expect("write");
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).expect("chmod");
}

/// A command with a clean environment: the fake `sbatch` first on PATH, and `$CANARY`, the
/// file every payload touches.
fn clean(program: impl AsRef<OsStr>, kit: &Kit, case: &Path) -> Command {
    let mut c = Command::new(program);
    c.env_clear()
        .env(
            "PATH",
            format!("{}:/usr/bin:/bin", kit.path().join("bin").display()),
        )
        .env("CANARY", case.join("canary"))
        .env("SBATCH_RECORD", case.join("sbatch"))
        .env("SOLSIM_RECORD", case.join("argv"))
        .current_dir(case);
    c
}

/// The NUL-separated fields a fake recorded.
fn record(path: &Path) -> Vec<OsString> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut fields: Vec<OsString> = bytes
        .split(|&b| b == 0)
        .map(|f| OsString::from_vec(f.to_vec()))
        .collect();
    assert_eq!(fields.pop(), Some(OsString::new()), "NUL-terminated");
    fields
}

fn os(parts: &[&OsStr]) -> OsString {
    parts.iter().fold(OsString::new(), |mut s, p| {
        s.push(p);
        s
    })
}

/// Whether a terminal, a script or an XML document may not hold `c` as it is (the rule
/// `maps::input_file::is_unsafe_char` implements, restated so the test does not trust it).
fn unsafe_char(c: char) -> bool {
    c.is_control() || matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
}

/// Whether `s` may reach the script: UTF-8 without unsafe characters.
fn script_safe(s: &OsStr) -> bool {
    s.to_str().is_some_and(|t| !t.chars().any(unsafe_char))
}

/// Hostile pieces that are text a script may hold: shell syntax, quotes, here-document
/// terminators, payloads touching `$CANARY`, globs, a leading `-`, unicode.
const SHELL_FRAGMENTS: &[&str] = &[
    "SOLSIM_JOB",
    "EOF",
    "<<'SOLSIM_JOB'",
    ": <<'EOF'",
    "'",
    "\"",
    "'\\''",
    "'\\''$(touch $CANARY)'\\''",
    "\\",
    "`touch $CANARY`",
    "$(touch $CANARY)",
    "'$(touch $CANARY)'",
    "\"$(touch $CANARY)\"",
    "${CANARY:+$(touch $CANARY)}",
    ";touch $CANARY;",
    "&touch $CANARY&",
    "|touch $CANARY|",
    "&&touch $CANARY",
    "||touch $CANARY",
    "$CANARY",
    "*",
    "?",
    "[a-z]",
    "{a,b}",
    "~",
    "!",
    "#",
    "%",
    "%s%n",
    "-",
    "--out",
    " ",
    "é",
    "日本語",
    "🚀",
    "$'\\n'",
    ">",
    "<(touch $CANARY)",
    "=",
    "x",
    "shard-0-of-2",
];

/// Pieces a script may not hold: newlines that end a here-document, carriage returns,
/// escape sequences, other control characters, bidi overrides.
const CONTROL_FRAGMENTS: &[&str] = &[
    "\n",
    "\r",
    "\r\n",
    "\t",
    "\u{b}",
    "\u{1b}[2J",
    "\u{1b}]0;pwned\u{7}",
    "\u{7f}",
    "\u{85}",
    "\u{202e}",
    "\u{2066}",
    "\nSOLSIM_JOB\ntouch \"$CANARY\"\n: <<'SOLSIM_JOB'\n",
    "\nEOF\ntouch $CANARY\n",
    "\ntouch $CANARY\n",
];

/// 1-5 shell fragments, and with probability 1/8 one control fragment among them.
fn fragments(rng: &mut ChaCha8Rng) -> Vec<&'static str> {
    let mut parts: Vec<&str> = (0..rng.random_range(1..=5))
        .map(|_| SHELL_FRAGMENTS[rng.random_range(0..SHELL_FRAGMENTS.len())])
        .collect();
    if rng.random_bool(0.125) {
        let at = rng.random_range(0..=parts.len());
        parts.insert(
            at,
            CONTROL_FRAGMENTS[rng.random_range(0..CONTROL_FRAGMENTS.len())],
        );
    }
    parts
}

/// A hostile path component: [`fragments`], sometimes a leading `-`, a long run or non-UTF-8
/// bytes; never empty, `.`, `..` or holding `/`, at most 240 bytes.
fn component(rng: &mut ChaCha8Rng) -> OsString {
    let mut bytes = Vec::new();
    if rng.random_bool(0.15) {
        bytes.push(b'-');
    }
    for f in fragments(rng) {
        bytes.extend_from_slice(f.as_bytes());
    }
    if rng.random_bool(0.05) {
        bytes.extend(std::iter::repeat_n(b'a', rng.random_range(100..200)));
    }
    if rng.random_bool(0.03) {
        bytes.extend_from_slice(b"\xff\xfe");
    }
    bytes.truncate(240);
    if bytes == b"." || bytes == b".." {
        bytes.push(b'x');
    }
    OsString::from_vec(bytes)
}

/// A hostile scenario name the loader takes apart from its characters: at most 60
/// characters, without `/` or `\`, not blank.
fn hostile_name(rng: &mut ChaCha8Rng) -> String {
    let name: String = fragments(rng).concat();
    format!("n{}", name.replace(['/', '\\'], "_"))
        .chars()
        .take(60)
        .collect()
}

/// One generated case: what `solsim sweep slurm` is given.
struct Case {
    dir: PathBuf,
    name: String,
    /// The scenario file, absolute.
    scenario: PathBuf,
    /// As given on the command line (absolute or `./`-relative to `dir`).
    scenario_arg: OsString,
    out_arg: Option<OsString>,
    solsim_arg: OsString,
}

impl Case {
    fn generate(kit: &Kit, index: u64) -> Case {
        let mut rng = ChaCha8Rng::seed_from_u64(0x26_0001 ^ (index << 8));
        let dir = kit.path().join(format!("case-{index}"));
        std::fs::create_dir(&dir).expect("case dir");
        let name = if rng.random_bool(0.25) {
            hostile_name(&mut rng)
        } else {
            "tiny".to_owned()
        };
        // A path under `dir`: `top/C1[/C2]`, absolute or `./`-relative.
        let hostile_path = |rng: &mut ChaCha8Rng, top: &str, leaf: Option<&str>| {
            let mut rel = PathBuf::from(top);
            for _ in 0..rng.random_range(1..=2) {
                rel.push(component(rng));
            }
            if let Some(leaf) = leaf {
                let mut last = rel.file_name().expect("a name").to_owned();
                last.push(leaf);
                rel.set_file_name(last);
            }
            let arg = if rng.random_bool(0.3) {
                os(&[OsStr::new("./"), rel.as_os_str()])
            } else {
                dir.join(&rel).into_os_string()
            };
            (dir.join(rel), arg)
        };
        let leaf = rng.random_bool(0.5).then_some(".toml");
        let (scenario, scenario_arg) = hostile_path(&mut rng, "s", leaf);
        std::fs::create_dir_all(scenario.parent().expect("parent")).expect("scenario dir");
        std::fs::write(&scenario, kit.scenario(&name)).expect("scenario");
        let out_arg = rng
            .random_bool(0.8)
            .then(|| hostile_path(&mut rng, "o", None).1);
        // Always a fake solsim, so the job scripts can be run: at a hostile path, or the kit's.
        let solsim_arg = if rng.random_bool(0.4) {
            let (path, arg) = hostile_path(&mut rng, "b", None);
            std::fs::create_dir_all(path.parent().expect("parent")).expect("solsim dir");
            std::fs::hard_link(kit.path().join("fake-solsim"), &path).expect("link");
            arg
        } else {
            kit.path().join("fake-solsim").into_os_string()
        };
        Case {
            dir,
            name,
            scenario,
            scenario_arg,
            out_arg,
            solsim_arg,
        }
    }

    /// `path` (as given) made absolute from the case directory.
    fn absolute(&self, arg: &OsStr) -> PathBuf {
        match arg.as_bytes().strip_prefix(b"./") {
            Some(rel) => self.dir.join(OsStr::from_bytes(rel)),
            None => PathBuf::from(arg),
        }
    }

    /// The argument `solsim sweep slurm` must refuse, with its label in the error, if any.
    fn refused(&self) -> Option<&'static str> {
        let out_default = Path::new("sweep-out").join(format!("{}-slurm", self.name));
        if !script_safe(&self.scenario_arg) {
            Some("SCENARIO")
        } else if self.out_arg.as_deref().is_some_and(|o| !script_safe(o)) {
            Some("--out")
        } else if !script_safe(&self.solsim_arg) {
            Some("--solsim")
        } else if !script_safe(self.name.as_ref()) || !script_safe(out_default.as_os_str()) {
            Some("name")
        } else if self
            .out_arg
            .as_deref()
            .is_some_and(|o| o.as_bytes().contains(&b'\\'))
        {
            // Slurm's log file names cannot hold one.
            Some("--out")
        } else {
            None
        }
    }
}

fn assert_no_control_bytes(what: &str, bytes: &[u8]) {
    let text = String::from_utf8_lossy(bytes);
    let bad = text
        .trim_end_matches('\n')
        .chars()
        .find(|&c| unsafe_char(c) && c != '\n');
    assert!(bad.is_none(), "{what} holds {bad:?}:\n{text}");
}

/// Runs one case; returns whether the script was accepted.
fn run_case(kit: &Kit, case: &Case) -> bool {
    let canary = case.dir.join("canary");
    let mut cmd = clean(env!("CARGO_BIN_EXE_solsim"), kit, &case.dir);
    cmd.args(["sweep", "slurm"])
        .arg(&case.scenario_arg)
        .args(["--runs", "4", "--shards", "2", "--strategies", "ground"])
        .args(["--baseline", "none"]);
    if let Some(out) = &case.out_arg {
        cmd.arg("--out").arg(out);
    }
    cmd.arg("--solsim").arg(&case.solsim_arg);
    let o = output_within(&mut cmd, LIMIT);
    let context = format!(
        "scenario {:?}, --out {:?}, --solsim {:?}, name {:?}",
        case.scenario_arg, case.out_arg, case.solsim_arg, case.name
    );
    if let Some(label) = case.refused() {
        if o.status.success() {
            // Accepted where it must not be: run the script, so that a payload shows as the
            // canary rather than only as a wrong exit code.
            let script = case.dir.join("submit.sh");
            std::fs::write(&script, &o.stdout).expect("script");
            let _ = output_within(clean("bash", kit, &case.dir).arg(&script), LIMIT);
            assert!(
                !canary.exists(),
                "{context}: accepted, and its script ran a payload (the canary exists)"
            );
        }
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{context}: exit; stderr {err}");
        assert!(
            o.stdout.is_empty(),
            "{context}: a script for a refused case"
        );
        assert!(
            err.starts_with("error: ") && err.trim_end().lines().count() == 1,
            "{context}: one error line expected:\n{err}"
        );
        assert!(err.contains(label), "{context}: {label} not named:\n{err}");
        assert!(
            err.contains("control characters")
                || err.contains("UTF-8")
                || err.contains("backslash"),
            "{context}: {err}"
        );
        assert_no_control_bytes("the error", &o.stderr);
        assert!(!canary.exists(), "{context}: the canary exists");
        return false;
    }
    assert!(o.status.success(), "{context}: {}", stderr(&o));
    assert_no_control_bytes("the script", &o.stdout);
    let script = case.dir.join("submit.sh");
    std::fs::write(&script, &o.stdout).expect("script");
    let text = String::from_utf8_lossy(&o.stdout);

    let submitted = output_within(clean("bash", kit, &case.dir).arg(&script), LIMIT);
    assert!(
        !canary.exists(),
        "{context}: the submit script made the canary:\n{text}"
    );
    assert!(
        submitted.status.success(),
        "{context}: bash submit.sh: {}\n{text}",
        stderr(&submitted)
    );
    assert_eq!(
        String::from_utf8_lossy(&submitted.stdout),
        "array job 4240\nmerge job 4241\n",
        "{context}"
    );

    let scenario = std::fs::canonicalize(&case.scenario).expect("canonical scenario");
    let out = match &case.out_arg {
        Some(o) => case.absolute(o),
        None => case
            .dir
            .join("sweep-out")
            .join(format!("{}-slurm", case.name)),
    };
    let solsim = case.absolute(&case.solsim_arg);
    let at = |tail: &str| os(&[out.as_os_str(), OsStr::new(tail)]);
    let strs = |v: &[&str]| v.iter().map(OsString::from).collect::<Vec<_>>();
    let mut array = strs(&[
        "--parsable",
        "--job-name=solsim-sweep",
        "--array=0-1",
        "--cpus-per-task=1",
    ]);
    // sbatch reads `%` in --output as a pattern: `%%` is a literal one.
    let logs = OsString::from_vec(out.as_os_str().as_bytes().iter().fold(
        Vec::new(),
        |mut v, &b| {
            v.push(b);
            if b == b'%' {
                v.push(b'%');
            }
            v
        },
    ));
    let log = |name: &str| os(&[OsStr::new("--output="), &logs, OsStr::new(name)]);
    array.push(log("/slurm/shard-%a.log"));
    array.push(at("/slurm/shard.sh"));
    assert_eq!(
        record(&case.dir.join("sbatch.0")),
        array,
        "{context}\n{text}"
    );
    let mut merge = strs(&[
        "--parsable",
        "--job-name=solsim-merge",
        "--dependency=afterok:4240",
    ]);
    merge.push(log("/slurm/merge.log"));
    merge.push(at("/slurm/merge.sh"));
    assert_eq!(
        record(&case.dir.join("sbatch.1")),
        merge,
        "{context}\n{text}"
    );

    // The array task K = 1, then (its shards done) the merge job, under the fake solsim.
    let argv = case.dir.join("argv");
    let shard = output_within(
        clean("bash", kit, &case.dir)
            .arg(at("/slurm/shard.sh"))
            .env("SLURM_ARRAY_TASK_ID", "1"),
        LIMIT,
    );
    assert!(
        shard.status.success(),
        "{context}: shard.sh: {}",
        stderr(&shard)
    );
    let mut expected = vec![solsim.clone().into_os_string(), "sweep".into()];
    expected.push(scenario.into_os_string());
    expected.extend(strs(&[
        "--runs",
        "4",
        "--strategies",
        "ground",
        "--seed",
        "1",
        "--baseline",
        "none",
        "--threads",
        "1",
        "--shard",
        "1/2",
        "--out",
    ]));
    expected.push(at("/shard-1-of-2"));
    expected.extend(strs(&["--resume", "--quiet"]));
    assert_eq!(
        record(&argv),
        expected,
        "{context}: shard.sh ran something else"
    );
    for k in 0..2 {
        std::fs::create_dir_all(at(&format!("/shard-{k}-of-2"))).expect("shard dir");
    }
    let merged = output_within(
        clean("bash", kit, &case.dir).arg(at("/slurm/merge.sh")),
        LIMIT,
    );
    assert!(
        merged.status.success(),
        "{context}: merge.sh: {}",
        stderr(&merged)
    );
    let mut expected = vec![solsim.into_os_string(), "sweep".into(), "merge".into()];
    expected.extend([at("/shard-0-of-2"), at("/shard-1-of-2"), "--out".into()]);
    expected.extend([at("/merged"), "--quiet".into()]);
    assert_eq!(
        record(&argv),
        expected,
        "{context}: merge.sh ran something else"
    );
    assert!(
        !canary.exists(),
        "{context}: the job scripts made the canary"
    );
    true
}

/// The issue's reproduction: the path closes the here-document and `touch`es a file.
#[test]
fn the_reported_path_does_not_run_its_payload() {
    let kit = Kit::new();
    let d = kit.path().join("D");
    std::fs::create_dir(&d).expect("D");
    let sc = PathBuf::from(format!(
        "{}/scen\nSOLSIM_JOB\ntouch {}/pwned\n: <<'SOLSIM_JOB'\n.toml",
        d.display(),
        d.display()
    ));
    std::fs::create_dir_all(sc.parent().expect("parent")).expect("dirs");
    std::fs::write(&sc, kit.scenario("tiny")).expect("scenario");
    let o = output_within(
        clean(env!("CARGO_BIN_EXE_solsim"), &kit, kit.path())
            .args(["sweep", "slurm"])
            .arg(&sc)
            .args(["--runs", "20", "--shards", "2", "--out"])
            .arg(&d),
        LIMIT,
    );
    if o.status.success() {
        let script = kit.path().join("s.sh");
        std::fs::write(&script, &o.stdout).expect("script");
        let _ = output_within(clean("bash", &kit, kit.path()).arg(&script), LIMIT);
    }
    assert!(
        !d.join("pwned").exists(),
        "bash s.sh ran the path's `touch`:\n{}",
        String::from_utf8_lossy(&o.stdout)
    );
    common::assert_bad_input(
        &o,
        &[
            "SCENARIO: expected a path without control characters",
            "\\nSOLSIM_JOB\\n",
        ],
    );
}

/// Paths that are not UTF-8 are refused by name, not converted (a lossy conversion would make
/// the script run another path).
#[test]
fn paths_that_are_not_utf8_are_refused() {
    let kit = Kit::new();
    let sc = kit.path().join(OsStr::from_bytes(b"scen\xff.toml"));
    std::fs::write(&sc, kit.scenario("tiny")).expect("scenario");
    let run = |scenario: &Path, out: &Path| {
        output_within(
            clean(env!("CARGO_BIN_EXE_solsim"), &kit, kit.path())
                .args(["sweep", "slurm"])
                .arg(scenario)
                .args(["--runs", "2", "--shards", "2", "--out"])
                .arg(out),
            LIMIT,
        )
    };
    let o = run(&sc, &kit.path().join("out"));
    common::assert_bad_input(
        &o,
        &[
            "SCENARIO: expected a path of UTF-8 text",
            "scen\u{fffd}.toml",
        ],
    );
    let good = kit.path().join("good.toml");
    std::fs::write(&good, kit.scenario("tiny")).expect("scenario");
    let o = run(&good, &kit.path().join(OsStr::from_bytes(b"out\x80")));
    common::assert_bad_input(&o, &["--out: expected a path of UTF-8 text"]);
}

/// 1,000 seeded hostile paths and names: the canary never appears, and what is accepted runs
/// exactly what was asked.
#[test]
fn hostile_paths_and_names_never_run_the_canary() {
    let kit = Kit::new();
    let started = Instant::now();
    // Cases are independent (a directory each, a seed each): two threads share them.
    let accepted: u64 = std::thread::scope(|s| {
        let workers: Vec<_> = (0..2)
            .map(|t| {
                let kit = &kit;
                s.spawn(move || {
                    (0..CASES)
                        .filter(|i| i % 2 == t)
                        .map(|i| u64::from(run_case(kit, &Case::generate(kit, i))))
                        .sum::<u64>()
                })
            })
            .collect();
        workers.into_iter().map(|w| w.join().expect("worker")).sum()
    });
    eprintln!(
        "{CASES} hostile cases ({accepted} accepted and run, {} refused) in {:.1} s",
        CASES - accepted,
        started.elapsed().as_secs_f64()
    );
    // Both branches are exercised in earnest.
    assert!(
        (200..=800).contains(&accepted),
        "{accepted} of {CASES} accepted"
    );
}
