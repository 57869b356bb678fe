//! The corner shortcut of the embedding's exact vertex-face sides
//! (`embed::exact_side`) against the sides from the cut-vertices'
//! homogeneous coordinates, on nearly coplanar triangles (where the
//! interval filter cannot decide and the shortcut matters).

use crate::cut::base::geom::{dot3, sub3, v3, Ctx, Def};
use crate::cut::embed::sides::{exact_side, exact_side_full};
use crate::cut::input::input::check_mesh;
use crate::cut::Support;
use rand::{Rng, SeedableRng};
use septa_exact::{Exact, Interval, Ring, Sign};

/// Whether `TPP(t, p, q)` lies strictly inside triangle `t`: its weights
/// `l1 = n1 / det`, `l2 = n2 / det`, `1 - l1 - l2` all positive, with
/// `n1`, `n2`, `det` as in `Ctx::hom` (TopoCut App. B), exactly.
fn strictly_inside(c: &Ctx, t: u32, p: u32, q: u32) -> bool {
    let [a, b, cc] = c.tris[t as usize].map(|i| v3::<Exact>(&c.verts[i as usize]));
    let (e1, e2) = (sub3(&b, &a), sub3(&cc, &a));
    let (np, nq) = (c.pn::<Exact>(p), c.pn::<Exact>(q));
    let (dp, dq) = (Exact::of(c.planes[p as usize][3]), Exact::of(c.planes[q as usize][3]));
    let (m00, m01, m10, m11) = (dot3(&np, &e1), dot3(&np, &e2), dot3(&nq, &e1), dot3(&nq, &e2));
    let r0 = dp.add(&dot3(&np, &a)).neg();
    let r1 = dq.add(&dot3(&nq, &a)).neg();
    let det = m00.mul(&m11).sub(&m01.mul(&m10));
    let n1 = r0.mul(&m11).sub(&m01.mul(&r1));
    let n2 = m00.mul(&r1).sub(&r0.mul(&m10));
    let l0 = det.sub(&n1).sub(&n2);
    let s = det.sign();
    s != Sign::Zero && n1.sign() == s && n2.sign() == s && l0.sign() == s
}

#[test]
fn corner_sides_equal_the_sides_from_coordinates() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0xc0de);
    // a flat octahedron (nearly coplanar neighbouring triangles, as on
    // plate_genus9) with its equator jittered by a few ulps
    let h = 1e-13;
    let mut verts = vec![[0.0, 0.0, h], [0.0, 0.0, -h]];
    for k in 0..4 {
        let a = k as f64 * std::f64::consts::FRAC_PI_2 + rng.gen_range(-1e-3..1e-3);
        verts.push([a.cos(), a.sin(), rng.gen_range(-1.0..1.0) * 1e-15]);
    }
    let tris: Vec<[u32; 3]> =
        (0..4u32).flat_map(|k| [[0, 2 + k, 2 + (k + 1) % 4], [1, 2 + (k + 1) % 4, 2 + k]]).collect();
    let planes: Vec<[f64; 4]> = (0..12)
        .map(|_| {
            let n: [f64; 3] = [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)];
            [n[0], n[1], n[2], rng.gen_range(-0.5..0.5)]
        })
        .collect();
    let (edges, tri_edges, edge_tris) = check_mesh(&verts, &tris).expect("closed mesh");
    let nv = verts.len();
    let pv: Vec<i8> =
        planes.iter().flat_map(|pl| verts.iter().map(|x| septa_exact::plane_point_sign(pl, x).as_i8())).collect();
    let c = Ctx {
        verts: &verts,
        tris: &tris,
        planes: &planes,
        edges,
        tri_edges,
        edge_tris,
        wedges: Default::default(),
        pv,
        tn_iv: Vec::new(),
        pp_iv: Vec::new(),
        tn_b: Vec::new(),
        pp_b: Vec::new(),
    };
    let tn_iv: Vec<[Interval; 3]> = (0..tris.len() as u32).map(|t| c.tn_compute::<Interval>(t)).collect();
    let c = Ctx { tn_iv, ..c };
    let np = planes.len() as u32;
    let mut defs: Vec<Def> = (0..nv as u32).map(Def::V).collect();
    for (e, &[u, v]) in c.edges.iter().enumerate() {
        for p in 0..np {
            if c.pv_sign(p, u) * c.pv_sign(p, v) < 0 {
                defs.push(Def::EP(e as u32, p));
            }
        }
    }
    for t in 0..tris.len() as u32 {
        for p in 0..np {
            for q in p + 1..np {
                if strictly_inside(&c, t, p, q) {
                    defs.push(Def::TPP(t, p, q));
                }
            }
        }
    }
    let (mut pairs, mut off_plane) = (0usize, 0usize);
    for &d in &defs {
        for t in 0..tris.len() as u32 {
            let s = Support::Tri(t);
            let full = exact_side_full(&c, d, s);
            assert_eq!(exact_side(&c, d, s), full, "{d:?} against triangle {t}");
            pairs += 1;
            off_plane += (full != Sign::Zero) as usize;
        }
    }
    // vertices, edge crossings and triangle interiors all met, on and off
    // the neighbouring planes
    let tpp = defs.iter().filter(|d| matches!(d, Def::TPP(..))).count();
    let ep = defs.iter().filter(|d| matches!(d, Def::EP(..))).count();
    assert!(tpp > 50 && ep > 20, "{tpp} TPP, {ep} EP");
    assert!(off_plane > pairs / 2 && off_plane < pairs, "{off_plane} of {pairs} pairs off the plane");
}
