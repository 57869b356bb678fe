//! The cut does not depend on plane order, plane scaling, duplicate planes
//! or thread count; bad input gives typed errors naming the element.

use crate::common;

use septa::cut::{cut_mesh, CutCellMesh, CutError, CutOptions};
use septa::io::{read_mesh, read_planes};
use std::path::Path;

fn data() -> String {
    common::shared_data().display().to_string()
}

fn load(mesh: &str, planes: &str) -> Option<(Vec<[f64; 3]>, Vec<[u32; 3]>, Vec<[f64; 4]>)> {
    let m = read_mesh(Path::new(&format!("{}/meshes/{mesh}", data()))).unwrap();
    let p = read_planes(Path::new(&format!("{}/topocut/{planes}", data()))).unwrap();
    Some((m.vertices, m.triangles, p))
}

/// Order-independent summary: counts plus the sorted multiset of cell volumes.
fn summary(m: &CutCellMesh) -> (septa::cut::CutCounts, Vec<i64>) {
    let mut v: Vec<i64> = m.cell_volumes.iter().map(|x| (x / m.mesh_volume * 1e9).round() as i64).collect();
    v.sort_unstable();
    (m.counts, v)
}

#[test]
fn plane_order_scale_and_threads_do_not_matter() {
    for (mesh, planes) in [
        ("staircase.obj", "staircase.R10.plane"),
        ("knight.obj", "knight.A5.plane"),
        ("plate_genus9.obj", "plate_genus9.R10.plane"),
    ] {
        let Some((v, t, p)) = load(mesh, planes) else {
            eprintln!("no data, skipped");
            return;
        };
        let base = cut_mesh(&v, &t, &p, &CutOptions { threads: 1, ..Default::default() }).unwrap();
        base.validate().unwrap();
        // reversed, rotated order; scaled by a power of two and negated (same planes)
        let mut q: Vec<[f64; 4]> = p.iter().rev().copied().collect();
        q.rotate_left(3);
        let q: Vec<[f64; 4]> =
            q.iter().enumerate().map(|(i, x)| if i % 2 == 0 { x.map(|c| -4.0 * c) } else { *x }).collect();
        let other = cut_mesh(&v, &t, &q, &CutOptions { threads: 2, ..Default::default() }).unwrap();
        assert_eq!(summary(&base), summary(&other), "{mesh} {planes}");
        // a duplicate plane is dropped with a note
        let mut d = p.clone();
        d.push(p[0].map(|c| 2.0 * c));
        let dup = cut_mesh(&v, &t, &d, &CutOptions { threads: 2, ..Default::default() }).unwrap();
        assert_eq!(dup.stats.dropped_planes, vec![(p.len(), 0)]);
        assert_eq!(summary(&base), summary(&dup));
    }
}

fn tet() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    (
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
}

#[test]
fn tetrahedron_through_a_vertex() {
    let (v, t) = tet();
    // x = 0 contains a face; y = z passes through two vertices
    let out = cut_mesh(&v, &t, &[[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, -1.0, 0.0]], &CutOptions::default()).unwrap();
    out.validate().unwrap();
    assert_eq!(out.counts.cut_cells, 2);
}

#[test]
fn bad_input_is_named() {
    let (v, t) = tet();
    let p = [[1.0, 0.0, 0.0, -0.5]];
    let opts = CutOptions::default();
    let mut flipped = t.clone();
    flipped[0].swap(1, 2);
    assert!(matches!(cut_mesh(&v, &flipped, &p, &opts), Err(CutError::NonManifoldOrFlipped { .. })));
    let inward: Vec<[u32; 3]> = t.iter().map(|f| [f[0], f[2], f[1]]).collect();
    assert!(matches!(cut_mesh(&v, &inward, &p, &opts), Err(CutError::InwardOrientation { .. })));
    assert!(matches!(cut_mesh(&v, &t[..3], &p, &opts), Err(CutError::NotWatertight { .. })));
    let mut dupv = v.clone();
    dupv.push(v[1]);
    assert!(matches!(cut_mesh(&dupv, &t, &p, &opts), Err(CutError::DuplicateVertex { first: 1, second: 4 })));
    assert!(matches!(cut_mesh(&v, &t, &[[0.0, 0.0, 0.0, 1.0]], &opts), Err(CutError::ZeroNormal { plane: 0 })));
    let mut degen = v.clone();
    degen[3] = [0.5, 0.5, 0.0];
    assert!(matches!(
        cut_mesh(&degen, &t, &p, &opts),
        Err(CutError::DegenerateTriangle { .. }) | Err(CutError::InwardOrientation { .. })
    ));
    let e = cut_mesh(&v, &flipped, &p, &opts).unwrap_err().to_string();
    assert!(e.contains("triangle"), "{e}");
}

#[test]
fn self_intersection_is_found() {
    let (mut v, mut t) = tet();
    // a second tetrahedron poking through the first one's slanted face
    let off = v.len() as u32;
    v.extend([[0.2, 0.2, 0.2], [1.2, 0.2, 0.2], [0.2, 1.2, 0.2], [0.2, 0.2, 1.2]]);
    t.extend(tet().1.iter().map(|f| f.map(|k| k + off)));
    let e = cut_mesh(&v, &t, &[[1.0, 0.0, 0.0, -0.5]], &CutOptions::default()).unwrap_err();
    assert!(matches!(e, CutError::SelfIntersection { .. }), "{e}");
    // apart, the two are fine
    for p in v.iter_mut().skip(4) {
        p[0] += 5.0;
    }
    cut_mesh(&v, &t, &[[1.0, 0.0, 0.0, -0.5]], &CutOptions::default()).unwrap();
}

#[test]
fn void_is_attached_to_its_cell() {
    let (cv, ct) = {
        let v: Vec<[f64; 3]> = (0..8).map(|i| [(i >> 2 & 1) as f64, (i >> 1 & 1) as f64, (i & 1) as f64]).collect();
        let t: Vec<[u32; 3]> = vec![
            [1, 3, 0],
            [4, 1, 0],
            [0, 3, 2],
            [2, 4, 0],
            [1, 7, 3],
            [5, 1, 4],
            [5, 7, 1],
            [3, 7, 2],
            [6, 4, 2],
            [2, 7, 6],
            [6, 5, 4],
            [7, 5, 6],
        ];
        (v, t)
    };
    // outer cube [0,3]^3, inner cube [1,2]^3 facing inwards (a void)
    let mut v: Vec<[f64; 3]> = cv.iter().map(|p| p.map(|x| 3.0 * x)).collect();
    v.extend(cv.iter().map(|p| p.map(|x| 1.0 + x)));
    let mut t = ct.clone();
    t.extend(ct.iter().map(|f| [f[0] + 8, f[2] + 8, f[1] + 8]));
    let out = cut_mesh(&v, &t, &[[1.0, 0.0, 0.0, -0.5]], &CutOptions::default()).unwrap();
    let check = out.validate().unwrap();
    assert_eq!(out.counts.cut_cells, 2);
    assert_eq!(out.stats.voids_attached, 1);
    assert_eq!(check.euler_by_cell, check.domain_euler);
    // a plane through the void: no void shell at all
    let out = cut_mesh(&v, &t, &[[1.0, 0.0, 0.0, -1.5]], &CutOptions::default()).unwrap();
    out.validate().unwrap();
    assert_eq!(out.counts.cut_cells, 2);
    assert_eq!(out.stats.voids_attached, 0);
}
