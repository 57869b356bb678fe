//! Cut-faces inside input triangles: each triangle is clipped by the planes
//! that cross it, in plane order, into convex pieces (the half-edge
//! structure `H(t)` of TopoCut Sec. 4, which for a triangle is a set of
//! convex polygons because every cut is a full plane).

use crate::cut::base::geom::{Ctx, Def};
use rayon::prelude::*;
use septa_exact::Sign;
use septa_exact::{Bounded, Ring};
use smallvec::SmallVec;

/// The line an edge of a piece lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeLine {
    /// Part of mesh edge `e`.
    Mesh(u32),
    /// Part of the intersection with plane `p`; the flag is true when the
    /// piece lies on the positive side of `p` (then the piece runs along
    /// `n_p x n_t`, see [`crate::cut::base::geom::LineDir::TriPlane`]).
    Plane(u32, bool),
}

/// A convex piece of a triangle, counter-clockwise about the outward normal.
#[derive(Clone, Debug)]
pub struct Piece {
    /// The triangle.
    pub tri: u32,
    /// Corners as face triples (merged into cut-vertices later).
    pub nodes: SmallVec<[Def; 6]>,
    /// Line of the edge from corner `i` to corner `i + 1`.
    pub lines: SmallVec<[EdgeLine; 6]>,
}

/// A piece during clipping, with bounded coordinates of its corners (a
/// filter for side tests; `None` when the filter could not bound them).
struct Work {
    tri: u32,
    nodes: SmallVec<[Def; 8]>,
    lines: SmallVec<[EdgeLine; 8]>,
    boxes: SmallVec<[Option<[Bounded; 3]>; 8]>,
}

/// Coordinates of a cut-vertex with proven error bounds ([`Bounded`]: a
/// few multiplications per operation, where the outward-rounded intervals
/// used before were a tenth of the cut of a cube by 20 random planes).
fn coords(c: &Ctx, d: Def) -> Option<[Bounded; 3]> {
    let (h, w) = c.hom::<Bounded>(d);
    Some([h[0].div(&w)?, h[1].div(&w)?, h[2].div(&w)?])
}

/// Side of a corner on plane `q`: a test on its bounded coordinates (a
/// strict sign only), then the full filtered predicate.
fn corner_side(c: &Ctx, d: Def, b: &Option<[Bounded; 3]>, q: u32) -> Sign {
    if let Def::V(v) = d {
        return Sign::from_i8(c.pv_sign(q, v));
    }
    if let Some(x) = b {
        let pl = &c.planes[q as usize];
        let v = Bounded::of(pl[3])
            .add(&Bounded::of(pl[0]).mul(&x[0]))
            .add(&Bounded::of(pl[1]).mul(&x[1]))
            .add(&Bounded::of(pl[2]).mul(&x[2]));
        match v.sign() {
            Some(s) if s != Sign::Zero => return s,
            _ => {}
        }
    }
    c.side(d, q)
}

/// Triangles clipped by one task into one list of pieces (a list per
/// triangle, then copied into one, was two allocations per triangle and
/// twice the pieces' pages on the large meshes).
const RUN: usize = 512;

/// Output of clipping all triangles.
pub struct Clipped {
    /// The pieces, triangle after triangle, in runs of [`RUN`] triangles'.
    runs: Vec<Vec<Piece>>,
    /// Interior cut-vertices of triangles with the planes through them
    /// (including planes containing the triangle), for line point lists.
    pub interior: Vec<(Def, SmallVec<[u32; 4]>)>,
}

impl Clipped {
    /// All pieces, triangle after triangle.
    pub fn pieces(&self) -> impl Iterator<Item = &Piece> {
        self.runs.iter().flatten()
    }

    /// The number of pieces.
    pub fn num_pieces(&self) -> usize {
        self.runs.iter().map(Vec::len).sum()
    }
}

/// What clipping one triangle works in, kept from triangle to triangle.
#[derive(Default)]
struct Scratch {
    work: Vec<Work>,
    polys: Vec<u32>,
    next: Vec<u32>,
    signs: Vec<Sign>,
    inner: Vec<(Def, SmallVec<[u32; 4]>)>,
}

/// Clips every triangle by the planes crossing it (in parallel; the
/// result is in triangle order whatever the thread count).
pub fn clip_all(c: &Ctx) -> Clipped {
    let nt = c.tris.len();
    let per: Vec<(Vec<Piece>, Vec<(Def, SmallVec<[u32; 4]>)>)> = (0..nt.div_ceil(RUN))
        .into_par_iter()
        .map(|k| {
            let (mut s, mut pieces, mut interior) = (Scratch::default(), Vec::new(), Vec::new());
            for t in k * RUN..(nt.min((k + 1) * RUN)) {
                clip_tri(c, t as u32, &mut s, &mut pieces, &mut interior);
            }
            (pieces, interior)
        })
        .collect();
    let mut interior = Vec::with_capacity(per.iter().map(|p| p.1.len()).sum());
    let mut runs = Vec::with_capacity(per.len());
    for (p, i) in per {
        runs.push(p);
        interior.extend(i);
    }
    Clipped { runs, interior }
}

/// Clips triangle `t`, appending its pieces and its interior cut-vertices.
fn clip_tri(c: &Ctx, t: u32, s: &mut Scratch, pieces: &mut Vec<Piece>, interior: &mut Vec<(Def, SmallVec<[u32; 4]>)>) {
    let np = c.planes.len() as u32;
    // the pieces are kept where they were made (`work`, several hundred
    // bytes each) and listed in order by index: a piece a plane does not
    // split stays in place instead of being moved once per plane
    let Scratch { work, polys, next, signs, inner } = s;
    work.clear();
    polys.clear();
    inner.clear();
    let tri = &c.tris[t as usize];
    let mut crossing: SmallVec<[u32; 16]> = SmallVec::new();
    let mut coplanar: SmallVec<[u32; 4]> = SmallVec::new();
    for p in 0..np {
        let s = tri.map(|v| c.pv_sign(p, v));
        if s.iter().any(|&x| x > 0) && s.iter().any(|&x| x < 0) {
            crossing.push(p);
        } else if s.iter().all(|&x| x == 0) {
            coplanar.push(p);
        }
    }
    work.push(Work {
        tri: t,
        nodes: tri.iter().map(|&v| Def::V(v)).collect(),
        boxes: tri.iter().map(|_| None).collect(),
        lines: c.tri_edges[t as usize].iter().map(|&e| EdgeLine::Mesh(e)).collect(),
    });
    polys.push(0);
    // planes through each interior vertex, local to this triangle (`inner`)
    for &q in &crossing {
        next.clear();
        for &w in polys.iter() {
            let poly = &work[w as usize];
            signs.clear();
            for (&n, bx) in poly.nodes.iter().zip(&poly.boxes) {
                let d = n;
                let s = corner_side(c, d, bx, q);
                if s == Sign::Zero {
                    if let Def::TPP(..) = d {
                        if let Some(e) = inner.iter_mut().find(|e| e.0 == n) {
                            if !e.1.contains(&q) {
                                e.1.push(q);
                            }
                        }
                    }
                }
                signs.push(s);
            }
            let pos = signs.contains(&Sign::Positive);
            let neg = signs.contains(&Sign::Negative);
            if !(pos && neg) {
                next.push(w);
                continue;
            }
            let mut a = Work { tri: t, nodes: SmallVec::new(), lines: SmallVec::new(), boxes: SmallVec::new() };
            let mut b = Work { tri: t, nodes: SmallVec::new(), lines: SmallVec::new(), boxes: SmallVec::new() };
            let mut a_on: SmallVec<[bool; 8]> = SmallVec::new();
            let mut b_on: SmallVec<[bool; 8]> = SmallVec::new();
            let n = poly.nodes.len();
            for i in 0..n {
                let j = (i + 1) % n;
                let (si, sj) = (signs[i], signs[j]);
                let line = poly.lines[i];
                let zero = si == Sign::Zero;
                if si != Sign::Negative {
                    a.nodes.push(poly.nodes[i]);
                    a.boxes.push(poly.boxes[i]);
                    a.lines.push(line);
                    a_on.push(zero);
                }
                if si != Sign::Positive {
                    b.nodes.push(poly.nodes[i]);
                    b.boxes.push(poly.boxes[i]);
                    b.lines.push(line);
                    b_on.push(zero);
                }
                if si.as_i8() * sj.as_i8() < 0 {
                    let x = match line {
                        EdgeLine::Mesh(e) => Def::EP(e, q),
                        EdgeLine::Plane(p, _) => {
                            let k = Def::TPP(t, p.min(q), p.max(q));
                            let mut z: SmallVec<[u32; 4]> = SmallVec::new();
                            z.push(p);
                            z.push(q);
                            inner.push((k, z));
                            k
                        }
                    };
                    let bx = coords(c, x);
                    for (piece, on) in [(&mut a, &mut a_on), (&mut b, &mut b_on)] {
                        piece.nodes.push(x);
                        piece.boxes.push(bx);
                        piece.lines.push(line);
                        on.push(true);
                    }
                }
            }
            // In a convex piece, an edge with both ends on q lies on q.
            for (piece, on, pos) in [(&mut a, &a_on, true), (&mut b, &b_on, false)] {
                let m = piece.nodes.len();
                for i in 0..m {
                    if on[i] && on[(i + 1) % m] {
                        let in_q = match piece.lines[i] {
                            EdgeLine::Mesh(e) => {
                                let [u, v] = c.edges[e as usize];
                                c.pv_sign(q, u) == 0 && c.pv_sign(q, v) == 0
                            }
                            EdgeLine::Plane(..) => false,
                        };
                        if !in_q {
                            piece.lines[i] = EdgeLine::Plane(q, pos);
                        }
                    }
                }
            }
            next.push(work.len() as u32);
            work.push(a);
            next.push(work.len() as u32);
            work.push(b);
        }
        std::mem::swap(polys, next);
    }
    for (k, mut z) in inner.drain(..) {
        z.extend(coplanar.iter().copied());
        interior.push((k, z));
    }
    pieces.extend(polys.iter().map(|&w| {
        let w = &work[w as usize];
        Piece { tri: w.tri, nodes: w.nodes.iter().copied().collect(), lines: w.lines.iter().copied().collect() }
    }));
}
