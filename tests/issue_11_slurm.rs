//! Issue 11: a sweep fanned out on a real Slurm cluster gives the same files as one local sweep.
//!
//! `solsim sweep slurm` writes a submit script: a job array whose task K runs shard K/M, and a
//! merge job that waits for all of them (`afterok`). This test starts a real single-node cluster
//! from Debian's packages (`tests/slurm/cluster.sh`), runs that script, waits for both jobs, and
//! checks the merged `runs.parquet`, `sols.parquet`, `summary.json` and `manifest.json` are
//! byte-identical to those of `solsim sweep` run locally with the same arguments.
//!
//! When it runs: the cluster needs root (it installs packages, starts munged and the Slurm
//! daemons, and jobs run as root). As root the test always runs, and any failure to start the
//! cluster (no apt-get, no network, a daemon that does not come up) fails it. Not root, it is
//! skipped with a message on stderr — unless the environment variable `CI` is set: then not
//! being root fails it too, so CI can never pass without having run it.
//!
//! Cost (2 cores, test binary built): 9 s with the packages installed (cluster up in 0.3-1.4 s,
//! both jobs done 4-6 s after submission, then the local sweep); 17-24 s on a machine without
//! them (apt-get update and install: 11-15 s).
#![cfg(target_os = "linux")]

use crate::common;

use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use common::{output_within, root, solsim, stderr};

const SCENARIO: &str = "scenarios/rapid-traverse-379-409.toml";
const RUNS: u64 = 12;
const SHARDS: u64 = 3;
const STRATEGIES: &str = "ground,extension+onboard";
const FILES: [&str; 4] = [
    "runs.parquet",
    "sols.parquet",
    "summary.json",
    "manifest.json",
];
/// How long both jobs may take, from submission to the merge job's end.
const JOBS_LIMIT: Duration = Duration::from_secs(300);

/// A running cluster; dropping it stops it, whether the test passed or panicked.
struct Cluster {
    state: PathBuf,
    slurm_conf: String,
}

fn cluster_sh() -> PathBuf {
    root().join("tests/slurm/cluster.sh")
}

impl Cluster {
    /// `cluster.sh start STATE` (installs the packages if missing); panics with its output if the
    /// cluster does not come up.
    fn start(state: &Path) -> Cluster {
        let started = Instant::now();
        let o = output_within(
            Command::new("bash")
                .arg(cluster_sh())
                .arg("start")
                .arg(state),
            Duration::from_secs(900),
        );
        // Stop whatever did start, even if the start as a whole failed.
        let mut cluster = Cluster {
            state: state.to_path_buf(),
            slurm_conf: String::new(),
        };
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(
            o.status.success(),
            "the Slurm cluster did not start ({}):\n{}{}",
            o.status,
            out,
            stderr(&o)
        );
        cluster.slurm_conf = out
            .lines()
            .find_map(|l| l.strip_prefix("export SLURM_CONF="))
            .unwrap_or_else(|| panic!("no `export SLURM_CONF=` line in:\n{out}"))
            .to_string();
        eprintln!(
            "slurm cluster up in {:.1} s (SLURM_CONF={})",
            started.elapsed().as_secs_f64(),
            cluster.slurm_conf
        );
        cluster
    }

    /// A Slurm client command pointed at this cluster.
    fn client(&self, program: &str) -> Command {
        let mut c = Command::new(program);
        c.env("SLURM_CONF", &self.slurm_conf);
        c
    }

    /// Runs a client command; panics unless it exits 0.
    fn query(&self, program: &str, args: &[&str]) -> String {
        let o = output_within(self.client(program).args(args), Duration::from_secs(60));
        assert!(
            o.status.success(),
            "{program} {args:?}: {}\n{}",
            o.status,
            stderr(&o)
        );
        String::from_utf8_lossy(&o.stdout).into_owned()
    }

    /// The daemons' logs, for a failure message.
    fn logs(&self) -> String {
        dir_listing(&self.state.join("log"))
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        match Command::new("bash")
            .arg(cluster_sh())
            .arg("stop")
            .arg(&self.state)
            .output()
        {
            Ok(o) if o.status.success() => {}
            Ok(o) => eprintln!("cluster.sh stop: {}\n{}", o.status, stderr(&o)),
            Err(e) => eprintln!("cluster.sh stop did not run: {e}"),
        }
    }
}

/// Every file of `dir` with its content (Slurm job logs, daemon logs), for failure messages.
fn dir_listing(dir: &Path) -> String {
    let mut paths: Vec<PathBuf> = match std::fs::read_dir(dir) {
        Ok(entries) => entries.filter_map(|e| e.ok().map(|e| e.path())).collect(),
        Err(e) => return format!("({}: {e})\n", dir.display()),
    };
    paths.sort();
    let mut text = String::new();
    for p in paths {
        let content = std::fs::read(&p).unwrap_or_default();
        // The tail: daemon logs can be long, the end is where the error is.
        let tail = &content[content.len().saturating_sub(6000)..];
        text += &format!(
            "----- {} -----\n{}\n",
            p.display(),
            String::from_utf8_lossy(tail)
        );
    }
    text
}

/// Whether this process runs as root (the owner of /proc/self is the effective uid).
fn is_root() -> bool {
    std::fs::metadata("/proc/self").is_ok_and(|m| m.uid() == 0)
}

/// `JobState=` of every record `scontrol show job ID` prints (one per array task).
fn job_states(cluster: &Cluster, id: &str) -> Vec<String> {
    cluster
        .query("scontrol", &["show", "job", id])
        .split_whitespace()
        .filter_map(|w| w.strip_prefix("JobState=").map(str::to_string))
        .collect()
}

fn assert_ok(o: &Output, what: &str) {
    assert!(
        o.status.success(),
        "{what}: {}\nstdout:\n{}\nstderr:\n{}",
        o.status,
        String::from_utf8_lossy(&o.stdout),
        stderr(o)
    );
}

#[test]
fn slurm_job_array_sweep_merges_to_the_local_sweep() {
    if !is_root() {
        common::external::unavailable(
            "the Slurm job-array sweep on a real single-node cluster",
            "the tests do not run as root (the cluster installs Debian's slurmctld, slurmd and \
             munge and starts their daemons)",
            "sudo scripts/test.sh",
        );
        return;
    }
    let tmp = tempfile::tempdir().expect("tempdir");
    let cluster = Cluster::start(&tmp.path().join("cluster"));

    // The submit script, written by solsim; run from another directory than the one solsim ran
    // in, so the paths in it must be absolute.
    let out = tmp.path().join("slurm-out");
    let o = output_within(
        solsim()
            .current_dir(root())
            .args(["sweep", "slurm", SCENARIO, "--runs", &RUNS.to_string()])
            .args(["--shards", &SHARDS.to_string()])
            .args(["--strategies", STRATEGIES, "--out"])
            .arg(&out),
        Duration::from_secs(60),
    );
    assert_ok(&o, "solsim sweep slurm");
    let script = tmp.path().join("submit.sh");
    std::fs::write(&script, &o.stdout).expect("write the script");
    let script_text = String::from_utf8_lossy(&o.stdout).into_owned();
    let exe = Path::new(env!("CARGO_BIN_EXE_solsim"));
    let exe_canonical = exe.canonicalize().expect("canonical solsim path");
    assert!(
        script_text.contains(&*exe.to_string_lossy())
            || script_text.contains(&*exe_canonical.to_string_lossy()),
        "the script does not name solsim by its absolute path {}:\n{script_text}",
        exe.display()
    );

    let submitted = Instant::now();
    let o = output_within(
        cluster.client("bash").arg(&script).current_dir(tmp.path()),
        Duration::from_secs(120),
    );
    assert_ok(&o, &format!("bash {}", script.display()));
    let printed = String::from_utf8_lossy(&o.stdout).into_owned();
    let job_id = |prefix: &str| -> String {
        printed
            .lines()
            .find_map(|l| l.strip_prefix(prefix))
            .map(|id| id.trim().to_string())
            .filter(|id| !id.is_empty() && id.bytes().all(|b| b.is_ascii_digit()))
            .unwrap_or_else(|| panic!("no line `{prefix}<id>` in the script's output:\n{printed}"))
    };
    let (array, merge) = (job_id("array job "), job_id("merge job "));
    eprintln!("submitted array job {array} and merge job {merge}");

    // Both jobs done: squeue lists only pending, running and completing jobs.
    let ids = format!("{array},{merge}");
    let failure = |why: &str| -> String {
        format!(
            "{why}\nscontrol show job {array}:\n{}\nscontrol show job {merge}:\n{}\n\
             slurm job logs:\n{}\ndaemon logs:\n{}",
            cluster
                .client("scontrol")
                .args(["show", "job", &array])
                .output()
                .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
                .unwrap_or_default(),
            cluster
                .client("scontrol")
                .args(["show", "job", &merge])
                .output()
                .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
                .unwrap_or_default(),
            dir_listing(&out.join("slurm")),
            cluster.logs()
        )
    };
    loop {
        let active = cluster.query("squeue", &["-h", "-o", "%i %T", "-j", &ids]);
        if active.trim().is_empty() {
            break;
        }
        if submitted.elapsed() > JOBS_LIMIT {
            panic!(
                "{}",
                failure(&format!(
                    "jobs still queued or running after {JOBS_LIMIT:?}:\n{active}"
                ))
            );
        }
        std::thread::sleep(Duration::from_millis(500));
    }
    eprintln!(
        "both jobs done {:.1} s after submission",
        submitted.elapsed().as_secs_f64()
    );
    let array_states = job_states(&cluster, &array);
    let merge_states = job_states(&cluster, &merge);
    if array_states.len() as u64 != SHARDS
        || merge_states.len() != 1
        || array_states
            .iter()
            .chain(&merge_states)
            .any(|s| s != "COMPLETED")
    {
        panic!(
            "{}",
            failure(&format!(
                "expected {SHARDS} array tasks and the merge job COMPLETED; array tasks: \
                 {array_states:?}, merge job: {merge_states:?}"
            ))
        );
    }

    // One shard directory per array task, and nothing else shard-like.
    let mut shards: Vec<String> = std::fs::read_dir(&out)
        .expect("list the sweep directory")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("shard-"))
        .collect();
    shards.sort();
    let expected: Vec<String> = (0..SHARDS)
        .map(|k| format!("shard-{k}-of-{SHARDS}"))
        .collect();
    assert_eq!(shards, expected, "shard directories in {}", out.display());
    // Each a complete shard, the slices disjoint and together every run index, in order.
    let mut next_run = 0;
    for (k, name) in shards.iter().enumerate() {
        let m = common::manifest(&out.join(name));
        assert_eq!(m["state"], "complete", "{name}: {m}");
        assert_eq!(m["shard"]["index"], k as u64, "{name}: {m}");
        assert_eq!(m["shard"]["count"], SHARDS, "{name}: {m}");
        assert_eq!(m["shard"]["first_run"], next_run, "{name}: {m}");
        next_run = m["shard"]["end_run"].as_u64().expect("end_run");
    }
    assert_eq!(next_run, RUNS, "the shards' run slices end at --runs");
    let m = common::manifest(&out.join("merged"));
    assert_eq!(m["state"], "complete", "merged manifest: {m}");
    assert_eq!(m["runs"], RUNS, "merged manifest: {m}");
    assert!(m["shard"].is_null(), "merged manifest: {m}");

    // The same sweep, locally, in one process.
    let local = tmp.path().join("local");
    let o = output_within(
        solsim()
            .current_dir(root())
            .args(["sweep", SCENARIO, "--runs", &RUNS.to_string()])
            .args(["--strategies", STRATEGIES, "--quiet", "--out"])
            .arg(&local),
        Duration::from_secs(600),
    );
    assert_ok(&o, "local solsim sweep");

    let merged = out.join("merged");
    for name in FILES {
        let from_slurm = std::fs::read(merged.join(name))
            .unwrap_or_else(|e| panic!("{}", failure(&format!("merged {name}: {e}"))));
        let from_local = std::fs::read(local.join(name)).expect("local sweep file");
        assert!(
            from_slurm == from_local,
            "{name} differs: merged from Slurm shards {} bytes, local sweep {} bytes{}",
            from_slurm.len(),
            from_local.len(),
            if name.ends_with(".json") {
                format!(
                    "\n--- merged ---\n{}\n--- local ---\n{}",
                    String::from_utf8_lossy(&from_slurm),
                    String::from_utf8_lossy(&from_local)
                )
            } else {
                String::new()
            }
        );
    }
    drop(cluster);
}
