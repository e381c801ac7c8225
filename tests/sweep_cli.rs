//! Bad input to `solsim sweep` (and `sweep merge`, `sweep slurm`) gets one clear error line and
//! exit code 2 — no panic, no half-made output directory, nothing changed in a directory that
//! was refused — and a complete sweep directory is refused without `--resume` and left as it is
//! with it. Every sweep here is tiny (rapid traverse, at most 4 runs of one strategy).

use crate::common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::{Duration, Instant};

use common::{assert_bad_input, output_within, root, solsim, stderr};

const SCENARIO: &str = "scenarios/rapid-traverse-379-409.toml";
/// How long any command here may take (a hang is a bug, not a slow test).
const LIMIT: Duration = Duration::from_secs(60);

/// `solsim ARGS…` run from the repository root.
fn run(args: &[&str]) -> Output {
    output_within(solsim().current_dir(root()).args(args), LIMIT)
}

/// `solsim sweep SCENARIO --strategies ground --quiet ARGS…`.
fn sweep(args: &[&str]) -> Output {
    let mut all = vec!["sweep", SCENARIO, "--strategies", "ground", "--quiet"];
    all.extend_from_slice(args);
    run(&all)
}

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 temporary path")
}

fn assert_ok(o: &Output) {
    assert!(
        o.status.success(),
        "{}\nstdout:\n{}\nstderr:\n{}",
        o.status,
        String::from_utf8_lossy(&o.stdout),
        stderr(o)
    );
}

/// Every file under `dir` (relative path → bytes): a directory's state, to compare before and
/// after a refused command.
fn contents(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).expect("list") {
            let p = e.expect("entry").path();
            if p.is_dir() {
                todo.push(p);
            } else {
                let rel = p.strip_prefix(dir).expect("under dir").to_path_buf();
                files.insert(rel, std::fs::read(&p).expect("read"));
            }
        }
    }
    files
}

/// Bad input, and `out` not created.
fn assert_refused(o: &Output, must_contain: &[&str], out: &Path) {
    assert_bad_input(o, must_contain);
    assert!(
        !out.exists(),
        "{} was created by a refused command",
        out.display()
    );
}

/// A usage error reported by clap (a missing argument, a value outside its range): exit 2, no
/// panic, the first line `error: ` naming the option. Clap follows that line with a usage block,
/// so these do not (yet) meet the one-line rule; `clap_errors_are_one_line` checks that.
fn assert_usage_error(o: &Output, must_contain: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "exit code; stderr: {err}");
    assert!(!err.contains("panicked"), "panic: {err}");
    let first = err.lines().next().unwrap_or_default();
    assert!(first.starts_with("error: "), "{err}");
    for s in must_contain {
        assert!(first.contains(s), "first line lacks {s:?}:\n{err}");
    }
}

#[test]
fn runs_out_of_range_are_refused() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    let range = format!("from 1 to {}", sweep::engine::MAX_RUNS);
    for runs in ["0", "99999999999"] {
        let o = sweep(&["--runs", runs, "--out", s(&out)]);
        assert_refused(&o, &["--runs", &range, &format!("got {runs}")], &out);
    }
}

#[test]
fn bad_strategies_are_refused() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    let cases: [(&[&str], &[&str]); 3] = [
        (
            &["--strategies", "bogus"],
            &["--strategies", "\"bogus\"", "extension+onboard"],
        ),
        (
            &["--strategies", "ground,ground"],
            &["--strategies", "each strategy once", "ground twice"],
        ),
        (
            &["--strategies", "ground", "--baseline", "onboard"],
            &[
                "--baseline",
                "one of the swept strategies (ground)",
                "onboard",
            ],
        ),
    ];
    for (args, must) in cases {
        let mut all = vec!["sweep", SCENARIO, "--runs", "2", "--out", s(&out)];
        all.extend_from_slice(args);
        assert_refused(&run(&all), must, &out);
    }
}

/// `replay` needs historic drives; of the bundled scenarios only the self-reliant campaign has
/// none.
#[test]
fn replay_without_history_is_refused() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    let o = run(&[
        "sweep",
        "scenarios/self-reliant-campaign.toml",
        "--runs",
        "1",
        "--strategies",
        "replay",
        "--out",
        s(&out),
    ]);
    assert_refused(
        &o,
        &[
            "--strategies",
            "self-reliant-campaign.toml",
            "no historic drives",
            "replay",
        ],
        &out,
    );
}

#[test]
fn bad_shards_are_refused() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    for shard in ["4/4", "x", "1/0"] {
        let o = sweep(&["--runs", "4", "--shard", shard, "--out", s(&out)]);
        assert_refused(&o, &["--shard", "K/N with 0 ≤ K < N", shard], &out);
    }
}

#[test]
fn an_out_that_is_not_a_sweep_directory_is_refused_and_left_alone() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let busy = tmp.path().join("busy");
    std::fs::create_dir(&busy).expect("mkdir");
    std::fs::write(busy.join("notes.txt"), "mine").expect("write");
    let before = contents(tmp.path());
    let o = sweep(&["--runs", "2", "--out", s(&busy)]);
    assert_bad_input(&o, &["--out", s(&busy), "notes.txt", "no sweep manifest"]);

    let file = tmp.path().join("file");
    std::fs::write(&file, "mine").expect("write");
    let o = sweep(&["--runs", "2", "--out", s(&file)]);
    assert_bad_input(&o, &["--out", s(&file), "not a directory"]);
    std::fs::remove_file(&file).expect("rm");
    assert_eq!(contents(tmp.path()), before);
}

/// A complete sweep is refused without `--resume`; with it, nothing is run and nothing changes;
/// with another seed it is refused, naming the manifest's field.
#[test]
fn a_complete_sweep_is_refused_without_resume_and_kept_with_it() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("done");
    assert_ok(&sweep(&["--runs", "2", "--out", s(&out)]));
    let done = contents(&out);
    assert_eq!(
        done.keys().map(|p| s(p)).collect::<Vec<_>>(),
        [
            "manifest.json",
            "runs.parquet",
            "sols.parquet",
            "summary.json"
        ]
    );

    let o = sweep(&["--runs", "2", "--out", s(&out)]);
    assert_bad_input(&o, &["--out", "--resume", "manifest.json"]);
    assert_eq!(contents(&out), done);

    let started = Instant::now();
    let o = run(&[
        "sweep",
        SCENARIO,
        "--strategies",
        "ground",
        "--runs",
        "2",
        "--out",
        s(&out),
        "--resume",
    ]);
    let took = started.elapsed();
    assert_ok(&o);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("already complete"), "{stdout}");
    assert!(took < Duration::from_secs(10), "resuming took {took:?}");
    assert_eq!(contents(&out), done);

    let o = sweep(&["--runs", "2", "--seed", "5", "--out", s(&out), "--resume"]);
    assert_bad_input(&o, &["manifest.json", "(seed 379), got seed 5"]);
    assert_eq!(contents(&out), done);
}

#[test]
fn a_missing_scenario_is_refused() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    let missing = tmp.path().join("no-such-scenario.toml");
    let o = run(&[
        "sweep",
        s(&missing),
        "--runs",
        "2",
        "--strategies",
        "ground",
        "--out",
        s(&out),
    ]);
    assert_refused(&o, &[s(&missing), "No such file or directory"], &out);
}

/// The run table must fit `--memory-budget-mib`, checked before anything runs. At 1 MiB the
/// scenario's own planning grid is refused first; at 300 MiB the grid fits and 10⁷ runs do not.
#[test]
fn a_sweep_over_the_memory_budget_is_refused_before_running() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    let runs = sweep::engine::MAX_RUNS.to_string();
    for (mib, must) in [
        ("1", ["grid.resolution_m", "--memory-budget-mib", "1 MiB"]),
        (
            "300",
            [
                "--runs",
                "memory budget (--memory-budget-mib, 300 MiB)",
                "runs × 1 strategy need",
            ],
        ),
    ] {
        let started = Instant::now();
        let o = run(&[
            "--memory-budget-mib",
            mib,
            "sweep",
            SCENARIO,
            "--runs",
            &runs,
            "--strategies",
            "ground",
            "--out",
            s(&out),
        ]);
        assert_refused(&o, &must, &out);
        assert!(started.elapsed() < Duration::from_secs(10), "{mib} MiB");
    }
}

/// Shard directories of one 4-run sweep (and of another seed), made once for the merge cases.
struct Shards {
    tmp: tempfile::TempDir,
}

impl Shards {
    fn make() -> Self {
        let tmp = tempfile::tempdir().expect("tempdir");
        for (name, extra) in [
            ("half0", ["--shard", "0/2"]),
            ("half1", ["--shard", "1/2"]),
            ("quarter1", ["--shard", "1/4"]),
        ] {
            let out = tmp.path().join(name);
            let mut args = vec!["--runs", "4", "--out", s(&out)];
            args.extend_from_slice(&extra);
            assert_ok(&sweep(&args));
        }
        let out = tmp.path().join("half1-seed7");
        assert_ok(&sweep(&[
            "--runs",
            "4",
            "--shard",
            "1/2",
            "--seed",
            "7",
            "--out",
            s(&out),
        ]));
        Self { tmp }
    }

    fn dir(&self, name: &str) -> String {
        s(&self.tmp.path().join(name)).to_string()
    }

    /// `solsim sweep merge DIRS… --out OUT`.
    fn merge(&self, dirs: &[&str], out: &str) -> Output {
        let dirs: Vec<String> = dirs.iter().map(|d| self.dir(d)).collect();
        let mut args = vec!["sweep", "merge", "--out", out];
        args.extend(dirs.iter().map(String::as_str));
        run(&args)
    }
}

#[test]
fn bad_merges_are_refused() {
    let shards = Shards::make();
    let out = shards.tmp.path().join("merged");
    let o = shards.merge(&[], s(&out));
    assert_usage_error(&o, &["required arguments were not provided"]);
    assert!(!out.exists());

    let empty = shards.tmp.path().join("empty");
    std::fs::create_dir(&empty).expect("mkdir");
    let cases: [(&[&str], Vec<String>); 5] = [
        (
            &["empty"],
            vec![
                format!("{}/manifest.json", s(&empty)),
                "expected a sweep manifest".into(),
            ],
        ),
        (
            &["half0", "quarter1", "half1"],
            vec![shards.dir("quarter1"), "overlap".into(), "runs 1..2".into()],
        ),
        (
            &["half1"],
            vec![
                shards.dir("half1"),
                "leave runs out".into(),
                "runs 2..4".into(),
            ],
        ),
        (
            &["half0"],
            vec!["shards covering runs 0..4".into(), "0..2".into()],
        ),
        (
            &["half0", "half1-seed7"],
            vec![
                shards.dir("half1-seed7"),
                format!("{}/manifest.json", shards.dir("half0")),
                "seed".into(),
                "got 7".into(),
            ],
        ),
    ];
    for (dirs, must) in cases {
        let must: Vec<&str> = must.iter().map(String::as_str).collect();
        assert_refused(&shards.merge(dirs, s(&out)), &must, &out);
    }

    let busy = shards.tmp.path().join("busy");
    std::fs::create_dir(&busy).expect("mkdir");
    std::fs::write(busy.join("notes.txt"), "mine").expect("write");
    let o = shards.merge(&["half0", "half1"], s(&busy));
    assert_bad_input(&o, &["--out", s(&busy), "not empty"]);
    assert_eq!(contents(&busy).len(), 1);

    // The same shards do merge into a new directory.
    assert_ok(&shards.merge(&["half1", "half0"], s(&out)));
}

#[test]
fn bad_slurm_shard_counts_are_refused() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("slurm");
    let slurm = |shards: &str| {
        run(&[
            "sweep",
            "slurm",
            SCENARIO,
            "--runs",
            "4",
            "--strategies",
            "ground",
            "--shards",
            shards,
            "--out",
            s(&out),
        ])
    };
    assert_usage_error(&slurm("0"), &["--shards", "'0'"]);
    assert!(!out.exists());
    assert_refused(&slurm("5"), &["--shards", "at most --runs (4)", "5"], &out);
}

/// Clap's own usage errors follow the `error:` line with a usage block and a `--help` hint,
/// breaking the one-line rule every other bad input keeps.
#[test]
fn clap_errors_are_one_line() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    let o = run(&["sweep", "merge", "--out", s(&out)]);
    assert_bad_input(&o, &["DIR"]);
    let o = run(&[
        "sweep",
        "slurm",
        SCENARIO,
        "--runs",
        "4",
        "--shards",
        "0",
        "--out",
        s(&out),
    ]);
    assert_bad_input(&o, &["--shards"]);
}

/// `--baseline ground` given explicitly with a sweep that leaves `ground` out is dropped as
/// quietly as the default is (the sweep runs with no baseline), while any other unswept
/// baseline is refused.
#[test]
fn an_explicit_baseline_that_is_not_swept_is_refused() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("out");
    let o = run(&[
        "sweep",
        SCENARIO,
        "--runs",
        "1",
        "--strategies",
        "onboard",
        "--baseline",
        "ground",
        "--quiet",
        "--out",
        s(&out),
    ]);
    assert_refused(&o, &["--baseline", "ground"], &out);
}
