//! Invariants of every output, determinism across thread counts, function
//! permutations, tet-mesh input, and exactly degenerate hand-derived cases.

use crate::common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use septa::complex::Mode;
use septa::complex::NONE;
use septa::grid::{BoxGrid, Grid, Split, TetMesh};
use septa::io::read_grid_input;
use septa::network::{compute, Network, NetworkError, NetworkOptions};
use septa::scene::{sample_grid as sample, Primitive};

fn data_dir() -> Option<PathBuf> {
    Some(common::shared_data().join("isn"))
}

fn load(dir: &Path, name: &str) -> (Grid, Vec<f64>, usize) {
    let input = read_grid_input(&dir.join(format!("{name}.npz"))).unwrap();
    let g = BoxGrid::new([input.grid_res.unwrap(); 3], input.bbox.unwrap(), Split::Five).unwrap();
    (Grid::Box(g), input.values, input.k)
}

fn run(grid: &Grid, values: &[f64], k: usize, mode: Mode, threads: usize) -> Network {
    let mut o = NetworkOptions::new(mode);
    o.block = 4;
    o.volumes = true;
    o.raytrace = false;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| compute(grid, values, k, &o)).unwrap()
}

/// Faces bound two different cells (one at the grid boundary), every shell is
/// closed away from the grid boundary with an even Euler characteristic at
/// most 2, every shell is in one cell, and cell volumes fill the grid.
fn check_invariants(net: &Network, grid: &Grid, name: &str) {
    let mut incidence: HashMap<[u32; 2], u32> = HashMap::new();
    for f in 0..net.num_faces() {
        let vs = net.face(f);
        for j in 0..vs.len() {
            let (a, b) = (vs[j], vs[(j + 1) % vs.len()]);
            *incidence.entry([a.min(b), a.max(b)]).or_default() += 1;
        }
    }
    for (f, c) in net.face_cells.iter().enumerate() {
        assert!(c[0] != c[1], "{name}: face {f} has cell {} on both sides", c[0]);
        assert!(c[0] != NONE || c[1] != NONE, "{name}: face {f} bounds no cell");
    }
    // Shell closure and Euler characteristic.
    let mut faces_of_patch: Vec<Vec<usize>> = vec![Vec::new(); net.patches.len()];
    for (f, &p) in net.face_patch.iter().enumerate() {
        faces_of_patch[p as usize].push(f);
    }
    let mut in_cell = vec![0; net.shells.len()];
    for c in &net.cells {
        for &s in &c.shells {
            in_cell[s as usize] += 1;
        }
    }
    assert!(in_cell.iter().all(|&n| n == 1), "{name}: a shell is not in exactly one cell");
    // Every side of every face in a shell faces that shell's cell.
    let mut cell_of_shell = vec![NONE; net.shells.len()];
    for (c, cell) in net.cells.iter().enumerate() {
        for &s in &cell.shells {
            cell_of_shell[s as usize] = c as u32;
        }
    }
    let mut shell_of_hp = vec![NONE; 2 * net.patches.len()];
    for (s, hps) in net.shells.iter().enumerate() {
        for &hp in hps {
            assert_eq!(shell_of_hp[hp as usize], NONE, "{name}: half-patch {hp} in two shells");
            shell_of_hp[hp as usize] = s as u32;
        }
    }
    for f in 0..net.num_faces() {
        for side in 0..2 {
            let c = net.face_cells[f][side];
            if c == NONE {
                continue;
            }
            let sh = shell_of_hp[2 * net.face_patch[f] as usize + side];
            assert_eq!(
                cell_of_shell[sh as usize], c,
                "{name}: face {f} side {side} (patch {}, shell {sh})",
                net.face_patch[f]
            );
        }
    }
    for (s, hps) in net.shells.iter().enumerate() {
        let mut edges: HashMap<[u32; 2], u32> = HashMap::new();
        let mut verts = std::collections::HashSet::new();
        let mut nf = 0i64;
        for &hp in hps {
            for &f in &faces_of_patch[hp as usize / 2] {
                nf += 1;
                let vs = net.face(f);
                for j in 0..vs.len() {
                    let (a, b) = (vs[j], vs[(j + 1) % vs.len()]);
                    *edges.entry([a.min(b), a.max(b)]).or_default() += 1;
                    verts.insert(a);
                }
            }
        }
        let mut open = false;
        for (e, &n) in &edges {
            if incidence[e] == 1 {
                open = true;
            } else {
                assert!(n % 2 == 0, "{name}: shell {s} uses edge {e:?} {n} times");
            }
        }
        if !open {
            let chi = verts.len() as i64 - edges.len() as i64 + nf;
            assert!(chi % 2 == 0 && chi <= 2, "{name}: shell {s} has Euler characteristic {chi}");
        }
    }
    let vol: f64 = net.cells.iter().map(|c| c.volume).sum();
    let want = grid.volume();
    assert!((vol - want).abs() <= 1e-9 * want, "{name}: cell volumes {vol} vs grid {want}");
}

fn json_without_seconds(net: &Network, tag: &str) -> String {
    common::network_json(net, tag)
}

#[test]
fn invariants_threads_and_permutations_on_reference_cases() {
    let Some(dir) = data_dir() else { return };
    for name in [
        "ia4_R20",
        "ia18_R20",
        "mi4_R20",
        "mi18_R20",
        "nested8_R20",
        "separate8_R20",
        "shifted4_ia_eps1e-7_R2_s0",
        "shifted4_mi_eps1e-7_R2_s0",
    ] {
        let mode = if name.contains("mi") { Mode::Mi } else { Mode::Ia };
        let (grid, values, k) = load(&dir, name);
        let one = run(&grid, &values, k, mode, 1);
        check_invariants(&one, &grid, name);
        let two = run(&grid, &values, k, mode, 2);
        assert_eq!(json_without_seconds(&one, "a"), json_without_seconds(&two, "b"), "{name}: 1 vs 2 threads");
        // Reverse the functions: same counts, same patch labels after mapping back.
        let rev: Vec<f64> = values.chunks(k).flat_map(|r| r.iter().rev().copied()).collect();
        let back = run(&grid, &rev, k, mode, 2);
        assert_eq!(one.counts(), back.counts(), "{name}: reversed functions");
        let labels = |n: &Network, map: &dyn Fn(u16) -> u16| {
            let mut l: Vec<[u16; 2]> = n
                .patches
                .iter()
                .map(|p| {
                    let (a, b) = (map(p.label[0]), map(p.label[1]));
                    [a.min(b), a.max(b)]
                })
                .collect();
            l.sort();
            l
        };
        assert_eq!(labels(&one, &|f| f), labels(&back, &|f| k as u16 - 1 - f), "{name}");
    }
}

#[test]
fn tet_mesh_input_equals_box_grid() {
    let Some(dir) = data_dir() else { return };
    let input = read_grid_input(&dir.join("mi4_R20.npz")).unwrap();
    let mesh = Grid::Mesh(TetMesh::new(input.vertices.clone(), &input.tets).unwrap());
    let (grid, values, k) = load(&dir, "mi4_R20");
    let a = run(&grid, &values, k, Mode::Mi, 2);
    let b = run(&mesh, &values, k, Mode::Mi, 2);
    assert_eq!(a.counts(), b.counts());
    check_invariants(&b, &mesh, "mi4 as a tet mesh");
}

fn box4(split: Split) -> Grid {
    Grid::Box(BoxGrid::new([4; 3], [[-1.0; 3], [1.0; 3]], split).unwrap())
}

fn counts(net: &Network) -> HashMap<&'static str, usize> {
    net.counts().into_iter().collect()
}

fn expect(net: &Network, want: &[(&str, usize)], name: &str) {
    let c = counts(net);
    for (k, v) in want {
        assert_eq!(c[k], *v, "{name}: {k} (all: {c:?})");
    }
}

fn plane(normal: [f64; 3]) -> Primitive {
    Primitive::plane([0.0; 3], normal)
}

fn sphere(center: [f64; 3], radius: f64) -> Primitive {
    Primitive::sphere(center, radius)
}

#[test]
fn two_coordinate_planes_through_grid_nodes() {
    // x = 0 and y = 0 lie on tet faces and meet along grid edges: 4 quadrant
    // cells, 4 half-plane patches, 1 chain (the z axis) with 2 corners where
    // it meets the grid boundary.
    for split in [Split::Five, Split::Six] {
        let grid = box4(split);
        let f = [plane([1.0, 0.0, 0.0]), plane([0.0, 1.0, 0.0])];
        let values = sample(&f, &grid.vertices());
        let net = run(&grid, &values, 2, Mode::Ia, 2);
        expect(
            &net,
            &[("cells", 4), ("patches", 4), ("chains", 1), ("corners", 2), ("shells", 4), ("components", 1)],
            &format!("{split:?}"),
        );
        check_invariants(&net, &grid, "two planes");
    }
}

#[test]
fn function_given_twice_and_sphere_through_grid_vertices() {
    let grid = box4(Split::Five);
    // Radius 0.5 passes through the grid vertices (+-0.5, 0, 0) etc.
    let f = [sphere([0.0; 3], 0.5), sphere([0.0; 3], 0.5)];
    let values = sample(&f, &grid.vertices());
    let once = run(&grid, &values[..].chunks(2).map(|r| r[0]).collect::<Vec<_>>(), 1, Mode::Ia, 1);
    expect(&once, &[("cells", 2), ("patches", 1), ("shells", 2), ("chains", 0), ("components", 1)], "sphere");
    check_invariants(&once, &grid, "sphere");
    let twice = run(&grid, &values, 2, Mode::Ia, 2);
    expect(&twice, &[("cells", 2), ("patches", 1), ("shells", 2), ("chains", 0), ("components", 1)], "twice");
    assert_eq!(once.num_faces(), twice.num_faces());
    check_invariants(&twice, &grid, "twice");
}

#[test]
fn spheres_tangent_at_a_grid_vertex() {
    // Touching at the origin (a grid vertex): 3 cells; the outside cell has
    // two shells (they share a point, not an edge); one network component.
    let grid = box4(Split::Five);
    let f = [sphere([-0.5, 0.0, 0.0], 0.5), sphere([0.5, 0.0, 0.0], 0.5)];
    let values = sample(&f, &grid.vertices());
    let net = run(&grid, &values, 2, Mode::Ia, 2);
    expect(&net, &[("cells", 3), ("patches", 2), ("shells", 4), ("chains", 0), ("components", 1)], "tangent");
    check_invariants(&net, &grid, "tangent");
}

#[test]
fn material_ties() {
    let grid = box4(Split::Five);
    // f0 = x, f1 = x (tied everywhere), f2 = -x: two materials meet on x = 0,
    // which lies on tet faces.
    let f = [plane([1.0, 0.0, 0.0]), plane([1.0, 0.0, 0.0]), plane([-1.0, 0.0, 0.0])];
    let values = sample(&f, &grid.vertices());
    let net = run(&grid, &values, 3, Mode::Mi, 2);
    expect(&net, &[("cells", 2), ("patches", 1), ("shells", 2), ("chains", 0)], "mi ties");
    check_invariants(&net, &grid, "mi ties");
    // Three planes through the z axis meeting at 120 degrees, tied along a grid line.
    let s = 3f64.sqrt() / 2.0;
    let f = [plane([1.0, 0.0, 0.0]), plane([-0.5, s, 0.0]), plane([-0.5, -s, 0.0])];
    let values = sample(&f, &grid.vertices());
    let net = run(&grid, &values, 3, Mode::Mi, 2);
    expect(&net, &[("cells", 3), ("patches", 3), ("chains", 1), ("corners", 2), ("shells", 3)], "mi tripod");
    check_invariants(&net, &grid, "mi tripod");
}

#[test]
fn bad_values_are_named() {
    let grid = box4(Split::Five);
    let mut values = vec![1.0; grid.num_vertices() * 2];
    values[7 * 2 + 1] = f64::NAN;
    let e = compute(&grid, &values, 2, &NetworkOptions::new(Mode::Ia)).unwrap_err();
    assert!(matches!(e, NetworkError::NonFinite { vertex: 7, function: 1, .. }), "{e}");
    let e = compute(&grid, &values[1..], 2, &NetworkOptions::new(Mode::Ia)).unwrap_err();
    assert!(matches!(e, NetworkError::ValueCount { .. }), "{e}");
}

#[test]
fn raytrace_equals_grouping() {
    let Some(dir) = data_dir() else { return };
    let expected: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    for (name, exp) in expected.as_object().unwrap() {
        let mode = if exp["mode"] == "mi" { Mode::Mi } else { Mode::Ia };
        let (grid, values, k) = load(&dir, name);
        let grouping = run(&grid, &values, k, mode, 2);
        let mut o = NetworkOptions::new(mode);
        o.block = 4; // the same blocks as `run`, hence the same shell numbering
        let ray = compute(&grid, &values, k, &o).unwrap();
        assert_eq!(ray.cells_method, "raytrace", "{name}");
        assert_eq!(grouping.cells_method, "grouping", "{name}");
        assert_eq!(ray.cells.len(), exp["cells"].as_u64().unwrap() as usize, "{name}");
        let (a, b) = (common::cell_partition(&ray), common::cell_partition(&grouping));
        if let Some(i) = (0..a.len()).find(|&i| a[i] != b[i]) {
            panic!("{name}: cell {i}: ray {:?} vs grouping {:?}", a[i], b[i]);
        }
    }
    // Network vertices at grid vertices: the same cells as grouping, and the
    // method each input must take (ray shooting handles the paper's round
    // spheres, planes lying in tet faces, nested spheres meeting at grid
    // vertices, and tangent spheres, sheets touching at a point).
    for split in [Split::Five, Split::Six] {
        let grid = box4(split);
        for (f, want) in [
            (vec![sphere([-0.5, 0.0, 0.0], 0.5), sphere([0.5, 0.0, 0.0], 0.5)], ["raytrace"; 2]),
            (vec![plane([1.0, 0.0, 0.0]), plane([0.0, 1.0, 0.0]), plane([0.0, 0.0, 1.0])], ["raytrace"; 2]),
            (vec![sphere([0.0; 3], 0.5), sphere([0.0; 3], 0.75), sphere([0.5, 0.5, 0.0], 0.25)], ["raytrace"; 2]),
            (
                vec![
                    sphere([0.0; 3], 0.5),
                    sphere([0.5, 0.0, 0.0], 0.5),
                    sphere([0.0, 0.5, 0.0], 0.5),
                    sphere([0.0, 0.0, 0.5], 0.5),
                ],
                ["raytrace"; 2],
            ),
        ] {
            let values = sample(&f, &grid.vertices());
            assert!(values.iter().any(|&x| x == 0.0), "{split:?} {f:?}: no value exactly 0");
            let grouping = run(&grid, &values, f.len(), Mode::Ia, 1);
            let mut o = NetworkOptions::new(Mode::Ia);
            o.block = 4;
            let ray = compute(&grid, &values, f.len(), &o).unwrap();
            let want = want[(split == Split::Six) as usize];
            assert_eq!(ray.cells_method, want, "{split:?} {f:?}");
            assert_eq!(grouping.cells_method, "grouping", "{split:?} {f:?}");
            assert_eq!(common::cell_partition(&ray), common::cell_partition(&grouping), "{split:?} {f:?}");
        }
    }
    // A tet mesh: grouping.
    let input = read_grid_input(&dir.join("mi4_R20.npz")).unwrap();
    let mesh = Grid::Mesh(TetMesh::new(input.vertices.clone(), &input.tets).unwrap());
    let net = compute(&mesh, &input.values, input.k, &NetworkOptions::new(Mode::Mi)).unwrap();
    assert_eq!(net.cells_method, "grouping");
}

#[test]
fn nested_spheres_off_grid_raytrace() {
    // Nested spheres not through grid vertices, on a 6-split grid: rays cross
    // empty blocks between shells.
    let grid = Grid::Box(BoxGrid::new([13, 11, 12], [[-1.0; 3], [1.0; 3]], Split::Six).unwrap());
    let f = [
        sphere([0.01, 0.02, 0.03], 0.83),
        sphere([0.013, 0.021, 0.029], 0.51),
        sphere([0.15, 0.16, 0.14], 0.2),
        sphere([-0.61, -0.6, -0.62], 0.21),
    ];
    let values = sample(&f, &grid.vertices());
    let grouping = run(&grid, &values, 4, Mode::Ia, 2);
    check_invariants(&grouping, &grid, "nested");
    let mut o = NetworkOptions::new(Mode::Ia);
    o.block = 4;
    let ray = compute(&grid, &values, 4, &o).unwrap();
    assert_eq!(ray.cells_method, "raytrace");
    expect(&ray, &[("cells", 5), ("shells", 8), ("patches", 4), ("components", 4)], "nested");
    assert_eq!(common::cell_partition(&ray), common::cell_partition(&grouping));
}

/// Spheres in the pattern of Du et al. Sec. 8.3 (IA: unit spheres at the
/// origin, on the axes and at cube corners), jittered by up to 1e-3 from a seed.
fn paper_spheres(k: usize, seed: u64) -> Vec<Primitive> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let centres = [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]];
    (0..k)
        .map(|i| {
            let c: [f64; 3] = centres[i % 4];
            let mut j = || rng.gen_range(-1e-3..1e-3);
            Primitive::sphere([c[0] + j(), c[1] + j(), c[2] + j()], 0.5 + j())
        })
        .collect()
}

#[test]
fn paper_pattern_with_other_jitter() {
    // The 4-sphere IA pattern with a different jitter has the reference's
    // combinatorics (ia4_R20: 32 patches, 24 chains, 8 corners, 16 cells).
    let f = paper_spheres(4, 7);
    let grid = Grid::Box(BoxGrid::new([20; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap());
    let values = sample(&f, &grid.vertices());
    let net = compute(&grid, &values, 4, &NetworkOptions::new(Mode::Ia)).unwrap();
    expect(
        &net,
        &[("patches", 32), ("chains", 24), ("corners", 8), ("shells", 16), ("cells", 16), ("components", 1)],
        "paper 4",
    );
}

#[test]
fn three_coordinate_planes_through_grid_nodes() {
    // Octants: 8 cells, 12 quarter-plane patches, 6 half-axis chains, and
    // 7 corners (the centre, where 6 chains meet, and 6 on the boundary).
    for split in [Split::Five, Split::Six] {
        let grid = box4(split);
        let f = [plane([1.0, 0.0, 0.0]), plane([0.0, 1.0, 0.0]), plane([0.0, 0.0, 1.0])];
        let values = sample(&f, &grid.vertices());
        let net = run(&grid, &values, 3, Mode::Ia, 2);
        expect(
            &net,
            &[("cells", 8), ("patches", 12), ("chains", 6), ("corners", 7), ("shells", 8), ("components", 1)],
            &format!("{split:?}"),
        );
        check_invariants(&net, &grid, "octants");
        // The same planes off the grid nodes: the generic case, by ray shooting.
        let f = [
            Primitive::plane([0.013, 0.0, 0.0], [1.0, 0.0, 0.0]),
            Primitive::plane([0.0, 0.021, 0.0], [0.0, 1.0, 0.0]),
            Primitive::plane([0.0, 0.0, -0.017], [0.0, 0.0, 1.0]),
        ];
        let values = sample(&f, &grid.vertices());
        let net = compute(&grid, &values, 3, &NetworkOptions::new(Mode::Ia)).unwrap();
        assert_eq!(net.cells_method, "raytrace");
        expect(
            &net,
            &[("cells", 8), ("patches", 12), ("chains", 6), ("corners", 7), ("shells", 8), ("components", 1)],
            "off-grid octants",
        );
    }
}

#[test]
fn no_network_is_one_labelled_cell() {
    let grid = box4(Split::Five);
    let f = [sphere([5.0; 3], 0.5), sphere([0.0; 3], 9.0)];
    let values = sample(&f, &grid.vertices());
    for raytrace in [true, false] {
        let mut o = NetworkOptions::new(Mode::Ia);
        o.raytrace = raytrace;
        let net = compute(&grid, &values, 2, &o).unwrap();
        expect(&net, &[("cells", 1), ("faces", 0), ("shells", 0), ("patches", 0)], "empty");
        assert_eq!(net.cells[0].label.to_vec(), vec![2u64], "f0 < 0, f1 > 0");
        let net = compute(&grid, &values, 2, &NetworkOptions::new(Mode::Mi)).unwrap();
        assert_eq!(net.cells[0].label.to_vec(), vec![1u64], "material 1 wins everywhere");
    }
}

#[test]
fn cyclic_order_of_patches_around_chains() {
    let Some(dir) = data_dir() else { return };
    // IA: two surfaces cross at a chain, 4 patches alternate between them;
    // MI: 3 materials meet, 3 interface patches.
    for (name, mode, around) in [("ia4_R20", Mode::Ia, 4), ("ia18_R20", Mode::Ia, 4), ("mi18_R20", Mode::Mi, 3)] {
        let (grid, values, k) = load(&dir, name);
        let net = run(&grid, &values, k, mode, 2);
        let known: Vec<&Vec<u32>> = net.chain_patches.iter().filter(|c| !c.is_empty()).collect();
        assert!(
            known.len() * 10 >= net.chains.len() * 9,
            "{name}: {} of {} chains ordered",
            known.len(),
            net.chains.len()
        );
        for c in known {
            assert_eq!(c.len(), around, "{name}: {c:?}");
            let mut sorted = c.clone();
            sorted.sort();
            sorted.dedup();
            assert_eq!(sorted.len(), around, "{name}: a patch twice around a chain: {c:?}");
            for i in 0..c.len() {
                let (p, q) = (&net.patches[c[i] as usize], &net.patches[c[(i + 1) % c.len()] as usize]);
                if mode == Mode::Ia {
                    assert_ne!(p.label, q.label, "{name}: neighbours around a chain on one surface: {c:?}");
                } else {
                    // Consecutive MI interfaces share the material of the cell between them.
                    assert!(p.label.iter().any(|m| q.label.contains(m)), "{name}: {c:?}");
                }
            }
        }
    }
}

#[test]
fn raytrace_equals_grouping_on_many_components() {
    // 27 separate spheres: more network components than ray shooting
    // answers by scanning the faces (`raytrace::SCANS`), so its
    // vertex-to-face index is built and used too.
    let grid = Grid::Box(BoxGrid::new([24; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap());
    let at = [-0.62, 0.03, 0.64];
    let mut f: Vec<Primitive> = Vec::new();
    for x in at {
        for y in at {
            for z in at {
                f.push(sphere([x, y, z], 0.17));
            }
        }
    }
    let values = sample(&f, &grid.vertices());
    let grouping = run(&grid, &values, f.len(), Mode::Ia, 2);
    let mut o = NetworkOptions::new(Mode::Ia);
    o.block = 4;
    let ray = compute(&grid, &values, f.len(), &o).unwrap();
    assert_eq!(ray.cells_method, "raytrace");
    assert_eq!(grouping.cells_method, "grouping");
    let c = counts(&ray);
    assert!(c["components"] > 20, "{c:?}");
    assert_eq!(c["cells"], 28, "{c:?}");
    assert_eq!(common::cell_partition(&ray), common::cell_partition(&grouping));
}
