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

/// The corner tet `x, y, z >= 0, x + y + z <= 1` cut by the planes
/// `x, y, z = 1/3, 2/3` (as doubles): the 10 grid cubes with `i + j + k <=
/// 2` meet the tet, and because `fl(1/3) + fl(1/3) + fl(1/3)` and `fl(1/3) +
/// fl(2/3)` fall just below 1, so do the 7 cubes with `i + j + k = 3`, each
/// in a corner tet of volume ~1e-48: 17 cells, all of positive exact
/// volume although their floating-point volume is 0.
#[test]
fn corner_tet_thirds_has_tiny_cells_of_positive_volume() {
    let v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let mut planes = vec![];
    for a in 0..3 {
        for x in [1.0 / 3.0, 2.0 / 3.0] {
            let mut p = [0.0; 4];
            p[a] = 1.0;
            p[3] = -x;
            planes.push(p);
        }
    }
    let out = cut_mesh(&v, &t, &planes, &CutOptions::default()).unwrap();
    assert_eq!(out.counts.cut_cells, 17);
    let tiny = out.cell_volumes.iter().filter(|&&x| x.abs() < 1e-30).count();
    assert_eq!(tiny, 7, "{:?}", out.cell_volumes);
    assert!(out.cell_volume_signs.iter().all(|s| *s == septa_exact::Sign::Positive));
    let check = out.validate().unwrap();
    assert_eq!((check.euler, check.domain_euler, check.euler_by_cell), (1, 1, 1));
    // The same cut with planes at exact dyadic values meets the face
    // exactly: only the 10 cubes, no sliver.
    let planes: Vec<[f64; 4]> = (0..3)
        .flat_map(|a| {
            [0.25, 0.5].map(move |x| {
                let mut p = [0.0; 4];
                p[a] = 1.0;
                p[3] = -x;
                p
            })
        })
        .collect();
    let out = cut_mesh(&v, &t, &planes, &CutOptions::default()).unwrap();
    out.validate().unwrap();
}

#[test]
fn progress_counts_every_stage_in_order() {
    // One call per stage, (1, STAGES) .. (STAGES, STAGES), one per entry of
    // `stats.seconds`, and the same cut as without a callback.
    let (v, t) = cube();
    let calls = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let seen = calls.clone();
    let progress = septa::Progress(std::sync::Arc::new(move |done, total| seen.lock().unwrap().push((done, total))));
    let opts = CutOptions { progress: Some(progress), ..Default::default() };
    let out = cut_mesh(&v, &t, &[[1.0, 0.0, 0.0, -0.5]], &opts).unwrap();
    let calls = calls.lock().unwrap().clone();
    let n = septa::cut::STAGES;
    assert_eq!(calls, (1..=n).map(|i| (i, n)).collect::<Vec<_>>());
    assert_eq!(out.stats.seconds.len(), n);
    let plain = cut_mesh(&v, &t, &[[1.0, 0.0, 0.0, -0.5]], &CutOptions::default()).unwrap();
    assert_eq!(out.counts, plain.counts);
    assert_eq!(out.vertices, plain.vertices);
}
