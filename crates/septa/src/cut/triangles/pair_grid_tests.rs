//! Tests of `pair_grid`: the grid's groups (key order, sweep order, every
//! overlapping pair in the cell of its overlap's low corner).

use super::*;

use crate::cut::test_rng::lcg;

/// Boxes of sizes up to `size` at random, and with `long` a few long,
/// flat, point-like ones.
fn boxes(size: f64, long: bool) -> Vec<Aabb> {
    let mut r = lcg(11);
    let mut f = move || (r() as f64) / (1u64 << 53) as f64;
    let mut boxes: Vec<Aabb> = (0..600)
        .map(|_| {
            let c = [f(), f(), f()];
            let e = [size * f(), size * f(), size * f()];
            (c, std::array::from_fn(|k| c[k] + e[k]))
        })
        .collect();
    if !long {
        return boxes;
    }
    // long and flat boxes, one point box, repeated low x
    boxes.push(([0.0, 0.1, 0.5], [1.0, 0.9, 0.5]));
    boxes.push(([0.3, 0.3, 0.3], [0.3, 0.3, 0.3]));
    boxes.push(([0.3, 0.0, 0.0], [0.4, 1.0, 1.0]));
    boxes
}

/// Boxes of about the grid's cell size fill one counter per cell; tiny
/// scattered boxes make a fine grid of mostly empty cells, grouped by
/// sorting (key, box) pairs instead.
#[test]
fn groups_are_in_sweep_order_and_hold_every_overlap() {
    for (size, long, dense) in [(0.05, true, true), (1e-4, false, false)] {
        groups_hold_every_overlap(&boxes(size, long), dense);
    }
}

fn groups_hold_every_overlap(boxes: &[Aabb], dense: bool) {
    for fresh in [None, Some((0..boxes.len()).map(|i| i % 5 == 0).collect::<Vec<bool>>())] {
        let g = PairGrid::new(boxes, fresh.as_deref());
        assert_eq!(g.dense, dense);
        let mut keys = Vec::new();
        let mut in_cell: rustc_hash::FxHashSet<([u32; 3], u32)> = Default::default();
        let mut end = 0;
        for &(k, s, e) in &g.groups {
            assert!(s == end && s < e, "groups cover the boxes' entries one after the other, none empty");
            end = e;
            let run = &g.ids[s as usize..e as usize];
            assert!(run.windows(2).all(|w| boxes[w[0] as usize].0[0] <= boxes[w[1] as usize].0[0]));
            keys.push(k);
            in_cell.extend(run.iter().map(|&t| (g.coords(k), t)));
        }
        assert!(keys.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(end as usize, g.ids.len());
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
