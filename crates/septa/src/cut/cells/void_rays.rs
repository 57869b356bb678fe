//! Which cell encloses a void shell, decided exactly by a ray (TopoCut
//! Sec. 6.1 leaves nested shells to the cell's boundary; here every nesting
//! is resolved). A void (a shell of triangle pieces with negative volume:
//! a cavity, or the cavity around an island) lies in one open cell `A` of
//! the plane arrangement; when more than one positive cell of `A` could hold
//! it (an island in the cavity is in `A` too), the ray answers.
//!
//! The ray starts at the centroid `g` of a whole input triangle of the void
//! and runs along `+x` or `-x`, away from the cavity (the triangle faces
//! into the cavity, so the domain lies behind it). The neighbourhood of a
//! connected closed shell on its domain side is connected, so the region
//! just beyond `g` is the enclosing cell's. Walking the faces the ray
//! crosses in order, the side of each face the ray arrives from names the
//! region it was in: the first positive cell met while still in the void's
//! region is the answer; another void met there shares the cell (the walk
//! goes on). The ray leaves `A` through a face of the enclosing cell at the
//! latest, so the walk ends.
//!
//! Exactness: `g = (a + b + c) / 3` in homogeneous coordinates; the ray's
//! origin is perturbed symbolically to `g + (0, eps, eps^2)`, so it meets
//! no edge or vertex of any face and no face parallel to it, and every sign
//! below is the sign of the leading coefficient in `eps` of a polynomial in
//! the input doubles, evaluated by [`filtered_sign_bounded`].

use crate::cut::base::geom::{dot3, sub3, v3, Ctx, Def, V3};
use crate::cut::{CutCellMesh, Support};
use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// An exact sign of a polynomial in the input, written once over [`Ring`].
trait Expr {
    fn eval<R: Ring>(&self, c: &Ctx) -> R;
}

fn sign<E: Expr>(c: &Ctx, e: &E) -> Sign {
    filtered_sign_bounded(|| e.eval::<Bounded>(c), || e.eval::<Interval>(c), || e.eval::<Exact>(c))
}

/// Centroid of input triangle `t` as `(a + b + c, 3)`.
fn centroid<R: Ring>(c: &Ctx, t: u32) -> (V3<R>, R) {
    let [a, b, d] = c.tris[t as usize].map(|v| v3::<R>(&c.verts[v as usize]));
    ([0, 1, 2].map(|k| a[k].add(&b[k]).add(&d[k])), R::of(3.0))
}

/// `sign(A_k - G_k)` for cut-vertex `A` and the centroid `G` of `t`.
struct CoordCmp {
    a: Def,
    t: u32,
    k: usize,
}

impl Expr for CoordCmp {
    fn eval<R: Ring>(&self, c: &Ctx) -> R {
        let (ha, wa) = c.hom::<R>(self.a);
        let (hg, wg) = centroid::<R>(c, self.t);
        ha[self.k].mul(&wg).sub(&hg[self.k].mul(&wa)).mul(&wa).mul(&wg)
    }
}

/// `orient2d(A, B, G)` in the `(y, z)` coordinates: its sign.
struct Orient {
    a: Def,
    b: Def,
    t: u32,
}

impl Expr for Orient {
    fn eval<R: Ring>(&self, c: &Ctx) -> R {
        let (ha, wa) = c.hom::<R>(self.a);
        let (hb, wb) = c.hom::<R>(self.b);
        let (hg, wg) = centroid::<R>(c, self.t);
        // (B - A) and (G - A) scaled by wa wb and wa wg
        let by = hb[1].mul(&wa).sub(&ha[1].mul(&wb));
        let bz = hb[2].mul(&wa).sub(&ha[2].mul(&wb));
        let gy = hg[1].mul(&wa).sub(&ha[1].mul(&wg));
        let gz = hg[2].mul(&wa).sub(&ha[2].mul(&wg));
        // the value divided by wa^2 wb wg: the sign needs wb wg
        by.mul(&gz).sub(&bz.mul(&gy)).mul(&wb).mul(&wg)
    }
}

/// Winding number of the perturbed origin `g + (0, eps, eps^2)` about the
/// face's loops projected to `(y, z)`: `+1` when the face's normal has a
/// positive `x` component and the ray meets it, `-1` negative, 0 missed.
fn winding(c: &Ctx, out: &CutCellMesh, face: usize, t: u32) -> i32 {
    let mut w = 0;
    for l in &out.faces[face].loops {
        let n = l.len();
        // `above`: A_z > g_z + eps^2, i.e. A_z > g_z
        let above: Vec<bool> = l
            .iter()
            .map(|&v| sign(c, &CoordCmp { a: out.vertex_defs[v as usize], t, k: 2 }) == Sign::Positive)
            .collect();
        for i in 0..n {
            let j = (i + 1) % n;
            if above[i] == above[j] {
                continue;
            }
            let (a, b) = (out.vertex_defs[l[i] as usize], out.vertex_defs[l[j] as usize]);
            // orient2d(A, B, g') = O + eps (A_z - B_z) + eps^2 (B_y - A_y):
            // at O = 0 the sign is that of A_z - B_z (nonzero on a crossing)
            let up = above[j];
            let s = match sign(c, &Orient { a, b, t }) {
                Sign::Zero => {
                    if up {
                        Sign::Negative
                    } else {
                        Sign::Positive
                    }
                }
                s => s,
            };
            if up && s == Sign::Positive {
                w += 1;
            } else if !up && s == Sign::Negative {
                w -= 1;
            }
        }
    }
    w
}

/// The ray parameter `s` (along `+x`) where the perturbed ray meets the
/// support of a face: `s = (n0 + n1 eps + n2 eps^2) / den`, times 3.
fn hit<R: Ring>(c: &Ctx, s: Support, t: u32) -> ([R; 3], R) {
    let (hg, _) = centroid::<R>(c, t);
    let three = R::of(3.0);
    let (n, n0) = match s {
        Support::Plane(p) => {
            let n = c.pn::<R>(p);
            let d = R::of(c.planes[p as usize][3]);
            // n . (g + s e_x) + d = 0 with g = hg / 3
            let n0 = dot3(&n, &hg).add(&d.mul(&three)).neg();
            (n, n0)
        }
        Support::Tri(u) => {
            let n = c.tn_compute::<R>(u);
            let a = v3::<R>(&c.verts[c.tris[u as usize][0] as usize]);
            let a3 = [0, 1, 2].map(|k| a[k].mul(&three));
            (n.clone(), dot3(&n, &sub3(&a3, &hg)))
        }
    };
    ([n0, n[1].mul(&three).neg(), n[2].mul(&three).neg()], n[0].mul(&three))
}

/// `sign(coefficient k of s_f - s_h)`, or of `s_f` alone.
struct HitCmp {
    f: Support,
    h: Option<Support>,
    t: u32,
    k: usize,
}

impl Expr for HitCmp {
    fn eval<R: Ring>(&self, c: &Ctx) -> R {
        let (nf, df) = hit::<R>(c, self.f, self.t);
        match self.h {
            None => nf[self.k].mul(&df),
            Some(h) => {
                let (nh, dh) = hit::<R>(c, h, self.t);
                nf[self.k].mul(&dh).sub(&nh[self.k].mul(&df)).mul(&df).mul(&dh)
            }
        }
    }
}

/// The leading sign in `eps` of `s_f` (`h = None`) or of `s_f - s_h`.
fn hit_sign(c: &Ctx, f: Support, h: Option<Support>, t: u32) -> Sign {
    (0..3).map(|k| sign(c, &HitCmp { f, h, t, k })).find(|&s| s != Sign::Zero).unwrap_or(Sign::Zero)
}

/// `sign(n_t . e_x)` of input triangle `t`.
struct NormalX(u32);

impl Expr for NormalX {
    fn eval<R: Ring>(&self, c: &Ctx) -> R {
        c.tn_compute::<R>(self.0)[0].clone()
    }
}

/// What the ray from void `void` found.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Enclosing {
    /// The positive cell holding the void.
    Cell(u32),
    /// No whole input triangle of the void to start from, a tie between two
    /// faces at one point, or an inconsistent walk (not expected for valid
    /// input; reported as an unresolved void).
    Unknown,
}

/// The positive cell enclosing void cell `void` (faces `faces_of[void]`);
/// `is_void[k]` for every cell. `boxes[v]` encloses cut-vertex `v` (or is
/// `None`): faces whose boxes miss the ray are skipped before any exact test.
pub(crate) fn enclosing_cell(
    c: &Ctx,
    out: &CutCellMesh,
    void_faces: &[usize],
    void: u32,
    is_void: &[bool],
    boxes: &[Option<[Interval; 3]>],
) -> Enclosing {
    // a whole input triangle of the void, not parallel to the ray
    let start = void_faces.iter().copied().find_map(|fi| {
        let f = &out.faces[fi];
        let Support::Tri(t) = f.support else { return None };
        if f.loops.len() != 1 || f.loops[0].len() != 3 {
            return None;
        }
        let whole = f.loops[0]
            .iter()
            .all(|&v| matches!(out.vertex_defs[v as usize], Def::V(x) if c.tris[t as usize].contains(&x)));
        let nx = sign(c, &NormalX(t));
        (whole && nx != Sign::Zero).then_some((fi, t, nx))
    });
    let Some((f0, t, nx)) = start else { return Enclosing::Unknown };
    // into the domain: against the outward normal
    let along = nx.flip();
    let (hg, wg) = centroid::<Interval>(c, t);
    let g: [Interval; 3] = std::array::from_fn(|k| hg[k].div(&wg).unwrap_or(Interval { lo: f64::MIN, hi: f64::MAX }));
    // candidate faces: boxes that may hold the ray
    let mut hits: Vec<(usize, i32)> = Vec::new();
    for (fi, f) in out.faces.iter().enumerate() {
        if fi == f0 {
            continue;
        }
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut unknown = false;
        for &v in f.loops.iter().flatten() {
            match boxes.get(v as usize).copied().flatten() {
                Some(b) => {
                    for k in 0..3 {
                        lo[k] = lo[k].min(b[k].lo);
                        hi[k] = hi[k].max(b[k].hi);
                    }
                }
                None => unknown = true,
            }
        }
        if !unknown {
            let miss_yz = (1..3).any(|k| hi[k] < g[k].lo || lo[k] > g[k].hi);
            let behind = if along == Sign::Positive { hi[0] < g[0].lo } else { lo[0] > g[0].hi };
            if miss_yz || behind {
                continue;
            }
        }
        let w = winding(c, out, fi, t);
        if w == 0 {
            continue;
        }
        match hit_sign(c, f.support, None, t) {
            Sign::Zero => return Enclosing::Unknown,
            s if s == along => hits.push((fi, w)),
            _ => {}
        }
    }
    // in the order met along the ray
    let mut tie = false;
    hits.sort_by(|&(a, _), &(b, _)| {
        if a == b {
            return std::cmp::Ordering::Equal;
        }
        let s = hit_sign(c, out.faces[a].support, Some(out.faces[b].support), t);
        if s == Sign::Zero {
            tie = true;
        }
        // s_a - s_b along the ray direction
        match if along == Sign::Positive { s } else { s.flip() } {
            Sign::Negative => std::cmp::Ordering::Less,
            Sign::Positive => std::cmp::Ordering::Greater,
            Sign::Zero => a.cmp(&b),
        }
    });
    if tie {
        return Enclosing::Unknown;
    }
    // the walk: `group` holds the voids of the region the ray started in
    let mut group = vec![void];
    let mut in_group = true;
    for (fi, w) in hits {
        let cells = out.faces[fi].cells;
        // the loop normal points from cells[0] to cells[1]; its x sign is w's
        let forward = (w > 0) == (along == Sign::Positive);
        let (from, to) = if forward { (cells[0], cells[1]) } else { (cells[1], cells[0]) };
        if in_group {
            if from == u32::MAX {
                return Enclosing::Unknown;
            }
            if !is_void[from as usize] {
                return Enclosing::Cell(from);
            }
            if !group.contains(&from) {
                group.push(from);
            }
        }
        in_group = to != u32::MAX && group.contains(&to);
    }
    Enclosing::Unknown
}
