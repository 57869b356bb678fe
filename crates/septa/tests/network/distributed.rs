//! The three steps of a sparse job, with every block result sent through
//! its byte encoding and merged in a shuffled order (as a cluster would),
//! give exactly the dense network (docs/distributed.md).

use std::path::Path;

use rand::seq::SliceRandom;
use rand::SeedableRng;
use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::network::{compute, finish_sparse, plan_sparse, run_block, BlockResult, NetworkOptions};
use septa::scene::{load_function_list, sample_grid, Primitive};

fn spec(name: &str) -> Vec<Primitive> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/specs").join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap();
    load_function_list(&text, &path.display().to_string(), None).unwrap()
}

#[test]
fn steps_through_bytes_in_any_order_equal_dense() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(6);
    for (name, mode) in [("ia18", Mode::Ia), ("mi18", Mode::Mi), ("nested8", Mode::Ia), ("separate8", Mode::Ia)] {
        let f = spec(name);
        let grid = BoxGrid::new([20; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap();
        let mut o = NetworkOptions::new(mode);
        o.block = 4;
        let plan = plan_sparse(&grid, &f, &o).unwrap();
        let mut bytes: Vec<Vec<u8>> =
            plan.kept.iter().map(|&i| run_block(&grid, &f, &o, i).unwrap().to_bytes()).collect();
        bytes.shuffle(&mut rng);
        let results: Vec<BlockResult> = bytes.iter().map(|b| BlockResult::from_bytes(b).unwrap()).collect();
        let (net, stats) = finish_sparse(&grid, &f, &o, &plan, results).unwrap();
        let g = Grid::Box(grid.clone());
        let dense = compute(&g, &sample_grid(&f, &g.vertices()), f.len(), &o).unwrap();
        assert!(!stats.dense_fallback, "{name}");
        assert_eq!(net.counts(), dense.counts(), "{name}");
        assert_eq!(net.keys, dense.keys, "{name}");
        assert!(net.points.iter().zip(&dense.points).all(|(p, q)| p.map(f64::to_bits) == q.map(f64::to_bits)));
        assert_eq!(
            (net.face_start, net.face_verts, net.face_label),
            (dense.face_start, dense.face_verts, dense.face_label)
        );
        assert_eq!((net.face_cells, net.face_patch, net.patches), (dense.face_cells, dense.face_patch, dense.patches));
        assert_eq!(
            (net.chains, net.corners, net.shells, net.cells),
            (dense.chains, dense.corners, dense.shells, dense.cells)
        );
    }
}
