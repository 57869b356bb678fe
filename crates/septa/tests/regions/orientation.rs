//! Orientation direction of every surface of interest of every built-in
//! scene, against the scene's own functions rather than the network's
//! labels: a kept polygon is counter-clockwise seen from the lesser region
//! of its pair (Bloomenthal 4.5.2.4), so a short step from its centroid
//! along its right-hand (Newell) normal lands in the lesser region and a
//! step against it in the greater one. The regions at the probe points come
//! from the scene's functions, interpolated linearly in the grid tet that
//! holds the probe (the functions the network partitions, Du et al. Sec.
//! 3), and the region rule, so the check is independent of which network
//! cell is on which side of a face and of `must_flip`. Pairs between two inner regions (saucer-square
//! 1|2, 1|3, 2|3; sphere-plane-hole 2|3; patch-blend) are covered like those
//! against the outside.
//!
//! A probe near a curve or a corner can land in a third region; such
//! polygons are counted as undecided. A polygon whose probes are both in
//! the swapped regions is wrong, whatever its neighbours say.

use std::collections::BTreeMap;

use septa::grid::{BoxGrid, Split};
use septa::regions::{region_surfaces, RegionOptions};
use septa::scene::{Mode, RegionId, Scene};

/// Region of the point `p` by the scene's functions interpolated linearly
/// in the grid tet holding `p`, and the scene's rule.
fn region_at(scene: &Scene, grid: &BoxGrid, p: [f64; 3]) -> RegionId {
    let g = &scene.grid;
    let ijk = [0, 1, 2].map(|a| {
        let h = (g.bounds[1][a] - g.bounds[0][a]) / g.resolution[a] as f64;
        (((p[a] - g.bounds[0][a]) / h).floor().max(0.0) as usize).min(g.resolution[a] - 1)
    });
    let per = if g.split == 6 { 6 } else { 5 };
    let mut best = (f64::NEG_INFINITY, [0.0; 4], [[0.0; 3]; 4]);
    for local in 0..per {
        let q = grid.tet_corners(ijk, local).map(|c| {
            let d = [(c >> 2) as usize & 1, (c >> 1) as usize & 1, c as usize & 1];
            grid.vertex(grid.vertex_index([ijk[0] + d[0], ijk[1] + d[1], ijk[2] + d[2]]))
        });
        let det = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])
        };
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let (e1, e2, e3, x) = (sub(q[1], q[0]), sub(q[2], q[0]), sub(q[3], q[0]), sub(p, q[0]));
        let vol = det(e1, e2, e3);
        let b1 = det(x, e2, e3) / vol;
        let b2 = det(e1, x, e3) / vol;
        let b3 = det(e1, e2, x) / vol;
        let b = [1.0 - b1 - b2 - b3, b1, b2, b3];
        let worst = b.iter().copied().fold(f64::INFINITY, f64::min);
        if worst > best.0 {
            best = (worst, b, q);
        }
    }
    let (_, b, q) = best;
    let v: Vec<f64> = scene.functions.iter().map(|f| (0..4).map(|i| b[i] * f.eval(q[i])).sum::<f64>()).collect();
    match scene.mode {
        Mode::Ia => scene.regions.region_ia(&v.iter().map(|&x| x > 0.0).collect::<Vec<_>>()),
        Mode::Mi => {
            let m = (0..v.len()).max_by(|&a, &b| v[a].total_cmp(&v[b])).unwrap();
            scene.regions.region_mi(m)
        }
    }
}

#[derive(Default, Debug)]
struct Count {
    agree: usize,
    flipped: usize,
    undecided: usize,
}

/// Per region pair: polygons whose probes agree with the rule, are swapped,
/// or land elsewhere.
fn probe(name: &str) -> BTreeMap<[RegionId; 2], Count> {
    let scene = Scene::load(&format!("builtin:{name}")).unwrap();
    let r = region_surfaces(&scene, &RegionOptions::default()).unwrap();
    let g = &scene.grid;
    let split = if g.split == 6 { Split::Six } else { Split::Five };
    let grid = BoxGrid::new(g.resolution, g.bounds, split).unwrap();
    let h = (0..3).map(|a| (g.bounds[1][a] - g.bounds[0][a]) / g.resolution[a] as f64).fold(f64::INFINITY, f64::min);
    let mut out: BTreeMap<[RegionId; 2], Count> = BTreeMap::new();
    for (i, &f) in r.faces.iter().enumerate() {
        let [cp, cn] = r.network.face_cells[f as usize];
        let (a, b) = (r.cell_region[cp as usize], r.cell_region[cn as usize]);
        let pair = [a.min(b), a.max(b)];
        let pts: Vec<[f64; 3]> = r.loops[r.loop_start[i] as usize..r.loop_start[i + 1] as usize]
            .iter()
            .map(|&v| r.network.points[v as usize])
            .collect();
        let (mut n, mut c) = ([0.0; 3], [0.0; 3]);
        for k in 0..pts.len() {
            let (p, q) = (pts[k], pts[(k + 1) % pts.len()]);
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
            for j in 0..3 {
                c[j] += p[j] / pts.len() as f64;
            }
        }
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let e = out.entry(pair).or_default();
        // A polygon of (nearly) no area in floating point (an exact sliver
        // where two planes meet a grid edge, e.g. cad-part's boss_bottom
        // z = -0.15 and xhi x = 0.7: |normal| 2e-32 against h^2 2e-3) has a
        // Newell normal of rounding noise: its direction decides nothing.
        if len <= 1e-12 * h * h {
            e.undecided += 1;
            continue;
        }
        let step = 0.05 * h / len;
        let front = region_at(&scene, &grid, [0, 1, 2].map(|k| c[k] + step * n[k]));
        let back = region_at(&scene, &grid, [0, 1, 2].map(|k| c[k] - step * n[k]));
        if (front, back) == (pair[0], pair[1]) {
            e.agree += 1;
        } else if (front, back) == (pair[1], pair[0]) {
            e.flipped += 1;
        } else {
            e.undecided += 1;
        }
    }
    out
}

#[test]
fn every_surface_faces_its_lesser_region() {
    let (mut pairs, mut inner) = (0, 0);
    let mut bad = Vec::new();
    for (name, _) in septa::scene::builtin::list() {
        let counts = probe(name);
        assert!(!counts.is_empty(), "{name}: no surfaces of interest");
        for (pair, c) in &counts {
            eprintln!("{name} {pair:?}: {c:?}");
            let total = c.agree + c.flipped + c.undecided;
            if c.flipped > 0 {
                bad.push(format!("{name} {pair:?}: {} of {total} polygons face the greater region", c.flipped));
            }
            // most polygons are decided, so the check cannot pass vacuously
            if c.agree * 10 < total * 9 {
                bad.push(format!("{name} {pair:?}: only {} of {total} polygons decided", c.agree));
            }
            pairs += 1;
            inner += (pair[0] != 0) as usize;
        }
    }
    eprintln!("{pairs} region pairs, {inner} between two regions other than 0");
    assert!(bad.is_empty(), "{bad:#?}");
    assert!(inner >= 5, "too few pairs between inner regions: {inner}");
}
