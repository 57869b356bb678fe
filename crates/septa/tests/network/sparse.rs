//! Sparse evaluation (docs/sparse.md) gives exactly the dense network: every
//! count, every array, and the same network.json bytes apart from timings.

use crate::common;

use std::path::Path;

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::network::{compute, Network, NetworkOptions};
use septa::network::{compute_sparse, BoundedField, SparseStats};
use septa::regions::{region_surfaces, RegionOptions};
use septa::scene::{sample_grid, Primitive, Scene};

use common::{cube_grid, spec};

fn assert_same(a: &Network, b: &Network, what: &str) {
    common::assert_same_network(a, b, what);
}

/// Dense and sparse on the same functions and grid; returns the sparse stats.
fn check(functions: &[Primitive], grid: &BoxGrid, mode: Mode, block: usize, what: &str) -> SparseStats {
    let mut o = NetworkOptions::new(mode);
    o.block = block;
    let g = Grid::Box(grid.clone());
    let values = sample_grid(functions, &g.vertices());
    let dense = compute(&g, &values, functions.len(), &o).unwrap();
    let (sparse, stats) = compute_sparse(grid, functions, &o).unwrap();
    assert_same(&dense, &sparse, what);
    eprintln!("{what}: {stats:?}");
    assert_eq!(stats.blocks, stats.skipped + stats.sampled);
    assert!(stats.active <= stats.sampled);
    stats
}

/// Every `data/specs/*.json` (IA, and MI for the `mi` ones), found by
/// listing the folder so that a new spec is covered too.
fn all_specs() -> Vec<(String, Mode)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/specs");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().to_str()?.strip_suffix(".json").map(str::to_string))
        .collect();
    names.sort();
    assert!(names.len() >= 4, "{names:?}");
    names.into_iter().map(|n| (n.clone(), if n.starts_with("mi") { Mode::Mi } else { Mode::Ia })).collect()
}

#[test]
fn reference_specs_20_and_40() {
    for (name, mode) in all_specs() {
        let name = name.as_str();
        let f = spec(name);
        for (n, block) in [(13, 4), (20, 4), (40, 8), (40, 16)] {
            let s = check(&f, &cube_grid(n), mode, block, &format!("{name}-{n}-b{block}"));
            if block < 16 && name != "ia18" {
                // Away from these spheres whole blocks are empty (ia18 fills the box).
                assert!(s.skipped > 0, "{name} {n}: {s:?}");
            }
        }
    }
}

#[test]
fn reference_specs_sample_like_the_cli() {
    // The job model's dense values (what `septa ia F.json --dense` samples)
    // must be bit-identical to the sparse path's samples of the same file.
    for name in ["ia18", "mi18", "nested8", "separate8"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/specs").join(format!("{name}.json"));
        let over = septa::job::GridOverride { resolution: Some(20), ..Default::default() };
        let job = septa::job::Job::load(path.to_str().unwrap(), &over).unwrap();
        let g = Grid::Box(cube_grid(20));
        let a = job.values();
        let b = sample_grid(&spec(name), &g.vertices());
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()) && a.len() == b.len(), "{name}");
    }
}

#[test]
fn sub_boxes_proven_empty_inside_sampled_blocks_are_not_sampled() {
    // Blocks of 16 cubes hold 4^3 sub-boxes; the bounds prove most of them
    // empty, so their vertices are not sampled and their cubes not visited
    // (`block/mask.rs`), and the network is still the dense one.
    for (name, mode) in [("ia18", Mode::Ia), ("mi18", Mode::Mi), ("nested8", Mode::Ia)] {
        let s = check(&spec(name), &cube_grid(48), mode, 16, &format!("{name}-masked"));
        let every = s.sampled * 17usize.pow(3);
        assert!(s.sampled > 0 && s.sampled_vertices < every, "{name}: {s:?}");
    }
}

#[test]
fn nested_and_separate_shells_skip_empty_blocks_between_them() {
    // Nested: three concentric shells, empty blocks between them; cells
    // are bounded by two shells each.
    let nested: Vec<Primitive> =
        [0.25, 0.55, 0.9].iter().map(|&r| Primitive::sphere([0.013, -0.007, 0.004], r)).collect();
    let s = check(&nested, &cube_grid(48), Mode::Ia, 4, "nested3");
    assert!(s.skipped > 0 && !s.dense_fallback, "{s:?}");
    // Separate: small far-apart spheres, each cell one shell; most blocks empty.
    let separate: Vec<Primitive> = [[-0.6, -0.6, -0.6], [0.6, 0.55, -0.5], [0.0, 0.61, 0.6], [0.55, -0.6, 0.5]]
        .iter()
        .map(|&c| Primitive::sphere(c, 0.23))
        .collect();
    let s = check(&separate, &cube_grid(48), Mode::Ia, 4, "separate4");
    assert!(s.skipped > s.sampled && !s.dense_fallback, "{s:?}");
    // MI: symmetric centres tie at grid vertices; the sparse path keeps
    // skipping blocks (no dense fallback) and still equals the dense path.
    let s = check(&separate, &cube_grid(48), Mode::Mi, 4, "separate4-mi-ties");
    assert!(s.skipped > 0 && !s.dense_fallback, "{s:?}");
    let generic: Vec<Primitive> =
        [[-0.61, -0.58, -0.63], [0.57, 0.53, -0.49], [0.013, 0.62, 0.59], [0.56, -0.61, 0.52]]
            .iter()
            .zip([0.21, 0.24, 0.22, 0.25])
            .map(|(&c, r)| Primitive::sphere(c, r))
            .collect();
    let s = check(&generic, &cube_grid(48), Mode::Mi, 4, "separate4-mi");
    assert!(s.skipped > 0 && !s.dense_fallback, "{s:?}");
    // No network at all: every block skipped, one cell labelled from vertex 0.
    let tiny = vec![Primitive::sphere([5.0, 5.0, 5.0], 0.5)];
    let s = check(&tiny, &cube_grid(16), Mode::Ia, 4, "empty");
    assert_eq!((s.sampled, s.skipped), (0, s.blocks));
}

#[test]
fn builtin_scenes_regions_sparse_equals_dense() {
    // Every built-in scene (sphere-with-hole and apollonius-18 among them).
    let names: Vec<String> = septa::scene::builtin::list().iter().map(|(n, _)| format!("builtin:{n}")).collect();
    assert!(
        names.iter().any(|n| n == "builtin:sphere-with-hole") && names.iter().any(|n| n == "builtin:apollonius-18")
    );
    for name in &names {
        let name = name.as_str();
        let scene = Scene::load(name).unwrap();
        let dense = region_surfaces(&scene, &RegionOptions { sparse: false, ..Default::default() }).unwrap();
        let sparse = region_surfaces(&scene, &RegionOptions::default()).unwrap();
        assert_same(&dense.network, &sparse.network, name);
        assert_eq!(dense.faces, sparse.faces, "{name}");
        assert_eq!(dense.loops, sparse.loops, "{name}");
        assert_eq!(dense.surfaces.len(), sparse.surfaces.len(), "{name}");
        assert_eq!(dense.curves.len(), sparse.curves.len(), "{name}");
        let s = sparse.sparse.unwrap();
        eprintln!("{name}: {s:?}");
        assert_eq!(s.blocks, s.skipped + s.sampled, "{name}");
    }
}

#[test]
fn builtin_scenes_ia_and_mi_at_several_resolutions() {
    // The functions of every built-in scene, as an IA and as an MI, on
    // odd and even grids over the scene's bounds: blocks whose bounds
    // touch the surfaces at different places each time.
    let (mut sparse_runs, mut fallbacks) = (0, 0);
    for (name, _) in septa::scene::builtin::list() {
        let scene = Scene::load(&format!("builtin:{name}")).unwrap();
        for n in [9, 16, 23] {
            let grid = BoxGrid::new([n; 3], scene.grid.bounds, Split::Five).unwrap();
            for mode in [Mode::Ia, Mode::Mi] {
                if mode == Mode::Mi && scene.functions.len() < 2 {
                    continue;
                }
                let what = format!("{name}-{n}-{mode:?}");
                let mut o = NetworkOptions::new(mode);
                o.block = 4;
                let g = Grid::Box(grid.clone());
                let values = sample_grid(&scene.functions, &g.vertices());
                match compute(&g, &values, scene.functions.len(), &o) {
                    Ok(_) => {
                        let s = check(&scene.functions, &grid, mode, 4, &what);
                        if s.dense_fallback {
                            fallbacks += 1;
                        } else {
                            sparse_runs += 1;
                        }
                    }
                    // Input the network rejects (a function vanishing on a
                    // whole tet): sparse must reject it the same way.
                    Err(e) => {
                        let s = compute_sparse(&grid, &scene.functions, &o).map(|_| ()).unwrap_err();
                        assert_eq!(format!("{e:?}"), format!("{s:?}"), "{what}");
                        eprintln!("{what}: both reject: {e}");
                    }
                }
            }
        }
    }
    // "sparse = dense" must not hold only because the sparse run fell back:
    // most of these runs are really sparse (the rest are planes and boxes
    // through grid vertices, whose rays run along the network).
    eprintln!("built-in scenes: {sparse_runs} sparse runs, {fallbacks} dense fallbacks");
    assert!(sparse_runs >= 3 * fallbacks && sparse_runs >= 30, "{sparse_runs} sparse, {fallbacks} fallbacks");
}

/// Two functions, the second not finite at one grid vertex: the sparse
/// path names the same vertex and function as the dense path, in both modes.
struct NanAt {
    at: [f64; 3],
}

impl BoundedField for NanAt {
    fn functions(&self) -> usize {
        2
    }
    fn value(&self, f: usize, p: [f64; 3]) -> f64 {
        match f {
            0 => p[0] - 0.1,
            _ if p == self.at => f64::NAN,
            _ => p[1] - 0.1,
        }
    }
    fn may_be_active(&self, _mode: Mode, _min: [f64; 3], _max: [f64; 3]) -> bool {
        true
    }
}

#[test]
fn a_non_finite_sample_is_named_like_the_dense_path() {
    let grid = BoxGrid::new([8; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap();
    let g = Grid::Box(grid.clone());
    let v = grid.vertex_index([5, 2, 6]);
    let field = NanAt { at: g.vertex(v) };
    for mode in [Mode::Ia, Mode::Mi] {
        let mut o = NetworkOptions::new(mode);
        o.block = 4;
        let values: Vec<f64> = g.vertices().iter().flat_map(|&p| [field.value(0, p), field.value(1, p)]).collect();
        let dense = compute(&g, &values, 2, &o).unwrap_err();
        let sparse = compute_sparse(&grid, &field, &o).unwrap_err();
        assert_eq!(format!("{dense}"), format!("{sparse}"), "{mode:?}");
        assert!(
            matches!(sparse, septa::network::NetworkError::NonFinite { vertex, function: 1, .. } if vertex == v as usize),
            "{mode:?}: {sparse}"
        );
    }
}
