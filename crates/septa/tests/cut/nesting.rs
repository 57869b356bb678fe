//! Nested shells (solid, cavity, island in the cavity, cavity in the
//! island, ...) cut by axis-aligned planes through, between and outside
//! the levels: every cell and void assigned by exact containment, the cell
//! count equal to an independent count on a fine grid, and the count
//! TopoCut reports (its void shells counted as cells of their own).

use super::shapes::{axis_planes, boxes_mesh, cut_checked, grid_cells, untouched_cavities, BoxShell};
use rand::{Rng, SeedableRng};

/// The island: the unit cube with a cubic cavity of side 0.3 in one
/// octant, holding a cube of side 0.1.
pub fn island() -> Vec<BoxShell> {
    vec![
        BoxShell { lo: [0.0; 3], hi: [1.0; 3], inward: false },
        BoxShell { lo: [0.1; 3], hi: [0.4; 3], inward: true },
        BoxShell { lo: [0.2; 3], hi: [0.3; 3], inward: false },
    ]
}

/// TopoCut's `plane -s bound_box_xyz --nx n --ny n --nz n` on the unit box.
fn unit_grid(n: usize) -> Vec<(usize, f64)> {
    (0..3).flat_map(|k| (0..n).map(move |j| (k, j as f64 / (n - 1) as f64))).collect()
}

#[test]
fn island_in_a_cavity() {
    let shells = island();
    let (v, t) = boxes_mesh(&shells);
    // TopoCut (built from its public repository): 3 cells with 2 planes per
    // axis, 10 with 3; each counts the untouched cavity as a cell
    for (n, topocut) in [(2, 3), (3, 10)] {
        let planes = unit_grid(n);
        let out = cut_checked(&v, &t, &axis_planes(&planes), &format!("island grid {n}"));
        assert_eq!(out.counts.cut_cells, grid_cells(&shells, &planes));
        assert_eq!(out.stats.voids_attached, untouched_cavities(&shells, &planes));
        assert_eq!(out.counts.cut_cells + out.stats.voids_attached, topocut);
        let total: f64 = out.cell_volumes.iter().sum();
        assert!((total - (1.0 - 0.027 + 0.001)).abs() < 1e-12, "{total}");
    }
}

/// Two cavities cut by one plane: the plane's face has two holes, both
/// bridged to the outer corner at (64, 38.25); the second bridge used to be
/// inserted at the first copy of that corner, crossing the first bridge
/// (206 intersecting triangle pairs in the written cells with two islands).
#[test]
fn two_holes_bridged_to_one_corner() {
    let shells = vec![
        BoxShell { lo: [0.0; 3], hi: [64.0; 3], inward: false },
        BoxShell { lo: [9.0, 5.0, 3.0], hi: [62.0, 31.0, 53.0], inward: true },
        BoxShell { lo: [6.0, 39.0, 19.0], hi: [62.0, 56.0, 55.0], inward: true },
        BoxShell { lo: [43.0, 42.0, 22.0], hi: [58.0, 54.0, 54.0], inward: false },
    ];
    let (v, t) = boxes_mesh(&shells);
    let planes = [(2, 38.25)];
    let out = cut_checked(&v, &t, &axis_planes(&planes), "two holes");
    assert_eq!(out.counts.cut_cells, grid_cells(&shells, &planes));
    assert_eq!(out.stats.holes, 2);
}

/// A random tree of boxes on an integer lattice: each box holds up to two
/// disjoint children, shells alternate orientation, depth at most 4.
fn random_nest(rng: &mut impl Rng) -> Vec<BoxShell> {
    let mut out = vec![BoxShell { lo: [0.0; 3], hi: [64.0; 3], inward: false }];
    let mut open = vec![(0usize, 0usize)];
    while let Some((b, depth)) = open.pop() {
        if depth >= 4 {
            continue;
        }
        let (lo, hi) = (out[b].lo, out[b].hi);
        let kids = rng.gen_range(0..=2usize);
        // children side by side along one axis, each with a margin
        let axis = rng.gen_range(0..3);
        let slots: Vec<(f64, f64)> = if kids == 2 {
            let mid = ((lo[axis] + hi[axis]) / 2.0).floor();
            vec![(lo[axis], mid), (mid, hi[axis])]
        } else {
            vec![(lo[axis], hi[axis]); kids]
        };
        for (a, z) in slots {
            let mut clo = [0.0; 3];
            let mut chi = [0.0; 3];
            let mut ok = true;
            for k in 0..3 {
                let (l, h) = if k == axis { (a, z) } else { (lo[k], hi[k]) };
                if h - l < 5.0 {
                    ok = false;
                    break;
                }
                let x0 = l + rng.gen_range(1..=((h - l) as i64 / 3).max(1)) as f64;
                let x1 = h - rng.gen_range(1..=((h - x0) as i64 / 3).max(1)) as f64;
                if x1 - x0 < 2.0 {
                    ok = false;
                    break;
                }
                clo[k] = x0;
                chi[k] = x1;
            }
            if ok {
                out.push(BoxShell { lo: clo, hi: chi, inward: depth % 2 == 0 });
                open.push((out.len() - 1, depth + 1));
            }
        }
    }
    out
}

/// Planes through a level (inside a box), between levels (in a gap, at a
/// half-integer), outside everything, and on a box face (degenerate).
fn random_planes(rng: &mut impl Rng, shells: &[BoxShell]) -> Vec<(usize, f64)> {
    let mut out: Vec<(usize, f64)> = Vec::new();
    for _ in 0..rng.gen_range(1..=7) {
        let k = rng.gen_range(0..3);
        let s = &shells[rng.gen_range(0..shells.len())];
        let x = match rng.gen_range(0..4) {
            0 => (s.lo[k] + s.hi[k]) / 2.0 + 0.25,
            1 => s.lo[k] - 0.5,
            2 => [-3.0, 70.0][rng.gen_range(0..2)],
            _ => [s.lo[k], s.hi[k]][rng.gen_range(0..2)],
        };
        if !out.contains(&(k, x)) {
            out.push((k, x));
        }
    }
    out
}

#[test]
fn random_nests_to_depth_four() {
    // 200 nests by default (under a second), 5,000 with SEPTA_FULL=1
    let cases = if std::env::var_os("SEPTA_FULL").is_some() { 5000 } else { 200 };
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(46);
    let (mut deepest, mut voids) = (0, 0);
    for case in 0..cases {
        let shells = random_nest(&mut rng);
        // TopoCut's grid planes through the whole box every fourth case
        // (bound_box_xyz: on the outer box's faces and between), else
        // planes through, between and outside the levels
        let planes = if case % 4 == 3 {
            let n = rng.gen_range(2..=5);
            (0..3).flat_map(|k| (0..n).map(move |j| (k, 64.0 * j as f64 / (n - 1) as f64))).collect()
        } else {
            random_planes(&mut rng, &shells)
        };
        let (v, t) = boxes_mesh(&shells);
        let what = format!("nest {case}: {} shells, planes {planes:?}", shells.len());
        // cut_checked: cell volumes sum to the domain's (1e-12), exact
        // positive volumes, 0 violations of the exact embedding check
        let out = cut_checked(&v, &t, &axis_planes(&planes), &what);
        assert_eq!(out.counts.cut_cells, grid_cells(&shells, &planes), "{what}");
        assert_eq!(out.stats.voids_attached, untouched_cavities(&shells, &planes), "{what}");
        voids += out.stats.voids_attached;
        deepest = deepest.max(shells.len());
    }
    // the family reaches what it is for
    assert!(deepest >= 5 && voids >= 20, "{deepest} {voids}");
}

#[test]
fn random_nests_with_oblique_planes() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4646);
    for case in 0..20 {
        let shells = random_nest(&mut rng);
        let (v, t) = boxes_mesh(&shells);
        let planes: Vec<[f64; 4]> = (0..rng.gen_range(1..=5))
            .map(|_| {
                let n: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                let s = &shells[rng.gen_range(0..shells.len())];
                let x: [f64; 3] = std::array::from_fn(|k| rng.gen_range(s.lo[k]..s.hi[k]));
                [n[0], n[1], n[2], -(n[0] * x[0] + n[1] * x[1] + n[2] * x[2])]
            })
            .collect();
        cut_checked(&v, &t, &planes, &format!("oblique nest {case}"));
    }
}

/// Found by the nest family (case 1024 with SEPTA_FULL): two cavities, one
/// with its face on the plane y = 13 (a hole of that plane's face) and one
/// crossed by it with its top face on the plane z = 53 (a notch of the same
/// face). The hole's loop came first in the plane's list and was written
/// as the face's outer boundary: its triangles overlapped the cavity's
/// (111 intersecting pairs, 23 after the repair). Now the outer loop is
/// first.
#[test]
fn a_hole_beside_a_notch() {
    let shells = vec![
        BoxShell { lo: [0.0; 3], hi: [64.0; 3], inward: false },
        BoxShell { lo: [2.0, 13.0, 11.0], hi: [22.0, 55.0, 50.0], inward: true },
        BoxShell { lo: [39.0, 11.0, 13.0], hi: [58.0, 47.0, 53.0], inward: true },
    ];
    let (v, t) = boxes_mesh(&shells);
    let planes = [(2, 53.0), (1, 13.0)];
    let out = cut_checked(&v, &t, &axis_planes(&planes), "a hole beside a notch");
    assert_eq!(out.counts.cut_cells, grid_cells(&shells, &planes));
}
