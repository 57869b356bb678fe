//! Where the reference data lives: `$SEPTA_SHARED`, the `shared/` folder
//! beside the repository (as CI lays it out), or `/work/shared`. A missing
//! folder fails the test: reference checks must never pass vacuously.
#![allow(dead_code)]

use std::path::PathBuf;

/// The `shared/data` folder.
pub fn shared_data() -> PathBuf {
    let mut candidates = Vec::new();
    if let Ok(d) = std::env::var("SEPTA_SHARED") {
        candidates.push(PathBuf::from(d).join("data"));
    }
    candidates.push(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"));
    candidates.push(PathBuf::from("/work/shared/data"));
    candidates
        .into_iter()
        .find(|d| d.join("isn/expected.json").exists())
        .expect("reference data shared/data not found: set SEPTA_SHARED to the shared/ folder")
}

/// A network's `network.json` text up to its timings (everything else must
/// be byte-identical between runs that should agree).
pub fn network_json(net: &septa::network::Network, tag: &str) -> String {
    let dir = std::env::temp_dir().join(format!("septa-test-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("network.json");
    septa::io::write_network_json(net, &Default::default(), &path, &[]).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    text.split("\"seconds\"").next().unwrap().to_string()
}

/// The functions of `data/specs/<name>.json` (the reference cases' spheres).
pub fn spec(name: &str) -> Vec<septa::scene::Primitive> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/specs").join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap();
    septa::scene::load_function_list(&text, &path.display().to_string(), None).unwrap()
}

/// An `n^3` box grid over `[-1, 1]^3`, 5 tets per cube.
pub fn cube_grid(n: usize) -> septa::grid::BoxGrid {
    septa::grid::BoxGrid::new([n; 3], [[-1.0; 3], [1.0; 3]], septa::grid::Split::Five).unwrap()
}

/// Asserts two networks are the same, array by array and as network.json
/// bytes (apart from timings); `what` names the case in failures.
pub fn assert_same_network(a: &septa::network::Network, b: &septa::network::Network, what: &str) {
    assert_eq!(a.counts(), b.counts(), "{what}: counts");
    assert_eq!(a.keys, b.keys, "{what}: keys");
    assert!(a.points.iter().zip(&b.points).all(|(p, q)| p.map(f64::to_bits) == q.map(f64::to_bits)), "{what}: points");
    assert_eq!(a.face_start, b.face_start, "{what}: face_start");
    assert_eq!(a.face_verts, b.face_verts, "{what}: face_verts");
    assert_eq!(a.face_label, b.face_label, "{what}: face_label");
    assert_eq!(a.face_cells, b.face_cells, "{what}: face_cells");
    assert_eq!(a.face_patch, b.face_patch, "{what}: face_patch");
    assert_eq!(a.edges, b.edges, "{what}: edges");
    assert_eq!(a.patches, b.patches, "{what}: patches");
    assert_eq!(a.chains, b.chains, "{what}: chains");
    assert_eq!(a.chain_patches, b.chain_patches, "{what}: chain_patches");
    assert_eq!(a.corners, b.corners, "{what}: corners");
    assert_eq!(a.shells, b.shells, "{what}: shells");
    assert_eq!(a.cells, b.cells, "{what}: cells");
    assert_eq!(a.cells_method, b.cells_method, "{what}: cells method");
    assert!(network_json(a, &format!("{what}-a")) == network_json(b, &format!("{what}-b")), "{what}: network.json");
}

/// Cells as a partition of shells, with their labels, for comparing methods.
pub fn cell_partition(net: &septa::network::Network) -> Vec<(Vec<u32>, Vec<u64>)> {
    let mut p: Vec<(Vec<u32>, Vec<u64>)> = net
        .cells
        .iter()
        .map(|c| {
            let mut s = c.shells.clone();
            s.sort();
            (s, c.label.to_vec())
        })
        .collect();
    p.sort();
    p
}

/// Whether `net` has an edge of one face off the boundary of the box grid
/// `grid` (a crack: one point reached under two vertex keys). Decided on
/// the vertex keys, not on rounded coordinates: an edge is on the boundary
/// when the grid vertices of both its keys lie on one boundary plane.
pub fn cracked(net: &septa::network::Network, grid: &septa::grid::BoxGrid) -> bool {
    let mut count: std::collections::HashMap<[u32; 2], u32> = Default::default();
    for f in 0..net.num_faces() {
        let vs = net.face(f);
        for j in 0..vs.len() {
            let (a, b) = (vs[j], vs[(j + 1) % vs.len()]);
            *count.entry([a.min(b), a.max(b)]).or_default() += 1;
        }
    }
    let on_boundary = |e: &[u32; 2]| {
        let ijk: Vec<[usize; 3]> = e
            .iter()
            .flat_map(|&v| net.keys[v as usize].grid.into_iter().filter(|&g| g != u32::MAX))
            .map(|g| grid.vertex_ijk(g))
            .collect();
        (0..3).any(|x| ijk.iter().all(|p| p[x] == 0) || ijk.iter().all(|p| p[x] == grid.res[x]))
    };
    count.iter().any(|(e, &n)| n == 1 && !on_boundary(e))
}
