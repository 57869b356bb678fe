//! Small hostile inputs: each family either exits with code 2
//! and a message naming the file (or argument) and the element, or succeeds
//! with a correct result; none may crash, hang, or fill the memory. The
//! decompression bombs are checked by the child's peak resident memory.
#![cfg(unix)]
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-hostile-inputs-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run_env(dir: &Path, args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_septa"));
    c.current_dir(dir).args(args).stdin(Stdio::null());
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().unwrap()
}

#[track_caller]
fn refused_env(dir: &Path, args: &[&str], env: &[(&str, &str)], needles: &[&str]) -> String {
    let out = run_env(dir, args, env);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: message lacks {n:?}: {err}");
    }
    err
}

#[track_caller]
fn refused(dir: &Path, args: &[&str], needles: &[&str]) -> String {
    refused_env(dir, args, &[], needles)
}

#[track_caller]
fn succeeds(dir: &Path, args: &[&str]) -> Output {
    let out = run_env(dir, args, &[]);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    out
}

fn json(out: &Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout).unwrap()
}

const CUBE: &str = "v 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 1 1\nv 1 0 0\nv 1 0 1\nv 1 1 0\nv 1 1 1\n\
f 2 4 1\nf 5 2 1\nf 1 4 3\nf 3 5 1\nf 2 8 4\nf 6 2 5\nf 6 8 2\nf 4 8 3\nf 7 5 3\nf 3 8 7\nf 7 6 5\nf 8 6 7\n";

fn scene(functions: &str, extra: &str) -> String {
    format!(r#"{{"grid":{{"resolution":4,"bounds":[[-1,-1,-1],[1,1,1]]}},"functions":{functions}{extra}}}"#)
}

const TWO: &str = r#"[{"name":"a","type":"sphere","center":[0,0,0],"radius":0.6},{"name":"b","type":"sphere","center":[0.3,0,0],"radius":0.4}]"#;

#[test]
fn region_rules_nested_deeply_are_refused_not_a_crash() {
    let d = scratch("rules");
    let cases = [
        ("long.json", format!("{}a", "!".repeat(1_000_000)), "longer than the limit"),
        ("bangs.json", format!("{}a", "!".repeat(5_000)), "nested deeper than 256"),
        ("parens.json", format!("{}a{}", "(".repeat(20_000), ")".repeat(20_000)), "nested deeper than 256"),
    ];
    for (name, rule, needle) in cases {
        std::fs::write(d.join(name), scene(TWO, &format!(r#","solid":"{rule}""#))).unwrap();
        refused(&d, &["regions", name, "-o", "r"], &[name, "solid", needle]);
    }
    // A long chain of differences stays flat: a - b - b - ... = a - b.
    let chain = format!("a{}", " - b".repeat(10_000));
    std::fs::write(d.join("chain.json"), scene(TWO, &format!(r#","solid":"{chain}""#))).unwrap();
    std::fs::write(d.join("one.json"), scene(TWO, r#","solid":"a - b""#)).unwrap();
    let a = json(&succeeds(&d, &["regions", "chain.json", "-o", "c", "--json"]));
    let b = json(&succeeds(&d, &["regions", "one.json", "-o", "o", "--json"]));
    assert_eq!(a["faces"], b["faces"]);
    assert!(a["faces"].as_u64().unwrap() > 0);
    let _ = std::fs::remove_dir_all(&d);
}

/// A `.vtu` for `cut --verify` with one tetrahedron-like cell, its faces
/// stream given as text.
fn vtu(faces: &str, connectivity: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="1">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>
<Cells>
<DataArray type="Int64" Name="connectivity" format="ascii">{connectivity}</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">4</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">42</DataArray>
<DataArray type="Int64" Name="faces" format="ascii">{faces}</DataArray>
<DataArray type="Int64" Name="faceoffsets" format="ascii">17</DataArray>
</Cells></Piece></UnstructuredGrid></VTKFile>
"#
    )
}

#[test]
fn verify_reads_counts_and_indices_strictly() {
    let d = scratch("vtu");
    let good = "4 3 0 2 1 3 0 1 3 3 0 3 2 3 1 2 3";
    std::fs::write(d.join("good.vtu"), vtu(good, "0 1 2 3")).unwrap();
    let out = succeeds(&d, &["cut", "good.vtu", "--verify", "--json"]);
    assert_eq!(json(&out)["violations"], 0);
    for (name, faces, needle) in [
        ("e19.vtu", "1e19 3 0 2 1", "face count"),
        ("e12.vtu", "1e12 3 0 2 1", "face count"),
        ("e15.vtu", "4 1e15 0 2 1", "face size"),
        ("nan.vtu", "4 3 nan 2 1 3 0 1 3 3 0 3 2 3 1 2 3", "point NaN"),
        ("frac.vtu", "4 3 0.7 2 1 3 0 1 3 3 0 3 2 3 1 2 3", "point 0.7"),
    ] {
        std::fs::write(d.join(name), vtu(faces, "0 1 2 3")).unwrap();
        refused(&d, &["cut", name, "--verify"], &[name, needle]);
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn ply_counts_are_checked_against_the_file() {
    let d = scratch("ply");
    let head = |extra: &str| {
        format!("ply\nformat ascii 1.0\n{extra}element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n")
    };
    // a closed tetrahedron, with an element of no properties and a count
    // of 1.8e19 before it: it reads nothing, so it is skipped at once (was: a hang)
    let tet = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    let tet_head =
        head("element junk 18000000000000000000\n").replace("vertex 3", "vertex 4").replace("face 1", "face 4");
    std::fs::write(d.join("empty.ply"), tet_head + tet).unwrap();
    succeeds(&d, &["cut", "empty.ply", "--grid", "2", "-o", "t"]);
    // an element with properties and a count the file cannot hold
    std::fs::write(
        d.join("big.ply"),
        "ply\nformat binary_little_endian 1.0\nelement vertex 100000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
    )
    .unwrap();
    refused(&d, &["cut", "big.ply", "--grid", "2", "-o", "x"], &["big.ply", "element vertex", "100000000000 declared"]);
    // a vertex without z (was: z = 0 silently)
    std::fs::write(d.join("noz.ply"), head("").replace("property float z\n", "") + "0 0\n1 0\n0 1\n3 0 1 2\n").unwrap();
    refused(&d, &["cut", "noz.ply", "--grid", "2", "-o", "x"], &["noz.ply", "no `z` property"]);
    // a binary STL whose triangle count does not match its length
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&5u32.to_le_bytes());
    stl.extend_from_slice(&[0xffu8; 50 * 3]);
    std::fs::write(d.join("count.stl"), stl).unwrap();
    refused(&d, &["cut", "count.stl", "--grid", "2", "-o", "x"], &["count.stl", "says 5 triangles", "234 bytes"]);
    assert!(!d.join("x").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// The eight voxels (two labels) then zeros up to [`BOMB`] bytes, written
/// through `w` a megabyte at a time: the test never holds the bomb in
/// memory (a child forked from a large test process would count the
/// parent's pages in its peak).
fn bomb_into(w: &mut impl Write, head: &[u8]) {
    w.write_all(head).unwrap();
    let mut chunk = vec![0u8; 1 << 20];
    chunk[..8].copy_from_slice(&[0, 1, 0, 1, 0, 1, 0, 1]);
    for _ in 0..BOMB >> 20 {
        w.write_all(&chunk).unwrap();
        chunk[..8].fill(0);
    }
}

fn gz_file(path: &Path, prefix: &[u8], head: &[u8]) {
    let mut f = std::fs::File::create(path).unwrap();
    f.write_all(prefix).unwrap();
    let mut e = flate2::write::GzEncoder::new(f, flate2::Compression::fast());
    bomb_into(&mut e, head);
    e.finish().unwrap();
}

/// `septa ARGS` and the child's peak resident memory in bytes.
fn peak(dir: &Path, args: &[&str]) -> (Output, u64) {
    let child = Command::new(env!("CARGO_BIN_EXE_septa"))
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let (mut status, mut usage) = (0, unsafe { std::mem::zeroed::<libc::rusage>() });
    // SAFETY: waiting for our own child with valid out-pointers.
    let pid = unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    assert_eq!(pid, child.id() as i32);
    let code = if libc::WIFEXITED(status) { libc::WEXITSTATUS(status) } else { -1 };
    let out = Output {
        status: std::os::unix::process::ExitStatusExt::from_raw(code << 8),
        stdout: Vec::new(),
        stderr: Vec::new(),
    };
    (out, usage.ru_maxrss as u64 * 1024)
}

/// 192 MiB of zeros: a bomb of a few hundred kilobytes once compressed.
const BOMB: usize = 192 << 20;

#[test]
fn decompression_is_bounded_by_the_declared_shape() {
    let d = scratch("bombs");
    // NRRD, gzip: 2x2x2 int8 declared, the gzip stream holds 192 MiB.
    gz_file(&d.join("bomb.nrrd"), b"NRRD0004\ntype: int8\ndimension: 3\nsizes: 2 2 2\nencoding: gzip\n\n", b"");
    // NIfTI-1, gzip: 2x2x2 uint8 after the 352-byte header, then the zeros.
    let mut hdr = vec![0u8; 352];
    hdr[0..4].copy_from_slice(&348i32.to_le_bytes());
    for (k, v) in [3i16, 2, 2, 2, 1, 1, 1, 1].iter().enumerate() {
        hdr[40 + 2 * k..42 + 2 * k].copy_from_slice(&v.to_le_bytes());
    }
    hdr[70..72].copy_from_slice(&2i16.to_le_bytes()); // uint8
    hdr[72..74].copy_from_slice(&8i16.to_le_bytes()); // bitpix
    hdr[108..112].copy_from_slice(&352f32.to_le_bytes());
    hdr[344..348].copy_from_slice(b"n+1\0");
    gz_file(&d.join("bomb.nii.gz"), b"", &hdr);
    for name in ["bomb.nrrd", "bomb.nii.gz"] {
        let (out, rss) = peak(&d, &["labels", name, "--json", "-o", "l"]);
        assert!(out.status.success(), "{name}");
        assert!(rss < (BOMB as u64) / 2, "{name}: peak {rss} bytes: the bomb was inflated");
    }
    // .npz: 4 vertices, 1 tet, values, and an unused member of 192 MiB.
    let npy = |descr: &str, shape: &str, data: &[u8]| {
        let mut h = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
        while (10 + h.len() + 1) % 64 != 0 {
            h.push(' ');
        }
        h.push('\n');
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        out.extend_from_slice(&(h.len() as u16).to_le_bytes());
        out.extend_from_slice(h.as_bytes());
        out.extend_from_slice(data);
        out
    };
    let f8 = |v: &[f64]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut z = zip::ZipWriter::new(std::fs::File::create(d.join("bomb.npz")).unwrap());
    let opts = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .compression_level(Some(1));
    let members = [
        ("vertices.npy", npy("<f8", "(4, 3)", &f8(&[0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.]))),
        ("tets.npy", npy("<i8", "(1, 4)", &[0i64, 1, 2, 3].iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<_>>())),
        ("values.npy", npy("<f8", "(4,)", &f8(&[-1.0, 1.0, 1.0, 1.0]))),
    ];
    for (name, bytes) in &members {
        z.start_file(*name, opts).unwrap();
        z.write_all(bytes).unwrap();
    }
    z.start_file("junk.npy", opts).unwrap();
    bomb_into(&mut z, &npy("|u1", &format!("({BOMB},)"), b""));
    z.finish().unwrap();
    let (out, rss) = peak(&d, &["ia", "bomb.npz", "--no-output", "--json"]);
    assert!(out.status.success());
    assert!(rss < (BOMB as u64) / 2, "npz: peak {rss} bytes: an unused member was inflated");
    // NRRD sizes whose product wraps around (was: an index out of bounds)
    std::fs::write(
        d.join("wrap.nrrd"),
        "NRRD0004\ntype: int8\ndimension: 3\nsizes: 2305843009213693953 4 2\nencoding: raw\n\n\0\0\0\0\0\0\0\0",
    )
    .unwrap();
    refused(&d, &["labels", "wrap.nrrd"], &["wrap.nrrd", "sizes", "overflows"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn ranges_are_checked_and_name_the_field() {
    let d = scratch("ranges");
    std::fs::write(d.join("f.json"), r#"[{"type":"sphere","center":[0,0,0],"radius":0.5}]"#).unwrap();
    let big = ["--bounds", "-1e308", "-1e308", "-1e308", "1e308", "1e308", "1e308"];
    refused(&d, &[&["ia", "f.json", "--grid", "4", "-o", "o"][..], &big].concat(), &["axis 0", "overflows"]);
    let near = ["--bounds", "1e16", "0", "0", "10000000000000008", "1", "1"];
    refused(&d, &[&["mi", "f.json", "--grid", "16", "-o", "o"][..], &near].concat(), &["axis 0", "grid lines"]);
    // `-1e-300` is a value of --bounds, not a flag
    let tiny = ["--bounds", "-1e-300", "-1", "-1", "1", "1", "1"];
    succeeds(&d, &[&["ia", "f.json", "--grid", "4", "--no-output"][..], &tiny].concat());
    // label placement beyond the doubles
    let lab: Vec<u8> = (0..27).flat_map(|i: i64| (i % 2).to_le_bytes()).collect();
    let mut npy = b"\x93NUMPY\x01\x00".to_vec();
    let mut h = "{'descr': '<i8', 'fortran_order': False, 'shape': (3, 3, 3), }".to_string();
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    npy.extend_from_slice(&(h.len() as u16).to_le_bytes());
    npy.extend_from_slice(h.as_bytes());
    npy.extend_from_slice(&lab);
    std::fs::write(d.join("v.npy"), npy).unwrap();
    refused(&d, &["labels", "v.npy", "--spacing", "1e308", "1", "1"], &["--spacing", "finite"]);
    refused(&d, &["labels", "v.npy", "--origin", "1.7e308", "0", "0", "--spacing", "1e307", "1", "1"], &["--origin"]);
    succeeds(&d, &["labels", "v.npy", "--origin", "-1e-300", "0", "0", "-o", "l"]);
    assert!(!d.join("o").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn cut_at_any_scale_is_the_unit_cut_scaled() {
    let d = scratch("scale");
    std::fs::write(d.join("cube.obj"), CUBE).unwrap();
    let unit = json(&succeeds(&d, &["cut", "cube.obj", "--grid", "2", "-o", "u", "--json"]));
    for s in ["1e300", "1e200", "1e160", "1e-200", "1e-300", "1e-310"] {
        let f: f64 = s.parse().unwrap();
        let scaled: String = CUBE
            .lines()
            .map(|l| match l.strip_prefix("v ") {
                Some(c) => {
                    let c: Vec<f64> = c.split(' ').map(|x| x.parse::<f64>().unwrap() * f).collect();
                    format!("v {:e} {:e} {:e}\n", c[0], c[1], c[2])
                }
                None => format!("{l}\n"),
            })
            .collect();
        let name = format!("cube{s}.obj");
        std::fs::write(d.join(&name), scaled).unwrap();
        let out = format!("o{s}");
        let j = json(&succeeds(&d, &["cut", &name, "--grid", "2", "-o", &out, "--json", "--verify"]));
        assert_eq!(j["cut_cells"], unit["cut_cells"], "{s}");
        assert_eq!(j["check"], "ok", "{s}");
        // compared at the cut's scale: 1e300^3 overflows, 1e-200^3 underflows
        // (the error was NaN, printed "volume error NaN", and passed)
        let e = &j["volume_relative_error"];
        assert!(e.as_f64().is_some_and(|e| e < 1e-12), "{s}: volume error {e}");
        let obj = std::fs::read_to_string(d.join(&out).join("cells.obj")).unwrap();
        for l in obj.lines().filter(|l| l.starts_with("v ")) {
            let c: Vec<f64> = l[2..].split_whitespace().map(|x| x.parse().unwrap()).collect();
            assert!(c.iter().all(|x| x.is_finite() && x.abs() <= 1.0000001 * f), "{s}: {l}");
        }
    }
    // the cut's plane tables alone beyond the memory limit: refused up front
    let lim = [("SEPTA_MEMORY_LIMIT", "64M")];
    refused_env(&d, &["cut", "cube.obj", "--grid", "2000", "-o", "g"], &lim, &["6000 planes", "fewer planes"]);
    assert!(!d.join("g").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn scene_fields_are_strict() {
    let d = scratch("strict");
    let misspelt = scene(
        r#"[{"type":"sphere","center":[0,0,0],
  "radiuss":0.5, "radius": 0.4}]"#,
        "",
    );
    std::fs::write(d.join("typo.json"), misspelt).unwrap();
    refused(&d, &["ia", "typo.json", "-o", "o"], &["typo.json:2:", "radiuss"]);
    let twice = scene("[{\"type\":\"sphere\",\"center\":[0,0,0],\n\"radius\":0.5,\n\"radius\":0.4}]", "");
    std::fs::write(d.join("twice.json"), twice).unwrap();
    refused(&d, &["ia", "twice.json", "-o", "o"], &["twice.json:3:", "duplicate key `radius`"]);
    std::fs::write(d.join("top.json"), scene(TWO, r#","surface":"all""#)).unwrap();
    refused(&d, &["regions", "top.json", "-o", "o"], &["top.json", "`surface`"]);
    // The reference's function format: a key it does not use is a warning.
    std::fs::write(d.join("ref.json"), r#"[{"type":"sphere","center":[0,0,0],"radius":0.5,"negate":true}]"#).unwrap();
    let out = succeeds(&d, &["ia", "ref.json", "--grid", "4", "--no-output"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("warning") && err.contains("ref.json:1:") && err.contains("negate"), "{err}");
    // Gmsh: a node tag given twice (was: the later node won silently).
    let msh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n2 5 5 5\n$EndNodes\n$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n";
    std::fs::write(d.join("dup.msh"), msh).unwrap();
    std::fs::write(d.join("f.json"), r#"[{"type":"sphere","center":[0,0,0],"radius":0.5}]"#).unwrap();
    refused(&d, &["ia", "f.json", "--mesh", "dup.msh", "-o", "o"], &["dup.msh:10:", "node tag 2 is given twice"]);
    // Two vertex ids at one position: a seam (was: accepted, cells split).
    let seam = "[[[0,0,0],[1,0,0],[0,1,0],[0,0,1],[1,0,0],[1,1,1]],[[0,1,2,3],[4,2,3,5]]]";
    std::fs::write(d.join("seam.json"), seam).unwrap();
    refused(
        &d,
        &["ia", "f.json", "--mesh", "seam.json", "-o", "o"],
        &["seam.json", "vertices 1 and 4", "same position"],
    );
    assert!(!d.join("o").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// `SEPTA_MEMORY_LIMIT` is a cap: a run that passes the estimates but grows
/// past the limit stops with exit 2 and a message naming the limit (was:
/// ran on past it). The same run without the limit succeeds.
#[test]
fn the_memory_limit_is_a_cap() {
    let d = scratch("cap");
    std::fs::write(
        d.join("f.json"),
        r#"[{"type":"sphere","center":[0.1,0,0],"radius":0.7},{"type":"sphere","center":[-0.1,0.05,0],"radius":0.6}]"#,
    )
    .unwrap();
    let args = ["ia", "f.json", "--grid", "160", "--no-output", "--json"];
    succeeds(&d, &args);
    refused_env(&d, &args, &[("SEPTA_MEMORY_LIMIT", "48M")], &["SEPTA_MEMORY_LIMIT", "memory limit"]);
    let _ = std::fs::remove_dir_all(&d);
}
