//! The sidedness filter of the cut embedding (`side_filter.rs`, TopoCut
//! Sec. 6.1) against exact rationals: when [`FloatPlane::box_sign`] claims a
//! strict sign, every plane within the stated error bounds (`|n*_i - n_i| <=
//! dn_i`, `|d* - d| <= dd`) has that strict sign at every real point of the
//! box `c +- w`. The extremes of that bilinear expression lie at the
//! corners of the product of intervals, so the oracle evaluates every
//! corner product in `num-rational` (not with the crate's own predicates).

use crate::cut::embed::side_filter::FloatPlane;
use num_rational::BigRational;
use num_traits::Zero;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn q(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite")
}

/// The exact minimum and maximum of `n* . y + d*` over `|n*_i - n_i| <=
/// dn_i`, `|d* - d| <= dd` and `|y_i - c_i| <= w_i`.
fn exact_range(p: &FloatPlane, c: &[f64; 3], w: &[f64; 3]) -> (BigRational, BigRational) {
    let (mut lo, mut hi) = (q(p.d) - q(p.dd), q(p.d) + q(p.dd));
    for k in 0..3 {
        let ns = [q(p.n[k]) - q(p.dn[k]), q(p.n[k]) + q(p.dn[k])];
        let ys = [q(c[k]) - q(w[k]), q(c[k]) + q(w[k])];
        let prods: Vec<BigRational> = ns.iter().flat_map(|a| ys.iter().map(move |b| a * b)).collect();
        lo += prods.iter().min().unwrap().clone();
        hi += prods.iter().max().unwrap().clone();
    }
    (lo, hi)
}

fn pow2(e: i32) -> f64 {
    2f64.powi(e)
}

#[test]
fn box_sign_holds_on_the_whole_box_for_every_plane_within_the_bounds() {
    let mut r = ChaCha8Rng::seed_from_u64(0x51de);
    let (mut decided, mut near_decided, mut cases) = (0usize, 0usize, 0usize);
    for i in 0..60_000 {
        // the scale of the scene: cut inputs from 1e-90 to 1e90
        let scale = pow2(r.gen_range(-300..300));
        let n: [f64; 3] = [0, 1, 2].map(|_| r.gen_range(-1.0..1.0));
        let mut c = [0, 1, 2].map(|_| r.gen_range(-1.0..1.0) * scale);
        let d0 = r.gen_range(-1.0..1.0) * scale;
        // a point on the plane (coordinate k solved for), then moved off it
        // by a relative distance from 1e-3 down to a few ulps
        let k = (0..3).max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs())).unwrap();
        c[k] = -(d0 + (0..3).filter(|&j| j != k).map(|j| n[j] * c[j]).sum::<f64>()) / n[k];
        let off = match i % 4 {
            0 => 1e-3,
            1 => 1e-9,
            2 => 1e-14,
            _ => 1e-16 * (i % 9) as f64,
        };
        c[k] += off * scale * r.gen_range(-1.0..1.0);
        // error bounds of a triangle plane (zero for an input cut plane)
        let (dn, dd) = if i % 3 == 0 {
            ([0.0; 3], 0.0)
        } else {
            let e = pow2(-r.gen_range(40..60));
            ([0, 1, 2].map(|_| r.gen_range(0.0..e)), r.gen_range(0.0..e) * scale)
        };
        let w = match i % 5 {
            0 => [0.0; 3],
            1 => [f64::EPSILON * scale; 3],
            2 => [0, 1, 2].map(|_| r.gen_range(0.0..1e-12) * scale),
            3 => [0, 1, 2].map(|_| r.gen_range(0.0..1e-6) * scale),
            _ => [1e-17 * scale, 0.0, 1e-15 * scale],
        };
        let p = FloatPlane { n, d: d0, dn, dd };
        cases += 1;
        if let Some(s) = p.box_sign(&c, &w) {
            decided += 1;
            let (lo, hi) = exact_range(&p, &c, &w);
            if s > 0 {
                assert!(lo > BigRational::zero(), "case {i}: {p:?} claimed + on {c:?} +- {w:?}, exact minimum <= 0");
            } else {
                assert!(hi < BigRational::zero(), "case {i}: {p:?} claimed - on {c:?} +- {w:?}, exact maximum >= 0");
            }
            // decided although the plane passes within 1e-12 of the terms'
            // magnitude: the filter is checked where it is tight, not only
            // on clear cases
            let margin = if s > 0 { lo } else { -hi };
            let mag: f64 = (0..3).map(|k| (n[k] * c[k]).abs()).sum::<f64>() + d0.abs();
            near_decided += (margin < q(1e-12 * mag)) as usize;
        }
    }
    eprintln!("{cases} boxes: {decided} decided, {near_decided} of them within 1e-12 of the terms' magnitude");
    assert!(decided > cases / 2, "the filter decided only {decided} of {cases}");
    assert!(near_decided > 1_000, "only {near_decided} tight decisions");
}
