//! Volumes, areas and lengths (`septa::measure`): against exact values where
//! the surfaces are planes the grid reproduces, within the discretisation
//! error where they are curved, against voxel counts for label volumes, and
//! summing to the domain always (cells reaching the grid's boundary too).

use septa::io::{diagonal_affine, place_surfaces};
use septa::regions::{label_surfaces, region_surfaces, RegionOptions, RegionSurfaces};
use septa::scene::Scene;

fn volumes(r: &RegionSurfaces) -> Vec<(i64, f64)> {
    r.region_ids().into_iter().zip(r.measures.cell_volume.iter().copied()).collect()
}

fn total(r: &RegionSurfaces) -> f64 {
    r.measures.cell_volume.iter().sum()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

fn scene(json: &str) -> RegionSurfaces {
    let s = Scene::from_json(json, "<test>", None).unwrap();
    region_surfaces(&s, &RegionOptions::default()).unwrap()
}

#[test]
fn sphere_in_a_box_within_the_discretisation_error() {
    // A sphere of radius 0.6 in [-1, 1]^3: the polygons are chords of the
    // sphere, so the volume is below 4/3 pi r^3 by O(h^2); the outside
    // reaches the whole box boundary and gets the rest.
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.6f64.powi(3);
    let mut errors = Vec::new();
    for n in [17, 33] {
        let r = scene(&format!(
            r#"{{"grid": {{"resolution": {n}, "bounds": [[-1,-1,-1],[1,1,1]]}},
                "functions": [{{"name": "ball", "type": "sphere", "center": [0.013, -0.021, 0.007], "radius": 0.6}}],
                "solid": "ball"}}"#
        ));
        let v = volumes(&r);
        assert_eq!(v.iter().map(|x| x.0).collect::<Vec<_>>(), vec![0, 1]);
        let (outside, inside) = (v[0].1, v[1].1);
        let h = 2.0 / n as f64;
        // Chords of a circle of radius 0.6 at spacing h miss at most
        // h^2 / (8 r) of depth: a crude bound on the volume lost.
        let bound = 4.0 * std::f64::consts::PI * 0.36 * h * h / (8.0 * 0.6) * 2.0;
        assert!(inside < exact && exact - inside < bound, "n = {n}: {inside} vs {exact} (bound {bound})");
        assert!(close(inside + outside, 8.0, 1e-12), "sum {}", inside + outside);
        // The one surface's area is that of a sphere within O(h^2) too.
        let area = r.measures.patch_area[0];
        assert!((area - 4.0 * std::f64::consts::PI * 0.36).abs() < 0.05, "area {area}");
        errors.push(exact - inside);
    }
    // Second order: doubling the resolution divides the error by about 4.
    assert!(errors[1] < errors[0] / 2.5, "{errors:?}");
}

#[test]
fn cad_part_solid_and_box_minus_cylinder() {
    let r = region_surfaces(&Scene::load("builtin:box-minus-cylinder").unwrap(), &RegionOptions::default()).unwrap();
    let v = volumes(&r);
    let exact = septa::scene::builtin::box_minus_cylinder_volume();
    assert!((v[1].1 - exact).abs() < 0.003, "{} vs {exact}", v[1].1);
    assert!(close(total(&r), 8.0, 1e-12));
    // The box's 12 edges have length 1 and its curves are all measured.
    assert_eq!(r.measures.chain_length.len(), r.curves.len());
    assert_eq!(r.measures.chain_length.iter().filter(|&&l| (l - 1.0).abs() < 1e-12).count(), 12);
}

/// Two labels split by a voxel plane: the surface lies halfway between
/// voxel centres (the grid spans the voxel centres), so both volumes are
/// exact, the far one made almost wholly of its footprints on the box.
#[test]
fn two_labels_split_by_a_plane_are_exact() {
    let (nx, ny, nz) = (9usize, 7usize, 8usize);
    for axis in 0..3 {
        let mut labels = vec![0i64; nx * ny * nz];
        for i in 0..nx {
            for j in 0..ny {
                for k in 0..nz {
                    labels[(i * ny + j) * nz + k] = 5 + ([i, j, k][axis] >= 3) as i64;
                }
            }
        }
        let r = label_surfaces(&labels, [nx, ny, nz], 0.0).unwrap();
        let n = [nx, ny, nz];
        let cross_section: f64 = (0..3).filter(|&a| a != axis).map(|a| (n[a] - 1) as f64).product();
        let want = [2.5 * cross_section, ((n[axis] - 1) as f64 - 2.5) * cross_section];
        let got: Vec<f64> = volumes(&r).iter().map(|x| x.1).collect();
        assert!(close(got[0], want[0], 1e-12) && close(got[1], want[1], 1e-12), "axis {axis}: {got:?} vs {want:?}");
    }
}

/// Labels that split the volume at a voxel plane on every axis: 8 octant
/// labels, each reaching the boundary on three faces (the far ones on far
/// faces and edges, one on the far corner). Away from the lines where
/// three labels meet the surfaces are those planes; along them the
/// material interface of the interpolated indicators bends within a voxel.
#[test]
fn octant_labels_touching_the_boundary() {
    let (nx, ny, nz) = (9usize, 7usize, 8usize);
    let (kx, ky, kz) = (4usize, 3usize, 5usize);
    let mut labels = vec![0i64; nx * ny * nz];
    for i in 0..nx {
        for j in 0..ny {
            for k in 0..nz {
                labels[(i * ny + j) * nz + k] = 1 + (i >= kx) as i64 + 2 * (j >= ky) as i64 + 4 * (k >= kz) as i64;
            }
        }
    }
    let r = label_surfaces(&labels, [nx, ny, nz], 0.0).unwrap();
    let side = |k: usize, n: usize, hi: bool| if hi { (n - 1) as f64 - (k as f64 - 0.5) } else { k as f64 - 0.5 };
    for (l, v) in volumes(&r) {
        let b = l - 1;
        let want = side(kx, nx, b & 1 != 0) * side(ky, ny, b & 2 != 0) * side(kz, nz, b & 4 != 0);
        // The junction lines bend the surfaces within a voxel of them.
        assert!((v - want).abs() < 0.2, "label {l}: {v} vs {want}");
    }
    assert!(close(total(&r), ((nx - 1) * (ny - 1) * (nz - 1)) as f64, 1e-12));
    // Placed by a map that mirrors and stretches: volumes scale by |det|.
    let before = volumes(&r);
    let mut placed = r.clone();
    place_surfaces(&mut placed, &diagonal_affine([-0.5, 2.0, 1.5], [3.0, -1.0, 0.0])).unwrap();
    for ((l, a), (_, b)) in before.iter().zip(volumes(&placed)) {
        assert!(close(b, a * 1.5, 1e-12), "label {l}: {b} vs {}", a * 1.5);
    }
}

/// A smooth label volume (nested balls cut by a slab, some reaching the
/// boundary): each label's volume within 1% of its voxel count.
#[test]
fn smooth_label_volumes_match_voxel_counts() {
    let n = 40usize;
    let mut labels = vec![0i64; n * n * n];
    let c = [19.3, 20.1, 18.7];
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let d = ((i as f64 - c[0]).powi(2) + (j as f64 - c[1]).powi(2) + (k as f64 - c[2]).powi(2)).sqrt();
                labels[(i * n + j) * n + k] = if d < 8.0 {
                    3
                } else if d < 15.0 {
                    if (k as f64) < 0.6 * i as f64 + 5.0 {
                        2
                    } else {
                        1
                    }
                } else {
                    0
                };
            }
        }
    }
    let r = label_surfaces(&labels, [n, n, n], 0.0).unwrap();
    for (l, v) in volumes(&r) {
        let count = labels.iter().filter(|&&x| x == l).count() as f64;
        // A voxel count measures the box [-0.5, n - 0.5]^3, the grid the
        // box [0, n - 1]^3: the background gets the difference of shells.
        if l == 0 {
            continue;
        }
        assert!((v - count).abs() < 0.01 * count, "label {l}: {v} vs {count} voxels");
    }
    assert!(close(total(&r), ((n - 1) as f64).powi(3), 1e-12));
}

/// An arrangement of two planes on a box grid: four cells, each reaching
/// the boundary, with exact volumes (planes are exact on the grid); patch
/// areas and the chain's length too. On a tet mesh of the same points
/// (no box known) the cells reach the mesh's boundary: no volume (NaN).
#[test]
fn network_cells_of_two_planes() {
    use septa::grid::{BoxGrid, Grid, Split};
    use septa::measure::{network_measures, BoxDomain};
    use septa::network::{compute, NetworkOptions};
    use septa::scene::{sample_grid, Primitive};
    let g = BoxGrid::new([7, 6, 5], [[-1.0, -1.0, 0.0], [1.0, 2.0, 1.0]], Split::Five).unwrap();
    let planes =
        [Primitive::plane([0.3, 0.0, 0.0], [1.0, 0.0, 0.0]), Primitive::plane([0.0, 0.25, 0.0], [0.0, 1.0, 0.0])];
    let grid = Grid::Box(g.clone());
    let values = sample_grid(&planes, &grid.vertices());
    let net = compute(&grid, &values, 2, &NetworkOptions::new(septa::complex::Mode::Ia)).unwrap();
    let m = network_measures(&net, Some(&BoxDomain::of_box(&g)));
    let mut got: Vec<f64> = m.cell_volume.clone();
    got.sort_by(f64::total_cmp);
    let (xs, ys) = ([1.3, 0.7], [1.25, 1.75]);
    let mut want: Vec<f64> = xs.iter().flat_map(|x| ys.iter().map(move |y| x * y)).collect();
    want.sort_by(f64::total_cmp);
    for (a, b) in got.iter().zip(&want) {
        assert!(close(*a, *b, 1e-12), "{got:?} vs {want:?}");
    }
    let mut areas = m.patch_area.clone();
    areas.sort_by(f64::total_cmp);
    let mut want_areas = vec![1.25, 1.75, 1.3, 0.7];
    want_areas.sort_by(f64::total_cmp);
    for (a, b) in areas.iter().zip(&want_areas) {
        assert!(close(*a, *b, 1e-12), "{areas:?}");
    }
    assert_eq!(m.chain_length.len(), 1);
    assert!(close(m.chain_length[0], 1.0, 1e-12));
    let no_box = network_measures(&net, None);
    assert!(no_box.cell_volume.iter().all(|v| v.is_nan()));
}
