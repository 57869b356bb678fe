//! The same network.json (apart from timings) for any permutation of the
//! functions, after mapping the function ids back (invariant 2 of docs/architecture.md), with ray
//! shooting and with cell grouping, and for other block sizes.

use std::path::{Path, PathBuf};

use crate::common;

use septa::complex::Mode;
use septa::complex::NONE;
use septa::grid::{BoxGrid, Grid, Split, TetMesh};
use septa::io::read_grid_input;
use septa::network::{compute, Network, NetworkOptions};

fn data_dir() -> Option<PathBuf> {
    Some(common::shared_data().join("isn"))
}

fn load(dir: &Path, name: &str) -> (Grid, Vec<f64>, usize) {
    let input = read_grid_input(&dir.join(format!("{name}.npz"))).unwrap();
    let g = BoxGrid::new([input.grid_res.unwrap(); 3], input.bbox.unwrap(), Split::Five).unwrap();
    (Grid::Box(g), input.values, input.k)
}

fn json(net: &Network, tag: &str) -> String {
    common::network_json(net, tag)
}

/// A deterministic pseudo-random permutation of `0..k` (xorshift, Fisher-Yates).
fn permutation(k: usize, seed: u64) -> Vec<usize> {
    let mut s = seed | 1;
    let mut p: Vec<usize> = (0..k).collect();
    for i in (1..k).rev() {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        p.swap(i, (s % (i as u64 + 1)) as usize);
    }
    p
}

/// Maps the function ids of `net` (computed on the permuted functions, where
/// function `i` is original function `p[i]`) back to the original ids.
/// MI faces are oriented from the smaller material, so where the mapped pair
/// changes order the face flips: reversed polygon (rotated to its smallest
/// vertex), swapped cells, swapped half-patches in shells; shells and cells
/// are then renumbered by their smallest member again, as the library does.
fn map_back(net: &mut Network, p: &[usize]) {
    let m = |f: u16| p[f as usize] as u16;
    match net.mode {
        Mode::Ia => {
            for l in net.face_label.iter_mut() {
                *l = l.map(m);
            }
            for pa in net.patches.iter_mut() {
                pa.label = pa.label.map(m);
            }
            for c in net.cells.iter_mut() {
                let mut bits = c.label.clone();
                bits.iter_mut().for_each(|w| *w = 0);
                for (i, &o) in p.iter().enumerate() {
                    if c.label[i / 64] >> (i % 64) & 1 == 1 {
                        bits[o / 64] |= 1 << (o % 64);
                    }
                }
                c.label = bits;
            }
        }
        Mode::Mi => {
            for c in net.cells.iter_mut() {
                c.label[0] = p[c.label[0] as usize] as u64;
            }
            let mut flipped = vec![false; net.patches.len()];
            for (i, pa) in net.patches.iter_mut().enumerate() {
                let (a, b) = (m(pa.label[0]), m(pa.label[1]));
                flipped[i] = a > b;
                pa.label = [a.min(b), a.max(b)];
            }
            for f in 0..net.num_faces() {
                let [a, b] = net.face_label[f].map(m);
                net.face_label[f] = [a.min(b), a.max(b)];
                if a > b {
                    assert!(flipped[net.face_patch[f] as usize]);
                    net.face_cells[f].swap(0, 1);
                    let r = net.face_start[f] as usize..net.face_start[f + 1] as usize;
                    let vs = &mut net.face_verts[r];
                    vs.reverse();
                    let min = (0..vs.len()).min_by_key(|&j| vs[j]).unwrap();
                    vs.rotate_left(min);
                }
            }
            for s in net.shells.iter_mut() {
                for hp in s.iter_mut() {
                    if flipped[*hp as usize / 2] {
                        *hp ^= 1;
                    }
                }
                s.sort_unstable();
            }
            let mut order: Vec<usize> = (0..net.shells.len()).collect();
            order.sort_by_key(|&s| net.shells[s][0]);
            let mut snew = vec![0u32; order.len()];
            for (i, &o) in order.iter().enumerate() {
                snew[o] = i as u32;
            }
            net.shells = order.iter().map(|&o| net.shells[o].clone()).collect();
            for c in net.cells.iter_mut() {
                for s in c.shells.iter_mut() {
                    *s = snew[*s as usize];
                }
                c.shells.sort_unstable();
            }
            let mut corder: Vec<usize> = (0..net.cells.len()).collect();
            corder.sort_by_key(|&c| net.cells[c].shells.first().copied().unwrap_or(u32::MAX));
            let mut cnew = vec![0u32; corder.len()];
            for (i, &o) in corder.iter().enumerate() {
                cnew[o] = i as u32;
            }
            net.cells = corder.iter().map(|&o| net.cells[o].clone()).collect();
            for fc in net.face_cells.iter_mut() {
                *fc = fc.map(|c| if c == NONE { NONE } else { cnew[c as usize] });
            }
        }
    }
}

fn run(grid: &Grid, values: &[f64], k: usize, mode: Mode, raytrace: bool, block: usize) -> Network {
    let mut o = NetworkOptions::new(mode);
    o.block = block;
    o.raytrace = raytrace;
    compute(grid, values, k, &o).unwrap()
}

#[test]
fn permuted_functions_give_the_same_json() {
    let Some(dir) = data_dir() else { return };
    for name in ["ia4_R20", "mi4_R20", "ia18_R20", "mi18_R20", "shifted4_ia_eps1e-7_R2_s0"] {
        let mode = if name.contains("mi") { Mode::Mi } else { Mode::Ia };
        let (grid, values, k) = load(&dir, name);
        for raytrace in [true, false] {
            let base = run(&grid, &values, k, mode, raytrace, 8);
            let want = json(&base, "a");
            for seed in [1u64, 0x9e37_79b9_7f4a_7c15] {
                let p = permutation(k, seed);
                // Permuted function i is original function p[i].
                let permuted: Vec<f64> = values.chunks(k).flat_map(|r| p.iter().map(|&o| r[o])).collect();
                let mut net = run(&grid, &permuted, k, mode, raytrace, 5);
                assert_eq!(net.cells_method, base.cells_method, "{name}");
                map_back(&mut net, &p);
                let got = json(&net, "b");
                if got != want {
                    let (a, b): (Vec<&str>, Vec<&str>) = (want.lines().collect(), got.lines().collect());
                    let bad: Vec<&str> =
                        a.iter().zip(&b).filter(|(x, y)| x != y).map(|(x, _)| &x[..x.len().min(20)]).collect();
                    panic!("{name} raytrace={raytrace} permutation {p:?}: lines differ: {bad:?}");
                }
            }
        }
    }
}

/// The same on a general tet mesh (the npz tets, not a box grid): cells by
/// grouping across tet faces, blocks as ranges of tets.
#[test]
fn permuted_functions_give_the_same_json_on_a_tet_mesh() {
    let dir = data_dir().unwrap();
    for name in ["ia4_R20", "mi4_R20"] {
        let mode = if name.contains("mi") { Mode::Mi } else { Mode::Ia };
        let input = read_grid_input(&dir.join(format!("{name}.npz"))).unwrap();
        let grid = Grid::Mesh(TetMesh::new(input.vertices.clone(), &input.tets).unwrap());
        let (values, k) = (&input.values, input.k);
        let base = run(&grid, values, k, mode, true, 4096);
        assert_eq!(base.cells_method, "grouping", "{name}: a tet mesh groups cells");
        let want = json(&base, "m");
        let p = permutation(k, 7);
        let permuted: Vec<f64> = values.chunks(k).flat_map(|r| p.iter().map(|&o| r[o])).collect();
        let mut net = run(&grid, &permuted, k, mode, true, 1000);
        map_back(&mut net, &p);
        assert!(json(&net, "n") == want, "{name}: a permutation changed the tet-mesh network");
    }
}
