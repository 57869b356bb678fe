//! `Expansion` (stack expansions behind `Ring`) against the bignum tier
//! `Exact`: the same exact values on random and
//! adversarial inputs inside the window (exact cancellation to zero, near
//! cancellation, mixed magnitudes at the window's edges, negative zero),
//! so `to_exact().to_f64_approx()` rounds as the bignum evaluation does.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa_exact::{expansion_window, Exact, Expansion, Ring, Sign};

/// The homogeneous coordinates of a triangle-plane-plane vertex (the
/// degree-5 formula of `septa cut`'s `Ctx::hom`), over any ring.
fn tpp<R: Ring>(tri: &[[f64; 3]; 3], p: &[f64; 4], qq: &[f64; 4]) -> ([R; 3], R) {
    let v = |x: &[f64; 3]| [R::of(x[0]), R::of(x[1]), R::of(x[2])];
    let dot = |a: &[R; 3], b: &[R; 3]| a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]));
    let a = v(&tri[0]);
    let b = v(&tri[1]);
    let c = v(&tri[2]);
    let e1 = [b[0].sub(&a[0]), b[1].sub(&a[1]), b[2].sub(&a[2])];
    let e2 = [c[0].sub(&a[0]), c[1].sub(&a[1]), c[2].sub(&a[2])];
    let np = [R::of(p[0]), R::of(p[1]), R::of(p[2])];
    let nq = [R::of(qq[0]), R::of(qq[1]), R::of(qq[2])];
    let (m00, m01, m10, m11) = (dot(&np, &e1), dot(&np, &e2), dot(&nq, &e1), dot(&nq, &e2));
    let r0 = R::of(p[3]).add(&dot(&np, &a)).neg();
    let r1 = R::of(qq[3]).add(&dot(&nq, &a)).neg();
    let det = m00.mul(&m11).sub(&m01.mul(&m10));
    let n1 = r0.mul(&m11).sub(&m01.mul(&r1));
    let n2 = m00.mul(&r1).sub(&r0.mul(&m10));
    let h = [0, 1, 2].map(|k| a[k].mul(&det).add(&e1[k].mul(&n1)).add(&e2[k].mul(&n2)));
    (h, det)
}

/// Equal values (the representations may differ by trailing zero bits).
fn same(x: &Exact, y: &Exact) -> bool {
    (x - y).sign() == Sign::Zero
}

fn check(tri: &[[f64; 3]; 3], p: &[f64; 4], qq: &[f64; 4]) -> usize {
    let ins = tri.iter().flatten().chain(p).chain(qq).copied();
    assert!(expansion_window(ins));
    let (he, we) = tpp::<Exact>(tri, p, qq);
    let (hx, wx) = tpp::<Expansion>(tri, p, qq);
    let mut spilled = 0;
    for (e, x) in he.iter().chain([&we]).zip(hx.iter().chain([&wx])) {
        match x.to_exact() {
            Some(xe) => {
                assert!(same(e, &xe), "value differs");
                let (a, b) = (e.to_f64_approx(), xe.to_f64_approx());
                assert_eq!(a.to_bits(), b.to_bits(), "rounding differs");
                assert_eq!(x.to_f64_approx().map(f64::to_bits), Some(a.to_bits()), "direct rounding differs");
            }
            None => {
                assert!(x.is_spilled());
                spilled += 1;
            }
        }
    }
    spilled
}

fn rnd(r: &mut ChaCha8Rng, scale: f64) -> f64 {
    let x: f64 = r.gen_range(-1.0..1.0);
    x * scale
}

#[test]
fn random_inputs_match_bignums() {
    let mut r = ChaCha8Rng::seed_from_u64(7);
    let mut spilled = 0;
    for i in 0..3000 {
        let s = [1.0, 1e-3, 1e3, 2f64.powi(-80), 2f64.powi(80)][i % 5];
        let tri = [[0; 3]; 3].map(|t: [u8; 3]| t.map(|_| rnd(&mut r, s)));
        let p = [rnd(&mut r, 1.0), rnd(&mut r, 1.0), rnd(&mut r, 1.0), rnd(&mut r, s)];
        let qq = [rnd(&mut r, 1.0), rnd(&mut r, 1.0), rnd(&mut r, 1.0), rnd(&mut r, s)];
        spilled += check(&tri, &p, &qq);
    }
    assert_eq!(spilled, 0);
}

#[test]
fn degenerate_and_near_degenerate_inputs_match_bignums() {
    let mut r = ChaCha8Rng::seed_from_u64(11);
    for i in 0..2000 {
        // axis planes through dyadic points (exact zeros and cancellations),
        // planes equal up to an ulp (W near zero), triangles in a plane
        let c = (r.gen_range(-8..8) as f64) / 4.0;
        let p = [1.0, 0.0, 0.0, -c];
        let mut qq = [1.0, 0.0, 0.0, -c];
        match i % 4 {
            0 => qq = [0.0, 1.0, 0.0, -c],
            1 => qq[1] = f64::EPSILON * rnd(&mut r, 1.0),
            2 => qq = [0.0, 0.0, -0.0, 0.0],
            _ => qq[0] = 1.0 + f64::EPSILON,
        }
        let z = if i % 3 == 0 { c } else { rnd(&mut r, 1.0) };
        let tri = [[c, 0.0, z], [rnd(&mut r, 1.0), c, z], [0.1, 0.3, z + f64::EPSILON * (i % 2) as f64]];
        check(&tri, &p, &qq);
    }
}

#[test]
fn window_edges_and_spills_are_safe() {
    let tiny = 2f64.powi(-100);
    let huge = 2f64.powi(100);
    let tri = [[tiny, huge, -tiny], [huge, -huge, tiny * 3.0], [-tiny * 5.0, 1.0, huge * 0.75]];
    let p = [huge, tiny, 1.0, -huge];
    let qq = [tiny, -huge, 0.5, tiny];
    check(&tri, &p, &qq);
    assert!(!expansion_window([2f64.powi(-101)]));
    assert!(!expansion_window([2f64.powi(101)]));
    assert!(expansion_window([0.0, -0.0, 1.0]));
    // a long alternating sum outgrows the components: spilled, never wrong
    let mut x = Expansion::of(0.0);
    for k in 0..60 {
        x = x.add(&Expansion::of(2f64.powi(3 * k - 90)));
    }
    assert!(x.is_spilled() || x.to_exact().is_some());
}

#[test]
fn direct_rounding_matches_bignums_on_signed_sums() {
    // Sums and products of doubles of both signs and far-apart exponents:
    // values whose top 60 bits are followed by set bits (rounded down, so
    // away from zero for negatives), exactly 60 or 61 significant bits,
    // powers of two and their neighbours.
    let mut r = ChaCha8Rng::seed_from_u64(5);
    for i in 0..20000 {
        let terms = 1 + i % 5;
        let mut x = Expansion::of(0.0);
        let mut e = Exact::zero();
        for _ in 0..terms {
            let sa = 2f64.powi(r.gen_range(-60..60));
            let a = rnd(&mut r, sa);
            let sb = 2f64.powi(r.gen_range(-20..20));
            let b = if i % 3 == 0 { 1.0 } else { rnd(&mut r, sb) };
            let b = if i % 7 == 0 { 2f64.powi(r.gen_range(-5..5)) } else { b };
            x = x.add(&Expansion::of(a).mul(&Expansion::of(b)));
            e = &e + &(&Exact::from_f64(a) * &Exact::from_f64(b));
        }
        if i % 2 == 0 {
            x = x.neg();
            e = -&e;
        }
        if x.is_spilled() {
            continue;
        }
        assert!(same(&x.to_exact().unwrap(), &e));
        assert_eq!(x.to_f64_approx().unwrap().to_bits(), e.to_f64_approx().to_bits(), "case {i}");
    }
    for v in [1.0, -1.0, 2f64.powi(61), -(2f64.powi(61)), 0.0] {
        for d in [0.0, 1.0, -1.0, 0.5, -0.5, 2f64.powi(-30)] {
            let x = Expansion::of(v).add(&Expansion::of(d));
            let e = &Exact::from_f64(v) + &Exact::from_f64(d);
            assert_eq!(x.to_f64_approx().unwrap().to_bits(), e.to_f64_approx().to_bits(), "{v} + {d}");
        }
    }
}
