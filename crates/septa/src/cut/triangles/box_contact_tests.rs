//! Tests of `box_contact`: wherever it answers, the answer of the full
//! exact pair test, on lattice triangles whose boxes touch in every way
//! (points, segments, rectangles) and with coincident vertices of distinct
//! ids.

use super::*;
use crate::cut::certify::nudge::{meet as overlap, tri_box as aabb};
use crate::cut::test_rng::lcg;
use crate::cut::triangles::tri_pair::pair_intersects;

/// The points of a 3x3x3 lattice (a third of them with a second id at the
/// same point, one at -0.0 instead of 0.0), and random non-degenerate
/// triangles of them.
fn lattice_soup(seed: u64, n: usize) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let vals = [0.0, 0.5, 1.0];
    let mut x: Vec<[f64; 3]> = Vec::new();
    for i in 0..27 {
        x.push([vals[i % 3], vals[i / 3 % 3], vals[i / 9]]);
    }
    for i in (0..27).step_by(3) {
        let mut p = x[i];
        if p[0] == 0.0 {
            p[0] = -0.0;
        }
        x.push(p);
    }
    let mut r = lcg(seed);
    let mut tris = Vec::new();
    while tris.len() < n {
        let t = [0, 1, 2].map(|_| (r() % x.len() as u64) as u32);
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            continue;
        }
        let [a, b, c] = t.map(|v| x[v as usize]);
        let (u, v) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        if n != [0.0; 3] {
            tris.push(t);
        }
    }
    (x, tris)
}

#[test]
fn answers_agree_with_the_full_pair_test() {
    let (mut decided, mut meets, mut undecided) = ([0usize; 4], 0usize, 0usize);
    // one flat axis: (corners of the fewer, of the more on it) -> (apart, meeting)
    let mut in_plane = std::collections::BTreeMap::<(usize, usize), (usize, usize)>::new();
    for seed in 1..=6 {
        let (x, tris) = lattice_soup(seed, 300);
        let boxes: Vec<Aabb> = tris.iter().map(|t| aabb(&x, t)).collect();
        for a in 0..tris.len() {
            for b in a + 1..tris.len() {
                if !overlap(&boxes[a], &boxes[b]) {
                    continue;
                }
                let (t1, t2) = (&tris[a], &tris[b]);
                match box_contact(
                    &x,
                    t1,
                    &boxes[a],
                    extreme_corners(&x, t1, &boxes[a]),
                    t2,
                    &boxes[b],
                    extreme_corners(&x, t2, &boxes[b]),
                ) {
                    Some(m) => {
                        let want = pair_intersects(&x, t1, t2);
                        assert_eq!(
                            m,
                            want,
                            "{t1:?} {:?} / {t2:?} {:?}",
                            t1.map(|v| x[v as usize]),
                            t2.map(|v| x[v as usize])
                        );
                        let nflat = (0..3)
                            .filter(|&k| boxes[a].0[k].max(boxes[b].0[k]) == boxes[a].1[k].min(boxes[b].1[k]))
                            .count();
                        decided[nflat] += 1;
                        meets += m as usize;
                        if nflat == 1 {
                            let k = (0..3)
                                .find(|&k| boxes[a].0[k].max(boxes[b].0[k]) == boxes[a].1[k].min(boxes[b].1[k]))
                                .unwrap();
                            let c = boxes[a].0[k].max(boxes[b].0[k]);
                            let on = |t: &[u32; 3]| t.iter().filter(|&&v| x[v as usize][k] == c).count();
                            let (n1, n2) = (on(t1), on(t2));
                            let e = in_plane.entry((n1.min(n2), n1.max(n2))).or_default();
                            if m {
                                e.1 += 1
                            } else {
                                e.0 += 1
                            }
                        }
                    }
                    None => undecided += 1,
                }
            }
        }
    }
    // every kind of contact occurs and is answered, both ways
    assert!(decided[1] > 500 && decided[2] > 500 && decided[3] > 100, "{decided:?}");
    assert!(meets > 200 && meets + 200 < decided.iter().sum(), "{meets} of {decided:?}");
    assert!(undecided > 1000, "{undecided}");
    // every pair of faces in one axis plane but two whole triangles, both ways
    for key in [(1, 1), (1, 2), (1, 3), (2, 2), (2, 3)] {
        let (apart, meeting) = in_plane.get(&key).copied().unwrap_or_default();
        assert!(apart > 20 && meeting > 20, "{key:?}: {in_plane:?}");
    }
}

/// The faces of a grid of unit cubes, each square cut along a diagonal:
/// the contacts of an axis-aligned cut-cell mesh (shared edges, corners,
/// perpendicular neighbours), none of them an intersection.
#[test]
fn a_grid_of_cube_faces_has_no_intersection() {
    let n = 3usize;
    let id = |i: usize, j: usize, k: usize| (i * (n + 1) * (n + 1) + j * (n + 1) + k) as u32;
    let mut x = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            for k in 0..=n {
                x.push([i as f64 * 0.1, j as f64 * 0.1, k as f64 * 0.1]);
            }
        }
    }
    let mut tris = Vec::new();
    for a in 0..=n {
        for b in 0..n {
            for c in 0..n {
                for axis in 0..3 {
                    let at = |u: usize, v: usize| match axis {
                        0 => id(a, b + u, c + v),
                        1 => id(b + u, a, c + v),
                        _ => id(b + u, c + v, a),
                    };
                    // alternate diagonals
                    if (a + b + c) % 2 == 0 {
                        tris.push([at(0, 0), at(1, 0), at(1, 1)]);
                        tris.push([at(0, 0), at(1, 1), at(0, 1)]);
                    } else {
                        tris.push([at(0, 0), at(1, 0), at(0, 1)]);
                        tris.push([at(1, 0), at(1, 1), at(0, 1)]);
                    }
                }
            }
        }
    }
    let boxes: Vec<Aabb> = tris.iter().map(|t| aabb(&x, t)).collect();
    let mut answered = 0;
    for a in 0..tris.len() {
        for b in a + 1..tris.len() {
            if overlap(&boxes[a], &boxes[b]) {
                if let Some(m) = box_contact(
                    &x,
                    &tris[a],
                    &boxes[a],
                    extreme_corners(&x, &tris[a], &boxes[a]),
                    &tris[b],
                    &boxes[b],
                    extreme_corners(&x, &tris[b], &boxes[b]),
                ) {
                    assert!(!m, "{:?} {:?}", tris[a], tris[b]);
                    answered += 1;
                }
            }
        }
    }
    assert!(answered > 2000, "{answered}");
}
