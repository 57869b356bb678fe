//! Non-manifold edges of a closed mesh (TopoCut App. C, eq. 18): an edge
//! with `2k` triangles, `k` running each way, bounds `k` wedges of the
//! domain (two solids sharing the edge: `k = 2`). The triangles are sorted
//! by their angle about the edge, exactly, and each is paired with the one
//! across the wedge of the domain it bounds ("`t_i, t_j` adjacent within
//! the domain"). Each pair then plays the part of the two triangles of a
//! manifold edge: the shells it connects, the side of a plane's boundary
//! curve on the edge (`mesh_status`), the fans around a vertex.
//!
//! Around the edge `u -> v` (`d = v - u`) a triangle running `u -> v` has
//! the outward normal `d x (apex - u)`, the direction of the turn about `d`,
//! so the sector just after it (counter-clockwise about `d`) is outside the
//! domain; after a triangle running `v -> u` it is inside. The edge is a
//! valid boundary iff the orientations alternate around it; then the inside
//! sectors run from each `v -> u` triangle to the next one.

use crate::cut::CutError;
use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

type V3<R> = [R; 3];

fn v3<R: Ring>(x: &[f64; 3]) -> V3<R> {
    [R::of(x[0]), R::of(x[1]), R::of(x[2])]
}

fn sub<R: Ring>(a: &V3<R>, b: &V3<R>) -> V3<R> {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

fn dot<R: Ring>(a: &V3<R>, b: &V3<R>) -> R {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}

fn cross<R: Ring>(a: &V3<R>, b: &V3<R>) -> V3<R> {
    [
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}

/// The edge `u -> v` and two apexes `a`, `b`.
struct Around<'a> {
    verts: &'a [[f64; 3]],
    u: u32,
    v: u32,
    a: u32,
    b: u32,
}

impl Around<'_> {
    fn parts<R: Ring>(&self) -> (V3<R>, V3<R>, V3<R>) {
        let p = |i: u32| v3::<R>(&self.verts[i as usize]);
        let u = p(self.u);
        (sub(&p(self.v), &u), sub(&p(self.a), &u), sub(&p(self.b), &u))
    }

    /// `d . (x_a x x_b)`: positive when `b` is less than half a turn
    /// counter-clockwise from `a` about `d`.
    fn turn<R: Ring>(&self) -> R {
        let (d, xa, xb) = self.parts::<R>();
        dot(&d, &cross(&xa, &xb))
    }

    /// The dot product of the parts of `x_a`, `x_b` across `d`, times `|d|^2`:
    /// positive when `a`, `b` lie in one half-plane bounded by the edge line.
    fn across<R: Ring>(&self) -> R {
        let (d, xa, xb) = self.parts::<R>();
        dot(&xa, &xb).mul(&dot(&d, &d)).sub(&dot(&xa, &d).mul(&dot(&xb, &d)))
    }
}

fn turn_sign(x: &Around) -> Sign {
    filtered_sign_bounded(|| x.turn::<Bounded>(), || x.turn::<Interval>(), || x.turn::<Exact>())
}

fn across_sign(x: &Around) -> Sign {
    filtered_sign_bounded(|| x.across::<Bounded>(), || x.across::<Interval>(), || x.across::<Exact>())
}

/// The apex of triangle `t` opposite the edge `u v`.
fn apex(tri: &[u32; 3], u: u32, v: u32) -> u32 {
    *tri.iter().find(|&&x| x != u && x != v).expect("a triangle of the edge")
}

/// Pairs the triangles around the non-manifold edge `u -> v` (`u < v`):
/// `sides` are `(triangle, runs u -> v)`, as many each way. Returns the
/// wedges of the domain as `[triangle running u -> v, triangle running
/// v -> u]`, counter-clockwise about `v - u` from the first triangle.
pub(crate) fn pair_wedges(
    verts: &[[f64; 3]],
    tris: &[[u32; 3]],
    u: u32,
    v: u32,
    sides: &[(u32, bool)],
) -> Result<Vec<[u32; 2]>, CutError> {
    let ap: Vec<u32> = sides.iter().map(|&(t, _)| apex(&tris[t as usize], u, v)).collect();
    let at = |i: usize, j: usize| Around { verts, u, v, a: ap[i], b: ap[j] };
    let overlap = |i: usize, j: usize| {
        let (a, b) = (sides[i].0.min(sides[j].0), sides[i].0.max(sides[j].0));
        CutError::SelfIntersection { first: a as usize, second: b as usize }
    };
    // the half-turn of each triangle from the first: 0 for angles in
    // [0, pi), 1 for [pi, 2 pi)
    let mut half = vec![0u8; sides.len()];
    for i in 1..sides.len() {
        half[i] = match turn_sign(&at(0, i)) {
            Sign::Positive => 0,
            Sign::Negative => 1,
            // in the plane of the first triangle: beside it (the two
            // overlap along the edge) or opposite (angle pi)
            Sign::Zero => match across_sign(&at(0, i)) {
                Sign::Positive => return Err(overlap(0, i)),
                _ => 1,
            },
        };
    }
    // insertion sort by (half, turn): a handful of triangles
    let mut order: Vec<usize> = (0..sides.len()).collect();
    for k in 1..order.len() {
        let mut j = k;
        while j > 0 {
            let (x, y) = (order[j - 1], order[j]);
            let before = if half[x] != half[y] {
                half[y] < half[x]
            } else if x == 0 {
                false
            } else {
                match turn_sign(&at(x, y)) {
                    // y is within half a turn after x: after it
                    Sign::Positive => false,
                    Sign::Negative => true,
                    Sign::Zero => return Err(overlap(x, y)),
                }
            };
            if !before {
                break;
            }
            order.swap(j - 1, j);
            j -= 1;
        }
    }
    // orientations alternate; the inside sector runs from each v -> u
    // triangle to the next
    let n = order.len();
    let mut wedges = Vec::with_capacity(n / 2);
    for k in 0..n {
        let (x, y) = (order[k], order[(k + 1) % n]);
        if sides[x].1 == sides[y].1 {
            return Err(CutError::EdgeWinding {
                a: u,
                b: v,
                first: sides[x].0 as usize,
                second: sides[y].0 as usize,
                count: n,
            });
        }
        if !sides[x].1 {
            wedges.push([sides[y].0, sides[x].0]);
        }
    }
    Ok(wedges)
}
