//! The volume filter against exact evaluation (`septa_exact::Exact`): for
//! exact points anywhere in the boxes (corners, where the bound is tight,
//! and random doubles inside), the filter's sign, when it gives one, is the
//! exact sign of the fan sum; exactly flat cells (zero volume) and cells one
//! ulp off flat are never decided wrongly.

use super::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa_exact::{Exact, Ring};

/// Exact sign of `sum +-det[p_a - o, p_b - o, p_c - o]` for double points.
fn exact_sign(p: &[[f64; 3]], o: &[f64; 3], tris: &[([usize; 3], bool)]) -> Sign {
    let rel = |x: &[f64; 3]| [0, 1, 2].map(|k| Exact::of(x[k]).sub(&Exact::of(o[k])));
    let mut acc = Exact::zero();
    for &([a, b, c], pos) in tris {
        let (a, b, c) = (rel(&p[a]), rel(&p[b]), rel(&p[c]));
        let cr = [
            b[1].mul(&c[2]).sub(&b[2].mul(&c[1])),
            b[2].mul(&c[0]).sub(&b[0].mul(&c[2])),
            b[0].mul(&c[1]).sub(&b[1].mul(&c[0])),
        ];
        let d = a[0].mul(&cr[0]).add(&a[1].mul(&cr[1])).add(&a[2].mul(&cr[2]));
        acc = if pos { acc.add(&d) } else { acc.sub(&d) };
    }
    acc.sign()
}

/// The boundary of the tetrahedron `0 1 2 3` as a fan (outward when
/// `det[p1 - p0, p2 - p0, p3 - p0] > 0`).
const TET: [([usize; 3], bool); 4] = [([0, 2, 1], true), ([0, 1, 3], true), ([0, 3, 2], true), ([1, 2, 3], true)];

/// Boxes `[x - lo, x + hi]` around the points, and the exact points chosen
/// in them by `pick` (0: the midpoint's point itself, 1: a random corner,
/// 2: a random double inside).
fn run(r: &mut ChaCha8Rng, x: &[[f64; 3]], rad: f64, pick: u8, tris: &[([usize; 3], bool)]) -> (Option<Sign>, Sign) {
    let boxes: Vec<[Interval; 3]> = x
        .iter()
        .map(|p| {
            p.map(|c| {
                let (a, b) = (rad * r.gen::<f64>(), rad * r.gen::<f64>());
                Interval { lo: c - a, hi: c + b }
            })
        })
        .collect();
    let exact_pts: Vec<[f64; 3]> = boxes
        .iter()
        .zip(x)
        .map(|(b, p)| {
            std::array::from_fn(|k| match pick {
                0 => p[k].clamp(b[k].lo, b[k].hi),
                1 => {
                    if r.gen::<bool>() {
                        b[k].lo
                    } else {
                        b[k].hi
                    }
                }
                _ => (b[k].lo + (b[k].hi - b[k].lo) * r.gen::<f64>()).clamp(b[k].lo, b[k].hi),
            })
        })
        .collect();
    let o = x[0];
    let pts: Vec<FilterPoint> = boxes.iter().map(|b| FilterPoint::new(b, &o)).collect();
    (fan_sign(&pts, tris), exact_sign(&exact_pts, &o, tris))
}

#[test]
fn random_tetrahedra_agree_with_exact() {
    let mut r = ChaCha8Rng::seed_from_u64(3);
    let mut decided = 0;
    let total = 6000;
    for i in 0..total {
        let s = [1.0, 1e-6, 1e6, 3.7][i % 4];
        let x: Vec<[f64; 3]> = (0..4).map(|_| [0; 3].map(|_| s * r.gen_range(-1.0..1.0))).collect();
        let rad = [0.0, 1e-15 * s, 1e-9 * s, 0.1 * s][i % 4];
        let (f, e) = run(&mut r, &x, rad, (i % 3) as u8, &TET);
        if let Some(f) = f {
            assert_eq!(f, e, "case {i}");
            decided += 1;
        }
    }
    assert!(decided > total / 2, "the filter decided only {decided} of {total}");
}

#[test]
fn flat_and_nearly_flat_cells_are_never_decided_wrongly() {
    let mut r = ChaCha8Rng::seed_from_u64(9);
    for i in 0..6000 {
        // four points on a plane z = a x + b y + c with dyadic coefficients
        // and coordinates: the volume is exactly zero
        let (a, b, c) = ((r.gen_range(-8..8) as f64) / 8.0, (r.gen_range(-8..8) as f64) / 4.0, 0.5);
        let mut x: Vec<[f64; 3]> = (0..4)
            .map(|_| {
                let (px, py) = ((r.gen_range(-64..64) as f64) / 16.0, (r.gen_range(-64..64) as f64) / 16.0);
                [px, py, a * px + b * py + c]
            })
            .collect();
        // then one coordinate an ulp or two off, on every other case
        if i % 2 == 1 {
            let k = r.gen_range(0..4);
            let z = x[k][2];
            let d = if z == 0.0 { f64::MIN_POSITIVE } else { z.abs() * f64::EPSILON };
            x[k][2] = if r.gen::<bool>() { z + d } else { z - d };
        }
        let rad = [0.0, 0.0, 1e-300, 1e-17][i % 4];
        let (f, e) = run(&mut r, &x, rad, (i % 3) as u8, &TET);
        if i % 2 == 0 && rad == 0.0 {
            assert_eq!(e, Sign::Zero);
        }
        if let Some(f) = f {
            assert_eq!(f, e, "case {i}");
        }
    }
}

#[test]
fn closed_cubes_with_wide_fans_agree_with_exact() {
    // a unit cube's six faces as fans of quads, far from the origin, with
    // boxes of a few ulps: a closed surface like a cut-cell's
    let mut r = ChaCha8Rng::seed_from_u64(17);
    let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let mut tris = Vec::new();
    for q in quads {
        tris.push(([q[0], q[1], q[2]], true));
        tris.push(([q[0], q[2], q[3]], true));
    }
    for i in 0..2000 {
        let (off, size) = (1e3 * r.gen_range(-1.0..1.0), [1.0, 1e-9, 1e-13][i % 3]);
        let x: Vec<[f64; 3]> =
            (0..8).map(|v| [0, 1, 2].map(|k| off + size * ((v >> k) & 1) as f64 + 1e-3 * k as f64)).collect();
        let rad = [0.0, 4.0 * f64::EPSILON * 1e3, 1e-3 * size][i % 3];
        let (f, e) = run(&mut r, &x, rad, (i % 3) as u8, &tris);
        if let Some(f) = f {
            assert_eq!(f, e, "case {i}");
        }
    }
}
