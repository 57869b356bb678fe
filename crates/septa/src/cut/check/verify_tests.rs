//! The flat cells of the exact check against their nested form, and the
//! edge balance against a plain count per undirected edge.

use super::{unbalanced, verify_cells, verify_flat, CellPolygons};
use crate::cut::test_rng::{lcg, unit_cube as cube, xorshift_unit};
use crate::cut::{cut_mesh, CutOptions};

/// The balance of a cell's edges counted the plain way: per undirected
/// edge, uses from the smaller vertex minus uses from the larger.
fn unbalanced_by_count(edges: &[(u32, u32)]) -> Vec<(u32, u32)> {
    let mut bal: std::collections::BTreeMap<(u32, u32), i64> = Default::default();
    for &(a, b) in edges {
        *bal.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
    }
    bal.into_iter().filter(|&(_, v)| v != 0).map(|(k, _)| k).collect()
}

#[test]
fn edge_balance_equals_a_plain_count() {
    let mut r = lcg(11);
    for case in 0..2000 {
        // few vertices, so that edges repeat in both directions
        let nv = 2 + (r() % 6) as u32;
        let edges: Vec<(u32, u32)> = (0..r() % 24)
            .map(|_| {
                let a = (r() % nv as u64) as u32;
                let b = (a + 1 + (r() % (nv as u64 - 1)) as u32) % nv;
                (a, b)
            })
            .collect();
        let key = |a: u32, b: u32| (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
        let mut fwd: Vec<u64> = edges.iter().filter(|e| e.0 < e.1).map(|&(a, b)| key(a, b)).collect();
        let mut bwd: Vec<u64> = edges.iter().filter(|e| e.0 > e.1).map(|&(a, b)| key(a, b)).collect();
        let mut found = Vec::new();
        let n = unbalanced(&mut fwd, &mut bwd, |a, b| found.push((a, b)));
        let want = unbalanced_by_count(&edges);
        assert_eq!(n, want.len(), "case {case}: {edges:?}");
        assert_eq!(found, want, "case {case}: {edges:?}");
    }
}

#[test]
fn flat_cells_equal_the_nested_polygons() {
    let (v, t) = cube();
    let mut split_cases = 0;
    for seed in 1..=12u64 {
        // random planes through the cube: rounded cut-vertices leave some
        // faces not exactly planar, written as their triangles
        let mut r = xorshift_unit(seed);
        let planes: Vec<[f64; 4]> = (0..3 + seed as usize % 5)
            .map(|_| {
                let n = [r(), r(), r()];
                let p = [0.5 + 0.4 * r(), 0.5 + 0.4 * r(), 0.5 + 0.4 * r()];
                [n[0], n[1], n[2], -(n[0] * p[0] + n[1] * p[1] + n[2] * p[2])]
            })
            .collect();
        let out = cut_mesh(&v, &t, &planes, &CutOptions::default()).unwrap();
        split_cases += out.face_split.iter().any(|&s| s) as usize;
        let nested = out.cell_polygons();
        let flat = out.cell_polygons_flat();
        let want = CellPolygons::from_nested(&nested);
        assert_eq!(flat.cell_start, want.cell_start, "seed {seed}");
        assert_eq!(flat.poly_start, want.poly_start, "seed {seed}");
        assert_eq!(flat.verts, want.verts, "seed {seed}");
        let (a, b) = (verify_flat(&out.vertices, &flat, None, &[]), verify_cells(&out.vertices, &nested));
        assert_eq!(serde_json::to_string(&a).unwrap(), serde_json::to_string(&b).unwrap());
        // the cutting planes only speed the check up
        let c = verify_flat(&out.vertices, &flat, None, &planes);
        assert_eq!(serde_json::to_string(&a).unwrap(), serde_json::to_string(&c).unwrap());
        assert_eq!(a.violations(), 0, "seed {seed}: {:?}", a.examples);
        assert_eq!(a.cells, out.num_cells);
    }
    assert!(split_cases > 0, "no case wrote a face as triangles");
}

#[test]
fn flat_cells_keep_the_order_of_a_cell_listed_on_both_sides() {
    // a face whose two cells are one cell is copied reversed first
    let nested = vec![vec![vec![0, 1, 2], vec![2, 1, 0, 3]], vec![], vec![vec![4, 5, 6]]];
    let f = CellPolygons::from_nested(&nested);
    assert_eq!(f.num_cells(), 3);
    let back: Vec<Vec<Vec<u32>>> = (0..3).map(|c| f.cell(c).map(|p| p.to_vec()).collect()).collect();
    assert_eq!(back, nested);
}

/// A vertex at infinity or NaN is a violation of its own: the other
/// checks cannot prove anything of it (an infinite apex passed all of
/// them, the positive volume included).
#[test]
fn non_finite_vertices_are_violations() {
    let cells = vec![vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]]];
    let tet = |z: f64| vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, z], [f64::NAN; 3]];
    let r = verify_cells(&tet(1.0), &cells);
    assert_eq!(r.violations(), 0, "{r:?}");
    assert_eq!(r.nonfinite_points, 0, "an unused NaN vertex is not checked");
    for z in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
        let r = verify_cells(&tet(z), &cells);
        assert_eq!(r.nonfinite_points, 1, "{z}: {r:?}");
        assert!(r.violations() >= 1 && r.examples.iter().any(|e| e.contains("vertex 3 has a non-finite")), "{r:?}");
    }
}

/// With vertices moved so that cells cross each other and themselves, the
/// check with the cutting planes as separators finds the same
/// intersecting pairs as without them (the planes pass between many of
/// the moved triangles' neighbours, never between two that meet).
#[test]
fn separating_planes_hide_no_intersection() {
    let (v, t) = cube();
    let mut found = 0;
    for seed in 1..=8u64 {
        let mut r = xorshift_unit(100 + seed);
        let planes: Vec<[f64; 4]> = (0..4)
            .map(|_| {
                let n = [r(), r(), r()];
                let p = [0.5 + 0.3 * r(), 0.5 + 0.3 * r(), 0.5 + 0.3 * r()];
                [n[0], n[1], n[2], -(n[0] * p[0] + n[1] * p[1] + n[2] * p[2])]
            })
            .collect();
        let mut out = cut_mesh(&v, &t, &planes, &CutOptions::default()).unwrap();
        // push a few cut-vertices across their neighbours
        let nv = out.vertices.len();
        for i in 0..3 {
            let k = (seed as usize * 7 + i * 13) % nv;
            for c in 0..3 {
                out.vertices[k][c] += 0.2 * r();
            }
        }
        let flat = out.cell_polygons_flat();
        let (a, b) = (verify_flat(&out.vertices, &flat, None, &[]), verify_flat(&out.vertices, &flat, None, &planes));
        assert_eq!(serde_json::to_string(&a).unwrap(), serde_json::to_string(&b).unwrap(), "seed {seed}");
        found += a.intersecting_pairs;
    }
    assert!(found > 0, "no moved vertex made an intersection");
}
