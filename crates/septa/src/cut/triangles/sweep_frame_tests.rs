//! Tests of `sweep_frame`: the eigenvectors, the widened boxes holding the
//! exact images of their triangles, and when the frame is chosen.

use super::*;
use crate::cut::test_rng::{aabbs, lcg, plate};
use crate::cut::triangles::tri_pair::TriPlane;
use num_rational::BigRational;

/// Doubles in [0, 1) from a fixed LCG.
fn unit(seed: u64) -> impl FnMut() -> f64 {
    let mut r = lcg(seed);
    move || r() as f64 / (1u64 << 53) as f64
}

#[test]
fn eigenvectors_of_a_rotated_diagonal() {
    // A = Q diag(5, 2, 1) Q^T for an orthonormal Q: its eigenvectors are Q's columns
    let (c, s) = (0.6f64, 0.8f64);
    let q = [[c, -s, 0.0], [s * 0.6, c * 0.6, -0.8], [s * 0.8, c * 0.8, 0.6]];
    let d = [5.0, 2.0, 1.0];
    let a: [[f64; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| q[i][k] * d[k] * q[j][k]).sum()));
    let (values, vectors) = symmetric_eigen(a);
    for (l, v) in values.iter().zip(&vectors) {
        let av: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| a[i][j] * v[j]).sum());
        for i in 0..3 {
            assert!((av[i] - l * v[i]).abs() < 1e-12, "{values:?} {vectors:?}");
        }
        assert!(((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0).abs() < 1e-12);
    }
    let mut sorted = values;
    sorted.sort_by(f64::total_cmp);
    for (got, want) in sorted.iter().zip([1.0, 2.0, 5.0]) {
        assert!((got - want).abs() < 1e-12, "{values:?}");
    }
}

#[test]
fn widened_boxes_hold_the_exact_images() {
    // random frames over corners of every magnitude, checked in big rationals:
    // each corner's exact r_k . p lies in the computed box
    let mut r = unit(7);
    let mut checked = 0;
    for round in 0..200 {
        let scale = 2f64.powi((round % 40) * 7 - 140);
        let frame: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| r() * 2.0 - 1.0));
        let x: Vec<[f64; 3]> = (0..30).map(|_| std::array::from_fn(|_| (r() * 2.0 - 1.0) * scale)).collect();
        let tris: Vec<[u32; 3]> = (0..10).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        let boxes = framed_boxes(&x, &tris, &frame).unwrap();
        let q = |v: f64| BigRational::from_float(v).unwrap();
        for (t, (lo, hi)) in tris.iter().zip(&boxes) {
            for &v in t {
                for k in 0..3 {
                    let exact: BigRational = (0..3).map(|j| q(frame[k][j]) * q(x[v as usize][j])).sum();
                    assert!(q(lo[k]) <= exact && exact <= q(hi[k]), "round {round}, axis {k}");
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 200 * 30 * 3);
}

#[test]
fn non_finite_or_overflowing_coordinates_give_no_frame() {
    let x = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, f64::INFINITY, 0.0]];
    assert!(framed_boxes(&x, &[[0, 1, 2]], &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).is_none());
    assert!(normal_frame([[f64::NAN, 0.0, 0.0], [0.0; 3]].into_iter()).is_none());
    // images that could overflow (`S_k` = 1.2e308 is finite, twice it is not):
    // no frame rather than a box without its point
    let big = [[6e307, 6e307, 0.0], [-6e307, 6e307, 1.0], [0.0, -6e307, 6e307]];
    let diagonal = [[1.0, 1.0, 0.0], [0.0, 1.0, 1.0], [1.0, 0.0, 1.0]];
    assert!(framed_boxes(&big, &[[0, 1, 2]], &diagonal).is_none());
    let large = big.map(|p| p.map(|c| c / 8.0));
    let boxes = framed_boxes(&large, &[[0, 1, 2]], &diagonal).unwrap();
    assert!(boxes.iter().all(|(lo, hi)| lo.iter().chain(hi).all(|c| c.is_finite())));
}

fn normals(x: &[[f64; 3]], tris: &[[u32; 3]]) -> Vec<[f64; 3]> {
    tris.iter().map(|t| TriPlane::new(x, t).normal()).collect()
}

#[test]
fn a_tilted_plate_is_boxed_along_its_normal() {
    let n = [0.5564f64, -0.5092, -0.6566];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let (x, t) = plate(n.map(|c| c / l), 0.01, 12);
    let boxes = aabbs(&x, &t);
    let framed = sweep_boxes(&x, &t, normals(&x, &t).into_iter(), &boxes).expect("a frame for a tilted plate");
    // along the normal (some row of the frame) each box is thin
    let thin = (0..3).filter(|&k| framed.iter().all(|b| b.1[k] - b.0[k] < 1e-9)).count();
    assert_eq!(thin, 1);
}

#[test]
fn axis_aligned_and_isotropic_meshes_keep_the_axes() {
    // a plate along an axis plane: its axis-aligned boxes are already flat
    let (x, t) = plate([0.0, 0.0, 1.0], 0.01, 8);
    assert!(sweep_boxes(&x, &t, normals(&x, &t).into_iter(), &aabbs(&x, &t)).is_none());
    // random small triangles facing every way
    let mut r = unit(3);
    let x: Vec<[f64; 3]> = (0..300)
        .flat_map(|_| {
            let c: [f64; 3] = std::array::from_fn(|_| r());
            let p: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|k| c[k] + 0.05 * (r() - 0.5)));
            p
        })
        .collect();
    let t: Vec<[u32; 3]> = (0..300).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    assert!(sweep_boxes(&x, &t, normals(&x, &t).into_iter(), &aabbs(&x, &t)).is_none());
}
