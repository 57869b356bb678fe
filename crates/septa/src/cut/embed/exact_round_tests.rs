//! The double-word rounding of cut-vertices against the rounding of their
//! exact values: the same doubles whenever it answers.

use super::*;
use crate::cut::base::geom::Def;
use crate::cut::test_rng::tet_ctx;
use rand::{Rng, SeedableRng};

/// Every cut-vertex of random planes and the unit tetrahedron: when the
/// double-word path answers, it writes what the exact path writes; and it
/// answers for all three-plane points and nine in ten of all (the others
/// have a zero reached through rounded intermediates, or sit near a step).
#[test]
fn double_word_rounding_equals_the_exact_rounding() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x5eed);
    let (mut answered, mut total) = (0usize, 0usize);
    let (mut all_answered, mut all) = (0usize, 0usize);
    for round in 0..200 {
        let planes: Vec<[f64; 4]> = (0..6)
            .map(|k| {
                if round % 4 == 0 && k < 3 {
                    // axis planes at dyadic and decimal offsets
                    let mut p = [0.0; 4];
                    p[k] = 1.0;
                    p[3] = -[0.25, 0.1, 1.0 / 3.0][k];
                    p
                } else {
                    let n: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                    [n[0], n[1], n[2], rng.gen_range(-0.3..0.3)]
                }
            })
            .collect();
        let c = tet_ctx(&planes);
        let mut defs = Vec::new();
        for e in 0..c.edges.len() as u32 {
            for p in 0..6 {
                defs.push(Def::EP(e, p));
            }
        }
        for t in 0..c.tris.len() as u32 {
            for p in 0..6 {
                for q in p + 1..6 {
                    defs.push(Def::TPP(t, p, q));
                }
            }
        }
        for p in 0..6 {
            for q in p + 1..6 {
                for r in q + 1..6 {
                    defs.push(Def::PPP(p, q, r));
                }
            }
        }
        for d in defs {
            let want = exact_rounding_from_exact_values(&c, d);
            let ppp = matches!(d, Def::PPP(..));
            total += usize::from(ppp);
            all += 1;
            if let Some(x) = double_word_rounding(&c, d) {
                answered += usize::from(ppp);
                all_answered += 1;
                let same = want.is_some_and(|w| (0..3).all(|k| w[k].to_bits() == x[k].to_bits()));
                assert!(same, "round {round}: {d:?}: double-word {x:?}, exact {want:?}");
            }
        }
    }
    assert_eq!(answered, total, "three-plane points");
    assert!(all_answered * 10 >= all * 9, "{all_answered} of {all}");
}
