//! Issue 26, finding 4: with `chunks/` a symbolic link to another directory, `--resume`
//! exited 0, deleted `precious.txt` there and left 16 chunk files in it. `chunks/` must now be
//! the sweep directory's own: a link there is refused with one error line, and nothing in the
//! directory it points at is touched.
#![cfg(unix)]

use crate::common::killed_sweep::{Fixture, copy_dir, listing, refused, resume};

#[test]
fn resume_refuses_a_linked_chunks_directory_and_touches_nothing_there() {
    let f = Fixture::new(6, 2);
    let killed = f.killed("killed", 4);
    let elsewhere = f.tmp.path().join("elsewhere");
    std::fs::create_dir(&elsewhere).expect("mkdir");
    std::fs::write(elsewhere.join("precious.txt"), "keep me").expect("write");
    let dir = f.tmp.path().join("linked");
    copy_dir(&killed, &dir);
    // The chunks moved elsewhere and `chunks` made a link to them.
    for name in listing(&dir.join("chunks")) {
        std::fs::rename(dir.join("chunks").join(&name), elsewhere.join(&name)).expect("move");
    }
    std::fs::remove_dir(dir.join("chunks")).expect("rmdir");
    std::os::unix::fs::symlink(&elsewhere, dir.join("chunks")).expect("symlink");
    let before = listing(&elsewhere);
    refused(&mut resume(&f, &dir), &["chunks", "symbolic link"]);
    assert_eq!(listing(&elsewhere), before, "files elsewhere were touched");
    assert_eq!(
        std::fs::read_to_string(elsewhere.join("precious.txt")).expect("kept"),
        "keep me"
    );
}
