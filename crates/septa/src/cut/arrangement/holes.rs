//! Cut-faces with holes (TopoCut Sec. 2.2 and 6.1): a cut-face of a plane
//! may be bounded by several loops. Outer loops run counter-clockwise about
//! the plane normal, holes clockwise (decided exactly by the turn at the
//! smallest corner in a generic direction). A hole contains no point of another
//! plane (a line through it would also cross the face), so its face lies in
//! the same convex cell of the plane's line arrangement: candidates are the
//! outer loops with a compatible side on every other plane; when several
//! remain, an exact crossing-number test picks the innermost one containing
//! the hole.

use crate::cut::arrangement::plane_graph::{Ccw, PlaneLoop};
use crate::cut::base::geom::{Ctx, Def};
use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// Sign of `coord_k(b) - coord_k(a)`.
fn coord_cmp(c: &Ctx, a: Def, b: Def, k: usize) -> Sign {
    fn f<R: Ring>(c: &Ctx, a: Def, b: Def, k: usize) -> R {
        let (ha, wa) = c.hom::<R>(a);
        let (hb, wb) = c.hom::<R>(b);
        hb[k].mul(&wa).sub(&ha[k].mul(&wb)).mul(&wa).mul(&wb)
    }
    filtered_sign_bounded(|| f::<Bounded>(c, a, b, k), || f::<Interval>(c, a, b, k), || f::<Exact>(c, a, b, k))
}

/// Sign of `g . (b - a)` for a fixed direction `g` in general position with
/// respect to axis-aligned data (so ties, which need the exact path, are rare).
fn generic_cmp(c: &Ctx, a: Def, b: Def) -> Sign {
    const G: [f64; 3] = [0.7548776662466927, 0.5698402909980532, 0.324_717_957_244_746];
    fn f<R: Ring>(c: &Ctx, a: Def, b: Def) -> R {
        let (ha, wa) = c.hom::<R>(a);
        let (hb, wb) = c.hom::<R>(b);
        let g = [R::of(G[0]), R::of(G[1]), R::of(G[2])];
        let ga = ha[0].mul(&g[0]).add(&ha[1].mul(&g[1])).add(&ha[2].mul(&g[2]));
        let gb = hb[0].mul(&g[0]).add(&hb[1].mul(&g[1])).add(&hb[2].mul(&g[2]));
        gb.mul(&wa).sub(&ga.mul(&wb)).mul(&wa).mul(&wb)
    }
    filtered_sign_bounded(|| f::<Bounded>(c, a, b), || f::<Interval>(c, a, b), || f::<Exact>(c, a, b))
}

/// Position of the smallest corner in the order (g.x, x_i, x_j): a vertex of
/// the loop's convex hull.
fn lexmin(c: &Ctx, ccw: &Ccw, rep: &[Def], verts: &[u32]) -> usize {
    let mut best = 0;
    for m in 1..verts.len() {
        let (a, b) = (rep[verts[best] as usize], rep[verts[m] as usize]);
        let mut s = generic_cmp(c, a, b);
        if s == Sign::Zero {
            s = coord_cmp(c, a, b, ccw.i);
        }
        if s == Sign::Zero {
            s = coord_cmp(c, a, b, ccw.j);
        }
        if s == Sign::Negative {
            best = m;
        }
    }
    best
}

/// True when the loop runs counter-clockwise about the plane normal.
fn is_outer(c: &Ctx, ccw: &Ccw, rep: &[Def], l: &PlaneLoop) -> bool {
    let m = lexmin(c, ccw, rep, &l.verts);
    let n = l.verts.len();
    let turn = ccw.cross(c, l.dirs[(m + n - 1) % n], l.dirs[m]);
    (turn == Sign::Positive) != ccw.flip
}

/// Exact crossing number: is point `p` inside the loop (projected)?
fn contains(c: &Ctx, ccw: &Ccw, rep: &[Def], l: &PlaneLoop, p: Def) -> bool {
    let (i, j) = (ccw.i, ccw.j);
    // sign of (coord(a) - coord(p)) along axis k
    let above = |a: Def| coord_cmp(c, p, a, j) == Sign::Positive;
    let mut inside = false;
    let n = l.verts.len();
    for m in 0..n {
        let a = rep[l.verts[m] as usize];
        let b = rep[l.verts[(m + 1) % n] as usize];
        if above(a) == above(b) {
            continue;
        }
        // crossing of edge ab with the line y = p.y lies left of p?
        fn e<R: Ring>(c: &Ctx, a: Def, b: Def, p: Def, i: usize, j: usize) -> R {
            let (ha, aw) = c.hom::<R>(a);
            let (hb, bw) = c.hom::<R>(b);
            let (hp, pw) = c.hom::<R>(p);
            let (ax, ay, bx, by, px, py) = (&ha[i], &ha[j], &hb[i], &hb[j], &hp[i], &hp[j]);
            let t1 = ax.mul(&pw).sub(&px.mul(&aw)).mul(&by.mul(&aw).sub(&ay.mul(&bw)));
            let t2 = py.mul(&aw).sub(&ay.mul(&pw)).mul(&bx.mul(&aw).sub(&ax.mul(&bw)));
            // sign(E) * sign(B.y - A.y) = sign(N * pw * bw) * sign((by aw - ay bw) * aw * bw)
            let dy = by.mul(&aw).sub(&ay.mul(&bw)).mul(&aw).mul(&bw);
            t1.add(&t2).mul(&pw).mul(&bw).mul(&dy)
        }
        let s = filtered_sign_bounded(
            || e::<Bounded>(c, a, b, p, i, j),
            || e::<Interval>(c, a, b, p, i, j),
            || e::<Exact>(c, a, b, p, i, j),
        );
        if s == Sign::Negative {
            inside = !inside;
        }
    }
    inside
}

/// Sets `outer` of every loop; returns `(holes, holes needing a containment test)`.
pub fn assign_holes(c: &Ctx, p: u32, rep: &[Def], loops: &mut [PlaneLoop]) -> (usize, usize) {
    let pl = &c.planes[p as usize];
    let ccw = Ccw::new(&[pl[0], pl[1], pl[2]]);
    let outer: Vec<bool> = loops.iter().map(|l| l.has_line_edge || is_outer(c, &ccw, rep, l)).collect();
    let holes: Vec<usize> = (0..loops.len()).filter(|&k| !outer[k]).collect();
    for (k, l) in loops.iter_mut().enumerate() {
        l.outer = k as u32;
    }
    if holes.is_empty() {
        return (0, 0);
    }
    let np = c.planes.len() as u32;
    let others: Vec<u32> = (0..np).filter(|&q| q != p && c.planes_cross(p.min(q), p.max(q))).collect();
    let mut tested = 0;
    for &h in &holes {
        // side of the hole on each other plane
        let sig: Vec<Sign> = others
            .iter()
            .map(|&q| {
                loops[h]
                    .verts
                    .iter()
                    .map(|&v| c.side(rep[v as usize], q))
                    .find(|&s| s != Sign::Zero)
                    .unwrap_or(Sign::Zero)
            })
            .collect();
        let cands: Vec<usize> = (0..loops.len())
            .filter(|&k| outer[k])
            .filter(|&k| {
                others
                    .iter()
                    .zip(&sig)
                    .all(|(&q, &s)| s == Sign::Zero || loops[k].verts.iter().all(|&v| c.side(rep[v as usize], q) != -s))
            })
            .collect();
        let pick = if cands.len() == 1 {
            cands[0]
        } else {
            tested += 1;
            let pt = rep[loops[h].verts[lexmin(c, &ccw, rep, &loops[h].verts)] as usize];
            let inside: Vec<usize> = cands.iter().copied().filter(|&k| contains(c, &ccw, rep, &loops[k], pt)).collect();
            // innermost: the one whose corner lies inside every other candidate
            *inside
                .iter()
                .find(|&&x| {
                    let q = rep[loops[x].verts[0] as usize];
                    inside.iter().all(|&y| y == x || contains(c, &ccw, rep, &loops[y], q))
                })
                .or(inside.first())
                .unwrap_or(&h)
        };
        loops[h].outer = pick as u32;
    }
    (holes.len(), tested)
}
