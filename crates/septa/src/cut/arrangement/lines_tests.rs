//! [`sort_line`] against the exact order ([`Ctx::order`]): points of a
//! plane-plane line, many of them equal (planes through common points),
//! some a hair apart, come out strictly increasing, one node per distinct
//! point, the equal ones merged.

use super::*;
use crate::cut::test_rng::tet_ctx;
use rand::{Rng, SeedableRng};

#[test]
fn line_points_sorted_and_merged_exactly() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x11e5);
    let mut merged_total = 0;
    for round in 0..30 {
        // the line of planes 0 (z = 0) and 1 (y = 0), along x; the other
        // planes cross it at a few common points (integers over 8, so the
        // points repeat exactly), a few more at points 2^-50 from them, the
        // rest at random, with random tilts
        let mut planes: Vec<[f64; 4]> = vec![[0.0, 0.0, 1.0, 0.0], [0.0, 1.0, 0.0, 0.0]];
        for _ in 0..30 {
            let at: f64 = match rng.gen_range(0..4) {
                0 | 1 => rng.gen_range(-4i32..4) as f64 / 8.0,
                2 => rng.gen_range(-4i32..4) as f64 / 8.0 + f64::powi(2.0, -50),
                _ => rng.gen_range(-0.5..0.5),
            };
            // a x + b y + c z + d = 0 through (at, 0, 0): d = -a at
            let a: f64 = [1.0, 0.5, 3.0, 0.75][rng.gen_range(0..4)];
            let (b, c) = (rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0));
            planes.push([a, b, c, -a * at]);
        }
        let c = tet_ctx(&planes);
        let dir = LineDir::PlanePlane(0, 1);
        let mut nodes = Nodes::default();
        let mut pts: Vec<u32> = (2..planes.len() as u32).map(|r| nodes.get(Def::PPP(0, 1, r))).collect();
        let all = pts.clone();
        let mut cache = HomCache::default();
        let sorted = sort_line(&c, &mut nodes, &mut pts, dir, &mut cache);
        let defs = nodes.defs.clone();
        let def = |n: u32| defs[n as usize];
        for w in sorted.windows(2) {
            assert_eq!(c.order(def(w[0]), def(w[1]), dir), Sign::Positive, "round {round}: {w:?}");
        }
        // every point is one of the sorted ones, merged into it when not it
        for &n in &all {
            let same: Vec<u32> =
                sorted.iter().copied().filter(|&s| c.order(def(s), def(n), dir) == Sign::Zero).collect();
            assert_eq!(same.len(), 1, "round {round}: point {n}");
            assert_eq!(nodes.find(n), nodes.find(same[0]), "round {round}: point {n} not merged");
            merged_total += usize::from(same[0] != n);
        }
    }
    // the rounds did meet equal points
    assert!(merged_total > 100, "{merged_total}");
}
