//! The README's first output block — the main job, `solsim compare` on the rapid traverse,
//! with each strategy set against `ground` under the table — is what the command prints; so is
//! its block of `solsim compare --runs 200`, except the parts it marks `…` as left out.

use crate::common;

use common::{root, solsim, stderr};

#[test]
fn readme_main_job_block_is_what_compare_prints() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let cmd = "$ solsim compare scenarios/rapid-traverse-379-409.toml --no-files\n";
    let start = readme.find(cmd).expect("the README shows the command") + cmd.len();
    let block = &readme[start..start + readme[start..].find("```").expect("block end")];
    assert!(block.contains("Against ground"), "{block}");
    let o = solsim()
        .current_dir(root())
        .args([
            "compare",
            "scenarios/rapid-traverse-379-409.toml",
            "--no-files",
        ])
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains(block),
        "README:\n{block}\ncompare printed:\n{out}"
    );
}

#[test]
fn readme_compare_over_runs_block_is_what_compare_prints() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let cmd = "$ solsim compare scenarios/rapid-traverse-379-409.toml --runs 200 --no-files\n";
    let start = readme.find(cmd).expect("the README shows the command") + cmd.len();
    let block = &readme[start..start + readme[start..].find("```").expect("block end")];
    assert!(block.contains("Against ground over 200 runs"), "{block}");
    let o = solsim()
        .current_dir(root())
        .args([
            "compare",
            "scenarios/rapid-traverse-379-409.toml",
            "--runs",
            "200",
            "--no-files",
        ])
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    // A line with `…` stands for lines left out ("  replay: …": the strategy's lines); every
    // run of lines between them is printed as it stands.
    let mut chunk = String::new();
    for line in block.lines() {
        if let Some(kept) = line.split('…').next().filter(|_| line.contains('…')) {
            assert!(
                out.contains(&chunk),
                "README:\n{chunk}\ncompare printed:\n{out}"
            );
            chunk.clear();
            let kept = kept.trim_end();
            if !kept.is_empty() {
                assert!(
                    out.contains(&format!("{kept}\n")),
                    "{kept:?} not printed:\n{out}"
                );
            }
        } else {
            chunk.push_str(line);
            chunk.push('\n');
        }
    }
    assert!(
        out.contains(&chunk),
        "README:\n{chunk}\ncompare printed:\n{out}"
    );
}
