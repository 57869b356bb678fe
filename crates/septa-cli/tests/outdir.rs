//! Output-folder guarantees (`io/files/outdir.rs`): a second writer is
//! refused, runs killed at random points leave nothing a reader takes for a
//! result and nothing the next run keeps, Ctrl-C says so and removes its
//! partial files, and the folder never mixes two runs.
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-outdir-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn septa(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_septa")).args(args).output().unwrap()
}

/// A function file of `n` spheres (bigger outputs: longer writes to kill).
fn spheres(dir: &Path, n: usize) -> PathBuf {
    let list: Vec<String> = (0..n)
        .map(|i| {
            let t = i as f64 / n as f64;
            format!(
                r#"{{"type":"sphere","center":[{},{},{}],"radius":0.45}}"#,
                0.3 * t - 0.15,
                0.2 * t - 0.1,
                0.1 - 0.2 * t
            )
        })
        .collect();
    let p = dir.join(format!("spheres{n}.json"));
    std::fs::write(&p, format!("[{}]", list.join(","))).unwrap();
    p
}

fn temps(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.') && n.contains(".tmp"))
        .collect()
}

/// Every file of the manifest exists with its size, and the PLY and the
/// JSON come from one run (same vertex count).
fn assert_one_set(dir: &Path) {
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap();
    for f in m["files"].as_array().unwrap() {
        let len = std::fs::metadata(dir.join(f["name"].as_str().unwrap())).unwrap().len();
        assert_eq!(len, f["bytes"].as_u64().unwrap(), "{f}");
    }
    let net: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("network.json")).unwrap()).unwrap();
    let ply = std::fs::read(dir.join("network.ply")).unwrap();
    let head = String::from_utf8_lossy(&ply[..ply.len().min(400)]).into_owned();
    let nv: usize = head.lines().find_map(|l| l.strip_prefix("element vertex ")).unwrap().trim().parse().unwrap();
    assert_eq!(nv, net["points"].as_array().unwrap().len(), "network.ply and network.json from different runs");
}

#[test]
fn a_second_writer_is_refused() {
    let dir = scratch("lock");
    let f = spheres(&dir, 2);
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    // Hold the folder's lock as a running septa would.
    let lock = std::fs::File::create(out.join(".septa.lock")).unwrap();
    lock.lock().unwrap();
    let r = septa(&["ia", f.to_str().unwrap(), "--grid", "6", "-o", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(err.contains("another septa run is writing") && err.contains(out.to_str().unwrap()), "{err}");
    assert!(!out.join("network.json").exists());
    // While it is held, the viewer refuses the folder as being written.
    let v = septa(&["view", out.to_str().unwrap(), "--no-open"]);
    assert_eq!(v.status.code(), Some(2));
    drop(lock);
    let r = septa(&["ia", f.to_str().unwrap(), "--grid", "6", "-o", out.to_str().unwrap()]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert_one_set(&out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn concurrent_writers_never_mix() {
    let dir = scratch("race");
    let (a, b) = (spheres(&dir, 3), spheres(&dir, 5));
    let out = dir.join("out");
    for round in 0..4 {
        let spawn = |f: &Path, g: &str| {
            Command::new(env!("CARGO_BIN_EXE_septa"))
                .args(["ia", f.to_str().unwrap(), "--grid", g, "-o", out.to_str().unwrap()])
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        };
        let (pa, pb) = (spawn(&a, "20"), spawn(&b, "21"));
        let (ra, rb) = (pa.wait_with_output().unwrap(), pb.wait_with_output().unwrap());
        for r in [&ra, &rb] {
            let err = String::from_utf8_lossy(&r.stderr);
            assert!(r.status.success() || (r.status.code() == Some(2) && err.contains("another septa run")), "{err}");
        }
        assert!(ra.status.success() || rb.status.success(), "round {round}: both refused");
        assert_one_set(&out);
        assert!(temps(&out).is_empty(), "{:?}", temps(&out));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn killed_runs_leave_no_result_and_no_leftovers() {
    let dir = scratch("kill");
    let f = spheres(&dir, 6);
    let out = dir.join("out");
    // Deterministic "random" kill points from 0 to ~0.6 s.
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    for _ in 0..6 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let ms = x % 600;
        let mut child = Command::new(env!("CARGO_BIN_EXE_septa"))
            .args(["ia", f.to_str().unwrap(), "--grid", "48", "-o", out.to_str().unwrap()])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(ms));
        let _ = child.kill(); // SIGKILL
        let status = child.wait().unwrap();
        if out.join("manifest.json").exists() {
            // Killed after the manifest (or it finished): a whole set.
            assert_one_set(&out);
        } else if out.join(".septa.lock").exists() {
            // Killed mid-write: readers refuse the folder as incomplete.
            let v = septa(&["view", out.to_str().unwrap(), "--no-open"]);
            let err = String::from_utf8_lossy(&v.stderr);
            assert_eq!(v.status.code(), Some(2), "{status:?} {err}");
            assert!(err.contains("incomplete"), "{err}");
        }
    }
    // The next run removes every leftover (also one planted as a SIGKILL
    // mid-write leaves it, whatever the kill points above hit) and writes a whole set.
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join(".network.ply.tmp999999"), vec![0u8; 4096]).unwrap();
    let r = septa(&["ia", f.to_str().unwrap(), "--grid", "8", "-o", out.to_str().unwrap()]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert!(temps(&out).is_empty(), "{:?}", temps(&out));
    assert_one_set(&out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn ctrl_c_says_so_and_removes_partial_files() {
    let dir = scratch("sigint");
    let f = spheres(&dir, 6);
    let out = dir.join("out");
    for ms in [150, 400] {
        let child = Command::new(env!("CARGO_BIN_EXE_septa"))
            .args(["ia", f.to_str().unwrap(), "--grid", "48", "-o", out.to_str().unwrap()])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(ms));
        // SAFETY: signalling our own child by its id.
        unsafe { libc_kill(child.id() as i32, 2) };
        let r = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        if r.status.success() {
            assert_one_set(&out);
            continue;
        }
        assert_eq!(r.status.code(), Some(130), "{err}");
        assert!(err.contains("interrupted"), "{err}");
        if out.exists() {
            assert!(temps(&out).is_empty(), "{:?}", temps(&out));
            assert!(!out.join("manifest.json").exists());
        }
    }
}

#[cfg(unix)]
extern "C" {
    #[link_name = "kill"]
    fn libc_kill(pid: i32, sig: i32) -> i32;
}

/// A multiblock's pieces (`network/<block>.vtu`) belong to the set: listed
/// in the manifest with their sizes, staged like every file, and a piece
/// the next result has no cells for goes with the old set.
#[test]
fn multiblock_pieces_are_part_of_the_set() {
    let dir = scratch("vtm");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let run = |input: &Path| {
        let r = septa(&["ia", input.to_str().unwrap(), "-o", o, "--format", "json,ply,vtm", "--grid", "12"]);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        assert_one_set(&out);
        let m: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("manifest.json")).unwrap()).unwrap();
        let mut names: Vec<String> =
            m["files"].as_array().unwrap().iter().map(|f| f["name"].as_str().unwrap().to_string()).collect();
        names.sort();
        assert!(temps(&out).is_empty() && temps(&out.join("network")).is_empty());
        let vtm = std::fs::read_to_string(out.join("network.vtm")).unwrap();
        for n in names.iter().filter(|n| n.starts_with("network/")) {
            assert!(vtm.contains(&format!("file=\"{n}\"")), "{vtm}");
        }
        names
    };
    // Three spheres: chains (circles, no corners); one sphere: none.
    let three = run(&spheres(&dir, 3));
    for b in ["patches", "chains", "cells"] {
        assert!(three.contains(&format!("network/{b}.vtu")), "{three:?}");
    }
    let one = run(&spheres(&dir, 1));
    assert!(one.contains(&"network/patches.vtu".to_string()) && one.contains(&"network/cells.vtu".to_string()));
    assert!(!one.iter().any(|n| n.contains("chains") || n.contains("corners")), "{one:?}");
    assert!(!out.join("network/chains.vtu").exists() && !out.join("network/corners.vtu").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--fsync` / `SEPTA_FSYNC=1` (flush each file to the disk before its
/// rename) write the same set as the default, and the default issues no
/// flush: checked through `strace` where it is installed (the flush is not
/// visible to the files themselves).
#[test]
fn fsync_writes_the_same_set() {
    let dir = scratch("fsync");
    let f = spheres(&dir, 3);
    let run = |name: &str, flag: Option<&str>, env: bool| -> PathBuf {
        let out = dir.join(name);
        let mut args = vec!["ia", f.to_str().unwrap(), "--grid", "8", "-o", out.to_str().unwrap()];
        if let Some(flag) = flag {
            args.insert(0, flag);
        }
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_septa"));
        cmd.args(&args);
        if env {
            cmd.env("SEPTA_FSYNC", "1");
        } else {
            cmd.env_remove("SEPTA_FSYNC");
        }
        let r = cmd.output().unwrap();
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        assert_one_set(&out);
        out
    };
    let plain = run("plain", None, false);
    for other in [run("flag", Some("--fsync"), false), run("env", None, true)] {
        for file in ["network.ply", "network.obj"] {
            assert_eq!(std::fs::read(plain.join(file)).unwrap(), std::fs::read(other.join(file)).unwrap(), "{file}");
        }
    }
    let fsyncs = |flag: Option<&str>| -> Option<usize> {
        let out = dir.join("traced");
        let mut args = vec!["-f", "-e", "trace=fsync", env!("CARGO_BIN_EXE_septa")];
        args.extend(flag);
        args.extend(["ia", f.to_str().unwrap(), "--grid", "8", "-o", out.to_str().unwrap()]);
        let r = Command::new("strace").args(&args).env_remove("SEPTA_FSYNC").output().ok()?;
        r.status.success().then(|| String::from_utf8_lossy(&r.stderr).lines().filter(|l| l.contains("fsync(")).count())
    };
    match (fsyncs(None), fsyncs(Some("--fsync"))) {
        (Some(off), Some(on)) => {
            assert_eq!(off, 0, "the default flushed files");
            assert!(on >= 2, "--fsync flushed {on} files");
        }
        _ => eprintln!("strace not available: the flushes themselves were not observed"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}
