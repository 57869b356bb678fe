//! Closed meshes that are not manifolds (TopoCut App. C): solids sharing
//! an edge or a vertex, cut with TopoCut's cell counts, the exact embedding
//! check passing and the volumes summing to the domain's (TopoCut Appendix C; docs/guide.md); and
//! meshes that are truly invalid, each refusal naming its edge or vertex.

use crate::shapes::{axis_planes, boxes_mesh, cut_checked, grid_cells, BoxShell};
use rand::{Rng, SeedableRng};
use septa::cut::{cut_mesh, CutCellMesh, CutError, CutOptions};
use septa::io::grid_planes_xyz;

fn unit(lo: [f64; 3]) -> BoxShell {
    BoxShell { lo, hi: lo.map(|x| x + 1.0), inward: false }
}

fn cut(v: &[[f64; 3]], t: &[[u32; 3]]) -> Result<CutCellMesh, CutError> {
    let planes = axis_planes(&[(2, 0.5)]);
    cut_mesh(v, t, &planes, &CutOptions::default())
}

/// The axis planes of TopoCut's `plane -s bound_box_xyz --nx n --ny n --nz n`.
fn grid_axis_planes(v: &[[f64; 3]], n: usize) -> Vec<(usize, f64)> {
    grid_planes_xyz(v, [n; 3])
        .iter()
        .map(|p| {
            let k = (0..3).find(|&k| p[k] == 1.0).unwrap();
            (k, -p[3])
        })
        .collect()
}

fn volume(out: &CutCellMesh) -> f64 {
    out.cell_volumes.iter().sum()
}

#[test]
fn two_cubes_sharing_an_edge_or_a_vertex_cut_as_topocut() {
    // TopoCut (its public repository, `plane -s bound_box_xyz --nx 3 --ny 3
    // --nz 3`, then `cut`): 4 cells for the cubes sharing the edge x = y = 1
    // (four triangles around it, two each way), 2 for those sharing the
    // corner (1, 1, 1) (12 triangles there in 2 fans)
    for (second, topocut) in [([1.0, 1.0, 0.0], 4), ([1.0; 3], 2)] {
        let shells = [unit([0.0; 3]), unit(second)];
        let (v, t) = boxes_mesh(&shells);
        let planes = grid_axis_planes(&v, 3);
        let what = format!("cubes at 0 and {second:?}");
        let out = cut_checked(&v, &t, &axis_planes(&planes), &what);
        assert_eq!(out.counts.cut_cells, topocut, "{what}");
        assert_eq!(out.counts.cut_cells, grid_cells(&shells, &planes), "{what}");
        assert!((volume(&out) - 2.0).abs() < 1e-14, "{what}: {}", volume(&out));
        // the union of two balls glued along an edge or at a point is
        // contractible: chi = 1, and every cell a ball
        let check = out.validate().unwrap();
        assert_eq!((check.domain_euler, check.euler_by_cell, check.non_ball_cells), (1, 1, 0), "{what}: {check:?}");
        // the shared edge or corner is one cut-vertex (or several) shared
        // by the cells of both cubes, not a copy per cube
        let on: Vec<usize> =
            (0..out.vertices.len()).filter(|&i| out.vertices[i][0] == 1.0 && out.vertices[i][1] == 1.0).collect();
        let z: Vec<f64> = on.iter().map(|&i| out.vertices[i][2]).collect();
        let mut zs = z.clone();
        zs.sort_by(f64::total_cmp);
        zs.dedup();
        assert_eq!(z.len(), zs.len(), "{what}: duplicate cut-vertices on the shared edge {z:?}");
    }
}

/// The unit cubes of a 3D checkerboard (`i + j + k` even) on an `n^3`
/// lattice, a random subset: neighbours share an edge (two per edge at
/// most) or a corner (up to four), never a face.
fn checkerboard(rng: &mut impl Rng, n: usize) -> Vec<BoxShell> {
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                if (i + j + k) % 2 == 0 && rng.gen_bool(0.6) {
                    out.push(unit([i as f64, j as f64, k as f64]));
                }
            }
        }
    }
    if out.is_empty() {
        out.push(unit([0.0; 3]));
    }
    out
}

#[test]
fn random_checkerboards_of_cubes_touching_at_edges_and_corners() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4601);
    let mut touching = 0;
    for case in 0..24 {
        let shells = checkerboard(&mut rng, 3);
        let (v, t) = boxes_mesh(&shells);
        // planes through the cubes, on their faces (degenerate) and outside
        let planes: Vec<(usize, f64)> = (0..rng.gen_range(1..=6))
            .map(|_| (rng.gen_range(0..3), [0.5, 1.0, 1.25, 2.0, 2.5, -1.0][rng.gen_range(0..6)]))
            .collect();
        let what = format!("checkerboard {case}: {} cubes, planes {planes:?}", shells.len());
        let out = cut_checked(&v, &t, &axis_planes(&planes), &what);
        assert_eq!(out.counts.cut_cells, grid_cells(&shells, &planes), "{what}");
        assert!((volume(&out) - shells.len() as f64).abs() < 1e-12, "{what}");
        let check = out.validate().unwrap();
        assert_eq!(check.euler_by_cell, check.domain_euler, "{what}: {check:?}");
        // pairs of cubes touching (at an edge or a corner)
        touching += shells
            .iter()
            .enumerate()
            .flat_map(|(i, a)| shells[i + 1..].iter().map(move |b| (a, b)))
            .filter(|(a, b)| (0..3).all(|k| (a.lo[k] - b.lo[k]).abs() <= 1.0))
            .count();
    }
    assert!(touching >= 100, "{touching}");
    // oblique planes: the exact checks only
    for case in 0..8 {
        let shells = checkerboard(&mut rng, 3);
        let (v, t) = boxes_mesh(&shells);
        let planes: Vec<[f64; 4]> = (0..rng.gen_range(1..=4))
            .map(|_| {
                let n: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                let x: [f64; 3] = std::array::from_fn(|_| rng.gen_range(0.0..3.0));
                [n[0], n[1], n[2], -(n[0] * x[0] + n[1] * x[1] + n[2] * x[2])]
            })
            .collect();
        let out = cut_checked(&v, &t, &planes, &format!("oblique checkerboard {case}"));
        assert!((volume(&out) - shells.len() as f64).abs() < 1e-12);
    }
}

/// Triangular prisms `z in [0, 1]` over triangles of the xy-plane, one mesh
/// (equal corners one vertex), each facing outwards or (`inward`) in.
fn prisms(bases: &[([[f64; 2]; 3], bool)]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut verts: Vec<[f64; 3]> = Vec::new();
    let mut tris = Vec::new();
    let mut id = |p: [f64; 3]| match verts.iter().position(|q| *q == p) {
        Some(i) => i as u32,
        None => {
            verts.push(p);
            verts.len() as u32 - 1
        }
    };
    for &(b, inward) in bases {
        // counter-clockwise base seen from above
        let ccw = (b[1][0] - b[0][0]) * (b[2][1] - b[0][1]) - (b[1][1] - b[0][1]) * (b[2][0] - b[0][0]) > 0.0;
        let b = if ccw { b } else { [b[0], b[2], b[1]] };
        let lo: Vec<u32> = b.iter().map(|p| id([p[0], p[1], 0.0])).collect();
        let hi: Vec<u32> = b.iter().map(|p| id([p[0], p[1], 1.0])).collect();
        let mut out = vec![[lo[0], lo[2], lo[1]], [hi[0], hi[1], hi[2]]];
        for k in 0..3 {
            let l = (k + 1) % 3;
            out.push([lo[k], lo[l], hi[l]]);
            out.push([lo[k], hi[l], hi[k]]);
        }
        for t in out {
            tris.push(if inward { [t[0], t[2], t[1]] } else { t });
        }
    }
    (verts, tris)
}

fn at(deg: f64) -> [f64; 2] {
    [deg.to_radians().cos(), deg.to_radians().sin()]
}

#[test]
fn three_prisms_around_one_edge() {
    // sectors [0, 60], [120, 180], [240, 300] degrees about the z axis:
    // six triangles around the axis, alternating, three wedges
    let bases: Vec<([[f64; 2]; 3], bool)> =
        (0..3).map(|k| ([[0.0, 0.0], at(120.0 * k as f64), at(120.0 * k as f64 + 60.0)], false)).collect();
    let (v, t) = prisms(&bases);
    let vol = 3.0 * 0.5 * 60f64.to_radians().sin();
    // z = 1/2 halves each prism; x = 0 cuts the third (it holds 270
    // degrees); y = 0 holds faces of the first two and cuts none
    for (planes, cells) in [
        (vec![(2, 0.5)], 6),
        (vec![(2, 0.5), (0, 0.0)], 8),
        (vec![(2, 0.5), (1, 0.0)], 6),
        (vec![(0, 0.0), (1, 0.0), (0, 0.25)], 6),
    ] {
        let what = format!("three prisms, planes {planes:?}");
        let out = cut_checked(&v, &t, &axis_planes(&planes), &what);
        assert_eq!(out.counts.cut_cells, cells, "{what}");
        assert!((volume(&out) - vol).abs() < 1e-14, "{what}");
        let check = out.validate().unwrap();
        assert_eq!(check.euler_by_cell, check.domain_euler, "{what}: {check:?}");
        assert_eq!(check.domain_euler, 1, "{what}");
    }
    // planes through the axis at other angles
    let planes: Vec<[f64; 4]> = [10.0, 100.0, 250.0]
        .iter()
        .map(|&d: &f64| {
            let n = at(d + 90.0);
            [n[0], n[1], 0.0, 0.0]
        })
        .collect();
    let out = cut_checked(&v, &t, &planes, "three prisms, oblique planes through the axis");
    assert!((volume(&out) - vol).abs() < 1e-14);
}

/// Adds the tetrahedron `pts` to a mesh (equal points one vertex), facing
/// outwards or (`inward`) in; returns its volume.
fn add_tet(v: &mut Vec<[f64; 3]>, t: &mut Vec<[u32; 3]>, pts: [[f64; 3]; 4], inward: bool) -> f64 {
    let ids: Vec<u32> = pts
        .iter()
        .map(|p| match v.iter().position(|q| q == p) {
            Some(i) => i as u32,
            None => {
                v.push(*p);
                v.len() as u32 - 1
            }
        })
        .collect();
    let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let (e1, e2, e3) = (sub(pts[1], pts[0]), sub(pts[2], pts[0]), sub(pts[3], pts[0]));
    let det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0])
        + e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
    // with det > 0, [0, 2, 1] faces away from corner 3
    let mut faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    if (det > 0.0) == inward {
        for f in &mut faces {
            f.swap(1, 2);
        }
    }
    t.extend(faces.iter().map(|f| f.map(|i| ids[i])));
    det.abs() / 6.0
}

#[test]
fn a_cavity_touching_the_boundary_along_an_edge_or_at_a_corner() {
    // the unit cube less a tetrahedron on its edge x = y = 0 (its other two
    // corners inside): four triangles at the edge. Valid as a cavity (its
    // wedge lies between the cube's faces), refused as a solid inside the
    // cube sharing the edge (its inside covered twice)
    let edge_tet = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.5, 0.25, 0.5], [0.25, 0.5, 0.5]];
    // and a tetrahedron at the corner (1, 1, 1): a pinched vertex
    let corner_tet = [[1.0, 1.0, 1.0], [0.5, 0.75, 0.875], [0.75, 0.5, 0.875], [0.875, 0.875, 0.5]];
    for (tet, planes, cells) in
        [(edge_tet, vec![(2, 0.5), (0, 0.375)], 4), (corner_tet, vec![(2, 0.75), (0, 0.8), (1, 0.3)], 8)]
    {
        for inward in [true, false] {
            let (mut v, mut t) = boxes_mesh(&[unit([0.0; 3])]);
            let tv = add_tet(&mut v, &mut t, tet, inward);
            let what = format!("cube with tetrahedron {tet:?}, inward {inward}");
            if inward {
                let out = cut_checked(&v, &t, &axis_planes(&planes), &what);
                assert!((volume(&out) - (1.0 - tv)).abs() < 1e-14, "{what}: {}", volume(&out));
                assert_eq!(out.counts.cut_cells, cells, "{what}");
                continue;
            }
            let e = cut(&v, &t).unwrap_err();
            let msg = e.to_string();
            if tet == edge_tet {
                let CutError::EdgeWinding { a, b, count, .. } = e else { panic!("{what}: {msg}") };
                assert_eq!(count, 4, "{msg}");
                assert!([a, b].iter().all(|&i| v[i as usize][..2] == [0.0, 0.0]), "{msg}");
                assert!(
                    msg.contains(&format!("edge {a}-{b} is non-manifold")) && msg.contains("inside itself"),
                    "{msg}"
                );
            } else {
                assert!(matches!(e, CutError::ShellWinding { .. }), "{what}: {msg}");
            }
        }
    }
}

#[test]
fn open_and_inconsistent_meshes_are_refused_as_such() {
    let (v, t) = boxes_mesh(&[unit([0.0; 3])]);
    // one triangle flipped: its three edges run twice one way, never back
    let mut flipped = t.clone();
    flipped[3] = [t[3][0], t[3][2], t[3][1]];
    let e = cut(&v, &flipped).unwrap_err();
    let msg = e.to_string();
    let CutError::NonManifoldOrFlipped { a, b, forward, backward, triangle, other } = e else { panic!("{msg}") };
    assert_eq!((forward, backward), (2, 0), "{msg}");
    assert!(triangle == 3 || other == 3, "{msg}");
    assert!(msg.contains(&format!("edge {a}->{b}")) && msg.contains("inconsistent orientation"), "{msg}");
    // one triangle removed: open
    let open: Vec<[u32; 3]> = t.iter().copied().skip(1).collect();
    let e = cut(&v, &open).unwrap_err();
    assert!(matches!(e, CutError::NotWatertight { .. }), "{e}");
    assert!(e.to_string().contains("not watertight"), "{e}");
    // two cubes sharing an edge, one triangle at the edge flipped: three
    // one way, one the other there (and two one way on its other edges)
    let (v, mut t) = boxes_mesh(&[unit([0.0; 3]), unit([1.0, 1.0, 0.0])]);
    let k = (0..t.len()).find(|&k| t[k].iter().filter(|&&i| v[i as usize][..2] == [1.0, 1.0]).count() == 2).unwrap();
    t[k].swap(1, 2);
    let e = cut(&v, &t).unwrap_err();
    assert!(matches!(e, CutError::NonManifoldOrFlipped { .. }), "{e}");
    // two cubes sharing an edge, one of them with every triangle flipped:
    // as many each way, but not alternating about the edge
    let (v, mut t) = boxes_mesh(&[unit([0.0; 3]), unit([1.0, 1.0, 0.0])]);
    for f in &mut t[12..] {
        f.swap(1, 2);
    }
    let e = cut(&v, &t).unwrap_err();
    assert!(matches!(e, CutError::EdgeWinding { count: 4, .. }), "{e}");
}
