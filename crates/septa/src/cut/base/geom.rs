//! The input faces (triangles and planes), cut-vertices as face triples
//! (TopoCut Sec. 3, eq. 2) in homogeneous coordinates, and every exact
//! predicate of the cut, each written once over [`Ring`] and evaluated by
//! [`filtered_sign_bounded`] (bounded-error filter, interval filter, exact
//! fallback).

use septa_exact::{filtered_sign, filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// A cut-vertex by the faces that define it (before merging equal points).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Def {
    /// An input vertex (a triangle triple).
    V(u32),
    /// Mesh edge `e` crossed strictly inside by plane `p` (`(T,T,P)`).
    EP(u32, u32),
    /// Triangle `t` and planes `p < q` meeting strictly inside `t` (`(T,P,P)`).
    TPP(u32, u32, u32),
    /// Three planes `p < q < r` (`(P,P,P)`).
    PPP(u32, u32, u32),
}

/// A line carrying cut-edges: a direction known exactly from input data.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LineDir {
    /// Mesh edge `e`, direction `v - u`.
    Mesh(u32),
    /// Triangle `t` in plane `p`, direction `n_p x n_t`.
    TriPlane(u32, u32),
    /// Planes `p, q`, direction `n_p x n_q`.
    PlanePlane(u32, u32),
}

/// Input data shared by every stage.
pub struct Ctx<'a> {
    /// Mesh vertices.
    pub verts: &'a [[f64; 3]],
    /// Mesh triangles (outward orientation).
    pub tris: &'a [[u32; 3]],
    /// Cut planes `a x + b y + c z + d = 0`.
    pub planes: &'a [[f64; 4]],
    /// Mesh edges `(u, v)` with `u < v`.
    pub edges: Vec<[u32; 2]>,
    /// For each triangle, the edge index of its side `k` (from corner `k` to `k+1`).
    pub tri_edges: Vec<[u32; 3]>,
    /// For each edge, the triangle containing it as `u -> v` and the one with
    /// `v -> u` (of a non-manifold edge: its first wedge).
    pub edge_tris: Vec<[u32; 2]>,
    /// Non-manifold edges (TopoCut App. C): every wedge of the domain at
    /// each, `[t with u -> v, t with v -> u]` (`input/wedges.rs`).
    pub wedges: rustc_hash::FxHashMap<u32, Vec<[u32; 2]>>,
    /// `pv[p * nv + v]`: sign of plane `p` at vertex `v` (App. B, eq. 13).
    pub pv: Vec<i8>,
    /// Triangle normals in interval arithmetic (the filter's copy of
    /// [`Ctx::tn`], computed once).
    pub tn_iv: Vec<[Interval; 3]>,
    /// Plane-pair line directions `n_p x n_q` in interval arithmetic,
    /// `pp_iv[p * np + q]` for `p < q` (the filter's copy of
    /// [`Ctx::line_dir`], computed once; empty: computed on each call).
    pub pp_iv: Vec<[Interval; 3]>,
    /// [`Ctx::tn_iv`] in [`Bounded`] arithmetic (the first filter's copy).
    pub tn_b: Vec<[Bounded; 3]>,
    /// [`Ctx::pp_iv`] in [`Bounded`] arithmetic (the first filter's copy).
    pub pp_b: Vec<[Bounded; 3]>,
}

/// A 3-vector over a ring.
pub type V3<R> = [R; 3];

#[inline]
pub(crate) fn v3<R: Ring>(x: &[f64; 3]) -> V3<R> {
    [R::of(x[0]), R::of(x[1]), R::of(x[2])]
}
#[inline]
pub(crate) fn sub3<R: Ring>(a: &V3<R>, b: &V3<R>) -> V3<R> {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}
#[inline]
pub(crate) fn dot3<R: Ring>(a: &V3<R>, b: &V3<R>) -> R {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}
#[inline]
pub(crate) fn cross3<R: Ring>(a: &V3<R>, b: &V3<R>) -> V3<R> {
    [
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}
#[inline]
pub(crate) fn scale3<R: Ring>(a: &V3<R>, s: &R) -> V3<R> {
    [a[0].mul(s), a[1].mul(s), a[2].mul(s)]
}
#[inline]
pub(crate) fn neg3<R: Ring>(a: &V3<R>) -> V3<R> {
    [a[0].neg(), a[1].neg(), a[2].neg()]
}

impl Ctx<'_> {
    /// Whether triangle `t` runs along its side edge `e` as `u -> v`.
    #[inline]
    pub fn runs_forward(&self, t: u32, e: u32) -> bool {
        let k = self.tri_edges[t as usize].iter().position(|&x| x == e).expect("a side of the triangle");
        self.tris[t as usize][k] == self.edges[e as usize][0]
    }

    /// Sign of plane `p` at mesh vertex `v` (precomputed table).
    #[inline]
    pub fn pv_sign(&self, p: u32, v: u32) -> i8 {
        self.pv[p as usize * self.verts.len() + v as usize]
    }

    /// Plane normal.
    #[inline]
    pub fn pn<R: Ring>(&self, p: u32) -> V3<R> {
        let q = &self.planes[p as usize];
        [R::of(q[0]), R::of(q[1]), R::of(q[2])]
    }

    /// Plane value `n . x + d` at a mesh vertex.
    #[inline]
    pub fn pval<R: Ring>(&self, p: u32, v: u32) -> R {
        let q = &self.planes[p as usize];
        let x = &self.verts[v as usize];
        R::of(q[3])
            .add(&R::of(q[0]).mul(&R::of(x[0])))
            .add(&R::of(q[1]).mul(&R::of(x[1])))
            .add(&R::of(q[2]).mul(&R::of(x[2])))
    }

    /// Outward (unnormalised) triangle normal `(b - a) x (c - a)`.
    #[inline]
    pub fn tn<R: Ring>(&self, t: u32) -> V3<R> {
        if let Some(v) = (&self.tn_iv[t as usize] as &dyn std::any::Any).downcast_ref::<V3<R>>() {
            return v.clone();
        }
        if let Some(v) = self.tn_b.get(t as usize).and_then(|v| (v as &dyn std::any::Any).downcast_ref::<V3<R>>()) {
            return v.clone();
        }
        self.tn_compute(t)
    }

    /// Outward triangle normal computed from the vertices.
    pub fn tn_compute<R: Ring>(&self, t: u32) -> V3<R> {
        let [a, b, c] = self.tris[t as usize];
        let a = v3::<R>(&self.verts[a as usize]);
        let b = v3::<R>(&self.verts[b as usize]);
        let c = v3::<R>(&self.verts[c as usize]);
        cross3(&sub3(&b, &a), &sub3(&c, &a))
    }

    /// Exact direction of a line.
    pub fn line_dir<R: Ring>(&self, l: LineDir) -> V3<R> {
        match l {
            LineDir::Mesh(e) => {
                let [u, v] = self.edges[e as usize];
                sub3(&v3(&self.verts[v as usize]), &v3(&self.verts[u as usize]))
            }
            LineDir::TriPlane(t, p) => cross3(&self.pn(p), &self.tn(t)),
            LineDir::PlanePlane(p, q) => {
                let i = p as usize * self.planes.len() + q as usize;
                if p < q {
                    if let Some(v) = self.pp_iv.get(i).and_then(|v| (v as &dyn std::any::Any).downcast_ref::<V3<R>>()) {
                        return v.clone();
                    }
                    if let Some(v) = self.pp_b.get(i).and_then(|v| (v as &dyn std::any::Any).downcast_ref::<V3<R>>()) {
                        return v.clone();
                    }
                }
                self.pp_compute(p, q)
            }
        }
    }

    /// Direction `n_p x n_q` of the line of planes `p` and `q`.
    pub fn pp_compute<R: Ring>(&self, p: u32, q: u32) -> V3<R> {
        cross3(&self.pn(p), &self.pn(q))
    }

    /// Homogeneous coordinates `(H, W)` of a cut-vertex: the point is `H / W`.
    pub fn hom<R: Ring>(&self, d: Def) -> (V3<R>, R) {
        match d {
            Def::V(v) => (v3(&self.verts[v as usize]), R::of(1.0)),
            Def::EP(e, p) => {
                let [u, v] = self.edges[e as usize];
                let pu = self.pval::<R>(p, u);
                let pvv = self.pval::<R>(p, v);
                let xu = v3::<R>(&self.verts[u as usize]);
                let xv = v3::<R>(&self.verts[v as usize]);
                // x = (p(u) v - p(v) u) / (p(u) - p(v))
                (sub3(&scale3(&xv, &pu), &scale3(&xu, &pvv)), pu.sub(&pvv))
            }
            Def::TPP(t, p, q) => {
                // App. B: x = a + l1 (b - a) + l2 (c - a), M (l1, l2)^T = rhs.
                let [a, b, c] = self.tris[t as usize];
                let a = v3::<R>(&self.verts[a as usize]);
                let e1 = sub3(&v3(&self.verts[b as usize]), &a);
                let e2 = sub3(&v3(&self.verts[c as usize]), &a);
                let (np, nq) = (self.pn::<R>(p), self.pn::<R>(q));
                let (dp, dq) = (R::of(self.planes[p as usize][3]), R::of(self.planes[q as usize][3]));
                let m00 = dot3(&np, &e1);
                let m01 = dot3(&np, &e2);
                let m10 = dot3(&nq, &e1);
                let m11 = dot3(&nq, &e2);
                let r0 = dp.add(&dot3(&np, &a)).neg();
                let r1 = dq.add(&dot3(&nq, &a)).neg();
                let det = m00.mul(&m11).sub(&m01.mul(&m10));
                let n1 = r0.mul(&m11).sub(&m01.mul(&r1));
                let n2 = m00.mul(&r1).sub(&r0.mul(&m10));
                let h = [0, 1, 2].map(|k| a[k].mul(&det).add(&e1[k].mul(&n1)).add(&e2[k].mul(&n2)));
                (h, det)
            }
            Def::PPP(p, q, r) => {
                // Cramer on the rows n_p, n_q, n_r with right-hand side -d.
                let n = [self.pn::<R>(p), self.pn::<R>(q), self.pn::<R>(r)];
                let d = [p, q, r].map(|i| R::of(-self.planes[i as usize][3]));
                let det = dot3(&n[0], &cross3(&n[1], &n[2]));
                let h = [0, 1, 2].map(|k| {
                    let col = |i: usize| -> V3<R> {
                        let mut row = n[i].clone();
                        row[k] = d[i].clone();
                        row
                    };
                    dot3(&col(0), &cross3(&col(1), &col(2)))
                });
                (h, det)
            }
        }
    }

    /// Side of a cut-vertex with respect to plane `r`.
    pub fn side(&self, d: Def, r: u32) -> Sign {
        if let Def::V(v) = d {
            return Sign::from_i8(self.pv_sign(r, v));
        }
        fn f<R: Ring>(c: &Ctx, d: Def, r: u32) -> R {
            let (h, w) = c.hom::<R>(d);
            let v = dot3(&c.pn::<R>(r), &h).add(&R::of(c.planes[r as usize][3]).mul(&w));
            v.mul(&w)
        }
        filtered_sign_bounded(|| f::<Bounded>(self, d, r), || f::<Interval>(self, d, r), || f::<Exact>(self, d, r))
    }

    /// Order of two cut-vertices along direction `dir`: sign of `(B - A) . dir`.
    pub fn order(&self, a: Def, b: Def, dir: LineDir) -> Sign {
        fn f<R: Ring>(c: &Ctx, a: Def, b: Def, dir: LineDir) -> R {
            let dv = c.line_dir::<R>(dir);
            let (ha, wa) = c.hom::<R>(a);
            let (hb, wb) = c.hom::<R>(b);
            // (hb/wb - ha/wa) . dv  ~  (hb.dv wa - ha.dv wb) * wa * wb
            let x = dot3(&hb, &dv).mul(&wa).sub(&dot3(&ha, &dv).mul(&wb));
            x.mul(&wa).mul(&wb)
        }
        filtered_sign_bounded(
            || f::<Bounded>(self, a, b, dir),
            || f::<Interval>(self, a, b, dir),
            || f::<Exact>(self, a, b, dir),
        )
    }

    /// Approximate coordinates of a cut-vertex (for output).
    pub fn approx(&self, d: Def) -> [f64; 3] {
        let (h, w) = self.hom::<Interval>(d);
        let w = w.mid();
        let guess = [h[0].mid() / w, h[1].mid() / w, h[2].mid() / w];
        if guess.iter().all(|x| x.is_finite()) {
            guess
        } else {
            let (h, w) = self.hom::<Exact>(d);
            let w = w.to_f64_approx();
            [h[0].to_f64_approx() / w, h[1].to_f64_approx() / w, h[2].to_f64_approx() / w]
        }
    }

    /// True when planes `p` and `q` are not parallel (`n_p x n_q != 0`).
    pub fn planes_cross(&self, p: u32, q: u32) -> bool {
        (0..3).any(|k| {
            filtered_sign(
                || cross3(&self.pn::<Interval>(p), &self.pn(q))[k],
                || cross3(&self.pn::<Exact>(p), &self.pn(q))[k].clone(),
            ) != Sign::Zero
        })
    }

    /// Sign of `det(n_p, n_q, n_r)`: nonzero iff the three planes meet in one point.
    pub fn det3(&self, p: u32, q: u32, r: u32) -> Sign {
        fn f<R: Ring>(c: &Ctx, p: u32, q: u32, r: u32) -> R {
            dot3(&c.pn::<R>(p), &cross3(&c.pn(q), &c.pn(r)))
        }
        filtered_sign_bounded(
            || f::<Bounded>(self, p, q, r),
            || f::<Interval>(self, p, q, r),
            || f::<Exact>(self, p, q, r),
        )
    }
}
