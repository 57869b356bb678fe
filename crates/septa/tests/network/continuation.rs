//! Continuation (Bloomenthal 4.5.1, docs/sparse.md) gives exactly the dense
//! network when the seeds reach every component, and (by design) misses a
//! separate component that no seed reaches.

use crate::common;

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid};
use septa::network::{compute, Network, NetworkError, NetworkOptions};
use septa::network::{compute_continuation, Field, Seeds};
use septa::scene::Primitives;
use septa::scene::{sample_grid, Primitive};

use common::{cube_grid, spec};

fn assert_same(a: &Network, b: &Network, what: &str) {
    common::assert_same_network(a, b, what);
}

fn dense(f: &[Primitive], grid: &BoxGrid, o: &NetworkOptions) -> Network {
    let g = Grid::Box(grid.clone());
    compute(&g, &sample_grid(f, &g.vertices()), f.len(), o).unwrap()
}

#[test]
fn coarse_scan_seeds_reach_everything_on_reference_specs() {
    for (name, mode) in [("ia18", Mode::Ia), ("mi18", Mode::Mi), ("nested8", Mode::Ia), ("separate8", Mode::Ia)] {
        let f = spec(name);
        let grid = cube_grid(20);
        let mut o = NetworkOptions::new(mode);
        o.block = 4;
        let (net, stats) = compute_continuation(&grid, &Primitives(&f), Seeds::CoarseScan, &o).unwrap();
        assert_same(&net, &dense(&f, &grid, &o), name);
        assert!(!stats.blocks.dense_fallback && stats.seeds > 0 && stats.rounds > 0, "{name}: {stats:?}");
        assert_eq!(stats.blocks.sampled + stats.blocks.skipped, 125);
        eprintln!("{name}: {stats:?}");
    }
}

/// Four small, far-apart spheres (generic centres: no ties, no zeros).
fn separate() -> Vec<Primitive> {
    [[-0.61, -0.58, -0.63], [0.57, 0.53, -0.49], [0.013, 0.62, 0.59], [0.56, -0.61, 0.52]]
        .iter()
        .zip([0.21, 0.24, 0.22, 0.25])
        .map(|(&c, r)| Primitive::sphere(c, r))
        .collect()
}

#[test]
fn an_unseeded_separate_component_is_missed_by_design() {
    let f = separate();
    let grid = cube_grid(32);
    let mut o = NetworkOptions::new(Mode::Ia);
    o.block = 4;
    let full = dense(&f, &grid, &o);
    assert_eq!(full.components, 4);
    let centres = [[-0.61, -0.58, -0.63], [0.57, 0.53, -0.49], [0.013, 0.62, 0.59], [0.56, -0.61, 0.52]];
    // Seeds on all four spheres: the dense network exactly, most blocks never visited.
    let (net, stats) = compute_continuation(&grid, &Primitives(&f), Seeds::Points(&centres), &o).unwrap();
    assert_same(&net, &full, "all seeded");
    assert!(stats.blocks.skipped > stats.blocks.sampled, "{stats:?}");
    // No seed on sphere 3: its surface is missing, the rest is the same surface.
    let (net, stats) = compute_continuation(&grid, &Primitives(&f), Seeds::Points(&centres[..3]), &o).unwrap();
    assert_eq!(stats.seeds, 3);
    assert_eq!(net.components, 3);
    assert!(net.face_label.iter().all(|l| l[0] != 3));
    let kept = |n: &Network| -> Vec<Vec<[u64; 3]>> {
        let mut faces: Vec<Vec<[u64; 3]>> = (0..n.num_faces())
            .filter(|&i| n.face_label[i][0] != 3)
            .map(|i| n.face(i).iter().map(|&v| n.points[v as usize].map(f64::to_bits)).collect())
            .collect();
        faces.sort();
        faces
    };
    assert_eq!(kept(&net), kept(&full), "the reached spheres' polygons");
    assert_eq!(net.patches.len(), full.patches.len() - 1);
}

struct Bad(usize);

impl Field for Bad {
    fn functions(&self) -> usize {
        1
    }
    fn eval(&self, points: &[[f64; 3]], out: &mut Vec<f64>) -> Result<(), String> {
        match self.0 {
            0 => out.extend(points.iter().map(|p| if p[0] > 0.5 { f64::NAN } else { 0.3 - p[0].abs() })),
            1 => out.push(1.0),
            _ => return Err("user function raised".into()),
        }
        Ok(())
    }
}

#[test]
fn bad_fields_and_seeds_are_typed_errors() {
    let grid = cube_grid(8);
    let mut o = NetworkOptions::new(Mode::Ia);
    o.block = 4;
    let e = compute_continuation(&grid, &Bad(0), Seeds::CoarseScan, &o).unwrap_err();
    assert!(matches!(e, NetworkError::NonFinite { function: 0, .. }), "{e}");
    let e = compute_continuation(&grid, &Bad(1), Seeds::CoarseScan, &o).unwrap_err();
    assert!(e.to_string().contains("returned 1 values"), "{e}");
    let e = compute_continuation(&grid, &Bad(2), Seeds::CoarseScan, &o).unwrap_err();
    assert_eq!(e, NetworkError::FieldFailed("user function raised".into()));
    let f = separate();
    let e = compute_continuation(&grid, &Primitives(&f), Seeds::Points(&[[0.0, 2.0, 0.0]]), &o).unwrap_err();
    assert!(matches!(e, NetworkError::SeedOutside { seed: 0, point: [0.0, 2.0, 0.0] }), "{e}");
    assert!(e.to_string().contains("seed point 0"), "{e}");
}

#[test]
fn one_seed_grows_over_a_connected_network() {
    // Two spheres cut by a plane: one connected network; one
    // seed point on it, the search visits every block it meets.
    let f = vec![
        Primitive::sphere([0.013, -0.007, 0.004], 0.61),
        Primitive::plane([0.0123, 0.0271, 0.0339], [0.31, 0.52, 0.83]),
        Primitive::sphere([0.4113, 0.3687, -0.2209], 0.3317),
    ];
    for (mode, block) in [(Mode::Ia, 4), (Mode::Mi, 5)] {
        let grid = cube_grid(40);
        let mut o = NetworkOptions::new(mode);
        o.block = block;
        let full = dense(&f, &grid, &o);
        assert_eq!(full.components, 1, "{mode:?}");
        let seed = [[0.013 + 0.61, -0.007, 0.004]];
        let (net, stats) = compute_continuation(&grid, &Primitives(&f), Seeds::Points(&seed), &o).unwrap();
        assert_same(&net, &full, &format!("{mode:?} one seed"));
        assert!(stats.seeds == 1 && stats.rounds > 5 && stats.blocks.skipped > 0, "{mode:?} {stats:?}");
        eprintln!("{mode:?}: {stats:?}");
    }
}
