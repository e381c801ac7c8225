//! Issue 29 (found in review): `scripts/architecture_check.py` stopped reading a file at its
//! first `#[cfg(test)]`, even one on a single `use` at the top, and its string pattern did not
//! span a line. `localization/src/synthetic/truth.rs` counted 5 lines (it had 891) and its import
//! circle with `statics.rs` was invisible, so the rules' test passed over a breach. Now only the
//! test items themselves are left out, test modules in their own files too, and strings are
//! blanked whatever they hold.

use crate::issue_29_architecture::{architecture_check, plant, planted_tree};

#[test]
fn a_test_item_hides_only_itself() {
    let Some(dir) = planted_tree() else { return };
    let d = dir.path();
    let write = |p: &str, text: &str| plant(d, p, text);
    write(
        "a/src/lib.rs",
        "mod early;\nmod x;\nmod y;\nmod s;\nmod u;\n#[cfg(test)]\nmod t;\n",
    );
    let long: String = (0..601).map(|i| format!("// line {i}\n")).collect();
    // A test `use` at the top: the 601 lines after it still count.
    write(
        "a/src/early.rs",
        &format!("#[cfg(test)]\nuse std::fmt;\n{long}"),
    );
    // A circle behind a test `use`: x -> y -> x.
    write(
        "a/src/x.rs",
        "#[cfg(test)]\nuse std::fmt;\nuse crate::y::Y;\npub struct X;\n",
    );
    write("a/src/y.rs", "pub struct Y;\nfn f(_: crate::x::X) {}\n");
    // A circle behind a string continued over a line end (`\` then the newline), followed by
    // another string: s -> u -> s.
    write(
        "a/src/s.rs",
        "const S: &str = \"one \\\n two\";\nuse crate::u::U;\nconst T: &str = \"x\";\npub struct Z;\n",
    );
    write("a/src/u.rs", "pub struct U;\nfn g(_: crate::s::Z) {}\n");
    // A test module in a file of its own is not counted.
    write("a/src/t.rs", &long.repeat(2));
    write("src/main.rs", "fn main() {}\n");
    let o = architecture_check(d, &["a"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(out.contains("a/src/early.rs: 601 lines"), "{out}");
    assert!(out.contains("a: import circle between x.rs, y.rs"), "{out}");
    assert!(out.contains("a: import circle between s.rs, u.rs"), "{out}");
    assert!(!out.contains("t.rs"), "{out}");
    assert!(out.contains("3 breach(es)"), "{out}");
}
