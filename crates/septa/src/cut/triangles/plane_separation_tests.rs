//! Tests of `plane_separation`: every side it claims is the exact side
//! (big-rational reference), and every pair it separates is disjoint by the
//! full exact pair test, on points and triangles on, next to and across
//! oblique planes; the check's report is the same with and without planes.

use super::*;
use crate::cut::test_rng::{lcg, xorshift_unit};
use crate::cut::triangles::tri_pair::pair_intersects;
use septa_exact::{Exact, Ring, Sign};

/// Exact sign of `n . p + d - c`.
fn exact_side(n: &[f64; 3], d: f64, c: f64, p: &[f64; 3]) -> Sign {
    let e = |v: f64| Exact::of(v);
    let f = e(n[0]).mul(&e(p[0])).add(&e(n[1]).mul(&e(p[1]))).add(&e(n[2]).mul(&e(p[2]))).add(&e(d)).sub(&e(c));
    f.sign()
}

/// A random oblique plane `[a, b, c, d]` through the unit cube.
fn oblique_plane(r: &mut impl FnMut() -> f64) -> [f64; 4] {
    let n = [r(), r(), 0.5 + 0.5 * r().abs()];
    let p = [0.5 + 0.4 * r(), 0.5 + 0.4 * r(), 0.5 + 0.4 * r()];
    [n[0], n[1], n[2], -(n[0] * p[0] + n[1] * p[1] + n[2] * p[2])]
}

/// The point of the plane above `(u, v)`, rounded (a few ulps off it, on
/// either side, like a rounded cut-vertex), shifted by `h` along z.
fn on_plane(pl: &[f64; 4], u: f64, v: f64, h: f64) -> [f64; 3] {
    [u, v, -(pl[0] * u + pl[1] * v + pl[3]) / pl[2] + h]
}

#[test]
fn claimed_sides_are_exact() {
    let mut r = xorshift_unit(7);
    let (mut claims, mut undecided) = (0, 0);
    for _ in 0..400 {
        let pl = oblique_plane(&mut r);
        let (n, d) = ([pl[0], pl[1], pl[2]], pl[3]);
        let mu = MU_RELATIVE * (n[0].abs() + n[1].abs() + n[2].abs());
        // on the plane, at the thresholds (to rounding), and a few ulps
        // and far to either side of them
        let mut pts = Vec::new();
        for c in [0.0, mu, -mu] {
            for h in [0.0, c / n[2], c / n[2] * (1.0 + 1e-15), c / n[2] * (1.0 - 1e-15), 1e-300, -1e-300, 0.25, -0.25] {
                pts.push(on_plane(&pl, r(), r(), h));
            }
        }
        let mut max_abs = [0.0f64; 3];
        for p in &pts {
            for k in 0..3 {
                max_abs[k] = max_abs[k].max(p[k].abs());
            }
        }
        let sep = Separator::new(&pl, &max_abs, 1.0).expect("an oblique plane");
        for c in [0.0, mu, -mu] {
            let at = Separator { mu: c, ..sep };
            for p in &pts {
                // [f > c, f < c, f < -c, f > -c]
                let [above, under, below, over] = at.sides(p);
                let (s, t) = (exact_side(&n, d, c, p), exact_side(&n, d, -c, p));
                assert!(!(above && under) && !(below && over));
                for (claimed, exact, want) in [
                    (above, s, Sign::Positive),
                    (under, s, Sign::Negative),
                    (below, t, Sign::Negative),
                    (over, t, Sign::Positive),
                ] {
                    if claimed {
                        assert_eq!(exact, want, "{pl:?} {c} {p:?}");
                    }
                }
                claims += (above || under) as usize;
                undecided += !(above || under) as usize;
            }
        }
    }
    // both outcomes are exercised: far points are claimed, points at the
    // threshold are not
    assert!(claims > 10000 && undecided > 4000, "{claims} {undecided}");
}

#[test]
fn non_finite_and_tiny_values_claim_nothing() {
    let pl = [0.3, -0.7, 1.0, 0.0];
    // coordinates so small that products may leave the normal range
    assert!(Separator::new(&pl, &[1e-300; 3], 1e-300).is_none());
    // a NaN vertex claims nothing
    let sep = Separator::new(&pl, &[1.0; 3], 1.0).unwrap();
    assert_eq!(sep.sides(&[f64::NAN, 0.0, 0.0]), [false; 4]);
    assert_ne!(sep.sides(&[0.0, 0.0, 1.0]), [false; 4]);
    // non-finite planes, or an infinite coordinate anywhere, give no separator
    assert!(Separator::new(&[f64::NAN, 0.0, 1.0, 0.0], &[1.0; 3], 1.0).is_none());
    assert!(Separator::new(&[0.3, -0.7, 1.0, f64::INFINITY], &[1.0; 3], 1.0).is_none());
    let x = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [f64::INFINITY, 0.0, 0.0]];
    assert!(PlaneSeparation::new(&x, &[[0, 1, 2]], &[pl]).is_none());
}

/// Triangles like a cut-cell mesh's around a few oblique planes: pieces of
/// each plane (corners rounded on it), triangles just off a plane, and
/// triangles crossing planes, some sharing corners.
fn soup(seed: u64, planes: &[[f64; 4]]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut r = xorshift_unit(seed);
    let mut pick = lcg(seed ^ 0x5eed);
    let mut x: Vec<[f64; 3]> = Vec::new();
    for i in 0..240 {
        let pl = &planes[i % planes.len()];
        let h = match i % 4 {
            0 | 1 => 0.0,
            2 => 1e-12 * r(),
            _ => 0.3 * r(),
        };
        x.push(on_plane(pl, 0.5 + 0.5 * r(), 0.5 + 0.5 * r(), h));
    }
    let mut tris = Vec::new();
    while tris.len() < 900 {
        // mostly corners on one plane, some mixed
        let base = (pick() % x.len() as u64) as usize;
        let near = |k: u64| (base + planes.len() * (k as usize % 9)) % x.len();
        let t = if pick() % 3 == 0 {
            [base, (pick() % x.len() as u64) as usize, (pick() % x.len() as u64) as usize]
        } else {
            [base, near(pick()), near(pick())]
        };
        let t = t.map(|v| v as u32);
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] && !crate::cut::check::polygon::collinear(&x, t[0], t[1], t[2])
        {
            tris.push(t);
        }
    }
    (x, tris)
}

#[test]
fn separated_pairs_are_disjoint() {
    let mut r = xorshift_unit(11);
    let (mut separated, mut meeting) = (0, 0);
    for seed in 1..=6u64 {
        let planes: Vec<[f64; 4]> = (0..3).map(|_| oblique_plane(&mut r)).collect();
        let (x, tris) = soup(seed, &planes);
        let sep = PlaneSeparation::new(&x, &tris, &planes).expect("oblique planes give bits");
        for a in 0..tris.len() {
            for b in a + 1..tris.len() {
                let meets = pair_intersects(&x, &tris[a], &tris[b]);
                if sep.separated(a, b) {
                    assert!(!meets, "seed {seed}: {:?} {:?} separated but meeting", tris[a], tris[b]);
                    assert!(!tris[a].iter().any(|v| tris[b].contains(v)), "a shared corner is never separated");
                    separated += 1;
                }
                meeting += meets as usize;
            }
        }
    }
    // the test means something: many pairs separated, many pairs meeting
    assert!(separated > 100_000 && meeting > 10_000, "{separated} {meeting}");
}

#[test]
fn axis_aligned_and_degenerate_planes_give_no_bits() {
    let x = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let t = vec![[0, 1, 2]];
    let planes = [[1.0, 0.0, 0.0, -0.5], [0.0, 0.0, 2.0, 1.0], [0.0; 4], [f64::NAN, 1.0, 1.0, 0.0]];
    assert!(PlaneSeparation::new(&x, &t, &planes).is_none());
    assert!(PlaneSeparation::new(&x, &t, &[]).is_none());
    assert!(PlaneSeparation::new(&x, &t, &[[1.0, 1.0, 0.0, -0.5]]).is_some());
}

#[test]
fn more_planes_than_bits_are_sound() {
    // 80 planes: the first 64 give bits, the rest are left out
    let mut r = xorshift_unit(3);
    let planes: Vec<[f64; 4]> = (0..80).map(|_| oblique_plane(&mut r)).collect();
    let (x, tris) = soup(9, &planes);
    let sep = PlaneSeparation::new(&x, &tris, &planes).unwrap();
    let mut n = 0;
    for a in 0..tris.len() {
        for b in a + 1..tris.len() {
            if sep.separated(a, b) {
                assert!(!pair_intersects(&x, &tris[a], &tris[b]));
                n += 1;
            }
        }
    }
    assert!(n > 0);
}
