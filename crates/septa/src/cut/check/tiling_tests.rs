//! The certificate's pieces on small surfaces, and the whole certificate
//! against the test of every pair on cut meshes with vertices moved.

use super::Surface;
use crate::cut::check::verify::{verify_flat, verify_flat_with};
use crate::cut::test_rng::{lcg, unit_cube as cube, xorshift_unit};
use crate::cut::{cut_mesh, CutOptions};

/// A closed unit tetrahedron, outward.
fn tet() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let x = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    (x, vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
}

/// A bipyramid over a ring of `n` vertices whose angles advance by
/// `turns` full turns around the z axis (radii alternating so that no two
/// vertices coincide): with two turns every triangle still faces the
/// origin, but the fans at the apexes wind twice.
fn bipyramid(n: usize, turns: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut x = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
    for i in 0..n {
        let a = turns * std::f64::consts::TAU * i as f64 / n as f64;
        let r = if i < n / 2 { 1.0 } else { 1.5 };
        x.push([r * a.cos(), r * a.sin(), 0.0]);
    }
    let ring = |i: usize| (2 + i % n) as u32;
    let mut t = Vec::new();
    for i in 0..n {
        t.push([0, ring(i), ring(i + 1)]);
        t.push([1, ring(i + 1), ring(i)]);
    }
    (x, t)
}

#[test]
fn a_convex_surface_is_star_shaped_and_a_twice_wound_one_is_not() {
    let (x, t) = tet();
    let s = Surface::new(&t).expect("closed");
    assert!(s.connected_manifold());
    assert!(s.star_shaped(&x));
    // a point outside, and one on a face's plane, prove nothing
    assert!(!s.star_shaped_around(&x, [1.0, 1.0, 1.0]));
    assert!(!s.star_shaped_around(&x, [0.2, 0.2, 0.0]));
    let (x, t) = bipyramid(12, 1.0);
    let s = Surface::new(&t).expect("closed");
    assert!(s.connected_manifold() && s.star_shaped_around(&x, [0.0; 3]));
    // every triangle faces the origin, every edge is used both ways, it is
    // connected and a manifold: only the fans' winding tells
    let (x, t) = bipyramid(12, 2.0);
    let s = Surface::new(&t).expect("closed");
    assert!(s.connected_manifold());
    let p = |v: u32| x[v as usize];
    let faces_origin = t
        .iter()
        .all(|t| super::orient(&[p(t[0]), p(t[1]), p(t[2]), [0.0; 3]], 0, 1, 2, 3) == septa_exact::Sign::Negative);
    assert!(faces_origin);
    assert!(!s.star_shaped_around(&x, [0.0; 3]));
    assert!(!s.star_shaped(&x));
}

#[test]
fn surfaces_that_are_not_closed_connected_manifolds_are_refused() {
    let (_, t) = tet();
    // open: a triangle missing
    assert!(Surface::new(&t[..3]).is_none());
    // an edge used twice the same way
    let mut twice = t.clone();
    twice.extend_from_slice(&t);
    assert!(Surface::new(&twice).is_none());
    // two tetrahedra apart: closed, not connected
    let two: Vec<[u32; 3]> = t.iter().copied().chain(t.iter().map(|t| t.map(|v| v + 4))).collect();
    assert!(!Surface::new(&two).unwrap().connected_manifold());
    // two tetrahedra sharing vertex 0: connected through no edge, and the
    // shared vertex has two fans
    let pinched: Vec<[u32; 3]> =
        t.iter().copied().chain(t.iter().map(|t| t.map(|v| if v == 0 { 0 } else { v + 3 }))).collect();
    assert!(!Surface::new(&pinched).unwrap().connected_manifold());
    assert!(Surface::new(&[]).is_none());
}

/// An L-shaped prism (its cells are often not star-shaped).
fn l_prism() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let ring = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]];
    let x: Vec<[f64; 3]> = [0.0, 1.0].iter().flat_map(|&z| ring.iter().map(move |p| [p[0], p[1], z])).collect();
    // caps fanned from the inner corner 3, which sees the whole L
    let mut t = vec![[3, 5, 4], [3, 0, 5], [3, 1, 0], [3, 2, 1], [9, 10, 11], [9, 11, 6], [9, 6, 7], [9, 7, 8]];
    for i in 0..6u32 {
        let j = (i + 1) % 6;
        t.push([i, j, j + 6]);
        t.push([i, j + 6, i + 6]);
    }
    (x, t)
}

/// Random planes through the middle of `[0, 2]^3`-ish meshes.
fn planes(seed: u64, n: usize) -> Vec<[f64; 4]> {
    let mut r = xorshift_unit(seed);
    (0..n)
        .map(|_| {
            let nrm = [r(), r(), r()];
            let p = [0.5 + 0.4 * r(), 0.5 + 0.4 * r(), 0.5 + 0.4 * r()];
            [nrm[0], nrm[1], nrm[2], -(nrm[0] * p[0] + nrm[1] * p[1] + nrm[2] * p[2])]
        })
        .collect()
}

/// On cut meshes as written, and with vertices moved far, slightly, by
/// ulps, or onto another vertex's coordinate (exact coplanarities and
/// contacts), the report with the certificate is the report of the test of
/// every pair: the certificate never proves apart two triangles that meet.
/// `SEPTA_FULL=1`: twenty times the seeds.
#[test]
fn the_certificate_agrees_with_the_test_of_every_pair() {
    let seeds = if std::env::var_os("SEPTA_FULL").is_some() { 200 } else { 10 };
    let (mut tiled, mut meeting, mut cases) = (0, 0, 0);
    for (mesh, (v, t)) in [("cube", cube()), ("L prism", l_prism())] {
        for seed in 1..=seeds {
            let planes = planes(seed * 31 + v.len() as u64, 3 + seed as usize % 4);
            let out = cut_mesh(&v, &t, &planes, &CutOptions::default()).unwrap();
            let flat = out.cell_polygons_flat();
            let mut r = lcg(seed);
            for trial in 0..12 {
                let mut x = out.vertices.clone();
                let nv = x.len();
                for _ in 0..1 + trial % 3 {
                    let (k, c) = ((r() % nv as u64) as usize, (r() % 3) as usize);
                    let step = |r: &mut dyn FnMut() -> u64| (r() % 2000) as f64 / 1000.0 - 1.0;
                    match trial % 6 {
                        0 => {} // as written
                        1 => x[k][c] += 0.3 * step(&mut r),
                        2 => x[k][c] += 1e-3 * step(&mut r),
                        3 => x[k][c] += 1e-9 * step(&mut r),
                        4 => {
                            for _ in 0..1 + r() % 4 {
                                x[k][c] = if r() % 2 == 0 { x[k][c].next_up() } else { x[k][c].next_down() };
                            }
                        }
                        _ => x[k][c] = x[(r() % nv as u64) as usize][c],
                    }
                }
                let with = verify_flat(&x, &flat, None, &planes);
                let every = verify_flat_with(&x, &flat, None, &planes, false);
                assert_eq!(
                    serde_json::to_string(&with).unwrap(),
                    serde_json::to_string(&every).unwrap(),
                    "{mesh} seed {seed} trial {trial}"
                );
                assert!(!every.tiled);
                cases += 1;
                tiled += with.tiled as usize;
                meeting += (every.intersecting_pairs > 0) as usize;
            }
        }
    }
    eprintln!("{cases} cases: {tiled} proven by the certificate, {meeting} with meeting triangles");
    // both outcomes were met: proven by the certificate, and pairs found
    assert!(tiled > cases / 4, "certificate used in {tiled} of {cases}");
    assert!(meeting > cases / 10, "intersections in {meeting} of {cases}");
}

/// Two cells that overlap without sharing a face: each is convex, so only
/// the outer surface (here two separate shells, not a connected surface)
/// could tell; the plan is refused and the pairs are tested.
#[test]
fn overlapping_cells_with_no_shared_face_are_found() {
    let (v, t) = cube();
    let mut x = v.clone();
    x.extend(v.iter().map(|p| p.map(|c| c + 0.5)));
    let cell = |o: u32| -> Vec<Vec<u32>> { t.iter().map(|t| t.iter().map(|&i| i + o).collect()).collect() };
    let cells = vec![cell(0), cell(8)];
    let flat = crate::cut::CellPolygons::from_nested(&cells);
    let r = verify_flat(&x, &flat, None, &[]);
    assert!(!r.tiled);
    assert!(r.intersecting_pairs > 0, "{r:?}");
    // apart, the same two cells are proven by the pair test
    let far: Vec<[f64; 3]> = v.iter().copied().chain(v.iter().map(|p| p.map(|c| c + 2.0))).collect();
    let r = verify_flat(&far, &flat, None, &[]);
    assert_eq!(r.violations(), 0, "{r:?}");
}

/// A prism over a polygon star-shaped around the origin (its vertices in
/// order of angle), each cap a fan around its centre on the axis.
fn star_prism(p: &[[f64; 2]]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let n = p.len() as u32;
    let mut x: Vec<[f64; 3]> = p.iter().map(|q| [q[0], q[1], 0.0]).collect();
    x.extend(p.iter().map(|q| [q[0], q[1], 1.0]));
    x.extend([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
    let (bottom, top) = (2 * n, 2 * n + 1);
    let mut t = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        t.extend([[i, j, n + j], [i, n + j, n + i], [bottom, j, i], [top, n + i, n + j]]);
    }
    (x, t)
}

#[test]
fn a_kernel_away_from_the_centroid_and_the_corner_mean_is_found() {
    // a random octagon, star-shaped around the origin, whose kernel holds
    // neither the centroid of the prism's volume nor the mean of its
    // triangles' corners: `kernel_point` has to find a point
    let p = [
        [0.352, 0.142],
        [-0.282, 2.083],
        [-2.056, 1.65],
        [-0.836, 0.037],
        [-2.544, -0.927],
        [-1.174, -2.367],
        [0.141, -0.209],
        [1.587, -1.496],
    ];
    let (x, t) = star_prism(&p);
    let s = Surface::new(&t).expect("closed");
    assert!(s.connected_manifold());
    assert!(s.star_shaped_around(&x, [0.0, 0.0, 0.5]));
    // the polygon's area centroid, at mid-height
    let (mut a, mut c) = (0.0, [0.0; 2]);
    for i in 0..p.len() {
        let (u, v) = (p[i], p[(i + 1) % p.len()]);
        let w = u[0] * v[1] - v[0] * u[1];
        a += w / 2.0;
        c = [c[0] + (u[0] + v[0]) * w, c[1] + (u[1] + v[1]) * w];
    }
    let centroid = [c[0] / (6.0 * a), c[1] / (6.0 * a), 0.5];
    assert!(!s.star_shaped_around(&x, centroid));
    let n = (3 * t.len()) as f64;
    let mean = t.iter().flatten().fold([0.0; 3], |m, &v| std::array::from_fn(|k| m[k] + x[v as usize][k] / n));
    assert!(!s.star_shaped_around(&x, mean));
    assert!(s.star_shaped(&x));
}
