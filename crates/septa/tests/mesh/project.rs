//! Projection of vertices onto the true zero sets (`septa::mesh::
//! certify_network_on`): every vertex stays in its grid element (the
//! network's counts and polygons are the same), the exact check passes
//! after, and `|f| / |grad f|` falls from the interpolants' error (~h^2) to
//! rounding where the root finding converges.

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::mesh::{certify_network, certify_network_on, check_network};
use septa::network::{compute, Network, NetworkOptions};
use septa::scene::Primitive;

fn network(functions: &[Primitive], n: usize, mode: Mode) -> (Network, BoxGrid) {
    let grid = BoxGrid::new([n; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap();
    let g = Grid::Box(grid.clone());
    let values = septa::scene::sample_grid(functions, &g.vertices());
    (compute(&g, &values, functions.len(), &NetworkOptions::new(mode)).unwrap(), grid)
}

/// The smallest angle (degrees) of the written triangles and the share of
/// them under 5 degrees.
fn angles(net: &Network) -> (f64, f64) {
    let x = &net.points;
    let (mut min, mut small, mut n) = (180.0f64, 0usize, 0usize);
    for f in 0..net.face_start.len() - 1 {
        let l = &net.face_verts[net.face_start[f] as usize..net.face_start[f + 1] as usize];
        for k in 1..l.len() - 1 {
            let t = [l[0], l[k], l[k + 1]].map(|v| x[v as usize]);
            let mut m = 180.0f64;
            for i in 0..3 {
                let (a, b, c) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
                let u: [f64; 3] = std::array::from_fn(|j| b[j] - a[j]);
                let w: [f64; 3] = std::array::from_fn(|j| c[j] - a[j]);
                let d: f64 = (0..3).map(|j| u[j] * w[j]).sum();
                let nu = (0..3).map(|j| u[j] * u[j]).sum::<f64>().sqrt();
                let nw = (0..3).map(|j| w[j] * w[j]).sum::<f64>().sqrt();
                m = m.min((d / (nu * nw)).clamp(-1.0, 1.0).acos().to_degrees());
            }
            min = min.min(m);
            small += (m < 5.0) as usize;
            n += 1;
        }
    }
    (min, small as f64 / n.max(1) as f64)
}

/// Projects, and checks what every projection must keep.
fn projected(functions: &[Primitive], n: usize, mode: Mode) -> (Network, Network) {
    let (raw, grid) = network(functions, n, mode);
    let mut plain = raw.clone();
    let e0 = certify_network(&mut plain, Some(&grid));
    assert_eq!(e0.after.violations(), 0, "without projection: {:?}", e0.after);
    let mut net = raw.clone();
    let e = certify_network_on(&mut net, &grid, functions);
    assert_eq!(e.after.violations(), 0, "{:?}", e.after);
    assert_eq!(check_network(&net, Some(grid.bounds)), e.after, "the report is the check of what is written");
    assert_eq!(net.counts(), raw.counts());
    assert_eq!(net.face_verts.len(), raw.face_verts.len());
    let p = e.projection.clone().unwrap();
    assert!(p.moved > 0 && p.residual_before > 1e-4, "{p:?}");
    // each vertex stays within its grid element: never further than a
    // cube's diagonal from where the interpolants put it
    let h = 2.0 / n as f64 * 3f64.sqrt();
    for (a, b) in raw.points.iter().zip(&net.points) {
        assert!((0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt() <= h);
    }
    (plain, net)
}

#[test]
fn a_sphere_is_on_the_sphere() {
    let s = [Primitive::sphere([0.0; 3], 0.5)];
    let (plain, net) = projected(&s, 32, Mode::Ia);
    let p = net.embedding.as_ref().unwrap().projection.clone().unwrap();
    assert_eq!(p.kept, 0, "{p:?}");
    assert!(p.residual_after < 1e-9, "{p:?}");
    let off = |x: &[[f64; 3]]| {
        x.iter().map(|q| ((q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt() - 0.5).abs()).fold(0.0, f64::max)
    };
    assert!(off(&plain.points) > 1e-3 && off(&net.points) < 1e-12, "{} {}", off(&plain.points), off(&net.points));
    let (a0, a1) = (angles(&plain), angles(&net));
    eprintln!(
        "sphere 32^3: off {:.2e} -> {:.2e}, min angle {:.3} -> {:.3}, under 5 deg {:.4} -> {:.4}",
        off(&plain.points),
        off(&net.points),
        a0.0,
        a1.0,
        a0.1,
        a1.1
    );
}

#[test]
fn four_spheres_and_a_torus() {
    let spheres: Vec<Primitive> = [[0.3, 0.0, 0.0], [-0.3, 0.0, 0.0], [0.0, 0.3, 0.1], [0.0, -0.3, -0.1]]
        .into_iter()
        .map(|c| Primitive::sphere(c, 0.45))
        .collect();
    let torus = [
        Primitive::torus([0.0; 3], [0.0, 0.0, 1.0], 0.55, 0.2),
        Primitive::plane([0.013, 0.007, 0.021], [0.3, 0.2, 1.0]),
    ];
    for (fs, mode) in
        [(&spheres[..], Mode::Ia), (&torus[..1], Mode::Ia), (&torus[..], Mode::Ia), (&spheres[..], Mode::Mi)]
    {
        let (_, net) = projected(fs, 32, mode);
        let p = net.embedding.as_ref().unwrap().projection.clone().unwrap();
        eprintln!("{} functions {mode:?}: {p:?}", fs.len());
        // vertices left in place: chain vertices whose curve leaves their
        // grid triangle, and moves the exact check refused; few (under 2%)
        assert!(p.kept * 50 <= p.moved, "{p:?}");
        if p.kept == 0 {
            assert!(p.residual_after < 1e-9, "{p:?}");
        }
        // the torus alone and the four spheres as MI: every vertex on the
        // true surfaces (docs/results.md); IA of the four
        // spheres keeps 58 of 9952 (20 chain vertices whose true curve leaves
        // their grid triangle, 38 moves the exact check refuses: a free
        // Gauss-Newton step off the triangle converges for all 20 but the
        // check then refuses 86)
        if fs.len() == 1 || mode == Mode::Mi {
            assert_eq!(p.kept, 0, "{p:?}");
            assert!(p.residual_after < 1e-9 && p.residual_before > 2e-3, "{p:?}");
        }
    }
}

/// A plane through grid vertices (z = 0 and x = 1/16 are grid planes at
/// 32^3) with a torus: vertices exactly at grid vertices and chain vertices
/// on grid edges in the plane. Moves the exact check refuses are undone, so
/// the exact check passes whatever the root finding found.
#[test]
fn a_plane_through_grid_vertices_and_a_torus() {
    for plane in [Primitive::plane([0.0; 3], [0.0, 0.0, 1.0]), Primitive::plane([0.0625, 0.0, 0.0], [1.0, 0.0, 0.0])] {
        let fs = [Primitive::torus([0.0; 3], [0.0, 0.0, 1.0], 0.55, 0.2), plane];
        for mode in [Mode::Ia, Mode::Mi] {
            let (_, net) = projected(&fs, 32, mode);
            let p = net.embedding.as_ref().unwrap().projection.clone().unwrap();
            eprintln!("torus and a grid plane {mode:?}: {p:?}");
            assert!(p.kept * 50 <= p.moved, "{p:?}");
        }
    }
}
