//! The bad-input corpus, generated here: every case either
//! exits with code 2 and a message naming the file (or argument) and the
//! element, or succeeds with a correct result. None may panic (101), abort
//! (134) or leave a partial output folder.
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-bad-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(dir: &Path, args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_septa"));
    c.current_dir(dir).args(args);
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().unwrap()
}

/// Exit code 2 and every `needles` in stderr; no panic text.
#[track_caller]
fn refused(dir: &Path, args: &[&str], needles: &[&str]) {
    refused_env(dir, args, &[], needles)
}

#[track_caller]
fn refused_env(dir: &Path, args: &[&str], env: &[(&str, &str)], needles: &[&str]) {
    let out = run(dir, args, env);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: message lacks {n:?}: {err}");
    }
}

#[track_caller]
fn succeeds(dir: &Path, args: &[&str]) -> String {
    let out = run(dir, args, &[]);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// A `.npy` (version 1) with the given descr, shape and raw data.
fn npy(descr: &str, fortran: bool, shape: &[usize], data: &[u8]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|s| s.to_string()).collect();
    let shape = if dims.len() == 1 { format!("({},)", dims[0]) } else { format!("({})", dims.join(", ")) };
    let mut h = format!(
        "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}",
        if fortran { "True" } else { "False" }
    );
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(h.len() as u16).to_le_bytes());
    out.extend_from_slice(h.as_bytes());
    out.extend_from_slice(data);
    out
}

fn npz(path: &Path, members: &[(&str, Vec<u8>)]) {
    let mut z = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
    for (name, bytes) in members {
        z.start_file(format!("{name}.npy"), zip::write::SimpleFileOptions::default()).unwrap();
        z.write_all(bytes).unwrap();
    }
    z.finish().unwrap();
}

const SPHERE: &str = r#"[{"type":"sphere","center":[0.1,0.05,0.02],"radius":0.5}]"#;

#[test]
fn arguments_are_checked_before_any_work() {
    let d = scratch("args");
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    std::fs::write(d.join("cube.obj"), CUBE).unwrap();
    refused(&d, &["ia", "f.json", "--grid", "4", "--block", "0", "-o", "o"], &["--block", "0"]);
    refused(&d, &["ia", "f.json", "--grid", "4", "--block", "0", "--stream", "s.ply"], &["--block"]);
    refused(&d, &["ia", "f.json", "--grid", "18446744073709551615", "-o", "o"], &["--grid", "1..=1624"]);
    refused(&d, &["ia", "f.json", "--grid", "8", "--threads", "1000000", "-o", "o"], &["--threads"]);
    refused(&d, &["ia", "f.json", "--grid", "8", "--bounds", "0", "0", "0", "1", "1", "nan", "-o", "o"], &["--bounds"]);
    refused(&d, &["cut", "cube.obj", "--random", "18446744073709551615", "-o", "c"], &["--random"]);
    refused(&d, &["cut", "cube.obj", "--grid", "18446744073709551615", "-o", "c"], &["--grid"]);
    refused(&d, &["cut", "cube.obj", "--grid", "2", "--explode", "nan", "-o", "c"], &["--explode", "finite"]);
    refused(&d, &["cut", "cube.obj", "--grid", "2", "--explode", "inf", "-o", "c"], &["--explode"]);
    refused(&d, &["demo", "--grid", "0", "--out", "demo"], &["--grid"]);
    refused(&d, &["regions", "builtin:sphere-with-hole", "--clean", "nan"], &["--clean"]);
    // Nothing was started: no output folder at all.
    for o in ["o", "c", "demo", "s.ply"] {
        assert!(!d.join(o).exists(), "{o} was written");
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn memory_is_estimated_before_allocating() {
    let d = scratch("memory");
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    let lim = [("SEPTA_MEMORY_LIMIT", "64M")];
    refused_env(&d, &["ia", "f.json", "--grid", "1000", "--dense", "-o", "o"], &lim, &["GB", "drop --dense"]);
    refused_env(&d, &["regions", "builtin:sphere-with-hole", "--dense"], &[("SEPTA_MEMORY_LIMIT", "1K")], &["coarser"]);
    // The default sparse path runs the same grid size class without the dense allocation.
    let out = run(&d, &["ia", "f.json", "--grid", "100", "--no-output", "--json"], &lim);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let _ = std::fs::remove_dir_all(&d);
}

/// The unit cube, outward (as `meshes/cube.obj` in the shared data folder).
const CUBE: &str = "v 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 1 1\nv 1 0 0\nv 1 0 1\nv 1 1 0\nv 1 1 1\n\
f 2 4 1\nf 5 2 1\nf 1 4 3\nf 3 5 1\nf 2 8 4\nf 6 2 5\nf 6 8 2\nf 4 8 3\nf 7 5 3\nf 3 8 7\nf 7 6 5\nf 8 6 7\n";

#[test]
fn grid_readers_name_file_and_element() {
    let d = scratch("grid");
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    // npz with 0 vertices, 0 tets and 2 functions (panicked in the network).
    npz(
        &d.join("empty.npz"),
        &[
            ("vertices", npy("<f8", false, &[0, 3], &[])),
            ("tets", npy("<i8", false, &[0, 4], &[])),
            ("values", npy("<f8", false, &[0, 2], &[])),
        ],
    );
    refused(&d, &["ia", "empty.npz", "-o", "o"], &["empty.npz", "0 tets"]);
    // A config whose gridBbox has a 2-number corner.
    std::fs::write(d.join("cfg.json"), r#"{"funcFile":"f.json","gridResolution":4,"gridBbox":[[0,0],[1,1,1]]}"#)
        .unwrap();
    refused(&d, &["ia", "cfg.json", "-o", "o"], &["cfg.json", "gridBbox"]);
    // A tet-mesh JSON with an index out of range, a fractional index, overlapping faces.
    std::fs::write(d.join("m1.json"), "[[[0,0,0],[1,0,0],[0,1,0],[0,0,1]],[[0,1,2,7]]]").unwrap();
    refused(&d, &["ia", "f.json", "--mesh", "m1.json", "-o", "o"], &["m1.json", "tet 0", "vertex 7"]);
    std::fs::write(d.join("m2.json"), "[[[0,0,0],[1,0,0],[0,1,0],[0,0,1]],[[0,1,2,2.5]]]").unwrap();
    refused(&d, &["ia", "f.json", "--mesh", "m2.json", "-o", "o"], &["m2.json", "tet 0"]);
    std::fs::write(d.join("m3.json"), "[[[0,0,0],[1,0,0],[0,1,0],[0,0,1],[0.1,0.1,0.1]],[[0,1,2,3],[4,1,2,3]]]")
        .unwrap();
    refused(&d, &["ia", "f.json", "--mesh", "m3.json", "-o", "o"], &["m3.json", "face"]);
    // The unit cube in 5 tets plus a sixth laid over them, sharing no face
    // with them (was accepted: 6 cells instead of 5), as JSON and as Gmsh.
    let cube = "[[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]]";
    let tets = "[[0,3,5,6],[1,0,3,5],[2,0,3,6],[4,0,5,6],[7,3,5,6],[0,1,2,4]]";
    std::fs::write(d.join("m4.json"), format!("[{cube},{tets}]")).unwrap();
    refused(&d, &["ia", "f.json", "--mesh", "m4.json", "-o", "o"], &["m4.json", "tets 0 and 5 overlap"]);
    let nodes: Vec<String> = (0..8).map(|i| format!("{} {} {} {}", i + 1, i & 1, (i >> 1) & 1, (i >> 2) & 1)).collect();
    let elems = ["1 4 6 7", "2 1 4 6", "3 1 4 7", "5 1 6 7", "8 4 6 7", "1 2 3 5"];
    let elems: Vec<String> = elems.iter().enumerate().map(|(k, e)| format!("{} 4 0 {e}", k + 1)).collect();
    let msh = format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n{}\n$EndNodes\n$Elements\n6\n{}\n$EndElements\n",
        nodes.join("\n"),
        elems.join("\n")
    );
    std::fs::write(d.join("over.msh"), msh).unwrap();
    refused(&d, &["ia", "f.json", "--mesh", "over.msh", "-o", "o"], &["over.msh", "tets 0 and 5 overlap"]);
    // Gmsh: an element referring to a missing node.
    let msh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n1\n1 4 0 1 2 3 9\n$EndElements\n";
    std::fs::write(d.join("m.msh"), msh).unwrap();
    refused(&d, &["ia", "f.json", "--mesh", "m.msh", "-o", "o"], &["m.msh"]);
    // Function JSON and scenes.
    std::fs::write(d.join("g.json"), r#"[{"type":"sphere","center":[0,0],"radius":0.5}]"#).unwrap();
    refused(&d, &["ia", "g.json", "--grid", "4", "-o", "o"], &["g.json", "center"]);
    std::fs::write(d.join("s.toml"), "mode = \"ia\"\n[grid]\nresolution = 0\nbounds = [[-1,-1,-1],[1,1,1]]\n").unwrap();
    refused(&d, &["regions", "s.toml"], &["s.toml", "resolution"]);
    std::fs::write(d.join("bin.json"), [0xffu8, 0xfe, 0, 1, 2]).unwrap();
    refused(&d, &["ia", "bin.json", "--grid", "4", "-o", "o"], &["bin.json"]);
    assert!(!d.join("o").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn mesh_and_plane_readers() {
    let d = scratch("mesh");
    let cube = CUBE.to_string();
    // COFF with per-vertex and per-face colours: read, not taken as indices.
    let mut v = Vec::new();
    let mut f = Vec::new();
    for l in cube.lines() {
        let t: Vec<&str> = l.split_whitespace().collect();
        match t.first() {
            Some(&"v") => v.push(format!("{} {} {} 255 0 0 255", t[1], t[2], t[3])),
            Some(&"f") => {
                let ids: Vec<usize> =
                    t[1..].iter().map(|s| s.split('/').next().unwrap().parse::<usize>().unwrap() - 1).collect();
                f.push(format!("3 {} {} {} 255 255 0", ids[0], ids[1], ids[2]));
            }
            _ => {}
        }
    }
    std::fs::write(
        d.join("cube.off"),
        format!("COFF\n{} {} 0\n{}\n{}\n", v.len(), f.len(), v.join("\n"), f.join("\n")),
    )
    .unwrap();
    std::fs::write(d.join("cube.obj"), &cube).unwrap();
    let a = succeeds(&d, &["cut", "cube.off", "--grid", "2", "-o", "a", "--json"]);
    let b = succeeds(&d, &["cut", "cube.obj", "--grid", "2", "-o", "b", "--json"]);
    let cells = |s: &str| serde_json::from_str::<serde_json::Value>(s).unwrap()["cut_cells"].clone();
    assert_eq!(cells(&a), cells(&b));
    // -q: nothing on standard output, the same files
    assert_eq!(succeeds(&d, &["cut", "cube.obj", "--grid", "2", "-o", "q", "-q"]), "");
    assert_eq!(std::fs::read(d.join("q/cells.vtu")).unwrap(), std::fs::read(d.join("b/cells.vtu")).unwrap());
    // A closed cube scaled by 1e-200: outward, so it is cut like the unit cube.
    let tiny: String = cube
        .lines()
        .map(|l| {
            let t: Vec<&str> = l.split_whitespace().collect();
            if t.first() == Some(&"v") {
                let c: Vec<f64> = t[1..4].iter().map(|x| x.parse::<f64>().unwrap() * 1e-200).collect();
                format!("v {:e} {:e} {:e}\n", c[0], c[1], c[2])
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    std::fs::write(d.join("tiny.obj"), tiny).unwrap();
    let t = succeeds(&d, &["cut", "tiny.obj", "--grid", "2", "-o", "t", "--json"]);
    assert_eq!(cells(&t), cells(&b));
    // Two nested cubes (sides 3 and 1) facing the same way: refused, naming
    // the inner shell (was cut into overlapping cells of volumes 27 and 1).
    // Facing opposite ways (a cavity): cut.
    let nested = |inner_out: bool| {
        let mut s = String::new();
        for (lo, size) in [(0.0, 3.0), (1.0, 1.0)] {
            for l in cube.lines().filter(|l| l.starts_with("v ")) {
                let c: Vec<f64> = l[2..].split(' ').map(|x| lo + size * x.parse::<f64>().unwrap()).collect();
                s += &format!("v {} {} {}\n", c[0], c[1], c[2]);
            }
        }
        for (base, flip) in [(0, false), (8, !inner_out)] {
            for l in cube.lines().filter(|l| l.starts_with("f ")) {
                let ids: Vec<usize> = l[2..].split(' ').map(|x| x.parse::<usize>().unwrap() + base).collect();
                let (b, c) = if flip { (ids[2], ids[1]) } else { (ids[1], ids[2]) };
                s += &format!("f {} {b} {c}\n", ids[0]);
            }
        }
        s
    };
    std::fs::write(d.join("nested.obj"), nested(true)).unwrap();
    refused(&d, &["cut", "nested.obj", "--grid", "2", "-o", "x"], &["nested.obj", "shell 1", "inside shells [0]"]);
    std::fs::write(d.join("cavity.obj"), nested(false)).unwrap();
    let c = succeeds(&d, &["cut", "cavity.obj", "--grid", "2", "-o", "cav", "--json"]);
    assert!(c.contains("\"check\":\"ok\""), "{c}");
    // Bad meshes name the file and line or element.
    std::fs::write(d.join("bad.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n").unwrap();
    refused(&d, &["cut", "bad.off", "--grid", "2", "-o", "x"], &["bad.off", "index 5"]);
    std::fs::write(d.join("bad.obj"), "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n").unwrap();
    refused(&d, &["cut", "bad.obj", "--grid", "2", "-o", "x"], &["bad.obj"]);
    std::fs::write(d.join("bad.stl"), [0u8; 90]).unwrap();
    refused(&d, &["cut", "bad.stl", "--grid", "2", "-o", "x"], &["bad.stl"]);
    std::fs::write(d.join("bad.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n")
        .unwrap();
    refused(&d, &["cut", "bad.ply", "--grid", "2", "-o", "x"], &["bad.ply"]);
    std::fs::write(d.join("p.txt"), "1 0 0 -0.5\n0 1 0\n").unwrap();
    refused(&d, &["cut", "cube.obj", "--planes", "p.txt", "-o", "x"], &["p.txt", "2"]);
    // -o names an existing file.
    std::fs::write(d.join("afile"), "x").unwrap();
    refused(&d, &["cut", "cube.obj", "--grid", "2", "-o", "afile"], &["afile", "not a folder"]);
    assert!(!d.join("x").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn grid_counts_per_axis() {
    let d = scratch("grid_xyz");
    // a 4 x 1 x 1 box (the cube's x stretched by 4)
    let bar: String = CUBE.replace("v 1 ", "v 4 ");
    std::fs::write(d.join("bar.obj"), bar).unwrap();
    let cells = |args: &[&str]| {
        let j: serde_json::Value = serde_json::from_str(&succeeds(&d, args)).unwrap();
        assert_eq!(j["check"], "ok", "{args:?}");
        j["cut_cells"].as_u64().unwrap()
    };
    // 5 x planes (4 slabs of 1), 2 on the y and z faces: four unit cubes
    assert_eq!(cells(&["cut", "bar.obj", "--grid", "5", "2", "2", "-o", "a", "--json"]), 4);
    // one count on every axis: 4 x 4 x 4 slabs of aspect 4
    assert_eq!(cells(&["cut", "bar.obj", "--grid", "5", "-o", "b", "--json"]), 64);
    // a count of 1: one plane through the middle (2 cells along z)
    assert_eq!(cells(&["cut", "bar.obj", "--grid", "2", "2", "1", "-o", "c", "--json"]), 2);
    refused(&d, &["cut", "bar.obj", "--grid", "5", "2", "-o", "x"], &["--grid", "one count or three"]);
    refused(&d, &["cut", "bar.obj", "--grid", "5", "0", "2", "-o", "x"], &["--grid"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn label_volumes() {
    let d = scratch("labels");
    // 3x3x3 labels as int64 C order, with a block of label 1.
    let mut lab = vec![0i64; 27];
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                lab[(i * 3 + j) * 3 + k] = 1;
            }
        }
    }
    let bytes: Vec<u8> = lab.iter().flat_map(|x| x.to_le_bytes()).collect();
    std::fs::write(d.join("v.npy"), npy("<i8", false, &[3, 3, 3], &bytes)).unwrap();
    refused(&d, &["labels", "v.npy", "--sigma", "1e-300"], &["--sigma"]);
    refused(&d, &["labels", "v.npy", "--sigma", "1e9"], &["--sigma"]);
    std::fs::write(d.join("t.npy"), &npy("<i8", false, &[3, 3, 3], &bytes)[..100]).unwrap();
    refused(&d, &["labels", "t.npy"], &["t.npy"]);
    std::fs::write(d.join("two.npy"), npy("<i8", false, &[27], &bytes)).unwrap();
    refused(&d, &["labels", "two.npy"], &["two.npy", "3 axes"]);
    // NIfTI and NRRD: truncated or unsupported files name the file and field.
    std::fs::write(d.join("short.nii"), b"garbage").unwrap();
    refused(&d, &["labels", "short.nii"], &["short.nii", "NIfTI-1 header"]);
    std::fs::write(d.join("short.nii.gz"), [0x1fu8, 0x8b, 8, 0, 0]).unwrap();
    refused(&d, &["labels", "short.nii.gz"], &["short.nii.gz", "gzip"]);
    let ascii: String = lab.iter().map(|x| format!("{x}\n")).collect();
    let head = |extra: &str| format!("NRRD0004\ntype: int16\ndimension: 3\nsizes: 3 3 3\nencoding: ascii\n{extra}\n");
    std::fs::write(
        d.join("flat.nrrd"),
        head("").replace("dimension: 3\nsizes: 3 3 3", "dimension: 2\nsizes: 9 3") + &ascii,
    )
    .unwrap();
    refused(&d, &["labels", "flat.nrrd"], &["flat.nrrd", "3 axes"]);
    std::fs::write(d.join("det.nrrd"), head("data file: v.raw\n")).unwrap();
    refused(&d, &["labels", "det.nrrd"], &["det.nrrd", "detached"]);
    std::fs::write(d.join("few.nrrd"), head("") + "1 2 3\n").unwrap();
    refused(&d, &["labels", "few.nrrd"], &["few.nrrd", "3 ascii values, 27 expected"]);
    std::fs::write(d.join("dir.nrrd"), head("space directions: (1,0,0) (0,1,0)\n") + &ascii).unwrap();
    refused(&d, &["labels", "dir.nrrd"], &["dir.nrrd", "space directions"]);
    refused(&d, &["labels", "v.npy", "--spacing", "1", "0", "1"], &["--spacing"]);
    // --names: a label -> name table, into network.json and the summary; bad
    // tables name the file and the key before any work.
    std::fs::write(d.join("names.json"), r#"{"0": "background", "1": "liver"}"#).unwrap();
    let text = succeeds(&d, &["labels", "v.npy", "--names", "names.json", "-o", "named", "--format", "json"]);
    assert!(text.contains("1 (liver)") && text.contains("0 (background)"), "{text}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("named/network.json")).unwrap()).unwrap();
    assert_eq!(doc["names"]["regions"], serde_json::json!({"0": "background", "1": "liver"}), "{}", doc["names"]);
    for (bad, needles) in [
        (r#"{"one": "liver"}"#, &["names.json", "\"one\"", "not an integer label"][..]),
        (r#"{"1": 7}"#, &["names.json", "label 1", "non-empty text"][..]),
        (r#"{"1": "a", "1": "b"}"#, &["names.json", "duplicate key"][..]),
        (r#"["liver"]"#, &["names.json", "label -> name"][..]),
    ] {
        std::fs::write(d.join("names.json"), bad).unwrap();
        refused(&d, &["labels", "v.npy", "--names", "names.json", "-o", "bad"], needles);
        assert!(!d.join("bad").exists(), "{bad}: an output folder was made");
    }
    refused(&d, &["labels", "v.npy", "--names", "missing.json"], &["--names", "missing.json"]);
    // The same labels as ascii NRRD (first axis fastest) with a mirror: the
    // surfaces of the .npy, moved.
    std::fs::write(d.join("ok.nrrd"), head("space directions: (-1,0,0) (0,1,0) (0,0,1)\n") + &ascii).unwrap();
    let n = succeeds(&d, &["labels", "ok.nrrd", "--json", "-o", "n"]);
    let ok = succeeds(&d, &["labels", "v.npy", "--json"]);
    let faces = |s: &str| serde_json::from_str::<serde_json::Value>(s).unwrap()["faces"].clone();
    assert_eq!(faces(&n), faces(&ok));
    assert!(ok.contains("\"surfaces\""), "{ok}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn views_of_bad_results() {
    let d = scratch("view");
    std::fs::create_dir_all(d.join("r")).unwrap();
    for (body, needle) in [
        (r#"{"points":[[0,0,0],[1,0,0],[0,1,0]],"faces":[[0,1,-1]]}"#.as_bytes().to_vec(), "point -1"),
        (r#"{"points":[[0,0,0],[1,0,0],[0,1,0]],"faces":[[0,1,99999999]]}"#.as_bytes().to_vec(), "99999999"),
        (vec![0x89, b'P', b'N', b'G', 0xff, 0, 1], "not UTF-8"),
    ] {
        std::fs::write(d.join("r/network.json"), body).unwrap();
        refused(&d, &["view", "r", "--no-open"], &["network.json", needle]);
    }
    // cut then ia into one folder: the folder (and its viewer) hold the ia result only.
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    std::fs::write(d.join("cube.obj"), CUBE).unwrap();
    succeeds(&d, &["cut", "cube.obj", "--grid", "2", "-o", "one"]);
    succeeds(&d, &["ia", "f.json", "--grid", "6", "-o", "one"]);
    assert!(!d.join("one/cells.obj").exists() && !d.join("one/cut.json").exists());
    succeeds(&d, &["ia", "f.json", "--grid", "6", "-o", "two"]);
    succeeds(&d, &["cut", "cube.obj", "--grid", "2", "-o", "two"]);
    assert!(!d.join("two/network.json").exists());
    let v = succeeds(&d, &["view", "two", "--no-open"]);
    assert!(v.contains("viewer"), "{v}");
    let data = std::fs::read_to_string(d.join("two/viewer/data.js")).unwrap();
    assert!(data.contains("\"cut\""), "the viewer shows the cut, the folder's current result");
    let _ = std::fs::remove_dir_all(&d);
}

#[cfg(unix)]
#[test]
fn closed_pipe_ends_quietly() {
    use std::os::unix::process::ExitStatusExt;
    let d = scratch("pipe");
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_septa"))
        .current_dir(&d)
        .args(["ia", "f.json", "--grid", "12", "--no-output", "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Close the reading end before anything is printed (like `| head -c0`).
    let mut child = child;
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked") && !err.contains("Broken pipe"), "{err}");
    assert!(out.status.success() || out.status.signal() == Some(13), "{:?} {err}", out.status);
    let _ = std::fs::remove_dir_all(&d);
}
