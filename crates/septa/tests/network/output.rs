//! Output files round-trip: network.json parses to the same structure,
//! the binary PLY and the OBJ hold the same polygons, the VTU has the
//! announced sizes, and no temporary file is left behind.

use std::path::PathBuf;

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::io::write_network;
use septa::network::{compute, NetworkOptions};
use septa::scene::{sample_grid as sample, Primitive};

#[test]
fn outputs_round_trip() {
    let grid = Grid::Box(BoxGrid::new([6, 5, 7], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap());
    let f = [
        Primitive::sphere([0.1, 0.05, 0.02], 0.6),
        Primitive::sphere([0.4, 0.1, 0.03], 0.5),
        Primitive::sphere([-0.3, -0.2, 0.1], 0.45),
    ];
    let values = sample(&f, &grid.vertices());
    for mode in [Mode::Ia, Mode::Mi] {
        let net = compute(&grid, &values, 3, &NetworkOptions::new(mode)).unwrap();
        let dir: PathBuf = std::env::temp_dir().join(format!("septa-out-test-{}-{mode:?}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        write_network(&net, &Default::default(), &dir, &[("read", 0.0)]).unwrap();
        let names: Vec<String> =
            std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        // The five results (json npz ply obj vtu), the manifest written last
        // and the folder's lock (io/outdir.rs).
        assert_eq!(names.len(), 7, "{names:?}");
        assert!(names.iter().any(|n| n == "manifest.json") && names.iter().any(|n| n == ".septa.lock"), "{names:?}");
        // JSON
        let j: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("network.json")).unwrap()).unwrap();
        assert_eq!(j["faces"].as_array().unwrap().len(), net.num_faces());
        assert_eq!(j["points"].as_array().unwrap().len(), net.points.len());
        assert_eq!(j["cells"].as_array().unwrap().len(), net.cells.len());
        assert_eq!(j["shells"].as_array().unwrap().len(), net.shells.len());
        assert_eq!(j["counts"]["patches"].as_u64().unwrap() as usize, net.patches.len());
        for (f, face) in j["faces"].as_array().unwrap().iter().enumerate() {
            let vs: Vec<u32> = face.as_array().unwrap().iter().map(|v| v.as_u64().unwrap() as u32).collect();
            assert_eq!(vs, net.face(f));
        }
        // PLY
        let ply = std::fs::read(dir.join("network.ply")).unwrap();
        let end = ply.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        let mut pos = end + net.points.len() * 24;
        let int = |b: &[u8], p: usize| i32::from_le_bytes(b[p..p + 4].try_into().unwrap());
        for f in 0..net.num_faces() {
            // Polygon f as a fan of triangles, each naming f and its patch.
            let vs = net.face(f);
            for j in 1..vs.len() - 1 {
                assert_eq!(ply[pos], 3);
                pos += 1;
                let tri: Vec<u32> = (0..3).map(|i| int(&ply, pos + 4 * i) as u32).collect();
                assert_eq!(tri, [vs[0], vs[j], vs[j + 1]]);
                pos += 12;
                assert_eq!(int(&ply, pos) as usize, f);
                assert_eq!(int(&ply, pos + 4) as u32, net.face_patch[f]);
                let l = net.face_label[f];
                assert_eq!([int(&ply, pos + 8), int(&ply, pos + 12)], [l[0] as i32, l[1] as i32], "labels_0/1");
                let c = net.face_cells[f].map(|c| if c == u32::MAX { -1 } else { c as i32 });
                assert_eq!([int(&ply, pos + 16), int(&ply, pos + 20)], c, "cells_0/1");
                pos += 24 + 3;
            }
        }
        assert_eq!(pos, ply.len());
        // OBJ
        let obj = std::fs::read_to_string(dir.join("network.obj")).unwrap();
        assert_eq!(obj.lines().filter(|l| l.starts_with("f ")).count(), net.num_faces());
        assert_eq!(obj.lines().filter(|l| l.starts_with("l ")).count(), net.chains.len());
        assert_eq!(obj.lines().filter(|l| l.starts_with("g patch_")).count(), net.patches.len());
        // VTU: announced arrays fill the appended section exactly.
        let vtu = std::fs::read(dir.join("network.vtu")).unwrap();
        let start = vtu.windows(2).position(|w| w == b"\n_").unwrap() + 2;
        let nf = net.num_faces();
        let body =
            9 * 8 + net.points.len() * 24 + net.face_verts.len() * 4 + nf * 4 + nf + nf * 4 + nf * 16 + nf * 8 + nf * 4;
        // (each polygon's area, f64, and its face, i32: rows are grouped by size)
        assert_eq!(&vtu[start + body..], b"\n</AppendedData>\n</VTKFile>\n");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
