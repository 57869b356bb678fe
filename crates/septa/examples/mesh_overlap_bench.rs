//! Time of the tet-mesh validation (`TetMesh::new`) and of its exact
//! overlap test alone, on an `n^3` box grid read as an explicit mesh.
//! Usage: `cargo run --release -p septa --example mesh_overlap_bench -- 100 [five|six]`
use std::time::Instant;

use septa::grid::{BoxGrid, Split, TetMesh};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100);
    let split = if args.get(2).map(String::as_str) == Some("six") { Split::Six } else { Split::Five };
    let g = BoxGrid::new([n; 3], [[-1.0; 3], [1.0; 3]], split).expect("grid");
    let v: Vec<[f64; 3]> = (0..g.num_vertices() as u32).map(|i| g.vertex(i)).collect();
    let t: Vec<[i64; 4]> = (0..g.num_tets()).map(|i| g.tet(i).map(|x| x as i64)).collect();
    let (mut new_s, mut overlap_s) = (Vec::new(), Vec::new());
    for _ in 0..3 {
        let t0 = Instant::now();
        let m = TetMesh::new(v.clone(), &t).expect("a box grid is a valid mesh");
        new_s.push(t0.elapsed().as_secs_f64());
        let t1 = Instant::now();
        assert_eq!(m.first_overlap(), None);
        overlap_s.push(t1.elapsed().as_secs_f64());
    }
    new_s.sort_by(f64::total_cmp);
    overlap_s.sort_by(f64::total_cmp);
    println!(
        "{n}^3 {split:?}: {} tets, TetMesh::new median {:.3} s (min {:.3}), overlap test alone median {:.3} s (min {:.3})",
        t.len(),
        new_s[1],
        new_s[0],
        overlap_s[1],
        overlap_s[0]
    );
}
