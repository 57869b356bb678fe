//! Tests of the adaptive grid: conformity, shapes, and the certified
//! network's counts against analytic topology.

use super::lattice::Lattice;
use super::*;
use crate::grid::Grid;
use crate::job::{Functions, Job};
use crate::network::NetworkOptions;

fn counts(fs: &[Primitive], mode: Mode, g: &AdaptiveGrid) -> (usize, usize, usize, usize) {
    let job = Job {
        grid: Grid::Mesh(g.tet_mesh().unwrap()),
        functions: Functions::Formulas(fs.to_vec()),
        mode: None,
        scene: None,
    };
    let (net, _) = job.run(&NetworkOptions::new(mode), true).unwrap();
    let c: std::collections::HashMap<_, _> = net.counts().into_iter().collect();
    (c["patches"], c["chains"], c["corners"], c["cells"])
}

fn unit_box() -> [[f64; 3]; 2] {
    [[-1.0; 3], [1.0; 3]]
}

fn certified(g: &AdaptiveGrid) -> bool {
    g.count(Stop::MinEdge) == 0 && g.count(Stop::Budget) == 0
}

#[test]
fn bisection_conforms_and_keeps_volume() {
    let mut l = Lattice::kuhn([2, 1, 1]);
    let mut rng = 12345u64;
    for _ in 0..10 {
        let alive: Vec<u32> = (0..l.tets.len() as u32).filter(|&t| l.alive[t as usize]).collect();
        let marked: Vec<u32> = alive
            .iter()
            .copied()
            .filter(|_| {
                rng = rng.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                rng >> 61 == 0
            })
            .collect();
        l.refine(&marked);
        assert!(l.conforms());
    }
    let vol: i128 = (0..l.tets.len())
        .filter(|&t| l.alive[t])
        .map(|t| super::lattice::orient(&l.tets[t].map(|v| l.verts[v as usize])))
        .sum();
    assert_eq!(vol, 6 * 2 * (1i128 << (3 * super::lattice::SHIFT)));
    assert!((0..l.tets.len())
        .filter(|&t| l.alive[t])
        .all(|t| super::lattice::orient(&l.tets[t].map(|v| l.verts[v as usize])) > 0));
}

#[test]
fn shapes_stay_bounded_under_deep_refinement() {
    // Refine towards one corner many times: the worst radius ratio stays at
    // that of the first few levels.
    let f = [Primitive::sphere([0.3, 0.2, 0.1], 0.003)];
    let g = refine(&f, Mode::Ia, unit_box(), &AdaptiveOptions::for_box(unit_box())).unwrap();
    // Kuhn's tet has radius ratio 0.717 (3 r_in / r_circ); longest-edge
    // bisection keeps 0.641 however deep it goes.
    let q = g.worst_radius_ratio();
    assert!(q > 0.64, "worst radius ratio {q}");
    assert!(g.edge_range().0 < 0.01);
}

#[test]
fn tiny_sphere_is_found_and_certified() {
    // Radius 1/50 of a start cell: invisible to its start grid.
    let f = [Primitive::sphere([0.1, 0.2, 0.3], 0.01)];
    let g = refine(&f, Mode::Ia, unit_box(), &AdaptiveOptions::for_box(unit_box())).unwrap();
    assert!(certified(&g));
    assert_eq!(counts(&f, Mode::Ia, &g), (1, 0, 0, 2));
}

#[test]
fn near_spheres_ia_apart_and_overlapping() {
    // 1e-3 apart: two patches, three cells; overlapping by 1e-3: four
    // patches, one chain (a small circle), four cells.
    let r = 0.3;
    let apart = [
        Primitive::sphere([-r - 0.0005 + 0.0123, 0.0111, 0.0071], r),
        Primitive::sphere([r + 0.0005 + 0.0123, 0.0111, 0.0071], r),
    ];
    let mut o = AdaptiveOptions::for_box(unit_box());
    o.tolerance = 0.01;
    let g = refine(&apart, Mode::Ia, unit_box(), &o).unwrap();
    assert!(certified(&g), "{} min-edge {} budget", g.count(Stop::MinEdge), g.count(Stop::Budget));
    assert_eq!(counts(&apart, Mode::Ia, &g), (2, 0, 0, 3));
    let over = [Primitive::sphere([-0.2872, 0.0111, 0.0071], r), Primitive::sphere([0.3218, 0.0111, 0.0071], 0.31)];
    let g = refine(&over, Mode::Ia, unit_box(), &o).unwrap();
    assert!(certified(&g));
    assert_eq!(counts(&over, Mode::Ia, &g), (4, 1, 0, 4));
}

#[test]
fn plane_through_bisection_vertices() {
    // x = 0 and y = 0.25 hold many lattice vertices; with a sphere across.
    let f = [
        Primitive::plane([0.0; 3], [1.0, 0.0, 0.0]),
        Primitive::plane([0.0, 0.25, 0.0], [0.0, 1.0, 0.0]),
        Primitive::sphere([0.0313, 0.0171, 0.0237], 0.5),
    ];
    let mut o = AdaptiveOptions::for_box(unit_box());
    o.tolerance = 0.01;
    let g = refine(&f, Mode::Ia, unit_box(), &o).unwrap();
    assert!(certified(&g));
    // The sphere in 4 patches, each plane in 4 (inside and outside, either
    // side of the other plane); chains: the planes' line in 3 pieces and 2
    // circles in 4 arcs; 4 corners; 8 cells.
    assert_eq!(counts(&f, Mode::Ia, &g), (12, 7, 4, 8));
}

fn counts_uniform(fs: &[Primitive], mode: Mode, n: usize) -> (usize, usize, usize, usize) {
    let grid = crate::grid::BoxGrid::new([n; 3], unit_box(), crate::grid::Split::Five).unwrap();
    let job = Job { grid: Grid::Box(grid), functions: Functions::Formulas(fs.to_vec()), mode: None, scene: None };
    let (net, _) = job.run(&NetworkOptions::new(mode), true).unwrap();
    let c: std::collections::HashMap<_, _> = net.counts().into_iter().collect();
    (c["patches"], c["chains"], c["corners"], c["cells"])
}

#[test]
fn mi_of_four_spheres_matches_a_fine_grid() {
    let f = [
        Primitive::sphere([-0.31, -0.2, 0.013], 0.5),
        Primitive::sphere([0.33, -0.21, 0.017], 0.45),
        Primitive::sphere([0.01, 0.37, -0.011], 0.55),
        Primitive::sphere([0.02, 0.01, 0.41], 0.4),
    ];
    let mut o = AdaptiveOptions::for_box(unit_box());
    o.tolerance = 0.02;
    let g = refine(&f, Mode::Mi, unit_box(), &o).unwrap();
    assert!(certified(&g), "{} min-edge {} budget", g.count(Stop::MinEdge), g.count(Stop::Budget));
    // 6 interfaces, 4 triple curves, 5 corners (4 where four materials or
    // three and the box meet), 4 cells: as a uniform 64^3 grid gives.
    assert_eq!(counts(&f, Mode::Mi, &g), (6, 4, 5, 4));
    assert_eq!(counts_uniform(&f, Mode::Mi, 64), (6, 4, 5, 4));
}
