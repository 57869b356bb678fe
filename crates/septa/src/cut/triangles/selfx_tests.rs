//! Tests of `selfx`: the grid finds exactly the intersecting pairs that a
//! test of every pair finds, also with long triangles over many cells.

use super::*;
use crate::cut::triangles::tri_pair::pair_intersects;

/// A soup of small triangles in the unit cube with long ones across it
/// (oblique, axis-aligned, two sharing an edge), from a fixed LCG.
fn soup() -> (Vec<[f64; 3]>, Vec<[u32; 3]>, usize) {
    let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut r = move || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut x, mut t) = (Vec::new(), Vec::new());
    let mut tri = |x: &mut Vec<[f64; 3]>, p: [[f64; 3]; 3]| {
        let i = x.len() as u32;
        x.extend(p);
        t.push([i, i + 1, i + 2]);
    };
    for _ in 0..1500 {
        let c = [r(), r(), r()];
        let p = std::array::from_fn(|_| std::array::from_fn(|k| c[k] + 0.04 * (r() - 0.5)));
        tri(&mut x, p);
    }
    for _ in 0..5 {
        tri(&mut x, std::array::from_fn(|_| [r(), r(), r()]));
    }
    tri(&mut x, [[0.0, 0.0, 0.5], [1.0, 0.1, 0.5], [0.2, 1.0, 0.5]]);
    tri(&mut x, [[0.5, -0.1, 0.0], [0.5, 1.0, 0.1], [0.5, 0.3, 1.0]]);
    let long = t.len() - 1500;
    // two long triangles sharing an edge
    let i = x.len() as u32;
    x.extend([[0.1, 0.1, 0.1], [0.9, 0.8, 0.9], [0.9, 0.1, 0.2], [0.8, 0.2, 0.25]]);
    t.push([i, i + 1, i + 2]);
    t.push([i, i + 1, i + 3]);
    (x, t, long + 2)
}

fn every_pair(x: &[[f64; 3]], t: &[[u32; 3]], keep: impl Fn(usize, usize) -> bool) -> Vec<(u32, u32)> {
    let mut v = Vec::new();
    for a in 0..t.len() {
        for b in a + 1..t.len() {
            if keep(a, b) && pair_intersects(x, &t[a], &t[b]) {
                v.push((a as u32, b as u32));
            }
        }
    }
    v
}

#[test]
fn grid_finds_the_pairs_every_pair_test_finds() {
    let (x, t, long) = soup();
    let all = every_pair(&x, &t, |_, _| true);
    let first_long = (t.len() - long) as u32;
    // not vacuous: long triangles meet small ones and each other
    assert!(all.iter().filter(|p| p.1 >= first_long && p.0 < first_long).count() > 50, "{all:?}");
    assert!(all.iter().any(|p| p.0 >= first_long), "{all:?}");
    assert_eq!(intersecting_pairs(&x, &t, false), all);
    assert_eq!(intersecting_pairs(&x, &t, true), all[..1].to_vec());
}

#[test]
fn re_check_finds_the_pairs_with_a_fresh_triangle() {
    let (x, t, _) = soup();
    let fresh: Vec<bool> = (0..t.len()).map(|i| i % 7 == 3 || i + 3 >= t.len()).collect();
    let want = every_pair(&x, &t, |a, b| fresh[a] || fresh[b]);
    assert!(want.len() > 20, "{want:?}");
    assert_eq!(intersecting_pairs_touching(&x, &t, Some(&fresh), None, false), want);
}

/// A tilted thin plate (two parallel faces of small triangles) with walls
/// across it, some crossing the faces: boxed in the frame of its normal.
fn tilted_plate_with_walls() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let n = [0.5564f64, -0.5092, -0.6566];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let n = n.map(|c| c / l);
    let (mut x, mut t) = crate::cut::test_rng::plate(n, 0.02, 16);
    // walls joining the faces at grid vertices (meeting them in shared
    // corners only), and walls poking through both faces
    let per_face = 17 * 17;
    for i in (0..per_face as u32).step_by(23) {
        let j = if i % 17 == 16 { i - 1 } else { i + 1 };
        t.push([i, j, i + per_face as u32]);
    }
    let mut r = crate::cut::test_rng::lcg(11);
    let mut unit = move || r() as f64 / (1u64 << 53) as f64;
    for _ in 0..12 {
        let c = x[(unit() * per_face as f64) as usize];
        let i = x.len() as u32;
        for s in [-1.0, 1.0] {
            x.push(std::array::from_fn(|k| c[k] + s * 0.05 * n[k] + 0.01 * (unit() - 0.5)));
        }
        x.push(std::array::from_fn(|k| c[k] + 0.08 * (unit() - 0.5)));
        t.push([i, i + 1, i + 2]);
    }
    (x, t)
}

#[test]
fn a_framed_sweep_finds_the_pairs_every_pair_test_finds() {
    let (x, t) = tilted_plate_with_walls();
    // the sweep does go through the frame here
    let boxes = crate::cut::test_rng::aabbs(&x, &t);
    let normals = t.iter().map(|t| TriPlane::new(&x, t).normal());
    assert!(crate::cut::triangles::sweep_frame::sweep_boxes(&x, &t, normals, &boxes).is_some());
    let all = every_pair(&x, &t, |_, _| true);
    // not vacuous: the poking walls cross the faces
    assert!(all.len() >= 12, "{all:?}");
    assert_eq!(intersecting_pairs(&x, &t, false), all);
    assert_eq!(intersecting_pairs(&x, &t, true), all[..1].to_vec());
    let fresh: Vec<bool> = (0..t.len()).map(|i| i % 5 == 2).collect();
    let want = every_pair(&x, &t, |a, b| fresh[a] || fresh[b]);
    assert_eq!(intersecting_pairs_touching(&x, &t, Some(&fresh), None, false), want);
}
