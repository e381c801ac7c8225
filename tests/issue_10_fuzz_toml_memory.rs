//! Issue 10 (found by the fuzzer): at the 16 MiB cap on text inputs, hostile TOML made
//! `solsim validate` peak at 1.3–2.3 GB before rejecting it — the TOML parser holds about 150
//! times a file's size — over the 2 GiB default memory budget. TOML inputs (scenarios, campaign
//! files, recipes) are now capped at 1 MiB, some 150 times the largest bundled scenario: a
//! larger one is refused from its size, and the worst 1 MiB stays far below the budget.
#![cfg(unix)]

mod common;

use std::time::Duration;

use common::{assert_bad_input, output_within, solsim};

/// Largest resident set of the children this test process has waited for, bytes.
fn children_peak_rss_bytes() -> u64 {
    // SAFETY: getrusage only writes into the zeroed struct we pass.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let rc = unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) };
    assert_eq!(rc, 0, "getrusage");
    u64::try_from(usage.ru_maxrss).expect("non-negative") * 1024
}

#[test]
fn toml_inputs_are_capped_and_the_worst_megabyte_stays_small() {
    let dir = tempfile::tempdir().expect("tempdir");
    // 1 MiB of array-of-tables entries: the shape that cost the most per byte.
    let mut text = String::from("name = \"x\"\nseed = 1\n");
    let mut i = 0;
    while text.len() < (1 << 20) - 64 {
        text.push_str(&format!("[[sols]]\nsol = {i}\n"));
        i += 1;
    }
    let worst = dir.path().join("worst.toml");
    std::fs::write(&worst, &text).expect("write");
    let o = output_within(
        solsim().arg("validate").arg(&worst),
        Duration::from_secs(60),
    );
    assert_bad_input(&o, &["worst.toml"]);
    let peak = children_peak_rss_bytes();
    assert!(
        peak < 512 << 20,
        "validate of 1 MiB of TOML peaked at {} MiB",
        peak >> 20
    );

    let big = dir.path().join("big.toml");
    text.push_str(&"#\n".repeat(1 << 19));
    std::fs::write(&big, &text).expect("write");
    let o = output_within(solsim().arg("validate").arg(&big), Duration::from_secs(60));
    assert_bad_input(
        &o,
        &["big.toml", "expected at most 1 MiB of text, got 2.0 MiB"],
    );
}
