//! Exact orient3d of nearby points: the sign of `det(b - a, c - a, d - a)`
//! from the rounded differences, when rounding them lost nothing.
//!
//! Shewchuk 1997 ("Adaptive Precision Floating-Point Arithmetic and Fast
//! Robust Geometric Predicates", Sec. 4.3, `orient3dadapt`, stage B): once
//! the static filter has given up, the determinant of the nine *rounded*
//! differences is computed exactly in expansion arithmetic; if their
//! round-off tails are all zero (Two-Diff, Knuth) that determinant is the
//! exact one. Differences of nearby coordinates are exact (Sterbenz: `b - a`
//! is exact when `a / 2 <= b <= 2a`), which is the common case of the
//! nearly degenerate orientations of a mesh's neighbouring triangles; the
//! general tiers of [`crate::det_sign_diff`] (integers, expansions of the
//! two-component differences, bignums) cost several times more there.
//!
//! Exactness: the differences are exact doubles. Their determinant is taken
//! from integer rows when each row spans at most 62 bits (exact at any
//! magnitude, `integer_det`); otherwise, restricted to the exponent
//! window of `N = 3` (`filter::window`), every `two_product` and `two_sum`
//! below is error-free and no intermediate underflows (`expansion.rs`,
//! "Exactness argument under the window"), so the expansion equals the
//! determinant and its sign is that of its largest component.

use crate::expansion::{scale, sum, two_product, two_sum};
use crate::filter::in_window;
use crate::Sign;

/// Exact sign of `det(b - a, c - a, d - a)` when every difference of
/// coordinates is an exact double within the exponent window; `None`
/// otherwise (use [`crate::det_sign_diff`]).
pub fn orient3d_exact_diffs(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Option<Sign> {
    let mut x = [0.0f64; 9];
    for (i, p) in [b, c, d].into_iter().enumerate() {
        for k in 0..3 {
            let (s, tail) = two_sum(p[k], -a[k]);
            if tail != 0.0 || !s.is_finite() {
                return None;
            }
            x[3 * i + k] = s;
        }
    }
    // The exact differences as integer rows first (`integer_det`: each
    // row scaled by a power of two to `i64`s when its nonzero entries span
    // at most 62 bits, then the cofactor expansion in `i128` / 256 bits):
    // about a quarter of the instructions of the expansions below on the
    // nearly coplanar corners of a cut-cell mesh's rounded vertices.
    let rows = [[x[0], x[1], x[2]], [x[3], x[4], x[5]], [x[6], x[7], x[8]]];
    if let Some(s) = crate::integer_det::det_sign_ia::<3>(&rows) {
        return Some(s);
    }
    if !in_window(&x, 3) {
        return None;
    }
    // an exact product as an expansion (increasing magnitude, no zeros)
    fn product(p: f64, q: f64, h: &mut [f64; 2]) -> usize {
        let (hi, lo) = two_product(p, q);
        let mut n = 0;
        for v in [lo, hi] {
            if v != 0.0 {
                h[n] = v;
                n += 1;
            }
        }
        n
    }
    // minor (i, j) of the rows `c - a`, `d - a`: v_i w_j - v_j w_i
    let minor = |i: usize, j: usize, h: &mut [f64; 4]| -> usize {
        let (mut p, mut q) = ([0.0; 2], [0.0; 2]);
        let (np, nq) = (product(x[3 + i], x[6 + j], &mut p), product(x[3 + j], x[6 + i], &mut q));
        sum(&p[..np], &q[..nq], -1.0, h)
    };
    // det = u0 m12 - u1 m02 + u2 m01 with u = b - a
    let mut terms = [[0.0f64; 8]; 3];
    let mut lens = [0usize; 3];
    for (t, (k, (i, j))) in [(0, (1, 2)), (1, (0, 2)), (2, (0, 1))].into_iter().enumerate() {
        let mut m = [0.0; 4];
        let n = minor(i, j, &mut m);
        lens[t] = scale(&m[..n], x[k], &mut terms[t]);
    }
    let mut s01 = [0.0f64; 16];
    let n01 = sum(&terms[0][..lens[0]], &terms[1][..lens[1]], -1.0, &mut s01);
    let mut det = [0.0f64; 24];
    let n = sum(&s01[..n01], &terms[2][..lens[2]], 1.0, &mut det);
    Some(match n {
        0 => Sign::Zero,
        _ => Sign::of_f64(det[n - 1]),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Sign {
        crate::bignum::det_sign_diff(&[*b, *c, *d], &[*a, *a, *a])
    }

    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn agrees_with_bignums_on_nearly_and_exactly_degenerate_points() {
        let mut r = rng(0x2545_f491_4f6c_dd1d);
        let (mut some, mut zero, mut nonzero) = (0, 0, 0);
        for i in 0..20000 {
            // a small triangle near (1, 2, 3) and a point on its plane
            // (rounded), moved by -1..=1 ulps; every 4th case exactly
            // degenerate (integer multiples of 2^-10 on a plane)
            let base = [1.0 + r(), 2.0 + r(), 3.0 + r()];
            let mut p: [[f64; 3]; 4] = std::array::from_fn(|_| std::array::from_fn(|k| base[k] + 0.01 * (r() - 0.5)));
            if i % 4 == 0 {
                for q in p.iter_mut() {
                    let (u, v) = ((r() * 1024.0).floor() / 1024.0, (r() * 1024.0).floor() / 1024.0);
                    *q = [1.0 + u, 1.5 + v, 2.0 + (u - v) / 2.0];
                }
            } else {
                let (l, m) = (r(), r());
                p[3] = std::array::from_fn(|k| {
                    let v = p[0][k] + l * (p[1][k] - p[0][k]) + m * (p[2][k] - p[0][k]);
                    f64::from_bits((v.to_bits() as i64 + (i % 3) as i64 - 1) as u64)
                });
            }
            let want = reference(&p[0], &p[1], &p[2], &p[3]);
            if let Some(s) = orient3d_exact_diffs(&p[0], &p[1], &p[2], &p[3]) {
                assert_eq!(s, want, "{p:?}");
                some += 1;
                if s == Sign::Zero {
                    zero += 1;
                } else {
                    nonzero += 1;
                }
            }
        }
        // nearby points: the differences are exact nearly always
        assert!(some > 19000 && zero > 3000 && nonzero > 10000, "{some} {zero} {nonzero}");
    }

    #[test]
    fn expansions_decide_rows_too_wide_for_integers() {
        // exact differences whose rows span more than 62 bits (offsets of
        // 2^-10 next to offsets of 2^-72): the integer tier declines, the
        // expansions decide; every 3rd case exactly coplanar
        let mut r = rng(99);
        let mut k = || (r() * 64.0).floor() - 32.0;
        let (mut wide, mut zero) = (0, 0);
        for i in 0..5000 {
            let mut p: [[f64; 3]; 4] =
                std::array::from_fn(|_| [1.0 + k() * 2f64.powi(-10), k() * 2f64.powi(-72), 3.0 + k() * 2f64.powi(-10)]);
            if i % 3 == 0 {
                // d = a + (b - a) + (c - a), on the plane of a, b, c
                p[3] = std::array::from_fn(|j| p[1][j] + p[2][j] - p[0][j]);
            }
            let [a, b, c, d] = p;
            let rows = [b, c, d].map(|q| std::array::from_fn(|j| q[j] - a[j]));
            if crate::integer_det::det_sign_ia::<3>(&rows).is_none() {
                wide += 1;
            }
            let s = orient3d_exact_diffs(&a, &b, &c, &d).expect("exact differences in the window");
            assert_eq!(s, reference(&a, &b, &c, &d), "{p:?}");
            zero += (s == Sign::Zero) as usize;
        }
        assert!(wide > 4000 && zero > 1000, "{wide} {zero}");
    }

    #[test]
    fn agrees_with_bignums_on_random_points_or_declines() {
        let mut r = rng(7);
        let mut some = 0;
        for i in 0..20000 {
            // coordinates in [-4, 4) (multiples of 2^-50: exact differences),
            // or of scales 2^-30 .. 2^30 (mostly inexact ones)
            let p: [[f64; 3]; 4] = std::array::from_fn(|_| {
                std::array::from_fn(|_| match i % 2 {
                    0 => 8.0 * r() - 4.0,
                    _ => (r() - 0.5) * 2f64.powi((r() * 60.0) as i32 - 30),
                })
            });
            if let Some(s) = orient3d_exact_diffs(&p[0], &p[1], &p[2], &p[3]) {
                assert_eq!(s, reference(&p[0], &p[1], &p[2], &p[3]));
                some += 1;
            }
        }
        // both outcomes: differences of doubles of unlike scales are inexact
        assert!(some > 100 && some < 19000, "{some}");
        // inexact differences decline; so do rows too wide for integers
        // with values outside the expansions' window
        let o = [0.0; 3];
        assert_eq!(orient3d_exact_diffs(&[1.0, 0.0, 0.0], &[1e-20, 0.0, 0.0], &o, &o), None);
        assert_eq!(orient3d_exact_diffs(&o, &[1e-300, 1.0, 0.0], &[0.0, 1.0, 0.0], &[0.0, 0.0, 1.0]), None);
        // tiny values in narrow rows: exact integers at any magnitude
        assert_eq!(
            orient3d_exact_diffs(&o, &[1e-300, 0.0, 0.0], &[0.0, 1.0, 0.0], &[0.0, 0.0, 1.0]),
            Some(Sign::Positive)
        );
        assert_eq!(
            orient3d_exact_diffs(&o, &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], &[0.0, 0.0, 1.0]),
            Some(Sign::Positive)
        );
        assert_eq!(
            orient3d_exact_diffs(&o, &[0.0, 1.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 0.0, 1.0]),
            Some(Sign::Negative)
        );
    }
}
