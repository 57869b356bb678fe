//! Cut-faces inside input triangles: each triangle is clipped by the planes
//! that cross it, in plane order, into convex pieces (the half-edge
//! structure `H(t)` of TopoCut Sec. 4, which for a triangle is a set of
//! convex polygons because every cut is a full plane).

use super::geom::{Ctx, Def};
use super::nodes::Nodes;
use septa_exact::Sign;
use smallvec::SmallVec;

/// The line an edge of a piece lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeLine {
    /// Part of mesh edge `e`.
    Mesh(u32),
    /// Part of the intersection with plane `p`.
    Plane(u32),
}

/// A convex piece of a triangle, counter-clockwise about the outward normal.
#[derive(Clone, Debug)]
pub struct Piece {
    /// The triangle.
    pub tri: u32,
    /// Corner nodes.
    pub nodes: SmallVec<[u32; 8]>,
    /// Line of the edge from corner `i` to corner `i + 1`.
    pub lines: SmallVec<[EdgeLine; 8]>,
}

/// Output of clipping all triangles.
pub struct Clipped {
    /// All pieces.
    pub pieces: Vec<Piece>,
    /// Interior cut-vertices of triangles with the planes through them
    /// (including planes containing the triangle), for line point lists.
    pub interior: Vec<(u32, SmallVec<[u32; 4]>)>,
}

/// Clips every triangle by the planes crossing it.
pub fn clip_all(c: &Ctx, nodes: &mut Nodes) -> Clipped {
    let np = c.planes.len() as u32;
    let mut out = Clipped { pieces: Vec::new(), interior: Vec::new() };
    let mut polys: Vec<Piece> = Vec::new();
    let mut next: Vec<Piece> = Vec::new();
    let mut signs: Vec<Sign> = Vec::new();
    for (t, tri) in c.tris.iter().enumerate() {
        let t = t as u32;
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
        let first = Piece {
            tri: t,
            nodes: tri.iter().map(|&v| nodes.get(Def::V(v))).collect(),
            lines: c.tri_edges[t as usize].iter().map(|&e| EdgeLine::Mesh(e)).collect(),
        };
        polys.clear();
        polys.push(first);
        // planes through each interior vertex, local to this triangle
        let mut inner: Vec<(u32, SmallVec<[u32; 4]>)> = Vec::new();
        for &q in &crossing {
            next.clear();
            for poly in polys.drain(..) {
                signs.clear();
                for &n in &poly.nodes {
                    let d = nodes.defs[n as usize];
                    let s = c.side(d, q);
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
                let pos = signs.iter().any(|&s| s == Sign::Positive);
                let neg = signs.iter().any(|&s| s == Sign::Negative);
                if !(pos && neg) {
                    next.push(poly);
                    continue;
                }
                let mut a = Piece { tri: t, nodes: SmallVec::new(), lines: SmallVec::new() };
                let mut b = Piece { tri: t, nodes: SmallVec::new(), lines: SmallVec::new() };
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
                        a.lines.push(line);
                        a_on.push(zero);
                    }
                    if si != Sign::Positive {
                        b.nodes.push(poly.nodes[i]);
                        b.lines.push(line);
                        b_on.push(zero);
                    }
                    if si.as_i8() * sj.as_i8() < 0 {
                        let x = match line {
                            EdgeLine::Mesh(e) => nodes.get(Def::EP(e, q)),
                            EdgeLine::Plane(p) => {
                                let k = nodes.get(Def::TPP(t, p.min(q), p.max(q)));
                                let mut z: SmallVec<[u32; 4]> = SmallVec::new();
                                z.push(p);
                                z.push(q);
                                inner.push((k, z));
                                k
                            }
                        };
                        for (piece, on) in [(&mut a, &mut a_on), (&mut b, &mut b_on)] {
                            piece.nodes.push(x);
                            piece.lines.push(line);
                            on.push(true);
                        }
                    }
                }
                // In a convex piece, an edge with both ends on q lies on q.
                for (piece, on) in [(&mut a, &a_on), (&mut b, &b_on)] {
                    let m = piece.nodes.len();
                    for i in 0..m {
                        if on[i] && on[(i + 1) % m] {
                            let in_q = match piece.lines[i] {
                                EdgeLine::Mesh(e) => {
                                    let [u, v] = c.edges[e as usize];
                                    c.pv_sign(q, u) == 0 && c.pv_sign(q, v) == 0
                                }
                                EdgeLine::Plane(_) => false,
                            };
                            if !in_q {
                                piece.lines[i] = EdgeLine::Plane(q);
                            }
                        }
                    }
                }
                next.push(a);
                next.push(b);
            }
            std::mem::swap(&mut polys, &mut next);
        }
        for (k, mut z) in inner {
            z.extend(coplanar.iter().copied());
            out.interior.push((k, z));
        }
        out.pieces.extend(polys.drain(..));
    }
    out
}
