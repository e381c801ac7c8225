//! Issue 26, finding 2: `--resume` trusted `manifest.json`. After a kill, an edited chunk size
//! (5 → 7 gave 215 rows of 38 runs, 5 → 50 gave 50 rows), a chunk listed twice (225 rows,
//! statistics over 45 runs while the summary said 40) or a chunk file renamed under an edited
//! entry each ended "complete" with exit 0. Now a resume proves that the listed chunks tile the
//! run range exactly once, each chunk's checksums and rows agreeing with its entry, or refuses
//! with one error line; and over 1,000 seeded edits of a killed sweep's manifest it either
//! writes the uninterrupted sweep's bytes or refuses.

use std::path::Path;

use rand::{RngExt as _, SeedableRng as _};
use serde_json::Value;

use crate::common::killed_sweep::{Fixture, copy_dir, same_sweep};
use crate::common::{root, solsim};

fn read_manifest(dir: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).expect("read")).expect("json")
}

fn write_manifest(dir: &Path, m: &Value) {
    std::fs::write(
        dir.join("manifest.json"),
        serde_json::to_string_pretty(m).expect("json"),
    )
    .expect("write");
}

/// `solsim sweep --resume` on `dir`: `Ok` with the reference bytes, or `Err` with the error
/// line when refused with exit 2 and one line. Anything else (a different complete set, a
/// panic, two lines) fails the test.
fn resume_cli(f: &Fixture, dir: &Path, reference: &Path) -> Result<(), String> {
    let o = solsim()
        .current_dir(root())
        .args(f.cli_args())
        .arg("--resume")
        .arg("--out")
        .arg(dir)
        .output()
        .expect("run solsim");
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    if o.status.success() {
        if let Err(e) = same_sweep(dir, reference) {
            panic!(
                "{}: exit 0 with a different complete set: {e}",
                dir.display()
            );
        }
        return Ok(());
    }
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(
        err.starts_with("error: ") && !err.contains("panicked"),
        "{err}"
    );
    Err(err)
}

/// The four edits the campaign reproduced, on 40 runs in chunks of 5 killed after 15 runs.
#[test]
fn the_reproduced_edits_are_refused() {
    let f = Fixture::new(40, 5);
    let reference = f.complete("reference");
    let killed = f.killed("killed", 15);
    let m = read_manifest(&killed);
    assert_eq!(m["chunks"].as_array().map(Vec::len), Some(3), "{m}");

    let case = |name: &str, edit: &dyn Fn(&Path, &mut Value)| {
        let dir = f.tmp.path().join(name);
        copy_dir(&killed, &dir);
        let mut m = read_manifest(&dir);
        edit(&dir, &mut m);
        write_manifest(&dir, &m);
        let got = resume_cli(&f, &dir, &reference);
        let err = got.expect_err(&format!("{name}: resumed instead of refusing"));
        eprintln!("{name}: {}", err.trim_end());
        err
    };
    let e = case("chunk-runs-7", &|_, m| m["chunk_runs"] = 7.into());
    assert!(
        e.contains("chunks[0]") && e.contains("chunk of 7 runs"),
        "{e}"
    );
    let e = case("chunk-runs-50", &|_, m| m["chunk_runs"] = 50.into());
    assert!(e.contains("chunks[0]"), "{e}");
    let e = case("duplicated", &|_, m| {
        let c = m["chunks"].as_array_mut().expect("chunks");
        c.push(c[1].clone());
        c.sort_by_key(|c| c["first_run"].as_u64());
    });
    assert!(e.contains("listed once each"), "{e}");
    // The chunk of runs 0..5 renamed to runs 20..25 under an entry edited to say so: its
    // checksums agree, its rows do not.
    let e = case("renamed", &|dir, m| {
        let chunks = dir.join("chunks");
        for kind in ["runs", "sols"] {
            std::fs::rename(
                chunks.join(format!("{kind}-0000000000-0000000005.parquet")),
                chunks.join(format!("{kind}-0000000020-0000000025.parquet")),
            )
            .expect("rename");
        }
        let c = m["chunks"].as_array_mut().expect("chunks");
        let mut moved = c.remove(0);
        moved["first_run"] = 20.into();
        moved["end_run"] = 25.into();
        c.push(moved);
    });
    assert!(e.contains("row 0") && e.contains("expected run 20"), "{e}");
    // Unedited, the same directory resumes to the reference bytes.
    let dir = f.tmp.path().join("unedited");
    copy_dir(&killed, &dir);
    resume_cli(&f, &dir, &reference).expect("an unedited kill resumes");
}

/// One seeded edit of a manifest (and, for a few kinds, of the chunk files with it). Returns
/// what was done, for the failure message.
fn mutate(rng: &mut rand_chacha::ChaCha8Rng, dir: &Path, m: &mut Value) -> String {
    let numbers = [
        "runs",
        "seed",
        "chunk_runs",
        "chunks.first_run",
        "chunks.end_run",
    ];
    let odd_number = |rng: &mut rand_chacha::ChaCha8Rng, v: u64| -> Value {
        match rng.random_range(0..8) {
            0 => 0.into(),
            1 => (v + 1).into(),
            2 => v.saturating_sub(1).into(),
            3 => (v * 2).into(),
            4 => u64::MAX.into(),
            5 => Value::from(-1),
            6 => Value::from(1.5),
            _ => rng.random_range(0..60_u64).into(),
        }
    };
    let n_chunks = m["chunks"].as_array().map_or(0, Vec::len);
    let pick = |rng: &mut rand_chacha::ChaCha8Rng| rng.random_range(0..n_chunks.max(1));
    match rng.random_range(0..16) {
        0 => {
            let field = numbers[rng.random_range(0..numbers.len())];
            if let Some(f) = field.strip_prefix("chunks.") {
                if n_chunks == 0 {
                    return "nothing (no chunks)".into();
                }
                let i = pick(rng);
                let v = m["chunks"][i][f].as_u64().unwrap_or(0);
                m["chunks"][i][f] = odd_number(rng, v);
                format!("chunks[{i}].{f} = {}", m["chunks"][i][f])
            } else {
                let v = m[field].as_u64().unwrap_or(0);
                m[field] = odd_number(rng, v);
                format!("{field} = {}", m[field])
            }
        }
        1 if n_chunks > 0 => {
            let i = pick(rng);
            let c = m["chunks"][i].clone();
            let at = rng.random_range(0..=n_chunks);
            m["chunks"].as_array_mut().expect("chunks").insert(at, c);
            format!("chunks[{i}] listed again at {at}")
        }
        2 if n_chunks > 0 => {
            let i = pick(rng);
            m["chunks"].as_array_mut().expect("chunks").remove(i);
            format!("chunks[{i}] removed")
        }
        3 if n_chunks > 1 => {
            let (i, j) = (pick(rng), pick(rng));
            m["chunks"].as_array_mut().expect("chunks").swap(i, j);
            format!("chunks[{i}] and [{j}] swapped")
        }
        4 if n_chunks > 0 => {
            let (i, j) = (pick(rng), pick(rng));
            let kind = ["runs_sha256", "sols_sha256"][rng.random_range(0..2)];
            let other = m["chunks"][j][kind].clone();
            m["chunks"][i][kind] = other;
            format!("chunks[{i}].{kind} = chunks[{j}]'s")
        }
        5 if n_chunks > 0 => {
            let i = pick(rng);
            let kind = ["runs_sha256", "sols_sha256"][rng.random_range(0..2)];
            let mut sha: Vec<char> = m["chunks"][i][kind]
                .as_str()
                .unwrap_or("")
                .chars()
                .collect();
            let at = rng.random_range(0..sha.len().max(1));
            if let Some(c) = sha.get_mut(at) {
                *c = if *c == '0' { '1' } else { '0' };
            }
            m["chunks"][i][kind] = sha.into_iter().collect::<String>().into();
            format!("chunks[{i}].{kind} one digit changed")
        }
        6 => {
            let v = ["complete", "running", "done", ""][rng.random_range(0..4)];
            m["state"] = v.into();
            format!("state = {v:?}")
        }
        7 => {
            let field = ["format", "solsim_version", "baseline"][rng.random_range(0..3)];
            let v = ["solsim-sweep/1", "0.0.0", "onboard", "ground", "\u{1b}[2J"]
                [rng.random_range(0..5)];
            m[field] = v.into();
            format!("{field} = {v:?}")
        }
        8 => {
            let v = match rng.random_range(0..4) {
                0 => serde_json::json!([]),
                1 => serde_json::json!(["ground", "ground"]),
                2 => serde_json::json!(["onboard"]),
                _ => serde_json::json!(["ground", "onboard"]),
            };
            m["strategies"] = v.clone();
            format!("strategies = {v}")
        }
        9 => {
            let field = ["name", "sha256"][rng.random_range(0..2)];
            m["scenario"][field] = "other".into();
            format!("scenario.{field} = \"other\"")
        }
        10 => {
            let field = [
                "format",
                "runs",
                "seed",
                "state",
                "chunk_runs",
                "chunks",
                "strategies",
                "segment",
            ][rng.random_range(0..8)];
            if let Some(o) = m.as_object_mut() {
                o.remove(field);
            }
            format!("{field} removed")
        }
        11 => {
            let v = match rng.random_range(0..4) {
                0 => serde_json::json!({"index": 0, "count": 2, "first_run": 0, "end_run": 5}),
                1 => serde_json::json!({"index": 1, "count": 2, "first_run": 5, "end_run": 10}),
                2 => serde_json::json!({"index": 0, "count": 1, "first_run": 0, "end_run": 10}),
                _ => serde_json::json!({"index": 3, "count": 2, "first_run": 0, "end_run": 99}),
            };
            m["shard"] = v.clone();
            format!("shard = {v}")
        }
        12 => {
            m["files"] = serde_json::json!({"runs.parquet": "00"});
            "files listed while running".into()
        }
        13 if n_chunks > 0 => {
            // A chunk's files renamed to another cell of the grid, its entry edited to match.
            let i = pick(rng);
            let size = m["chunk_runs"].as_u64().unwrap_or(1).max(1);
            let runs = m["runs"].as_u64().unwrap_or(1);
            let first = rng.random_range(0..runs.div_ceil(size)) * size;
            let end = (first + size).min(runs);
            let (a, b) = (
                m["chunks"][i]["first_run"].as_u64().unwrap_or(0),
                m["chunks"][i]["end_run"].as_u64().unwrap_or(0),
            );
            for kind in ["runs", "sols"] {
                let _ = std::fs::rename(
                    dir.join(format!("chunks/{kind}-{a:010}-{b:010}.parquet")),
                    dir.join(format!("chunks/{kind}-{first:010}-{end:010}.parquet")),
                );
            }
            m["chunks"][i]["first_run"] = first.into();
            m["chunks"][i]["end_run"] = end.into();
            format!("chunk {a}..{b} renamed to {first}..{end} with its entry")
        }
        14 if n_chunks > 0 => {
            // A chunk's files swapped with another's, entries untouched.
            let (i, j) = (pick(rng), pick(rng));
            let name = |k: usize, kind: &str| {
                let (a, b) = (
                    m["chunks"][k]["first_run"].as_u64().unwrap_or(0),
                    m["chunks"][k]["end_run"].as_u64().unwrap_or(0),
                );
                dir.join(format!("chunks/{kind}-{a:010}-{b:010}.parquet"))
            };
            let kind = ["runs", "sols"][rng.random_range(0..2)];
            let tmp = dir.join("chunks/swap");
            let _ = std::fs::rename(name(i, kind), &tmp);
            let _ = std::fs::rename(name(j, kind), name(i, kind));
            let _ = std::fs::rename(&tmp, name(j, kind));
            format!("{kind} files of chunks[{i}] and [{j}] swapped")
        }
        _ => {
            // Text-level: the manifest cut short, or a byte changed.
            let mut text = serde_json::to_string_pretty(m).expect("json").into_bytes();
            let at = rng.random_range(0..text.len());
            let what = if rng.random_bool(0.5) {
                text.truncate(at);
                format!("cut at byte {at}")
            } else {
                let b = [b'0', b'9', b'"', b'}', b'x', 0, 0xff][rng.random_range(0..7)];
                text[at] = b;
                format!("byte {at} = {b:#x}")
            };
            std::fs::write(dir.join("manifest.json"), text).expect("write");
            *m = Value::Null;
            what
        }
    }
}

/// 1,000 seeded edits of killed sweeps' manifests: each resume writes the uninterrupted
/// sweep's bytes or refuses with one error line, never a different complete set.
#[test]
fn a_thousand_manifest_edits_resume_right_or_refuse() {
    let cases: u64 = std::env::var("SOLSIM_MUTATION_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000);
    let f = Fixture::new(10, 1);
    let reference = f.complete("reference");
    // Kills after a few chunks, and after the last one (before the files were assembled).
    let killed = [f.killed("killed-3", 3), f.killed("killed-10", 10)];
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x26_0002);
    let (mut same, mut refused) = (0, 0);
    for case in 0..cases {
        let dir = f.tmp.path().join(format!("case-{case}"));
        copy_dir(&killed[rng.random_range(0..killed.len())], &dir);
        let mut m = read_manifest(&dir);
        let edit = mutate(&mut rng, &dir, &mut m);
        if !m.is_null() {
            write_manifest(&dir, &m);
        }
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f.run(&dir, true)));
        match outcome {
            Err(_) => panic!("case {case} ({edit}): resume panicked"),
            Ok(Ok(_)) => {
                if let Err(e) = same_sweep(&dir, &reference) {
                    panic!("case {case} ({edit}): resumed to a different complete set: {e}");
                }
                same += 1;
            }
            Ok(Err(e)) => {
                let line = e.to_string();
                assert!(
                    !line.contains('\n') && !line.contains('\u{1b}'),
                    "case {case} ({edit}): not one printable line: {line:?}"
                );
                refused += 1;
            }
        }
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
    eprintln!("{cases} manifest edits: {same} resumed to the reference bytes, {refused} refused");
    // Both outcomes must occur, or the edits test only one side.
    assert!(
        same >= cases / 10 && refused >= cases / 10,
        "{same} / {refused}"
    );
}
