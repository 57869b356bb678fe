//! Tests of `verify_volume`: the static filter never contradicts the exact
//! volume sum, on random, exactly flat, nearly flat (one ulp), many-triangle
//! and extreme-magnitude cells, and decides the ordinary ones.

use super::*;
use crate::cut::check::verify_volume::volume_sum;
use septa_exact::Exact;

fn exact(x: &[[f64; 3]], tris: &[[u32; 3]]) -> Sign {
    volume_sum::<Exact>(x, x[tris[0][0] as usize], tris).sign()
}

/// Checks the filter against the exact sign; `Some(true)` if it decided.
fn check(x: &[[f64; 3]], tris: &[[u32; 3]]) -> bool {
    let o = x[tris[0][0] as usize];
    match volume_sign_static(x, o, tris) {
        Some(s) => {
            assert_eq!(s, exact(x, tris), "{x:?} {tris:?}");
            true
        }
        None => false,
    }
}

/// Doubles in `[-1, 1)` from the shared test generator.
fn lcg(seed: u64) -> impl FnMut() -> f64 {
    let mut g = crate::cut::test_rng::lcg(seed);
    move || g() as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

/// The four outward triangles of the tetrahedron `0 1 2 3` (outward when
/// `orient(0, 1, 2, 3)` is positive; inward, a negative volume, else).
const TET: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];

#[test]
fn random_flat_and_nearly_flat_tetrahedra() {
    let mut r = lcg(5);
    let (mut decided, mut undecided) = (0, 0);
    for i in 0..6000 {
        let scale = [1.0, 1e-3, 1e6, 2f64.powi(-1000), 2f64.powi(900), 2f64.powi(1020)][i % 6];
        let mut x: Vec<[f64; 3]> = (0..4).map(|_| [r() * scale, r() * scale, r() * scale]).collect();
        if i % 3 != 0 {
            // on the plane z = x + y exactly (small integers), then maybe
            // one ulp off it
            x = (0..4)
                .map(|_| {
                    let (a, b) = ((r() * 1000.0).round(), (r() * 1000.0).round());
                    [a * scale, b * scale, (a + b) * scale]
                })
                .collect();
            if i % 3 == 2 {
                let (z, up) = (x[3][2], r() > 0.0);
                // one step of the bits; z = 0 (a + b = 0) has no step below
                // its bits: the smallest subnormal of either sign instead
                x[3][2] = if z == 0.0 {
                    if up {
                        f64::from_bits(1)
                    } else {
                        -f64::from_bits(1)
                    }
                } else {
                    f64::from_bits(if up { z.to_bits() + 1 } else { z.to_bits() - 1 })
                };
            }
        }
        if check(&x, &TET) {
            decided += 1;
        } else {
            undecided += 1;
        }
    }
    assert!(decided > 900 && undecided > 1000, "{decided} {undecided}");
}

#[test]
fn many_triangle_cells() {
    // a fan of n triangles around a centre and the same fan reversed one
    // level up or on the same level (volume exactly zero), with the rim
    // nudged by ulps
    let mut r = lcg(9);
    let (mut decided, mut undecided) = (0, 0);
    for (i, n) in [3usize, 50, 1000, 20000].into_iter().cycle().take(24).enumerate() {
        let h = [0.0, 1e-12, 0.5][i % 3];
        let mut x = vec![[0.0, 0.0, 0.0], [0.0, 0.0, h]];
        for k in 0..n {
            let a = k as f64 / n as f64 * std::f64::consts::TAU;
            let (c, s) = (a.cos() * (1.0 + 0.1 * r()), a.sin());
            x.push([c, s, 0.0]);
            x.push([c, s, h]);
        }
        let mut tris = Vec::new();
        for k in 0..n as u32 {
            let (p, q) = (2 + 2 * k, 2 + 2 * ((k + 1) % n as u32));
            tris.push([0, q, p]);
            tris.push([1, p + 1, q + 1]);
            // the side wall between the two fans
            tris.push([p, q, q + 1]);
            tris.push([p, q + 1, p + 1]);
        }
        if check(&x, &tris) {
            decided += 1;
        } else {
            undecided += 1;
        }
    }
    assert!(decided > 4 && undecided > 4, "{decided} {undecided}");
}
