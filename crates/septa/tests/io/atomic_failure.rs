//! Failure injection for atomic writes (`io/atomic.rs`, architecture
//! invariant 3: nothing half-written is left behind). A write that fails
//! part-way, by an error of the writer or by a panic inside it, must leave
//! the old file byte for byte and no temporary sibling. The writer closure
//! is the injection point: it writes part of the new content, then fails.
//! The CLI's and Python's writers are tested against a real I/O error
//! (a file-size limit) in `septa-cli/tests/atomic_failure.rs` and
//! `tests/python/test_atomic_failure.py`.

use std::io::Write;
use std::path::{Path, PathBuf};

use septa::io::{write_atomic, write_atomic_with};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-atomic-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every file in `dir`, sorted (temporary files included: they start with
/// a dot).
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

const OLD: &[u8] = b"old content, complete\n";

#[test]
fn a_failing_writer_leaves_the_old_file_and_no_temporary() {
    let dir = scratch("error");
    let path = dir.join("network.json");
    write_atomic(&path, OLD).unwrap();
    // more than the 1 MiB buffer, so part of it reaches the temporary file
    let big = vec![b'x'; 3 << 20];
    let err = write_atomic_with(&path, |w| {
        w.write_all(&big)?;
        Err(std::io::Error::other("injected failure"))
    })
    .unwrap_err();
    assert!(err.to_string().contains("injected failure"), "{err}");
    assert!(err.to_string().contains("network.json"), "the error names the file: {err}");
    assert_eq!(std::fs::read(&path).unwrap(), OLD);
    assert_eq!(listing(&dir), vec!["network.json"]);
    // the same for a file that did not exist: nothing appears
    let fresh = dir.join("fresh.ply");
    assert!(write_atomic_with(&fresh, |w| {
        w.write_all(b"partial")?;
        Err(std::io::Error::other("injected"))
    })
    .is_err());
    assert_eq!(listing(&dir), vec!["network.json"]);
    // and a writer that succeeds replaces the file whole
    write_atomic(&path, b"new").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"new");
    assert_eq!(listing(&dir), vec!["network.json"]);
}

#[test]
fn a_panicking_writer_leaves_the_old_file_and_no_temporary() {
    let dir = scratch("panic");
    let path = dir.join("surfaces.obj");
    write_atomic(&path, OLD).unwrap();
    let caught = std::panic::catch_unwind(|| {
        let _ = write_atomic_with(&path, |w| {
            w.write_all(&vec![b'y'; 2 << 20])?;
            panic!("injected panic inside a writer");
        });
    });
    assert!(caught.is_err());
    assert_eq!(std::fs::read(&path).unwrap(), OLD);
    assert_eq!(listing(&dir), vec!["surfaces.obj"], "a temporary file survived the panic");
}

#[test]
fn a_failing_rename_leaves_no_temporary() {
    // The destination is a non-empty directory: everything is written,
    // then the rename fails.
    let dir = scratch("rename");
    let path = dir.join("out.json");
    std::fs::create_dir_all(path.join("inside")).unwrap();
    assert!(write_atomic(&path, b"data").is_err());
    assert!(path.join("inside").is_dir());
    assert_eq!(listing(&dir), vec!["out.json"]);
}
