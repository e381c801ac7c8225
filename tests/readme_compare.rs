//! The README's first output block — the main job, `solsim compare` on the rapid traverse,
//! with each strategy set against `ground` under the table — is what the command prints.

mod common;

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
