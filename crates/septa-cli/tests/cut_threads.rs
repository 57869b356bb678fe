//! `septa cut` writes the same files whatever the number of threads: with
//! `--threads 1` the main thread is the pool's only one, with more it works
//! beside the others (cut.rs), and the parallel stages sort what they find.
//! Checked on a degenerate cut (the cube's faces on the outermost planes of
//! an axis-aligned grid) and on random oblique planes.
use std::path::{Path, PathBuf};
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-cut-threads-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A closed, outward unit cube split into two triangles per side.
fn cube_obj() -> String {
    let mut s = String::new();
    for z in [0.0, 1.0] {
        for y in [0.0, 1.0] {
            for x in [0.0, 1.0] {
                s += &format!("v {x} {y} {z}\n");
            }
        }
    }
    for f in [
        [1, 3, 4, 2], // z = 0, facing -z
        [5, 6, 8, 7], // z = 1
        [1, 2, 6, 5], // y = 0
        [3, 7, 8, 4], // y = 1
        [1, 5, 7, 3], // x = 0
        [2, 4, 8, 6], // x = 1
    ] {
        s += &format!("f {} {} {}\nf {} {} {}\n", f[0], f[1], f[2], f[0], f[2], f[3]);
    }
    s
}

/// Runs a cut into `dir/out` and returns its files (cut.json without its
/// timings).
fn cut(dir: &Path, out: &str, args: &[&str]) -> Vec<(String, Vec<u8>)> {
    let res = Command::new(env!("CARGO_BIN_EXE_septa"))
        .current_dir(dir)
        .args(["cut", "cube.obj", "-o", out, "-q"])
        .args(args)
        .output()
        .unwrap();
    assert!(res.status.success(), "{args:?}: {}", String::from_utf8_lossy(&res.stderr));
    let mut files = Vec::new();
    for name in ["cells.vtu", "cells.obj", "cut.json"] {
        let bytes = std::fs::read(dir.join(out).join(name)).unwrap();
        let bytes = if name == "cut.json" {
            let mut j: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
            j.as_object_mut().unwrap().remove("seconds");
            serde_json::to_vec(&j).unwrap()
        } else {
            bytes
        };
        files.push((name.to_string(), bytes));
    }
    files
}

#[test]
fn cut_files_do_not_depend_on_the_thread_count() {
    let d = scratch("cube");
    std::fs::write(d.join("cube.obj"), cube_obj()).unwrap();
    for planes in [&["--grid", "5"][..], &["--random", "14", "--seed", "7"][..]] {
        let one = cut(&d, "t1", &[planes, &["--threads", "1"]].concat());
        let j: serde_json::Value = serde_json::from_slice(&one[2].1).unwrap();
        // a real cut, proven embedded
        assert!(j["cut_cells"].as_u64().unwrap() > 20, "{planes:?}: {j}");
        assert_eq!(j["check"], "ok", "{planes:?}");
        assert_eq!(j["embedding"]["report"]["intersecting_pairs"], 0, "{planes:?}");
        for threads in ["2", "0"] {
            let other = cut(&d, &format!("t{threads}"), &[planes, &["--threads", threads]].concat());
            for ((name, a), (_, b)) in one.iter().zip(&other) {
                assert!(a == b, "{planes:?}: {name} differs between --threads 1 and {threads}");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}
