//! Tests of `pair_grid`: the grid's groups (key order, sweep order, every
//! overlapping pair in the cell of its overlap's low corner).

use super::*;

use crate::cut::test_rng::lcg;

#[test]
fn groups_are_in_sweep_order_and_hold_every_overlap() {
    let mut r = lcg(11);
    let mut f = move || (r() as f64) / (1u64 << 53) as f64;
    let mut boxes: Vec<Aabb> = (0..600)
        .map(|_| {
            let c = [f(), f(), f()];
            let e = [0.05 * f(), 0.05 * f(), 0.05 * f()];
            (c, std::array::from_fn(|k| c[k] + e[k]))
        })
        .collect();
    // long and flat boxes, one point box, repeated low x
    boxes.push(([0.0, 0.1, 0.5], [1.0, 0.9, 0.5]));
    boxes.push(([0.3, 0.3, 0.3], [0.3, 0.3, 0.3]));
    boxes.push(([0.3, 0.0, 0.0], [0.4, 1.0, 1.0]));
    for fresh in [None, Some((0..boxes.len()).map(|i| i % 5 == 0).collect::<Vec<bool>>())] {
        let g = PairGrid::new(&boxes, fresh.as_deref());
        let mut keys = Vec::new();
        for &(s, e) in &g.groups {
            let run = &g.entries[s as usize..e as usize];
            assert!(run.iter().all(|q| q.0 == run[0].0));
            assert!(run.windows(2).all(|w| boxes[w[0].1 as usize].0[0] <= boxes[w[1].1 as usize].0[0]));
            keys.push(run[0].0);
        }
        assert!(keys.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(g.groups.last().map(|q| q.1 as usize), Some(g.entries.len()));
        let in_cell: rustc_hash::FxHashSet<([u32; 3], u32)> =
            g.entries.iter().map(|&(k, t)| (g.coords(k), t)).collect();
        let overlap = |a: &Aabb, b: &Aabb| (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k]);
        for a in 0..boxes.len() {
            for b in a + 1..boxes.len() {
                let wanted = fresh.as_ref().is_none_or(|f| f[a] || f[b]);
                if wanted && overlap(&boxes[a], &boxes[b]) {
                    let k: [u32; 3] = std::array::from_fn(|i| g.low_cell[a][i].max(g.low_cell[b][i]));
                    assert!(in_cell.contains(&(k, a as u32)) && in_cell.contains(&(k, b as u32)), "{a} {b}");
                }
            }
        }
    }
}
