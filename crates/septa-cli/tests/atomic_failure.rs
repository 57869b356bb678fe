//! Failure injection for the CLI's writers (architecture invariant 3): a
//! job whose output write fails part-way must leave every file of the old
//! output folder whole (old or, if it was written before the failure,
//! new; never half) and no temporary file. The failure is a real I/O
//! error: the job runs under a file-size limit (`ulimit -f`, with SIGXFSZ
//! ignored so that write(2) returns EFBIG instead of killing the process).
#![cfg(unix)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-atomic-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every file under `dir` (relative path -> bytes).
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fn walk(base: &Path, dir: &Path, out: &mut BTreeMap<String, Vec<u8>>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(base, &p, out);
            } else {
                out.insert(p.strip_prefix(base).unwrap().to_string_lossy().into_owned(), std::fs::read(&p).unwrap());
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

/// Runs `septa args`, under a file-size limit of `limit_kib` when given.
fn septa(args: &[&str], limit_kib: Option<u64>) -> std::process::Output {
    let bin = env!("CARGO_BIN_EXE_septa");
    match limit_kib {
        None => Command::new(bin).args(args).output().unwrap(),
        Some(k) => Command::new("bash")
            .arg("-c")
            .arg(format!("trap '' XFSZ; ulimit -f {k}; exec \"$0\" \"$@\""))
            .arg(bin)
            .args(args)
            .output()
            .unwrap(),
    }
}

#[test]
fn a_job_that_fails_to_write_leaves_the_old_output_whole() {
    let spec = root().join("data/specs/nested8.json");
    let spec = spec.to_str().unwrap();
    let (old, new) = (scratch("old"), scratch("new"));
    let run = |grid: &str, dir: &Path, limit: Option<u64>| {
        septa(&["ia", spec, "--grid", grid, "-o", dir.to_str().unwrap()], limit)
    };
    // the old output, and (elsewhere) what the new job writes when it can
    let a = run("12", &old, None);
    assert!(a.status.success(), "{}", String::from_utf8_lossy(&a.stderr));
    let b = run("20", &new, None);
    assert!(b.status.success(), "{}", String::from_utf8_lossy(&b.stderr));
    let (before, fresh) = (files(&old), files(&new));
    let big = fresh.values().map(Vec::len).max().unwrap();
    let limit_kib = 8u64;
    assert!(big > 4 * 1024 * limit_kib as usize, "the new output ({big} bytes) must exceed the limit");

    // the same job over the old folder, with writes failing past 8 KiB
    let c = run("20", &old, Some(limit_kib));
    let err = String::from_utf8_lossy(&c.stderr);
    assert!(!c.status.success(), "the job succeeded under a {limit_kib} KiB limit");
    assert!(!err.contains("panicked"), "a failed write must be an error, not a panic: {err}");
    assert!(err.to_lowercase().contains("too large"), "the error names the cause: {err}");
    assert!(err.contains("network."), "the error names the file: {err}");
    let after = files(&old);
    let mut kept = 0;
    for (name, bytes) in &after {
        assert!(!name.contains(".tmp"), "temporary file {name} left behind");
        let was_old = before.get(name) == Some(bytes);
        let is_new = fresh.get(name) == Some(bytes);
        assert!(was_old || is_new, "{name} is neither the old nor the new file ({} bytes)", bytes.len());
        kept += (was_old && !is_new) as usize;
    }
    // nothing of the old output was lost, and the large files stayed old
    for name in before.keys() {
        assert!(after.contains_key(name), "{name} vanished");
    }
    assert!(kept > 0, "no old file survived: the limit did not bite");
}
