//! Isotropic remeshing (`septa::mesh::remesh_network`, `remesh_regions`):
//! the same patches (each with its Euler characteristic and boundary
//! loops), chains (with the same end points), corners (at the same points),
//! shells and cells; 0 violations of the exact check of the written
//! triangles; triangles of the target size with no angle under 20 degrees
//! where the constraints allow it. Heavy scenes run with SEPTA_FULL=1.

use septa::job::{GridOverride, Job};
use septa::mesh::{certify_network, certify_regions, check_network, check_regions, remesh_network, remesh_regions};
use septa::mesh::{RemeshOptions, Remeshing};
use septa::network::{Network, NetworkOptions};
use septa::regions::{region_surfaces, RegionSurfaces};
use septa::scene::Scene;

fn full() -> bool {
    std::env::var_os("SEPTA_FULL").is_some()
}

/// Per patch (of `n`): Euler characteristic and boundary loops of its
/// triangles (polygons `start`/`verts`, patch of each in `patch`).
fn patch_topology(start: &[u32], verts: &[u32], patch: &[u32], n: usize) -> Vec<(i64, usize)> {
    let mut v: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut e: Vec<Vec<(u32, u32)>> = vec![Vec::new(); n];
    let mut f = vec![0i64; n];
    for i in 0..start.len() - 1 {
        let l = &verts[start[i] as usize..start[i + 1] as usize];
        let p = patch[i] as usize;
        f[p] += 1;
        v[p].extend_from_slice(l);
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            e[p].push((a.min(b), a.max(b)));
        }
    }
    (0..n)
        .map(|p| {
            v[p].sort_unstable();
            v[p].dedup();
            e[p].sort_unstable();
            let mut border: Vec<(u32, u32)> = Vec::new();
            for (i, x) in e[p].iter().enumerate() {
                let once = (i == 0 || e[p][i - 1] != *x) && (i + 1 == e[p].len() || e[p][i + 1] != *x);
                if once {
                    border.push(*x);
                }
            }
            let mut all = e[p].clone();
            all.dedup();
            // boundary loops: components of the border graph
            let mut ends: Vec<u32> = border.iter().flat_map(|&(a, b)| [a, b]).collect();
            ends.sort_unstable();
            ends.dedup();
            let mut parent: Vec<usize> = (0..ends.len()).collect();
            fn find(p: &mut [usize], i: usize) -> usize {
                if p[i] != i {
                    let r = find(p, p[i]);
                    p[i] = r;
                }
                p[i]
            }
            for &(a, b) in &border {
                let (i, j) = (ends.binary_search(&a).unwrap(), ends.binary_search(&b).unwrap());
                let (ri, rj) = (find(&mut parent, i), find(&mut parent, j));
                parent[ri] = rj;
            }
            let loops = (0..ends.len()).filter(|&i| find(&mut parent, i) == i).count();
            (v[p].len() as i64 - all.len() as i64 + f[p], loops)
        })
        .collect()
}

fn min_angle(x: &[[f64; 3]], verts: &[u32]) -> f64 {
    let mut best = 180.0f64;
    for t in verts.chunks(3) {
        for i in 0..3 {
            let (a, b, c) = (x[t[i] as usize], x[t[(i + 1) % 3] as usize], x[t[(i + 2) % 3] as usize]);
            let u: [f64; 3] = std::array::from_fn(|j| b[j] - a[j]);
            let w: [f64; 3] = std::array::from_fn(|j| c[j] - a[j]);
            let d: f64 = (0..3).map(|j| u[j] * w[j]).sum();
            let nu = (0..3).map(|j| u[j] * u[j]).sum::<f64>().sqrt();
            let nw = (0..3).map(|j| w[j] * w[j]).sum::<f64>().sqrt();
            best = best.min((d / (nu * nw)).clamp(-1.0, 1.0).acos().to_degrees());
        }
    }
    best
}

fn check_report(name: &str, r: &Remeshing, l: f64, min: f64) {
    assert_eq!(r.refused, 0, "{name}: {r:?}");
    assert!(r.patches_kept, "{name}: {r:?}");
    assert!(r.after.min_angle >= min, "{name}: smallest angle {} < {min}", r.after.min_angle);
    assert!(r.after.triangles > 0 && r.before.triangles > r.after.triangles, "{name}: {r:?}");
    // on the surface it came from, within the target size
    assert!(r.hausdorff[0] < l && r.hausdorff[1] < l, "{name}: {:?}", r.hausdorff);
}

/// A scene's grid network, certified, and remeshed to `l`; what must hold.
fn remeshed_network(name: &str, mode: septa::complex::Mode, l: f64, min: f64) -> (Network, Network, Remeshing) {
    let job = Job::load(name, &GridOverride::default()).unwrap();
    let (mut net, _) = job.run(&NetworkOptions::new(mode), false).unwrap();
    let grid = match &job.grid {
        septa::grid::Grid::Box(b) => b.clone(),
        _ => unreachable!(),
    };
    certify_network(&mut net, Some(&grid));
    let before = net.clone();
    let r = remesh_network(&mut net, &RemeshOptions::new(l), Some(grid.bounds)).unwrap();
    check_report(name, &r, l, min);
    assert!(net.face_verts.len() == 3 * net.num_faces(), "{name}: triangles");
    assert_eq!(min_angle(&net.points, &net.face_verts), r.after.min_angle, "{name}");
    // the counts that are the network's, unchanged
    let keep = |n: &Network| {
        let c = n.counts();
        ["patches", "chains", "corners", "shells", "cells", "components"]
            .map(|k| c.iter().find(|(q, _)| *q == k).unwrap().1)
    };
    assert_eq!(keep(&net), keep(&before), "{name}");
    assert_eq!(net.chain_patches, before.chain_patches, "{name}");
    let np = before.patches.len();
    assert_eq!(
        patch_topology(&net.face_start, &net.face_verts, &net.face_patch, np),
        patch_topology(&before.face_start, &before.face_verts, &before.face_patch, np),
        "{name}: per-patch Euler characteristic and boundary loops"
    );
    // corners at the same points; chains between the same points
    let at = |n: &Network, v: u32| n.points[v as usize];
    for (a, b) in net.corners.iter().zip(&before.corners) {
        assert_eq!(at(&net, *a), at(&before, *b), "{name}: corner");
    }
    for (c, d) in net.chains.iter().zip(&before.chains) {
        assert_eq!(at(&net, c[0]), at(&before, d[0]), "{name}: chain start");
        assert_eq!(at(&net, *c.last().unwrap()), at(&before, *d.last().unwrap()), "{name}: chain end");
        // a chain is a path of the remeshed triangles' edges
        for w in c.windows(2) {
            assert!(net.edges.binary_search(&[w[0].min(w[1]), w[0].max(w[1])]).is_ok(), "{name}: chain edge");
        }
    }
    // the exact check of what is written
    let e = net.embedding.clone().unwrap();
    assert_eq!(e.after.violations(), 0, "{name}: {:?}", e.after);
    let c = check_network(&net, Some(grid.bounds));
    assert_eq!(c, e.after, "{name}: the report is the check of what is written");
    let c0 = check_network(&before, Some(grid.bounds));
    assert_eq!((c.cells_checked, c.cells_positive), (c0.cells_checked, c0.cells_positive), "{name}");
    (before, net, r)
}

fn remeshed_regions(name: &str, l: f64, min: f64) -> (RegionSurfaces, RegionSurfaces, Remeshing) {
    let scene = Scene::load(name).unwrap();
    let mut r = region_surfaces(&scene, &Default::default()).unwrap();
    let grid = scene.grid.box_grid().unwrap();
    certify_regions(&mut r, Some(&grid), Some(grid.bounds));
    let before = r.clone();
    let rep = remesh_regions(&mut r, &RemeshOptions::new(l), Some(grid.bounds)).unwrap();
    check_report(name, &rep, l, min);
    let topo =
        |r: &RegionSurfaces| -> Vec<_> { r.surfaces.iter().map(|s| (s.regions, s.euler, s.boundary_loops)).collect() };
    let n = before.surfaces.len();
    assert_eq!(
        patch_topology(&r.loop_start, &r.loops, &r.face_surface, n),
        patch_topology(&before.loop_start, &before.loops, &before.face_surface, n),
        "{name}"
    );
    assert_eq!(topo(&r).len(), topo(&before).len());
    assert_eq!(r.curves.len(), before.curves.len());
    for (c, d) in r.curves.iter().zip(&before.curves) {
        let (p, q) = (&r.network.points, &before.network.points);
        assert_eq!(p[c.vertices[0] as usize], q[d.vertices[0] as usize], "{name}: curve start");
        assert_eq!(p[*c.vertices.last().unwrap() as usize], q[*d.vertices.last().unwrap() as usize], "{name}");
    }
    let e = r.embedding.clone().unwrap();
    assert_eq!(e.after.violations(), 0, "{name}: {:?}", e.after);
    assert_eq!(check_regions(&r, Some(grid.bounds)), e.after, "{name}");
    (before, r, rep)
}

#[test]
fn sphere_with_hole_ia_and_regions() {
    let (_, _, r) = remeshed_network("builtin:sphere-with-hole", septa::complex::Mode::Ia, 0.1, 20.0);
    assert!(r.after.min_angle >= 25.0, "{r:?}");
    remeshed_regions("builtin:sphere-with-hole", 0.1, 20.0);
}

#[test]
fn box_minus_cylinder_keeps_its_sharp_edges() {
    // 59 patches, 38 chains, 32 corners: the box's edges and the cylinder's rims
    let (before, net, _) = remeshed_network("builtin:box-minus-cylinder", septa::complex::Mode::Ia, 0.1, 20.0);
    assert_eq!(before.corners.len(), 32);
    assert_eq!(net.corners.len(), 32);
}

#[test]
fn sphere_plane_hole_regions() {
    remeshed_regions("builtin:sphere-plane-hole", 0.1, 20.0);
}

#[test]
fn heavy_scenes() {
    if !full() {
        return;
    }
    for name in ["builtin:saucer-square", "builtin:sphere-plane-hole"] {
        remeshed_network(name, septa::complex::Mode::Ia, 0.1, 20.0);
    }
    for name in ["builtin:saucer-square", "builtin:box-minus-cylinder", "builtin:voronoi-lines-5"] {
        remeshed_regions(name, 0.1, 20.0);
    }
    // where chains meet at small angles or corners are close, the smallest
    // angle is what those constraints leave (docs/results.md, Remeshing)
    for name in ["builtin:patch-blend", "builtin:cad-part"] {
        remeshed_regions(name, 0.1, 10.0);
    }
}

#[test]
fn a_bad_length_is_refused() {
    let scene = Scene::load("builtin:sphere-with-hole").unwrap();
    let mut r = region_surfaces(&scene, &Default::default()).unwrap();
    for l in [0.0, -1.0, f64::NAN, 1e-9] {
        let e = remesh_regions(&mut r, &RemeshOptions::new(l), None).unwrap_err();
        assert!(e.contains("--remesh"), "{e}");
    }
}

#[test]
fn label_volume_remeshes_on_its_own_triangles() {
    // sampled input: four labels in a ball, meeting along curves and at
    // points (no formulas: vertices stay on the unremeshed triangles)
    let n = 24;
    let mut v = vec![0i64; n * n * n];
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let (x, y, z) = (i as f64 - 11.3, j as f64 - 11.8, k as f64 - 12.1);
                v[(i * n + j) * n + k] =
                    if x * x + y * y + z * z < 80.0 { 1 + (x > 0.0) as i64 + 2 * (y > 0.4 * x) as i64 } else { 0 };
            }
        }
    }
    let affine = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]];
    let mut r = septa::regions::label_surfaces(&v, [n; 3], 0.0).unwrap();
    septa::mesh::place_labels(&mut r, [n; 3], &affine, true).unwrap();
    let before = r.clone();
    let bounds = septa::mesh::label_bounds([n; 3], &affine);
    let rep = remesh_regions(&mut r, &RemeshOptions::new(2.0), bounds).unwrap();
    check_report("labels", &rep, 2.0, 20.0);
    let s = before.surfaces.len();
    assert_eq!(
        patch_topology(&r.loop_start, &r.loops, &r.face_surface, s),
        patch_topology(&before.loop_start, &before.loops, &before.face_surface, s)
    );
    assert_eq!(r.curves.len(), before.curves.len());
    let e = r.embedding.clone().unwrap();
    assert_eq!(e.after.violations(), 0, "{:?}", e.after);
    assert_eq!(check_regions(&r, bounds), e.after);
}

#[test]
fn formulas_put_new_vertices_on_the_true_surface() {
    // a sphere of radius 0.5 and a plane through it (one chain, a circle)
    use septa::grid::{BoxGrid, Grid, Split};
    use septa::scene::Primitive;
    let fs = [Primitive::sphere([0.0; 3], 0.5), Primitive::plane([0.0, 0.0, 1.0], [0.0, 0.0, 0.1])];
    let grid = BoxGrid::new([24; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap();
    let g = Grid::Box(grid.clone());
    let values = septa::scene::sample_grid(&fs, &g.vertices());
    let opts = NetworkOptions::new(septa::complex::Mode::Ia);
    let mut net = septa::network::compute(&g, &values, fs.len(), &opts).unwrap();
    certify_network(&mut net, Some(&grid));
    let (mut plain, mut on) = (net.clone(), net.clone());
    let o = RemeshOptions::new(0.12);
    let rp = remesh_network(&mut plain, &o, Some(grid.bounds)).unwrap();
    let ro = septa::mesh::remesh_network_on(&mut on, &o, Some(grid.bounds), &fs).unwrap();
    for (name, r, n) in [("closest point", &rp, &plain), ("formulas", &ro, &on)] {
        check_report(name, r, 0.12, 20.0);
        assert_eq!(n.embedding.as_ref().unwrap().after.violations(), 0, "{name}");
    }
    // the largest distance of a sphere vertex from the sphere (those of
    // patches of the sphere's function: label 0)
    let off = |n: &Network| {
        let mut worst = 0.0f64;
        for f in 0..n.num_faces() {
            if n.face_label[f][0] == 0 {
                for &v in n.face(f) {
                    let p = n.points[v as usize];
                    worst = worst.max(((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 0.5).abs());
                }
            }
        }
        worst
    };
    assert!(off(&plain) > 1e-4, "{}", off(&plain));
    assert!(off(&on) < 1e-9, "{}", off(&on));
}
