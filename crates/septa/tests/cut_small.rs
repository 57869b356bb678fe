//! Small hand-checked cuts.

use septa::cut::{cut_mesh, CutOptions};

fn cube() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let v = vec![
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
        [1.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [1.0, 1.0, 1.0],
    ];
    let t = [
        [2, 4, 1],
        [5, 2, 1],
        [1, 4, 3],
        [3, 5, 1],
        [2, 8, 4],
        [6, 2, 5],
        [6, 8, 2],
        [4, 8, 3],
        [7, 5, 3],
        [3, 8, 7],
        [7, 6, 5],
        [8, 6, 7],
    ];
    (v, t.iter().map(|f| [f[0] - 1, f[1] - 1, f[2] - 1]).collect())
}

#[test]
fn cube_one_plane() {
    let (v, t) = cube();
    let out = cut_mesh(&v, &t, &[[1.0, 0.0, 0.0, -0.5]], &CutOptions::default()).unwrap();
    let c = out.counts;
    eprintln!("{c:?}");
    assert_eq!(c.cut_cells, 2);
    assert_eq!(c.cut_faces, 21);
    out.validate().unwrap();
}
