//! Shells of the input mesh and the winding number of the solid they bound
//! (TopoCut Sec. 2.1: the input is the boundary of a solid, every point
//! inside it once). A closed, consistently oriented, non-self-intersecting
//! mesh may still be made of several shells; nested shells must alternate
//! orientation (a cavity faces inwards). Two nested shells facing the same
//! way wrap their common inside twice, and used to be cut into overlapping
//! cells (of volumes 27 and 1 for cubes of sides 3 and 1).
//!
//! Shells are disjoint closed surfaces, so the winding number is constant
//! between them and changes by the orientation `s` of a shell across it.
//! It is 0 or 1 everywhere iff, for every shell, the winding number `w` of
//! the other shells at one of its vertices satisfies `w = 0` (then `s = +1`)
//! or `w = 1` (then `s = -1`). `w` is counted exactly by a ray along `+x`
//! (signed crossings; ties where the ray meets an edge or vertex broken by
//! a symbolic perturbation of the start point), `s` is the exact sign of the
//! shell's volume.

use super::input::NonManifold;
use crate::cut::triangles::orient::orient2;
use crate::cut::CutError;
use septa_exact::{det_sign_diff, filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// Triangles of each shell (edge-connected component; at a non-manifold
/// edge only the two triangles of a wedge are connected, so each shell is
/// a manifold surface away from pinched vertices), shells ordered by their
/// smallest triangle.
pub(crate) fn shells(
    num_tris: usize,
    edge_tris: &[[u32; 2]],
    tri_edges: &[[u32; 3]],
    nm: &NonManifold,
) -> Vec<Vec<u32>> {
    let mut shell = vec![u32::MAX; num_tris];
    let mut out: Vec<Vec<u32>> = Vec::new();
    for seed in 0..num_tris {
        if shell[seed] != u32::MAX {
            continue;
        }
        let id = out.len() as u32;
        let mut members = vec![seed as u32];
        shell[seed] = id;
        let mut k = 0;
        while k < members.len() {
            let t = members[k] as usize;
            k += 1;
            for &e in &tri_edges[t] {
                let o = nm.across(edge_tris, e, t as u32);
                if shell[o as usize] == u32::MAX {
                    shell[o as usize] = id;
                    members.push(o);
                }
            }
        }
        out.push(members);
    }
    out
}

/// Exact sign of a closed shell's volume (six times it is the sum of
/// `det[a, b, c]` over its triangles).
fn orientation(verts: &[[f64; 3]], tris: &[[u32; 3]], shell: &[u32]) -> Sign {
    fn vol6<R: Ring>(verts: &[[f64; 3]], tris: &[[u32; 3]], shell: &[u32]) -> R {
        let mut sum = R::of(0.0);
        for &t in shell {
            let [a, b, c] = tris[t as usize].map(|v| verts[v as usize].map(R::of));
            let cross = [
                a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
                a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
                a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
            ];
            sum = sum.add(&cross[0].mul(&c[0]).add(&cross[1].mul(&c[1])).add(&cross[2].mul(&c[2])));
        }
        sum
    }
    filtered_sign_bounded(
        || vol6::<Bounded>(verts, tris, shell),
        || vol6::<Interval>(verts, tris, shell),
        || vol6::<Exact>(verts, tris, shell),
    )
}

/// Where a ray starts: a mesh vertex, or (for a shell that has no vertex of
/// its own, every one shared with other shells at a non-manifold edge or a
/// pinched vertex) the centroid of one of its triangles, which lies on no
/// other shell (the input check: triangles meet only in shared vertices
/// and edges). The centroid `(a + b + c) / 3` is used as `a + b + c`
/// against corners scaled by 3, exactly.
#[derive(Clone, Copy)]
enum Query {
    Vertex(u32),
    Centroid(u32),
}

fn scaled_centroid<R: Ring>(verts: &[[f64; 3]], tris: &[[u32; 3]], t: u32) -> [R; 3] {
    let [a, b, c] = tris[t as usize].map(|v| verts[v as usize]);
    std::array::from_fn(|k| R::of(a[k]).add(&R::of(b[k])).add(&R::of(c[k])))
}

/// `orient2d(a, b, q)` in the `(y, z)` plane (as `tri_pair::orient2` with
/// axis 0).
fn orient2_q(verts: &[[f64; 3]], tris: &[[u32; 3]], a: u32, b: u32, q: Query) -> Sign {
    let t = match q {
        Query::Vertex(q) => return orient2(verts, 0, a, b, q),
        Query::Centroid(t) => t,
    };
    fn f<R: Ring>(verts: &[[f64; 3]], tris: &[[u32; 3]], a: u32, b: u32, t: u32) -> R {
        let (pa, pb) = (verts[a as usize], verts[b as usize]);
        let g = scaled_centroid::<R>(verts, tris, t);
        let three = R::of(3.0);
        let ba = |k: usize| R::of(pb[k]).sub(&R::of(pa[k]));
        let ga = |k: usize| g[k].sub(&three.mul(&R::of(pa[k])));
        ba(1).mul(&ga(2)).sub(&ba(2).mul(&ga(1)))
    }
    filtered_sign_bounded(
        || f::<Bounded>(verts, tris, a, b, t),
        || f::<Interval>(verts, tris, a, b, t),
        || f::<Exact>(verts, tris, a, b, t),
    )
}

/// `orient3d`: the sign of `det[b - a, c - a, q - a]`.
fn orient3_q(verts: &[[f64; 3]], tris: &[[u32; 3]], [a, b, c]: [u32; 3], q: Query) -> Sign {
    let [pa, pb, pc] = [a, b, c].map(|v| verts[v as usize]);
    let t = match q {
        Query::Vertex(q) => return det_sign_diff(&[pb, pc, verts[q as usize]], &[pa, pa, pa]),
        Query::Centroid(t) => t,
    };
    fn f<R: Ring>(verts: &[[f64; 3]], tris: &[[u32; 3]], [pa, pb, pc]: [[f64; 3]; 3], t: u32) -> R {
        let g = scaled_centroid::<R>(verts, tris, t);
        let three = R::of(3.0);
        let row = |p: [f64; 3]| -> [R; 3] { std::array::from_fn(|k| R::of(p[k]).sub(&R::of(pa[k]))) };
        let (u, v) = (row(pb), row(pc));
        let w: [R; 3] = std::array::from_fn(|k| g[k].sub(&three.mul(&R::of(pa[k]))));
        let cx = u[1].mul(&v[2]).sub(&u[2].mul(&v[1]));
        let cy = u[2].mul(&v[0]).sub(&u[0].mul(&v[2]));
        let cz = u[0].mul(&v[1]).sub(&u[1].mul(&v[0]));
        cx.mul(&w[0]).add(&cy.mul(&w[1])).add(&cz.mul(&w[2]))
    }
    let p = [pa, pb, pc];
    filtered_sign_bounded(
        || f::<Bounded>(verts, tris, p, t),
        || f::<Interval>(verts, tris, p, t),
        || f::<Exact>(verts, tris, p, t),
    )
}

/// `orient2d` in the `(y, z)` plane of `a, b` and the start point `q`
/// displaced by `(eps, eps^2)` (eps infinitesimal): never zero when `a, b`
/// differ in `(y, z)`. Swapping `a, b` flips it, so two triangles sharing
/// an edge agree on which side of it the start point is.
fn orient2_perturbed(verts: &[[f64; 3]], tris: &[[u32; 3]], a: u32, b: u32, q: Query) -> Sign {
    match orient2_q(verts, tris, a, b, q) {
        Sign::Zero => {
            let (pa, pb) = (verts[a as usize], verts[b as usize]);
            // Coefficients of eps and eps^2 in the expanded determinant.
            match Sign::of_f64(pa[2] - pb[2]) {
                Sign::Zero => Sign::of_f64(pb[1] - pa[1]),
                s => s,
            }
        }
        s => s,
    }
}

/// What the ray from `q` along `+x` meets on one shell.
enum Crossings {
    /// The signed number of crossings: the shell's winding number at `q`.
    Winding(i64),
    /// `q` lies on triangle `t` of the shell.
    OnTriangle(u32),
}

fn winding(verts: &[[f64; 3]], tris: &[[u32; 3]], shell: &[u32], q: Query) -> Crossings {
    let mut w = 0;
    for &t in shell {
        let [a, b, c] = tris[t as usize];
        let [pa, pb, pc] = [a, b, c].map(|v| verts[v as usize]);
        // Exact pre-tests on input coordinates (equal values go on).
        if let Query::Vertex(q) = q {
            let p = verts[q as usize];
            let out = |k: usize| {
                (p[k] < pa[k] && p[k] < pb[k] && p[k] < pc[k]) || (p[k] > pa[k] && p[k] > pb[k] && p[k] > pc[k])
            };
            if out(1) || out(2) || (p[0] > pa[0] && p[0] > pb[0] && p[0] > pc[0]) {
                continue;
            }
        }
        // The sign of the normal's x component; 0: the triangle contains
        // the ray direction, which the perturbed ray never crosses.
        let nx = orient2(verts, 0, a, b, c);
        if nx == Sign::Zero
            || orient2_perturbed(verts, tris, a, b, q) != nx
            || orient2_perturbed(verts, tris, b, c, q) != nx
            || orient2_perturbed(verts, tris, c, a, q) != nx
        {
            continue;
        }
        // The line through q along x meets the triangle: ahead of q iff q
        // lies on the side of the plane opposite the normal's x direction.
        match orient3_q(verts, tris, [a, b, c], q) {
            Sign::Zero => return Crossings::OnTriangle(t),
            s if s != nx => w += nx.as_i8() as i64,
            _ => {}
        }
    }
    Crossings::Winding(w)
}

/// Fails unless the winding number of the mesh is 0 or 1 everywhere
/// (nested shells alternate orientation; the outermost face outwards).
pub fn check_shells(
    verts: &[[f64; 3]],
    tris: &[[u32; 3]],
    edge_tris: &[[u32; 2]],
    tri_edges: &[[u32; 3]],
    nm: &NonManifold,
) -> Result<(), CutError> {
    let shells = shells(tris.len(), edge_tris, tri_edges, nm);
    if shells.len() < 2 {
        // One shell: its orientation is the mesh's, checked by the caller.
        return Ok(());
    }
    // Shells meet only where the mesh is not a manifold (a shared edge or
    // vertex): the winding of the others is asked at a vertex of a shell's
    // own, off every other shell.
    let mut owner = vec![u32::MAX; verts.len()];
    for (i, s) in shells.iter().enumerate() {
        for v in s.iter().flat_map(|&t| tris[t as usize]) {
            let o = &mut owner[v as usize];
            *o = if *o == u32::MAX || *o == i as u32 { i as u32 } else { u32::MAX - 1 };
        }
    }
    let boxes: Vec<[[f64; 3]; 2]> = shells
        .iter()
        .map(|s| {
            let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
            for v in s.iter().flat_map(|&t| tris[t as usize]) {
                for k in 0..3 {
                    b[0][k] = b[0][k].min(verts[v as usize][k]);
                    b[1][k] = b[1][k].max(verts[v as usize][k]);
                }
            }
            b
        })
        .collect();
    for (i, s) in shells.iter().enumerate() {
        let sign = match orientation(verts, tris, s) {
            Sign::Zero => return Err(CutError::FlatShell { shell: i, triangle: s[0] as usize }),
            x => x.as_i8() as i64,
        };
        let own = s.iter().flat_map(|&t| tris[t as usize]).find(|&v| owner[v as usize] == i as u32);
        let q = own.map_or(Query::Centroid(s[0]), Query::Vertex);
        // the points whose box the start point lies in: the vertex, or the
        // centroid's triangle
        let corners: Vec<[f64; 3]> = match own {
            Some(v) => vec![verts[v as usize]],
            None => tris[s[0] as usize].iter().map(|&v| verts[v as usize]).collect(),
        };
        let mut w = 0;
        let mut around = Vec::new();
        for (j, o) in shells.iter().enumerate() {
            let b = &boxes[j];
            let apart =
                (0..3).any(|k| corners.iter().all(|p| p[k] < b[0][k]) || corners.iter().all(|p| p[k] > b[1][k]));
            if j == i || apart {
                continue;
            }
            match winding(verts, tris, o, q) {
                Crossings::OnTriangle(t) => {
                    let vertex = own.unwrap_or(tris[s[0] as usize][0]) as usize;
                    return Err(CutError::ShellsTouch { vertex, triangle: t as usize });
                }
                Crossings::Winding(0) => {}
                Crossings::Winding(x) => {
                    w += x;
                    around.push(j);
                }
            }
        }
        if !(w == 0 && sign == 1 || w == 1 && sign == -1) {
            return Err(CutError::ShellWinding {
                shell: i,
                triangle: s[0] as usize,
                facing: if sign == 1 { "outwards" } else { "inwards" },
                around,
                winding: if w == 0 || w == 1 { w + sign } else { w },
            });
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "shells_tests.rs"]
mod tests;
