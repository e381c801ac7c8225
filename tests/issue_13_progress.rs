//! Issue 13: `map package` of the rapid traverse ran 254 s in silence, and `localize-bench`
//! and `seu-campaign` showed nothing while they ran. They now draw a progress bar on standard
//! error when it is a terminal (checked under a pseudo-terminal, `script` from util-linux),
//! like `sweep` and `compare --runs`, and print nothing there when it is piped.

use crate::common;

use common::{root, solsim, stderr};

const BENCH: [&str; 5] = ["localize-bench", "--cases", "24", "--methods", "ncc"];

#[test]
fn localize_bench_draws_a_bar_on_a_terminal_only() {
    if let Some(tty) = common::on_a_terminal(&BENCH) {
        assert!(tty.contains("ncc ") && tty.contains("/24 cases"), "{tty}");
        assert!(
            tty.contains("rejected by validity checks"),
            "the results too: {tty}"
        );
    }
    let o = solsim().args(BENCH).output().expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "", "nothing on a piped stderr");
}

#[test]
fn seu_campaign_draws_a_bar_on_a_terminal_only() {
    let args = ["seu-campaign", "--runs", "40"];
    if let Some(tty) = common::on_a_terminal(&args) {
        assert!(
            tty.contains("seu-campaign ") && tty.contains("/40 runs"),
            "{tty}"
        );
    }
    let o = solsim().args(args).output().expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "", "nothing on a piped stderr");
}

#[test]
fn map_package_draws_a_bar_on_a_terminal_only() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = |name: &str| dir.path().join(name).to_string_lossy().into_owned();
    let (tty_out, piped_out) = (out("tty"), out("piped"));
    let args = |o: &str| {
        [
            "map",
            "package",
            "scenarios/crater-floor-717.toml",
            "--out",
            o,
            "--resolution-m",
            "1",
            "--corridor-m",
            "30",
        ]
        .map(str::to_owned)
    };
    let tty_args = args(&tty_out);
    let tty_args: Vec<&str> = tty_args.iter().map(String::as_str).collect();
    if let Some(tty) = common::on_a_terminal(&tty_args) {
        assert!(
            tty.contains("map package ") && tty.contains(" tiles"),
            "{tty}"
        );
    }
    let o = solsim()
        .current_dir(root())
        .args(args(&piped_out))
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "", "nothing on a piped stderr");
}

#[test]
fn a_piped_sweep_prints_no_progress() {
    let dir = tempfile::tempdir().expect("tempdir");
    let o = solsim()
        .current_dir(root())
        .args([
            "sweep",
            "scenarios/crater-floor-717.toml",
            "--runs",
            "3",
            "--out",
        ])
        .arg(dir.path().join("s"))
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "", "nothing on a piped stderr");
}
