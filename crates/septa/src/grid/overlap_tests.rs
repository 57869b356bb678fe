//! Exact tet overlap: touching is not overlap; every kind of separating
//! plane (a face of either tet, an edge pair) is found.
use super::*;
use crate::grid::{MeshError, TetMesh};

fn shifted(t: &[[f64; 3]; 4], d: [f64; 3]) -> [[f64; 3]; 4] {
    t.map(|p| [p[0] + d[0], p[1] + d[1], p[2] + d[2]])
}

fn positive(mut t: [[f64; 3]; 4]) -> [[f64; 3]; 4] {
    if orientation(&t) == Sign::Negative {
        t.swap(2, 3);
    }
    assert_eq!(orientation(&t), Sign::Positive);
    t
}

#[test]
fn separating_planes_of_every_kind() {
    let unit = positive([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    // Sharing a face from the other side: a face plane separates.
    let mirror = positive([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]]);
    assert!(!interiors_overlap(&unit, &mirror));
    // A small tet inside, and a copy: overlap (in both argument orders).
    let small = positive([[0.1, 0.1, 0.1], [0.2, 0.1, 0.1], [0.1, 0.2, 0.1], [0.1, 0.1, 0.2]]);
    for (a, b) in [(unit, small), (small, unit), (unit, unit)] {
        assert!(interiors_overlap(&a, &b));
    }
    // Touching at a vertex, at a point of an edge: no overlap.
    assert!(!interiors_overlap(&unit, &shifted(&unit, [1.0, 0.0, 0.0])));
    // Two wedges whose ridge edges cross at the origin (x edge on top of a,
    // y edge under b). No face plane of either separates them; only the
    // plane z = 0 spanned by the two edges does.
    let a = positive([[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, -1.0, -1.0], [0.0, 1.0, -1.0]]);
    let b = positive([[0.0, -1.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]]);
    assert!(!face_separates(&a, &b) && !face_separates(&b, &a));
    assert!(edge_pair_separates(&a, &b));
    assert!(!interiors_overlap(&a, &b) && !interiors_overlap(&b, &a));
    // Pushed into each other by the smallest step: overlap, exactly.
    let down = shifted(&b, [0.0, 0.0, -f64::EPSILON]);
    assert!(interiors_overlap(&a, &down) && interiors_overlap(&down, &a));
    // Apart by the smallest step: separated.
    let up = shifted(&b, [0.0, 0.0, f64::EPSILON]);
    assert!(!interiors_overlap(&a, &up));
}

/// The unit cube split into 5 tets (one central tet, four corners).
fn cube5() -> (Vec<[f64; 3]>, Vec<[i64; 4]>) {
    let v: Vec<[f64; 3]> = (0..8).map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]).collect();
    // Even-parity corners 0, 3, 5, 6 form the central tet.
    let t = vec![[0, 3, 5, 6], [1, 0, 3, 5], [2, 0, 3, 6], [4, 0, 5, 6], [7, 3, 5, 6]];
    (v, t)
}

#[test]
fn extra_tet_over_a_cube_is_refused() {
    let (v, t) = cube5();
    let m = TetMesh::new(v.clone(), &t).unwrap();
    assert_eq!(m.tets.len(), 5);
    // A tet over corners 0, 1, 2, 4 shares no face with the 5 (it cuts
    // through the central tet): the overlap names it and the first tet it covers.
    let mut extra = t.clone();
    extra.push([0, 1, 2, 4]);
    assert_eq!(TetMesh::new(v.clone(), &extra), Err(MeshError::Overlap { first: 0, second: 5 }));
    // A translated copy of the cube beside it, touching on x = 1 with
    // vertex ids of its own: a seam (the faces on x = 1 are not shared),
    // refused naming the first pair of coincident vertices.
    let mut v2 = v.clone();
    v2.extend(v.iter().map(|p| [p[0] + 1.0, p[1], p[2]]));
    let mut t2 = t.clone();
    t2.extend(t.iter().map(|x| x.map(|i| i + 8)));
    assert!(matches!(TetMesh::new(v2.clone(), &t2), Err(MeshError::Coincident { first: 1, second: 8, .. })));
    // The copy 2^-40 away (a gap, no shared point): accepted.
    let mut gap = v2.clone();
    for p in &mut gap[8..] {
        p[0] += (2.0f64).powi(-40);
    }
    assert!(TetMesh::new(gap, &t2).is_ok());
    // The same copy moved back by 2^-40 overlaps, with no shared vertex.
    let mut v3 = v2.clone();
    for p in &mut v3[8..] {
        p[0] -= (2.0f64).powi(-40);
    }
    assert!(matches!(TetMesh::new(v3, &t2), Err(MeshError::Overlap { .. })));
}

#[test]
fn grid_meshes_are_accepted() {
    // A 6^3 box grid (5- and 6-tet splits) read back as an explicit mesh.
    for split in [crate::grid::Split::Five, crate::grid::Split::Six] {
        let g = crate::grid::BoxGrid::new([6, 5, 4], [[-1.0, -1.0, -1.0], [1.0, 0.7, 0.3]], split).unwrap();
        let v: Vec<[f64; 3]> = (0..g.num_vertices() as u32).map(|i| g.vertex(i)).collect();
        let t: Vec<[i64; 4]> = (0..g.num_tets()).map(|i| g.tet(i).map(|x| x as i64)).collect();
        assert!(TetMesh::new(v, &t).is_ok());
    }
}
