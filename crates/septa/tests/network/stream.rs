//! Streaming (docs/sparse.md): the polygons streamed block by block are exactly
//! the in-memory network's (same multiset of faces as sorted global-key
//! lists, same labels), for several block and window sizes, and the
//! streamed PLY holds them with every vertex once.

use crate::common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use septa::complex::Mode;
use septa::io::PlyStreamSink;
use septa::network::compute_sparse;
use septa::network::{stream_sparse, stream_topology, StreamBlock, StreamSink};
use septa::network::{Network, NetworkOptions, VKey};
use septa::scene::load_function_list;

use common::{cube_grid, spec};

type Face = (Vec<VKey>, [u16; 2]);

/// Collects every streamed polygon (sorted keys, label) and the first
/// point of each key, and checks the block order.
#[derive(Default)]
struct Collect {
    faces: Vec<Face>,
    last: Option<usize>,
    points: BTreeMap<VKey, [u64; 3]>,
    blocks: usize,
}

impl StreamSink for Collect {
    fn block(&mut self, b: &StreamBlock) -> std::io::Result<()> {
        assert!(self.last.is_none_or(|l| l < b.index), "blocks in ascending order");
        self.last = Some(b.index);
        self.blocks += 1;
        for p in 0..b.num_polygons() {
            for &v in b.polygon(p) {
                // The first block (in order) to use a vertex gives its point,
                // as in the merge (a repeat may differ in the last bits).
                self.points.entry(b.keys[v as usize]).or_insert(b.points[v as usize].map(f64::to_bits));
            }
            let mut keys: Vec<VKey> = b.polygon(p).iter().map(|&v| b.keys[v as usize]).collect();
            keys.sort_unstable();
            self.faces.push((keys, b.poly_label[p]));
        }
        Ok(())
    }
}

fn net_faces(net: &Network) -> Vec<Face> {
    let mut faces: Vec<Face> = (0..net.num_faces())
        .map(|f| {
            let mut keys: Vec<VKey> = net.face(f).iter().map(|&v| net.keys[v as usize]).collect();
            keys.sort_unstable();
            (keys, net.face_label[f])
        })
        .collect();
    faces.sort_unstable();
    faces
}

#[test]
fn streamed_polygons_equal_the_in_memory_network() {
    for (name, mode) in [("ia18", Mode::Ia), ("mi18", Mode::Mi)] {
        let f = spec(name);
        for (n, block, window) in [(20, 4, 1), (20, 8, 3), (32, 8, 0), (40, 16, 2), (40, 8, 5)] {
            let grid = cube_grid(n);
            let mut o = NetworkOptions::new(mode);
            o.block = block;
            let (net, sparse) = compute_sparse(&grid, &f, &o).unwrap();
            let mut c = Collect::default();
            let s = stream_sparse(&grid, &f, &o, window, &mut c).unwrap();
            let what = format!("{name} {n}^3 block {block} window {window}");
            assert!(net.num_faces() > 0, "{what}");
            assert_eq!(s.faces, net.num_faces(), "{what}");
            assert_eq!(s.active_tets, net.active_tets, "{what}");
            assert_eq!(
                (s.blocks, s.skipped, s.sampled, s.active, s.sampled_vertices),
                (sparse.blocks, sparse.skipped, sparse.sampled, sparse.active, sparse.sampled_vertices),
                "{what}"
            );
            assert_eq!(c.blocks, s.sampled, "{what}");
            let mut faces = c.faces;
            faces.sort_unstable();
            assert_eq!(faces, net_faces(&net), "{what}: faces");
            // The network's vertices are the polygons' keys, each with its first point.
            assert_eq!(c.points.len(), net.keys.len(), "{what}");
            for (k, p) in net.keys.iter().zip(&net.points) {
                assert_eq!(c.points.get(k), Some(&p.map(f64::to_bits)), "{what}: {k:?}");
            }
        }
    }
}

/// A parsed streamed PLY: points, faces (vertex ids, label, block) and
/// per face its patch and cells.
struct Ply {
    points: Vec<[f64; 3]>,
    faces: Vec<(Vec<u32>, [u16; 2], u32)>,
    topo: Vec<[i32; 3]>,
}

fn read_ply(path: &Path) -> Ply {
    let bytes = std::fs::read(path).unwrap();
    let end = bytes.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let head = std::str::from_utf8(&bytes[..end]).unwrap();
    let count = |el: &str| -> usize {
        let line = head.lines().find(|l| l.starts_with(&format!("element {el} "))).unwrap();
        line.rsplit(' ').next().unwrap().parse().unwrap()
    };
    let (nv, nf) = (count("vertex"), count("face"));
    assert!(head.starts_with("ply\nformat binary_little_endian 1.0\n"), "{head}");
    assert!(head.contains(
        "property list uchar int vertex_indices\nproperty int labels_0\nproperty int labels_1\nproperty int block\n\
         property int patch\nproperty int cells_0\nproperty int cells_1\nend_header"
    ));
    let mut at = end;
    let mut take = |n: usize| {
        let s = &bytes[at..at + n];
        at += n;
        s
    };
    let f64_ = |s: &[u8]| f64::from_le_bytes(s.try_into().unwrap());
    let i32_ = |s: &[u8]| i32::from_le_bytes(s.try_into().unwrap());
    let points = (0..nv).map(|_| [0; 3].map(|_| f64_(take(8)))).collect();
    let mut topo = Vec::new();
    let faces = (0..nf)
        .map(|_| {
            let len = take(1)[0] as usize;
            let vs: Vec<u32> = (0..len).map(|_| i32_(take(4)) as u32).collect();
            let l = [i32_(take(4)) as u16, i32_(take(4)) as u16];
            let block = i32_(take(4)) as u32;
            topo.push([0; 3].map(|_| i32_(take(4))));
            (vs, l, block)
        })
        .collect();
    assert_eq!(at, bytes.len(), "no bytes after the faces");
    Ply { points, faces, topo }
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-stream-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn streamed_ply_holds_the_network_with_each_vertex_once() {
    for (name, mode, n, block) in [("ia18", Mode::Ia, 24, 4), ("mi18", Mode::Mi, 32, 8)] {
        let f = spec(name);
        let grid = cube_grid(n);
        let mut o = NetworkOptions::new(mode);
        o.block = block;
        let (mut net, _) = compute_sparse(&grid, &f, &o).unwrap();
        // the files hold the points on the grid's lines where the exact vertices are
        septa::mesh::snap_to_grid(&mut net.points, &net.keys, &grid);
        let path = tmp(&format!("{name}.ply"));
        let mut sink = PlyStreamSink::create(&path, &grid, mode, f.len()).unwrap();
        assert!(!path.exists(), "nothing at the destination before finish");
        let s = stream_sparse(&grid, &f, &o, 3, &mut sink).unwrap();
        let ps = sink.finish().unwrap();
        assert_eq!(ps.faces as usize, net.num_faces());
        // Boundary vertices deduplicated: exactly the merged network's vertices.
        assert_eq!(ps.vertices as usize, net.points.len(), "{name}");
        assert!(s.peak_shared_keys > 0 && s.peak_shared_keys < net.points.len(), "{s:?}");
        let ply = read_ply(&path);
        assert!(ply.topo.iter().all(|t| *t == [-1; 3]), "no topology: patch and cells -1");
        assert_eq!((ply.points.len(), ply.faces.len()), (net.points.len(), net.num_faces()));
        // Same faces as point lists (a key's point is unique), labels, blocks in order.
        let bits = |p: &[f64; 3]| p.map(f64::to_bits);
        let mut a: Vec<(Vec<[u64; 3]>, [u16; 2])> = ply
            .faces
            .iter()
            .map(|(vs, l, _)| {
                let mut q: Vec<[u64; 3]> = vs.iter().map(|&v| bits(&ply.points[v as usize])).collect();
                q.sort_unstable();
                (q, *l)
            })
            .collect();
        let mut b: Vec<(Vec<[u64; 3]>, [u16; 2])> = (0..net.num_faces())
            .map(|f| {
                let mut q: Vec<[u64; 3]> = net.face(f).iter().map(|&v| bits(&net.points[v as usize])).collect();
                q.sort_unstable();
                (q, net.face_label[f])
            })
            .collect();
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b, "{name}");
        assert!(ply.faces.windows(2).all(|w| w[0].2 <= w[1].2), "faces in block order");
        assert!(ply.faces.iter().all(|x| (x.2 as usize) < s.blocks));
        // Every written vertex is used (only polygon vertices are written).
        let mut used = vec![false; ply.points.len()];
        ply.faces.iter().flat_map(|x| &x.0).for_each(|&v| used[v as usize] = true);
        assert!(used.iter().all(|&u| u));
        // Triangulated: the same vertices, each polygon as a fan, in order.
        let tri_path = tmp(&format!("{name}-tri.ply"));
        let mut sink = PlyStreamSink::create(&tri_path, &grid, mode, f.len()).unwrap().triangulated(true);
        stream_sparse(&grid, &f, &o, 2, &mut sink).unwrap();
        let ts = sink.finish().unwrap();
        let tri = read_ply(&tri_path);
        assert_eq!(ts.polygons as usize, net.num_faces());
        assert!(
            tri.points.iter().zip(&ply.points).all(|(p, q)| bits(p) == bits(q)) && tri.points.len() == ply.points.len()
        );
        let fans: Vec<(Vec<u32>, [u16; 2], u32)> = ply
            .faces
            .iter()
            .flat_map(|(vs, l, b)| (1..vs.len() - 1).map(move |i| (vec![vs[0], vs[i], vs[i + 1]], *l, *b)))
            .collect();
        assert_eq!(tri.faces, fans, "{name}: fans");
        assert_eq!(ts.faces as usize, fans.len());
        std::fs::remove_file(&path).unwrap();
        std::fs::remove_file(&tri_path).unwrap();
    }
}

#[test]
fn a_failed_stream_leaves_no_file() {
    // A plane through grid vertices lies in tet faces: its faces are paired
    // inside blocks and across block boundaries, and stream like any others.
    let f =
        load_function_list(r#"[{"type": "plane", "point": [0, 0, 0], "normal": [1, 0, 0]}]"#, "plane", None).unwrap();
    let grid = cube_grid(8);
    let mut o = NetworkOptions::new(Mode::Ia);
    o.block = 4;
    let (net, _) = compute_sparse(&grid, &f, &o).unwrap();
    let path = tmp("plane.ply");
    let mut sink = PlyStreamSink::create(&path, &grid, Mode::Ia, 1).unwrap();
    let stats = stream_sparse(&grid, &f, &o, 0, &mut sink).unwrap();
    sink.finish().unwrap();
    assert_eq!((stats.faces, stats.vertices as usize), (net.num_faces(), net.points.len()));
    assert_eq!(read_ply(&path).faces.len(), net.num_faces());
    std::fs::remove_file(&path).unwrap();
    // Two spheres touching at a point: their shells are linked at the
    // contact point, and the streamed topology equals the in-memory one.
    let f = load_function_list(
        r#"[{"type": "sphere", "center": [-0.5, 0, 0], "radius": 0.5},
            {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.5}]"#,
        "tangent",
        None,
    )
    .unwrap();
    let (net, _) = compute_sparse(&grid, &f, &o).unwrap();
    assert_eq!(net.cells_method, "raytrace");
    let path = tmp("tangent.ply");
    let mut sink = PlyStreamSink::create(&path, &grid, Mode::Ia, 2).unwrap();
    let (stats, summary) = stream_topology(&grid, &f, &o, 0, &mut sink).unwrap();
    sink.finish().unwrap();
    assert_eq!(summary.counts(), net.counts());
    assert_eq!((stats.vertices as usize, summary.cells.len()), (net.points.len(), 3));
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn streamed_ply_carries_each_faces_patch_and_cells() {
    for (name, mode) in [("ia18", Mode::Ia), ("mi18", Mode::Mi)] {
        let f = spec(name);
        let grid = cube_grid(24);
        let mut o = NetworkOptions::new(mode);
        o.block = 8;
        let (mut net, _) = compute_sparse(&grid, &f, &o).unwrap();
        // the files hold the points on the grid's lines where the exact vertices are
        septa::mesh::snap_to_grid(&mut net.points, &net.keys, &grid);
        let path = tmp(&format!("{name}-topo.ply"));
        let mut sink = PlyStreamSink::create(&path, &grid, mode, f.len()).unwrap();
        let (_, sum) = stream_topology(&grid, &f, &o, 2, &mut sink).unwrap();
        sink.finish_with(Some(&sum)).unwrap();
        let ply = read_ply(&path);
        // Faces by their point sets (a key's point is unique) -> in-memory face.
        let bits = |p: &[f64; 3]| p.map(f64::to_bits);
        let set = |pts: Vec<[u64; 3]>| {
            let mut q = pts;
            q.sort_unstable();
            q
        };
        let face_of: std::collections::HashMap<Vec<[u64; 3]>, usize> = (0..net.num_faces())
            .map(|g| (set(net.face(g).iter().map(|&v| bits(&net.points[v as usize])).collect()), g))
            .collect();
        let (mut patch, mut cell) = (BTreeMap::new(), BTreeMap::new());
        for ((vs, _, _), t) in ply.faces.iter().zip(&ply.topo) {
            let g = face_of[&set(vs.iter().map(|&v| bits(&ply.points[v as usize])).collect())];
            assert!(t.iter().all(|&x| x >= 0), "{name}: every face has a patch and cells");
            assert_eq!(*patch.entry(t[0]).or_insert(net.face_patch[g]), net.face_patch[g], "{name}: patch");
            for s in 0..2 {
                assert_eq!(*cell.entry(t[1 + s]).or_insert(net.face_cells[g][s]), net.face_cells[g][s], "{name}: cell");
            }
        }
        // One-to-one: as many patches and cells as the in-memory network has.
        let distinct = |m: &BTreeMap<i32, u32>| m.values().collect::<std::collections::BTreeSet<_>>().len();
        assert_eq!((patch.len(), distinct(&patch)), (net.patches.len(), net.patches.len()), "{name}");
        assert_eq!((cell.len(), distinct(&cell)), (net.cells.len(), net.cells.len()), "{name}");
        let _ = std::fs::remove_file(&path);
    }
}
