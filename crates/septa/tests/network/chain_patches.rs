//! The cyclic order of patches around every chain (`chain_patches`, Du et
//! al. Sec. 7), also for chains lying on tet faces or tet edges (functions
//! vanishing on grid faces: planes through grid nodes), where no single
//! per-tet complex sees the whole star of a chain edge.

use std::collections::HashMap;

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::network::{compute, Network, NetworkOptions};
use septa::scene::{sample_grid, Primitive};

fn network(functions: &[Primitive], n: usize, mode: Mode, split: Split, raytrace: bool) -> Network {
    let grid = Grid::Box(BoxGrid::new([n; 3], [[-1.0; 3], [1.0; 3]], split).unwrap());
    let values = sample_grid(functions, &grid.vertices());
    let mut o = NetworkOptions::new(mode);
    o.block = 4;
    o.raytrace = raytrace;
    compute(&grid, &values, functions.len(), &o).unwrap()
}

/// Every chain lists one patch per face around its first edge, in an
/// order where consecutive faces bound a common cell (the wedge between
/// them), and the cycle closes. Returns the number of chains.
fn check(net: &Network, what: &str) -> usize {
    // Faces around every edge.
    let mut around: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    for f in 0..net.face_patch.len() {
        let vs = &net.face_verts[net.face_start[f] as usize..net.face_start[f + 1] as usize];
        for j in 0..vs.len() {
            let (a, b) = (vs[j], vs[(j + 1) % vs.len()]);
            around.entry([a.min(b), a.max(b)]).or_default().push(f);
        }
    }
    assert_eq!(net.chain_patches.len(), net.chains.len(), "{what}");
    for (c, chain) in net.chains.iter().enumerate() {
        let cyc = &net.chain_patches[c];
        let e = [chain[0].min(chain[1]), chain[0].max(chain[1])];
        let faces = &around[&e];
        assert!(faces.len() >= 3, "{what}: chain {c} has {} faces", faces.len());
        assert_eq!(cyc.len(), faces.len(), "{what}: chain {c}: patches {cyc:?} around {} faces", faces.len());
        // Same patches, with multiplicity.
        let mut want: Vec<u32> = faces.iter().map(|&f| net.face_patch[f]).collect();
        let mut got = cyc.clone();
        want.sort_unstable();
        got.sort_unstable();
        assert_eq!(got, want, "{what}: chain {c}");
        // Consecutive patches share a cell (the wedge between them).
        let cells_of = |p: u32| -> Vec<u32> {
            faces.iter().filter(|&&f| net.face_patch[f] == p).flat_map(|&f| net.face_cells[f]).collect()
        };
        for k in 0..cyc.len() {
            let (p, q) = (cyc[k], cyc[(k + 1) % cyc.len()]);
            let (a, b) = (cells_of(p), cells_of(q));
            assert!(a.iter().any(|x| b.contains(x)), "{what}: chain {c}: patches {p} and {q} share no cell");
        }
    }
    net.chains.len()
}

#[test]
fn chains_on_tet_edges_and_faces_list_their_patches() {
    let cases: Vec<(&str, Vec<Primitive>)> = vec![
        // x = 0 and y = 0: the chain x = y = 0 runs along grid edges, both
        // planes lie in tet faces.
        (
            "two grid planes",
            vec![Primitive::plane([0.0; 3], [1.0, 0.0, 0.0]), Primitive::plane([0.0; 3], [0.0, 1.0, 0.0])],
        ),
        // Three grid planes: six chains meeting at a corner on a grid node.
        (
            "three grid planes",
            vec![
                Primitive::plane([0.0; 3], [1.0, 0.0, 0.0]),
                Primitive::plane([0.0; 3], [0.0, 1.0, 0.0]),
                Primitive::plane([0.0; 3], [0.0, 0.0, 1.0]),
            ],
        ),
        // A grid plane and a diagonal plane y = z: the chain lies in the
        // plane x = 0 (tet faces), along cube-face diagonals (tet edges or
        // across tet-face interiors, depending on the cube).
        (
            "grid plane and diagonal",
            vec![Primitive::plane([0.0; 3], [1.0, 0.0, 0.0]), Primitive::plane([0.0; 3], [0.0, 1.0, -1.0])],
        ),
        // A grid plane cut by a generic sphere: chains are circles in the plane x = 0.
        (
            "grid plane and sphere",
            vec![Primitive::plane([0.0; 3], [1.0, 0.0, 0.0]), Primitive::sphere([0.013, 0.021, -0.017], 0.61)],
        ),
        // |x| touches zero on the grid plane x = 0 without changing sign:
        // two wedges around the chain x = y = 0 carry the same sign vector
        // (different cells, separated by the sheet x = 0).
        (
            "touching grid plane",
            vec![
                Primitive::Abs(Box::new(Primitive::plane([0.0; 3], [1.0, 0.0, 0.0]))),
                Primitive::plane([0.0; 3], [0.0, 1.0, 0.0]),
            ],
        ),
        // Generic: chains inside tets (the wedges of one complex).
        (
            "three spheres",
            vec![
                Primitive::sphere([0.11, 0.03, -0.07], 0.5),
                Primitive::sphere([-0.21, 0.13, 0.05], 0.45),
                Primitive::sphere([0.02, -0.23, 0.17], 0.55),
            ],
        ),
    ];
    for (name, fs) in &cases {
        for n in [4, 7, 8] {
            for split in [Split::Five, Split::Six] {
                for mode in [Mode::Ia, Mode::Mi] {
                    for raytrace in [true, false] {
                        let what = format!("{name} n={n} {split:?} {mode:?} raytrace={raytrace}");
                        let net = network(fs, n, mode, split, raytrace);
                        let chains = check(&net, &what);
                        if mode == Mode::Ia && name.contains("grid plane") && n % 2 == 0 {
                            assert!(chains > 0, "{what}: no chain");
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn material_chains_on_grid_edges_list_their_patches() {
    // Materials x, y and 0: the triple line x = y = 0 runs along grid
    // edges (the z axis), the interfaces x = 0, y = 0 lie in tet faces and
    // x = y along cube-face diagonals.
    let fs = vec![
        Primitive::plane([0.0; 3], [1.0, 0.0, 0.0]),
        Primitive::plane([0.0; 3], [0.0, 1.0, 0.0]),
        Primitive::Constant(0.0),
    ];
    for n in [4, 6, 7] {
        for split in [Split::Five, Split::Six] {
            for raytrace in [true, false] {
                let what = format!("materials x, y, 0 n={n} {split:?} raytrace={raytrace}");
                let net = network(&fs, n, Mode::Mi, split, raytrace);
                let chains = check(&net, &what);
                assert!(chains > 0 || n % 2 == 1, "{what}: no chain");
            }
        }
    }
}

#[test]
fn reference_specs_every_chain_lists_its_patches() {
    for (name, mode) in [("ia18", Mode::Ia), ("mi18", Mode::Mi), ("nested8", Mode::Ia)] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../data/specs/{name}.json"));
        let text = std::fs::read_to_string(&path).unwrap();
        let fs = septa::scene::load_function_list(&text, name, None).unwrap();
        for n in [10, 20] {
            let net = network(&fs, n, mode, Split::Five, true);
            let chains = check(&net, &format!("{name} n={n}"));
            assert!(chains > 0 || name == "nested8", "{name} {n}: no chain");
        }
    }
}
