//! Mesh and plane readers: the same mesh in every format, and errors that
//! name file and line.

use crate::common;

use septa::io::read_mesh;
use septa::io::{grid_planes, grid_planes_xyz, parse_planes, random_planes};
use std::path::{Path, PathBuf};

fn tmp(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa_io_test_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

const V: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
const T: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

#[test]
fn every_format_reads_the_same_tetrahedron() {
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1/1 4/1 3/1\nf -3 -2 -1\n";
    let off = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    let mut stl_a = String::from("solid t\n");
    let mut stl_b = vec![0u8; 80];
    stl_b.extend(4u32.to_le_bytes());
    for t in T {
        stl_a.push_str("facet normal 0 0 0\nouter loop\n");
        stl_b.extend([0u8; 12]);
        for k in t {
            let v = V[k as usize];
            stl_a.push_str(&format!("vertex {} {} {}\n", v[0], v[1], v[2]));
            for c in v {
                stl_b.extend((c as f32).to_le_bytes());
            }
        }
        stl_a.push_str("endloop\nendfacet\n");
        stl_b.extend([0u8; 2]);
    }
    stl_a.push_str("endsolid t\n");
    let mut ply_b = b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    for v in V {
        for c in v {
            ply_b.extend(c.to_le_bytes());
        }
    }
    for t in T {
        ply_b.push(3);
        for k in t {
            ply_b.extend((k as i32).to_le_bytes());
        }
    }
    for (name, bytes) in [
        ("t.obj", obj.as_bytes().to_vec()),
        ("t.off", off.as_bytes().to_vec()),
        ("t.ply", ply.as_bytes().to_vec()),
        ("tb.ply", ply_b),
        ("ta.stl", stl_a.into_bytes()),
        ("tb.stl", stl_b),
    ] {
        let m = read_mesh(&tmp(name, &bytes)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(m.vertices.len(), 4, "{name}");
        // same triangles up to vertex renumbering (STL welds in first-use order)
        let tris: Vec<[[f64; 3]; 3]> = m.triangles.iter().map(|t| t.map(|k| m.vertices[k as usize])).collect();
        let want: Vec<[[f64; 3]; 3]> = T.iter().map(|t| t.map(|k| V[k as usize])).collect();
        assert_eq!(tris, want, "{name}");
    }
}

#[test]
fn errors_name_file_and_line() {
    let p = tmp("bad.obj", b"v 0 0 0\nv 1 x 0\n");
    let e = read_mesh(&p).unwrap_err();
    assert_eq!(e.line, 2);
    assert!(e.to_string().contains("bad.obj:2"), "{e}");
    let p = tmp("bad2.obj", b"v 0 0 0\nf 1 2 3\n");
    assert_eq!(read_mesh(&p).unwrap_err().line, 2);
    let e = parse_planes(Path::new("p.plane"), "2 4\n1 0 0 0\n").unwrap_err();
    assert!(e.to_string().contains("announces 2"), "{e}");
    let e = parse_planes(Path::new("p.plane"), "1 0 0\n").unwrap_err();
    assert_eq!(e.line, 1);
}

#[test]
fn plane_files_and_generators() {
    let with = parse_planes(Path::new("a"), "2 4\n1.0 0.0 0.0 -0.5\n0 1 0 -0.25\n").unwrap();
    let without = parse_planes(Path::new("b"), "1.0 0.0 0.0 -0.5\n0 1 0 -0.25\n").unwrap();
    assert_eq!(with, without);
    let g = grid_planes(&V, 5);
    assert_eq!(g.len(), 15);
    assert_eq!(g[0], [1.0, 0.0, 0.0, -0.0]);
    assert_eq!(g[4], [1.0, 0.0, 0.0, -1.0]);
    // per-axis counts (TopoCut's bound_box_xyz): 3 x planes on the box's
    // faces and its middle, 2 y planes on its faces, 1 z plane in the middle
    let g = grid_planes_xyz(&V, [3, 2, 1]);
    let want: Vec<[f64; 4]> = vec![
        [1.0, 0.0, 0.0, -0.0],
        [1.0, 0.0, 0.0, -0.5],
        [1.0, 0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0, -0.0],
        [0.0, 1.0, 0.0, -1.0],
        [0.0, 0.0, 1.0, -0.5],
    ];
    assert_eq!(g, want);
    assert_eq!(grid_planes_xyz(&V, [5; 3]), grid_planes(&V, 5));
    let r1 = random_planes(&V, 10, 7);
    assert_eq!(r1, random_planes(&V, 10, 7));
    assert_ne!(r1, random_planes(&V, 10, 8));
}

#[test]
fn reference_plane_files_match_the_grid_generator() {
    for mesh in ["cube", "staircase", "knight", "plate_genus9", "bunny", "fertility"] {
        let data = common::shared_data();
        let m = read_mesh(&data.join(format!("meshes/{mesh}.obj"))).unwrap();
        for n in [5, 10, 20] {
            let f =
                septa::io::read_planes(Path::new(&format!("{}/topocut/{mesh}.A{n}.plane", data.display()))).unwrap();
            assert_eq!(grid_planes(&m.vertices, n), f, "{mesh} A{n}");
        }
    }
}
