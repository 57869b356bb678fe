//! Small deterministic generators for the cut's unit tests (the same
//! sequences on every machine, without a dependency), and a tetrahedron's
//! context for tests of the plane-only predicates.

/// Knuth's MMIX linear congruential generator, its top 53 bits.
pub(crate) fn lcg(seed: u64) -> impl FnMut() -> u64 {
    let mut s = seed;
    move || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        s >> 11
    }
}

/// Marsaglia's xorshift64 (shifts 13, 7, 17), as a double in `[-1, 1)`.
pub(crate) fn xorshift_unit(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// A closed unit tetrahedron (outward), for tests that need a [`Ctx`] for
/// its planes only.
static TET_VERTS: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
static TET_TRIS: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

/// The cut context of the tetrahedron above and `planes` (plane-vertex
/// signs left zero, no filter copies): what the plane-only predicates
/// (line directions, three-plane points, orders) read.
pub(crate) fn tet_ctx(planes: &[[f64; 4]]) -> crate::cut::base::geom::Ctx<'_> {
    let (edges, tri_edges, edge_tris) =
        crate::cut::input::input::check_mesh(&TET_VERTS, &TET_TRIS).expect("closed mesh");
    crate::cut::base::geom::Ctx {
        verts: &TET_VERTS,
        tris: &TET_TRIS,
        planes,
        edges,
        tri_edges,
        edge_tris,
        wedges: Default::default(),
        pv: vec![0; planes.len() * TET_VERTS.len()],
        tn_iv: Vec::new(),
        pp_iv: Vec::new(),
        tn_b: Vec::new(),
        pp_b: Vec::new(),
    }
}

/// Two parallel grids of triangles `thickness` apart, in the plane through
/// the origin with unit normal `n` (a thin plate's two faces).
pub(crate) fn plate(n: [f64; 3], thickness: f64, cells: usize) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    // an orthonormal basis (e1, e2) of the plane
    let a = if n[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    let cross =
        |p: [f64; 3], q: [f64; 3]| [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]];
    let unit = |p: [f64; 3]| {
        let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        p.map(|c| c / l)
    };
    let e1 = unit(cross(n, a));
    let e2 = cross(n, e1);
    let (mut x, mut t) = (Vec::new(), Vec::new());
    for side in [0.0, thickness] {
        let base = x.len() as u32;
        for i in 0..=cells {
            for j in 0..=cells {
                let (u, v) = (i as f64 / cells as f64, j as f64 / cells as f64);
                x.push(std::array::from_fn(|k| u * e1[k] + v * e2[k] + side * n[k]));
            }
        }
        let id = |i: usize, j: usize| base + (i * (cells + 1) + j) as u32;
        for i in 0..cells {
            for j in 0..cells {
                t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    (x, t)
}

/// The axis-aligned bounding box of each triangle of `tris`.
pub(crate) fn aabbs(x: &[[f64; 3]], tris: &[[u32; 3]]) -> Vec<crate::cut::triangles::pair_grid::Aabb> {
    tris.iter()
        .map(|t| {
            let p = t.map(|v| x[v as usize]);
            (
                std::array::from_fn(|k| p[0][k].min(p[1][k]).min(p[2][k])),
                std::array::from_fn(|k| p[0][k].max(p[1][k]).max(p[2][k])),
            )
        })
        .collect()
}

/// A unit cube of 12 triangles, outward.
pub(crate) fn unit_cube() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let v: Vec<[f64; 3]> = (0..8).map(|i| [(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64]).collect();
    let t = vec![
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    (v, t)
}
