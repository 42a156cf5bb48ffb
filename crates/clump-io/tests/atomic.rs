//! Atomic output: an interrupted write (a writer dropped before commit, as
//! when the process dies mid-write) leaves the previous file intact and no
//! temporary file behind; a committed write replaces it whole.

use clump_io::atomic::{write_atomic, AtomicWriter};
use std::io::Write;

#[test]
fn interrupted_write_leaves_the_old_file() {
    let d = std::env::temp_dir().join(format!("clump-atomic-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let p = d.join("bodies_000100.vtp");
    write_atomic(&p, b"old complete file").unwrap();
    {
        let mut w = AtomicWriter::create(&p).unwrap();
        w.write_all(b"new, half writ").unwrap();
        // the target is untouched while the new file is being written
        assert_eq!(std::fs::read(&p).unwrap(), b"old complete file");
        // dropped without commit: the "crash"
    }
    assert_eq!(std::fs::read(&p).unwrap(), b"old complete file");
    let left: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 1, "temporary files left behind: {left:?}");
    let mut w = AtomicWriter::create(&p).unwrap();
    w.write_all(b"new complete file").unwrap();
    w.commit().unwrap();
    assert_eq!(std::fs::read(&p).unwrap(), b"new complete file");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
    std::fs::remove_dir_all(&d).unwrap();
}
