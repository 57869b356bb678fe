//! `septa remesh OUT L`: a written result remeshed in place, as one set of
//! files (the same formats, the same topology, quality triangles, the
//! exact check passing), and bad folders or lengths refused without
//! touching the folder.
use std::path::PathBuf;
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-remesh-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn septa(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_septa")).args(args).output().unwrap()
}

fn doc(dir: &std::path::Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join("network.json")).unwrap()).unwrap()
}

fn files(dir: &std::path::Path) -> Vec<String> {
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap();
    let mut f: Vec<String> =
        m["files"].as_array().unwrap().iter().map(|f| f["name"].as_str().unwrap().into()).collect();
    f.sort();
    f
}

#[test]
fn remesh_rewrites_a_network_and_a_regions_folder() {
    let dir = scratch("ok");
    for (job, scene) in [("ia", "builtin:sphere-with-hole"), ("regions", "builtin:sphere-plane-hole")] {
        let out = dir.join(job);
        let o = out.to_str().unwrap();
        let r = septa(&[job, scene, "-o", o, "-q"]);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let (before, set) = (doc(&out), files(&out));
        let r = septa(&["remesh", o, "0.1", "--json"]);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let rep: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
        let after = doc(&out);
        assert_eq!(files(&out), set, "{job}: the same files");
        for k in ["patches", "chains", "corners", "shells", "cells"] {
            assert_eq!(before[k].as_array().unwrap().len(), after[k].as_array().unwrap().len(), "{job} {k}");
        }
        assert_eq!(before["patches"].as_array().unwrap().len(), after["patches"].as_array().unwrap().len());
        assert_eq!(before["cells"], after["cells"], "{job}: the cells and their labels");
        let r = &rep["remesh"];
        assert_eq!(r["refused"], 0, "{job}");
        assert_eq!(r["patches_kept"], true, "{job}");
        assert!(r["after"]["min_angle"].as_f64().unwrap() >= 20.0, "{job}: {}", r["after"]);
        assert_eq!(after["remesh"], *r);
        let faces = after["faces"].as_array().unwrap();
        assert_eq!(faces.len(), r["after"]["triangles"].as_u64().unwrap() as usize);
        assert!(faces.iter().all(|f| f.as_array().unwrap().len() == 3));
        let e = &rep["embedding"]["after"];
        for k in ["coincident_points", "degenerate_triangles", "intersecting_pairs"] {
            assert_eq!(e[k], 0, "{job} {k}");
        }
        assert!(!std::fs::read_dir(&out).unwrap().flatten().any(|e| {
            let n = e.file_name().to_string_lossy().into_owned();
            n.starts_with('.') && n != ".septa.lock"
        }));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn remesh_refuses_bad_folders_and_lengths() {
    let dir = scratch("bad");
    let d = dir.to_str().unwrap();
    let r = septa(&["remesh", d, "0.1"]);
    assert_eq!(r.status.code(), Some(2));
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(err.contains(d) && err.contains("network.npz"), "{err}");
    let out = dir.join("json-only");
    let o = out.to_str().unwrap();
    assert!(septa(&["ia", "builtin:sphere-with-hole", "-o", o, "-q", "--format", "json"]).status.success());
    let before = std::fs::read(out.join("network.json")).unwrap();
    let r = septa(&["remesh", o, "0.1"]);
    assert_eq!(r.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&r.stderr).contains("--format npz"));
    for bad in ["0", "-1", "nan"] {
        let r = septa(&["remesh", o, bad]);
        assert_eq!(r.status.code(), Some(2), "{bad}");
    }
    assert_eq!(std::fs::read(out.join("network.json")).unwrap(), before, "the folder is untouched");
    let _ = std::fs::remove_dir_all(&dir);
}
