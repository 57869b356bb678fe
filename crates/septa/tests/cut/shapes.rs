//! Test inputs built from axis-aligned boxes (nested shells, boxes touching
//! at an edge or a corner) and an independent count of their cut-cells on a
//! fine rectilinear grid, for axis-aligned planes.

use septa::cut::{cut_mesh, CutCellMesh, CutOptions};

/// A closed box shell: outward (`inward = false`) or facing in (a cavity).
pub struct BoxShell {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
    pub inward: bool,
}

/// The triangles of box shells in one mesh; equal corners are one vertex
/// (boxes sharing an edge or a corner then share its vertices).
pub fn boxes_mesh(shells: &[BoxShell]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut verts: Vec<[f64; 3]> = Vec::new();
    let mut tris = Vec::new();
    let id = |p: [f64; 3], verts: &mut Vec<[f64; 3]>| -> u32 {
        match verts.iter().position(|q| *q == p) {
            Some(i) => i as u32,
            None => {
                verts.push(p);
                verts.len() as u32 - 1
            }
        }
    };
    // corner i has coordinate k at hi when bit k is set; quads outward
    const QUADS: [[usize; 4]; 6] = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    for s in shells {
        let c: Vec<u32> = (0..8)
            .map(|i| id(std::array::from_fn(|k| if (i >> k) & 1 == 1 { s.hi[k] } else { s.lo[k] }), &mut verts))
            .collect();
        for q in QUADS {
            for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
                let t = t.map(|i| c[i]);
                tris.push(if s.inward { [t[0], t[2], t[1]] } else { t });
            }
        }
    }
    (verts, tris)
}

/// Axis-aligned planes `x_axis = value`.
pub fn axis_planes(planes: &[(usize, f64)]) -> Vec<[f64; 4]> {
    planes
        .iter()
        .map(|&(a, x)| {
            let mut p = [0.0; 4];
            p[a] = 1.0;
            p[3] = -x;
            p
        })
        .collect()
}

/// Cut-cells of the domain of box shells (inside where an odd number of
/// boxes contain the point) cut by axis-aligned planes, counted on the grid
/// of every box and plane coordinate: fine boxes inside the domain joined
/// across each shared face that no plane holds. Independent of the cut.
pub fn grid_cells(shells: &[BoxShell], planes: &[(usize, f64)]) -> usize {
    let coords: Vec<Vec<f64>> = (0..3)
        .map(|k| {
            let mut c: Vec<f64> = shells.iter().flat_map(|s| [s.lo[k], s.hi[k]]).collect();
            c.extend(planes.iter().filter(|p| p.0 == k).map(|p| p.1));
            c.sort_by(f64::total_cmp);
            c.dedup();
            c
        })
        .collect();
    let n: Vec<usize> = coords.iter().map(|c| c.len() - 1).collect();
    let idx = |i: [usize; 3]| (i[2] * n[1] + i[1]) * n[0] + i[0];
    let inside = |i: [usize; 3]| {
        let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (coords[k][i[k]] + coords[k][i[k] + 1]));
        shells.iter().filter(|s| (0..3).all(|k| s.lo[k] < mid[k] && mid[k] < s.hi[k])).count() % 2 == 1
    };
    let total = n[0] * n[1] * n[2];
    let mut parent: Vec<usize> = (0..total).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut ins = vec![false; total];
    for z in 0..n[2] {
        for y in 0..n[1] {
            for x in 0..n[0] {
                ins[idx([x, y, z])] = inside([x, y, z]);
            }
        }
    }
    for z in 0..n[2] {
        for y in 0..n[1] {
            for x in 0..n[0] {
                let i = [x, y, z];
                if !ins[idx(i)] {
                    continue;
                }
                for k in 0..3 {
                    if i[k] + 1 >= n[k] {
                        continue;
                    }
                    let mut j = i;
                    j[k] += 1;
                    let wall = coords[k][j[k]];
                    if !ins[idx(j)] || planes.iter().any(|p| p.0 == k && p.1 == wall) {
                        continue;
                    }
                    let (a, b) = (find(&mut parent, idx(i)), find(&mut parent, idx(j)));
                    parent[a] = b;
                }
            }
        }
    }
    (0..total).filter(|&i| ins[i] && find(&mut parent, i) == i).count()
}

/// Cavities no plane meets (closed box test): TopoCut counts each as a
/// cell of its own; Septa attaches it to its enclosing cell.
pub fn untouched_cavities(shells: &[BoxShell], planes: &[(usize, f64)]) -> usize {
    shells.iter().filter(|s| s.inward && !planes.iter().any(|&(k, x)| s.lo[k] <= x && x <= s.hi[k])).count()
}

/// Cuts and checks what every valid cut must satisfy: the internal checks
/// (faces bound one or two cells, exact positive volumes summing to the
/// domain's), no unresolved void, and the exact check of the embedding.
pub fn cut_checked(v: &[[f64; 3]], t: &[[u32; 3]], planes: &[[f64; 4]], what: &str) -> CutCellMesh {
    let out = cut_mesh(v, t, planes, &CutOptions::default()).unwrap_or_else(|e| panic!("{what}: {e}"));
    let check = out.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(check.volume_relative_error < 1e-12, "{what}: {check:?}");
    assert_eq!(out.stats.voids_unresolved, 0, "{what}");
    let r = out.verify();
    assert_eq!(r.violations(), 0, "{what}: {:?}", r.examples);
    if let Some(e) = &out.stats.embedding {
        assert_eq!(e.report.violations(), 0, "{what}");
    }
    out
}
