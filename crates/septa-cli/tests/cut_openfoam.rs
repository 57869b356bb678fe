//! `septa cut --format foam --patch NAME=SIDE --check-mesh` against
//! OpenFOAM's own `checkMesh` (Debian's `openfoam` package, v1912): the
//! named patches, and every quantity `--check-mesh` reports equal to what
//! `checkMesh` prints for the same files, on a channel (a 4 x 1 x 1 box
//! less a cylinder and a sphere, inlet and outlet named) and on two cubes
//! sharing an edge (a non-manifold input, TopoCut App. C). Without
//! `checkMesh` on the PATH the comparison is skipped with a message
//! (`SEPTA_REQUIRE_OPENFOAM=1` makes that a failure); the patch and report
//! checks run regardless.
use std::path::{Path, PathBuf};
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-cut-openfoam-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// OBJ text of vertices and triangles (0-based).
fn obj(v: &[[f64; 3]], t: &[[u32; 3]]) -> String {
    let mut s = String::new();
    for p in v {
        s += &format!("v {:?} {:?} {:?}\n", p[0], p[1], p[2]);
    }
    for f in t {
        s += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    s
}

/// An axis-aligned box's 12 triangles, outward or (`inward`) facing in.
fn add_box(v: &mut Vec<[f64; 3]>, t: &mut Vec<[u32; 3]>, lo: [f64; 3], hi: [f64; 3], inward: bool) {
    let mut id = |p: [f64; 3]| match v.iter().position(|q| *q == p) {
        Some(i) => i as u32,
        None => {
            v.push(p);
            v.len() as u32 - 1
        }
    };
    let c: Vec<u32> =
        (0..8).map(|i: usize| id(std::array::from_fn(|k| if (i >> k) & 1 == 1 { hi[k] } else { lo[k] }))).collect();
    for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        for f in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            let f = f.map(|i| c[i]);
            t.push(if inward { [f[0], f[2], f[1]] } else { f });
        }
    }
}

/// The channel: the box [0, 4] x [0, 1]^2 less a cylinder (axis z through
/// (1, 0.5), radius 0.2, z in [0.15, 0.85], 32 sides) and a sphere (centre
/// (2.5, 0.5, 0.5), radius 0.25, 24 x 12), both cavities facing in.
fn channel() -> String {
    let (mut v, mut t) = (Vec::new(), Vec::new());
    add_box(&mut v, &mut t, [0.0; 3], [4.0, 1.0, 1.0], false);
    let push = |v: &mut Vec<[f64; 3]>, p: [f64; 3]| {
        v.push(p);
        v.len() as u32 - 1
    };
    let tau = std::f64::consts::TAU;
    let n = 32;
    let ring = |z: f64, k: usize| {
        [1.0 + 0.2 * (tau * k as f64 / n as f64).cos(), 0.5 + 0.2 * (tau * k as f64 / n as f64).sin(), z]
    };
    let b: Vec<u32> = (0..n).map(|k| push(&mut v, ring(0.15, k))).collect();
    let u: Vec<u32> = (0..n).map(|k| push(&mut v, ring(0.85, k))).collect();
    let (cb, cu) = (push(&mut v, [1.0, 0.5, 0.15]), push(&mut v, [1.0, 0.5, 0.85]));
    for i in 0..n {
        let j = (i + 1) % n;
        // outward, then flipped: a cavity
        for f in [[cb, b[j], b[i]], [cu, u[i], u[j]], [b[i], b[j], u[j]], [b[i], u[j], u[i]]] {
            t.push([f[0], f[2], f[1]]);
        }
    }
    let (c, r, nu, nv) = ([2.5, 0.5, 0.5], 0.25, 24, 12);
    let top = push(&mut v, [c[0], c[1], c[2] + r]);
    let bot = push(&mut v, [c[0], c[1], c[2] - r]);
    let rings: Vec<Vec<u32>> = (1..nv)
        .map(|i| {
            let th = std::f64::consts::PI * i as f64 / nv as f64;
            (0..nu)
                .map(|j| {
                    let ph = tau * j as f64 / nu as f64;
                    push(&mut v, [c[0] + r * th.sin() * ph.cos(), c[1] + r * th.sin() * ph.sin(), c[2] + r * th.cos()])
                })
                .collect()
        })
        .collect();
    for j in 0..nu {
        let k = (j + 1) % nu;
        let mut fs = vec![[top, rings[0][j], rings[0][k]], [bot, rings[nv - 2][k], rings[nv - 2][j]]];
        for a in 0..nv - 2 {
            let (r0, r1) = (&rings[a], &rings[a + 1]);
            fs.push([r0[j], r1[j], r1[k]]);
            fs.push([r0[j], r1[k], r0[k]]);
        }
        for f in fs {
            t.push([f[0], f[2], f[1]]);
        }
    }
    obj(&v, &t)
}

fn septa(dir: &Path, args: &[&str]) -> serde_json::Value {
    let res = Command::new(env!("CARGO_BIN_EXE_septa")).current_dir(dir).args(["cut"]).args(args).output().unwrap();
    assert!(res.status.success(), "{args:?}: {}", String::from_utf8_lossy(&res.stderr));
    serde_json::from_slice(&std::fs::read(dir.join("out/cut.json")).unwrap()).unwrap()
}

/// `checkMesh` in `case` (a copy of the polyMesh), or `None` without it.
fn check_mesh(case: &Path) -> Option<String> {
    let system = case.join("system");
    std::fs::create_dir_all(&system).unwrap();
    let head = |o: &str| format!("FoamFile {{ version 2.0; format ascii; class dictionary; object {o}; }}\n");
    std::fs::write(system.join("controlDict"), head("controlDict") + "application checkMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1; writeControl timeStep; writeInterval 1;\n").unwrap();
    std::fs::write(system.join("fvSchemes"), head("fvSchemes") + "ddtSchemes { default steadyState; } gradSchemes { default Gauss linear; } divSchemes { default none; } laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; } snGradSchemes { default corrected; }\n").unwrap();
    std::fs::write(system.join("fvSolution"), head("fvSolution")).unwrap();
    let mut cmd = Command::new("checkMesh");
    cmd.current_dir(case);
    if std::env::var_os("WM_PROJECT_DIR").is_none() && Path::new("/usr/share/openfoam/etc").is_dir() {
        cmd.env("WM_PROJECT_DIR", "/usr/share/openfoam");
    }
    match cmd.output() {
        Ok(o) => Some(String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)),
        Err(e) => {
            assert!(std::env::var_os("SEPTA_REQUIRE_OPENFOAM").is_none(), "checkMesh: {e}");
            eprintln!("checkMesh not found ({e}): the comparison with OpenFOAM is skipped (apt-get install openfoam)");
            None
        }
    }
}

/// The number after `key` (its first occurrence; `after` another key on
/// the same line when given).
fn number_after(text: &str, key: &str) -> f64 {
    let at = text.find(key).unwrap_or_else(|| panic!("'{key}' not in checkMesh's output:\n{text}")) + key.len();
    let s: String = text[at..].trim_start().chars().take_while(|c| c.is_ascii_digit() || "+-.e".contains(*c)).collect();
    s.trim_end_matches('.').parse().unwrap_or_else(|_| panic!("'{key}' followed by '{s}'"))
}

/// The line of `text` holding `key`, from `key` on.
fn line_from<'a>(text: &'a str, key: &str) -> &'a str {
    let at = text.find(key).unwrap_or_else(|| panic!("'{key}' not in checkMesh's output:\n{text}"));
    text[at..].lines().next().unwrap()
}

fn close(a: f64, b: f64) -> bool {
    // checkMesh prints 6 significant digits
    (a - b).abs() <= 1e-5 * a.abs().max(b.abs()) + 1e-12
}

/// Cuts `mesh` in `dir`, compares `--check-mesh` with `checkMesh`; returns
/// the report.
fn cut_and_compare(dir: &Path, args: &[&str]) -> serde_json::Value {
    let mut all = args.to_vec();
    all.extend_from_slice(&["-o", "out", "--format", "foam", "--check-mesh", "-q"]);
    let j = septa(dir, &all);
    let r = j["check_mesh"].clone();
    assert!(r.is_object(), "{j}");
    let Some(text) = check_mesh(&dir.join("out")) else { return j };
    assert!(text.contains("Upper triangular ordering OK"), "{text}");
    assert_eq!(number_after(&text, "cells:") as u64, r["cells"].as_u64().unwrap(), "{text}");
    for (key, field) in [
        ("Total volume =", "total_volume"),
        ("Min volume =", "min_volume"),
        ("Max volume =", "max_volume"),
        ("Minimum face area =", "min_face_area"),
        ("Maximum face area =", "max_face_area"),
        ("Max aspect ratio =", "max_aspect_ratio"),
    ] {
        let (a, b) = (number_after(&text, key), r[field].as_f64().unwrap());
        assert!(close(a, b), "{key} checkMesh {a}, septa {b}\n{text}");
    }
    let line = line_from(&text, "non-orthogonality Max:");
    for (key, field) in [("Max:", "max_non_orthogonality"), ("average:", "average_non_orthogonality")] {
        let (a, b) = (number_after(line, key), r[field].as_f64().unwrap());
        assert!(close(a, b), "{key} checkMesh {a}, septa {b}\n{text}");
    }
    let pyramids = r["wrong_pyramids"].as_u64().unwrap();
    if pyramids > 0 {
        assert_eq!(number_after(&text, "Error in face pyramids:") as u64, pyramids, "{text}");
    } else {
        assert!(text.contains("Face pyramids OK"), "{text}");
    }
    let skew = r["highly_skew_faces"].as_u64().unwrap();
    let line = line_from(&text, "Max skewness =");
    assert!(close(number_after(line, "Max skewness ="), r["max_skewness"].as_f64().unwrap()), "{text}");
    if skew > 0 {
        // "Max skewness = 9.58398, 277 highly skew faces detected ..."
        assert_eq!(number_after(line, ",") as u64, skew, "{text}");
    } else {
        assert!(line.contains("OK"), "{text}");
    }
    let failed = r["failed"].as_array().unwrap().len();
    if failed == 0 {
        assert!(text.contains("Mesh OK"), "{text}");
    } else {
        assert_eq!(number_after(&text, "Failed") as usize, failed, "{text}");
    }
    j
}

#[test]
fn channel_with_named_inlet_and_outlet_against_check_mesh() {
    let dir = scratch("channel");
    std::fs::write(dir.join("channel.obj"), channel()).unwrap();
    let j = cut_and_compare(
        &dir,
        &["channel.obj", "--grid", "17", "5", "5", "--patch", "inlet=xmin", "--patch", "outlet=xmax"],
    );
    // the inlet and outlet: the box's faces x = 0 and x = 4, each cut by the
    // y and z planes (16 squares, 4 of them across the triangles' diagonal)
    let patches = j["foam_patches"].as_array().unwrap();
    let names: Vec<&str> = patches.iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(names[..3], ["inlet", "outlet", "surface"]);
    assert_eq!((patches[0]["faces"].as_u64(), patches[1]["faces"].as_u64()), (Some(20), Some(20)));
    assert_eq!(patches[0]["type"], "patch");
    assert_eq!(patches[2]["type"], "wall");
    let boundary = std::fs::read_to_string(dir.join("out/constant/polyMesh/boundary")).unwrap();
    assert!(
        boundary.contains("    inlet\n    {\n        type            patch;\n        nFaces          20;"),
        "{boundary}"
    );
    // the domain's volume: 4 less the cylinder's and sphere's polyhedra
    let r = &j["check_mesh"];
    assert_eq!(r["cells"], 256);
    assert!((r["total_volume"].as_f64().unwrap() - 3.84899716).abs() < 1e-7, "{r}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cubes_sharing_an_edge_pass_check_mesh() {
    let dir = scratch("edge");
    let (mut v, mut t) = (Vec::new(), Vec::new());
    add_box(&mut v, &mut t, [0.0; 3], [1.0; 3], false);
    add_box(&mut v, &mut t, [1.0, 1.0, 0.0], [2.0, 2.0, 1.0], false);
    std::fs::write(dir.join("edge.obj"), obj(&v, &t)).unwrap();
    let j = cut_and_compare(&dir, &["edge.obj", "--grid", "3", "--patch", "bottom=zmin"]);
    let r = &j["check_mesh"];
    // TopoCut's 4 cells; nothing for checkMesh to fail
    assert_eq!((r["cells"].as_u64(), j["cut_cells"].as_u64()), (Some(4), Some(4)));
    assert_eq!(r["failed"].as_array().map(Vec::len), Some(0), "{r}");
    assert!((r["total_volume"].as_f64().unwrap() - 2.0).abs() < 1e-14);
    assert_eq!(j["foam_patches"][0]["faces"], 4, "{j}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn triangulated_channel_against_check_mesh() {
    let dir = scratch("triangulated");
    std::fs::write(dir.join("channel.obj"), channel()).unwrap();
    let j = cut_and_compare(&dir, &["channel.obj", "--grid", "9", "3", "3", "--triangulate"]);
    // every face a triangle, and the same cells
    let faces = std::fs::read_to_string(dir.join("out/constant/polyMesh/faces")).unwrap();
    let polys: Vec<&str> = faces.lines().filter(|l| l.ends_with(')') && l.contains('(')).collect();
    assert!(polys.len() > 100 && polys.iter().all(|l| l.starts_with("3(")), "{}", polys.len());
    assert_eq!(j["check_mesh"]["faces"].as_u64(), Some(polys.len() as u64));
    assert_eq!(j["check_mesh"]["cells"], j["cut_cells"]);
    // the exact check of the triangles as written
    let res = Command::new(env!("CARGO_BIN_EXE_septa"))
        .current_dir(&dir)
        .args(["cut", "channel.obj", "--grid", "9", "3", "3", "--triangulate", "--verify", "-o", "v", "-q"])
        .output()
        .unwrap();
    assert!(res.status.success(), "{}", String::from_utf8_lossy(&res.stderr));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("v/cut.json")).unwrap()).unwrap();
    let w = &v["verify_written_file"];
    assert_eq!(w["faces"], w["triangles"], "{w}");
    assert_eq!(w["intersecting_pairs"], 0, "{w}");
    assert_eq!(w["degenerate_faces"], 0, "{w}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_patches_are_refused_before_any_work() {
    let dir = scratch("bad");
    std::fs::write(dir.join("channel.obj"), channel()).unwrap();
    for (patch, says) in [
        ("inlet=xmid", "not a side"),
        ("inlet", "expected NAME=SIDE"),
        ("surface=xmin", "is taken"),
        ("1inlet=xmin", "use letters"),
    ] {
        let res = Command::new(env!("CARGO_BIN_EXE_septa"))
            .current_dir(&dir)
            .args(["cut", "channel.obj", "--grid", "3", "-o", "out", "--patch", patch])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&res.stderr);
        assert!(!res.status.success() && err.contains(says), "{patch}: {err}");
        assert!(!dir.join("out").exists(), "{patch}");
    }
    for (a, b, says) in [("a=xmin", "b=xmin", "named twice"), ("a=xmin", "a=xmax", "is taken")] {
        let res = Command::new(env!("CARGO_BIN_EXE_septa"))
            .current_dir(&dir)
            .args(["cut", "channel.obj", "--grid", "3", "-o", "out", "--patch", a, "--patch", b])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&res.stderr);
        assert!(!res.status.success() && err.contains(says), "{a} {b}: {err}");
    }
    // a side the mesh has no face on: the corner tetrahedron touches x = 1
    // in one vertex only
    std::fs::write(dir.join("tet.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
        .unwrap();
    let res = Command::new(env!("CARGO_BIN_EXE_septa"))
        .current_dir(&dir)
        .args(["cut", "tet.obj", "--grid", "3", "-o", "out", "--patch", "top=xmax"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&res.stderr);
    assert!(!res.status.success() && err.contains("no triangle of the mesh lies on that side"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
