//! The counter-clockwise order of the half-edges at a vertex of a plane's
//! graph ([`Ccw::sort`]): its stack path (a handful of directions) and its
//! vector path (more than `SMALL`) against an exact reference.

use super::*;
use crate::cut::test_rng::tet_ctx;
use rand::{Rng, SeedableRng};
use std::cmp::Ordering;

/// Counter-clockwise order about `n` of two directions, from exact
/// coordinates: the half-plane (`y > 0`, or `y = 0` and `x > 0`, first),
/// then the sign of the cross product.
fn exact_cmp(c: &Ctx, ccw: &Ccw, a: (LineDir, bool), b: (LineDir, bool)) -> Ordering {
    let (i, j) = (ccw.i, ccw.j);
    let half = |d: (LineDir, bool)| {
        let v = dir_vec::<Exact>(c, d.0, d.1);
        let (x, y) = (v[i].sign(), v[j].sign());
        u8::from(!(y == Sign::Positive || (y == Sign::Zero && x == Sign::Positive)))
    };
    let (ha, hb) = (half(a), half(b));
    if ha != hb {
        return ha.cmp(&hb);
    }
    let (u, v) = (dir_vec::<Exact>(c, a.0, a.1), dir_vec::<Exact>(c, b.0, b.1));
    match u[i].mul(&v[j]).sub(&u[j].mul(&v[i])).sign() {
        Sign::Positive => Ordering::Less,
        Sign::Negative => Ordering::Greater,
        Sign::Zero => Ordering::Equal,
    }
}

#[test]
fn directions_sort_counter_clockwise_and_stably() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x0cc3);
    for round in 0..40 {
        // plane 0 carries the directions `n_0 x n_q`; every third plane is
        // a multiple of an earlier one (the same direction, compared equal)
        let mut planes: Vec<[f64; 4]> = Vec::new();
        let n0: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        planes.push([n0[0], n0[1], n0[2], 0.0]);
        for q in 1..24 {
            let p = if q % 3 == 0 {
                let k = planes[q - 1];
                [2.0 * k[0], 2.0 * k[1], 2.0 * k[2], 0.5]
            } else {
                [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 0.0]
            };
            planes.push(p);
        }
        let c = tet_ctx(&planes);
        let ccw = Ccw::new(&n0);
        // sizes on both sides of the stack path's limit
        let n = [2, 3, 4, 7, 12, 13, 20, 46][round % 8];
        let mut items: Vec<(u32, (LineDir, bool))> = (0..n as u32)
            .map(|id| {
                let q = 1 + id / 2 % 23;
                (id, (LineDir::PlanePlane(0, q), rng.gen_bool(0.5)))
            })
            .collect();
        let before = items.clone();
        ccw.sort(&c, &mut items);
        if ccw.flip {
            items.reverse();
        }
        let mut ids: Vec<u32> = items.iter().map(|x| x.0).collect();
        ids.sort_unstable();
        assert_eq!(ids, (0..n as u32).collect::<Vec<_>>(), "a permutation");
        for w in items.windows(2) {
            match exact_cmp(&c, &ccw, w[0].1, w[1].1) {
                Ordering::Less => {}
                // equal directions keep their input order (ids are positions)
                Ordering::Equal => assert!(w[0].0 < w[1].0, "round {round}: unstable {w:?}"),
                Ordering::Greater => panic!("round {round}: out of order {w:?} (input {before:?})"),
            }
        }
    }
}
