//! The floating-point embedding of the cut-cell mesh (TopoCut Sec. 6.1,
//! "Floating-point coordinates"): every cut-vertex is rounded from its
//! exact face triple, then moved by the paper's heuristic so that the
//! rounded mesh keeps the two kinds of order of the exact one:
//!
//! 1. **vertex-vertex**: along every mesh edge and plane-plane line the
//!    vertices advance in the exact line order;
//! 2. **vertex-face** (the sidedness of Eq. (13)): for every cut-face `f`
//!    and every cut-vertex `v` of a cell bounded by `f` that is near `f`
//!    (see [`embed`]) and not on `f`'s supporting plane, the rounded `v`
//!    lies strictly on the same side of that plane as the exact `v`.
//!
//! Both are decided exactly: the exact side from the vertex's face triple
//! ([`Ctx::side`] and the triangle form below), the side of the rounded
//! point by exact orientation predicates on its doubles (the supporting
//! plane is exact in doubles: a cut plane's coefficients or a triangle's
//! three input vertices). Floating point only proposes positions. A vertex
//! that fails is moved along the line direction, or along the face normal
//! towards the exact side, by the smallest power-of-two multiple of its ulp
//! that satisfies the check. Moves can break other checks of the same
//! vertex, so both checks are repeated on the moved vertices for at most
//! [`MAX_ROUNDS`] rounds; what is still wrong is counted, never hidden
//! (the paper notes these local moves need not reach a global embedding).

use crate::cut::base::geom::{dot3, sub3, v3, Ctx, Def, LineDir};
use crate::cut::embed::round::ulp;
use crate::cut::embed::side_filter::{overlap, radius, FloatPlane, GridItem, VertexGrid};
use crate::cut::embed::sides::{exact_side, float_side};
use crate::cut::CutCellMesh;
use crate::cut::Support;
use rayon::prelude::*;
use septa_exact::{filtered_sign, Exact, Interval, Sign};

/// Rounds of (sidedness moves, line-order repair) on the moved vertices.
pub const MAX_ROUNDS: usize = 8;
/// Doublings of a line-order move's step before giving up in the first
/// sweep (2^64 ulps is far beyond any rounding error, so reaching it means
/// the order cannot be met there).
const MAX_DOUBLINGS: usize = 64;
/// Doublings in the rounds: a move there stays within 2^8 ulps, well
/// inside the [`NEAR_ULPS`] margin that decided which faces are near.
const ROUND_DOUBLINGS: usize = 8;
/// How far (in ulps of its largest coordinate, beyond the distance of its
/// rounded position from its exact point) a vertex counts as near a face:
/// four times the largest single move of the rounds ([`ROUND_DOUBLINGS`]),
/// so a vertex that is not near a face does not cross it.
const NEAR_ULPS: f64 = 1024.0;

/// A line carrying cut-vertices in their exact order along `dir`.
#[derive(Clone, Debug)]
pub struct Line {
    /// The exact line direction.
    pub dir: LineDir,
    /// Output vertex ids in increasing order along `dir`.
    pub verts: Vec<u32>,
}

/// What the embedding did.
#[derive(Clone, Copy, Debug, Default)]
pub struct EmbedStats {
    /// Vertices moved to keep a line order.
    pub line_moved: usize,
    /// Vertices moved to keep a vertex-face side.
    pub sidedness_moved: usize,
    /// (vertex, supporting plane) pairs of a cell on the wrong side (or on
    /// the plane) after plain rounding and the line-order moves.
    pub sidedness_violations_rounded: usize,
    /// Such pairs still wrong after the rounds (expected 0).
    pub sidedness_violations: usize,
    /// Consecutive vertex pairs of a line still out of order (expected 0).
    pub line_order_violations: usize,
}

/// Exact sign of `(q - p) . dir` for double points `p`, `q` and an exact
/// line direction; `div` is `dir` in intervals (computed once per line).
fn step_sign(c: &Ctx, p: &[f64; 3], q: &[f64; 3], dir: LineDir, div: &[Interval; 3]) -> Sign {
    // Float filter: with d the midpoint of div (|d* - d| <= rad), each
    // difference rounded (relative error u) and a 3-term dot product
    // (error <= 3u (1 + 3u) sum|..| < 2 eps sum|..|), the value
    // sum fl(q - p)_k d_k errs from the exact one by at most
    // sum |fl(q - p)_k| (rad_k + 3 eps |d_k|) (+ underflow), bounded
    // with the same safety factors as the side filter.
    let mut g = 0.0;
    let mut b = 0.0;
    for k in 0..3 {
        let dk = div[k].mid();
        let rad = (div[k].hi - dk).max(dk - div[k].lo);
        let e = q[k] - p[k];
        g += e * dk;
        b += e.abs() * (rad * 1.001 + 3.0 * f64::EPSILON * dk.abs());
    }
    let b = b * 1.001 + 1e-300;
    if g > b {
        return Sign::Positive;
    }
    if g < -b {
        return Sign::Negative;
    }
    filtered_sign(
        || dot3(&sub3(&v3::<Interval>(q), &v3(p)), div),
        || dot3(&sub3(&v3::<Exact>(q), &v3(p)), &c.line_dir::<Exact>(dir)),
    )
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n.is_finite() && n > 0.0).then(|| v.map(|x| x / n))
}

/// Moves `x` along `sign * u` by the smallest power-of-two multiple of its
/// ulp for which `ok` holds (TopoCut Sec. 6.1: "the smallest double
/// floating-point change"); `None` when no such multiple is found.
fn push(x: [f64; 3], u: [f64; 3], sign: f64, doublings: usize, ok: impl Fn(&[f64; 3]) -> bool) -> Option<[f64; 3]> {
    let mut step = ulp(&x); // of the largest coordinate
    for _ in 0..doublings {
        let y = [0, 1, 2].map(|k| x[k] + sign * step * u[k]);
        if y.iter().all(|c| c.is_finite()) && ok(&y) {
            return Some(y);
        }
        step *= 2.0;
    }
    None
}

/// Keeps the exact order along one line: each consecutive pair must
/// advance along the line. The later vertex is pushed forward; an input
/// vertex (exact coordinates) is never moved, its predecessor is pushed
/// back instead. A few sweeps settle chains of backward pushes. Returns
/// the number of pairs still out of order.
fn enforce_line(
    c: &Ctx,
    x: &mut [[f64; 3]],
    pinned: &[bool],
    line: &Line,
    doublings: usize,
    moved: &mut Vec<u32>,
) -> usize {
    if line.verts.len() < 2 {
        return 0;
    }
    let div = c.line_dir::<Interval>(line.dir);
    let ok =
        |x: &[[f64; 3]], a: u32, b: u32| step_sign(c, &x[a as usize], &x[b as usize], line.dir, &div) == Sign::Positive;
    let Some(t) = unit(div.map(|i| i.mid())) else {
        return 0;
    };
    for _ in 0..4 {
        let mut changed = false;
        for w in line.verts.windows(2) {
            let (a, b) = (w[0], w[1]);
            if ok(x, a, b) {
                continue;
            }
            let pa = x[a as usize];
            let pb = x[b as usize];
            let fixed = if !pinned[b as usize] {
                push(pb, t, 1.0, doublings, |y| step_sign(c, &pa, y, line.dir, &div) == Sign::Positive).map(|y| (b, y))
            } else if !pinned[a as usize] {
                push(pa, t, -1.0, doublings, |y| step_sign(c, y, &pb, line.dir, &div) == Sign::Positive).map(|y| (a, y))
            } else {
                None
            };
            if let Some((v, y)) = fixed {
                x[v as usize] = y;
                moved.push(v);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    line.verts.windows(2).filter(|w| !ok(x, w[0], w[1])).count()
}

fn code(s: Support, np: usize) -> usize {
    match s {
        Support::Plane(p) => p as usize,
        Support::Tri(t) => np + t as usize,
    }
}

/// Cells whose faces times vertices are at most this are checked pair by
/// pair (their data is in cache); larger ones through a [`VertexGrid`].
const BRUTE: usize = 1 << 12;

/// A near (vertex, face) pair with the cached exact side (2: unknown).
type NearPair = (u32, u32, i8);

fn extent(b: &([f64; 3], [f64; 3])) -> f64 {
    (0..3).map(|k| b.1[k] - b.0[k]).fold(0.0, f64::max)
}

/// A (vertex, support) pair whose rounded vertex is not strictly on the
/// exact side, with that exact side.
type Bad = (u32, Support, Sign);

/// The embedding: `out.vertices` holds the rounded `out.vertex_defs` and
/// `boxes` enclose their exact points (both from [`round`]);
/// enforces the line orders along `lines`, then the sidedness of every
/// vertex of a cell against the supporting plane of every face of the cell
/// that it is near (`out.faces[..].cells` are the final cells).
///
/// Input vertices are left out: written at their exact points and never
/// moved, they are on their exact side of every plane (on armadillo R20
/// most vertices of a cell are input vertices; leaving them out took the
/// embedding from 74 to 49 ms).
///
/// "Near" (the paper checks "all the near faces"): the vertex's box, its
/// rounded position widened by its distance from its exact point and by
/// `NEAR_ULPS` (1024) ulps, meets the box of the face's vertex boxes. While
/// every vertex stays in its box, a vertex that is not near a face cannot
/// cross the face's polygon, so such a pair cannot invert anything.
/// Checking every pair of a cell instead would be quadratic in the cell's
/// size (545 M pairs on nefertiti R10, 2.2 s) and, between nearly coplanar
/// input triangles far apart, often infeasible in doubles.
pub fn embed(c: &Ctx, out: &mut CutCellMesh, boxes: &[Option<[Interval; 3]>], lines: &[Line]) -> EmbedStats {
    let nv = out.vertices.len();
    let np = c.planes.len();
    let defs = &out.vertex_defs;
    let pinned: Vec<bool> = defs.iter().map(|d| matches!(d, Def::V(_))).collect();
    let mut st = EmbedStats::default();
    let dbg = std::env::var_os("SEPTA_DEBUG").is_some();
    let t0 = std::time::Instant::now();
    // 1. line orders (the first half of the paper's heuristic)
    let mut line_moved: Vec<u32> = Vec::new();
    for l in lines {
        enforce_line(c, &mut out.vertices, &pinned, l, MAX_DOUBLINGS, &mut line_moved);
    }
    if dbg {
        eprintln!("embed lines {:.4}", t0.elapsed().as_secs_f64());
    }
    // 2. sidedness: the proven filter first, exact predicates on the rest
    let mut r: Vec<f64> = out.vertices.iter().zip(boxes).map(|(x, b)| radius(x, b)).collect();
    let (rlo, rhi): (Vec<[f64; 3]>, Vec<[f64; 3]>) = out
        .vertices
        .iter()
        .zip(&r)
        .map(|(x, &rv)| {
            let reach = rv + NEAR_ULPS * ulp(x);
            (x.map(|a| a - reach), x.map(|a| a + reach))
        })
        .unzip();
    let mut planes: Vec<Option<FloatPlane>> = vec![None; np + c.tris.len()];
    let mut cell_faces: Vec<Vec<u32>> = vec![Vec::new(); out.num_cells];
    for (i, f) in out.faces.iter().enumerate() {
        let k = code(f.support, np);
        if planes[k].is_none() {
            planes[k] = Some(FloatPlane::of(c, f.support));
        }
        for &cell in f.cells.iter().filter(|&&x| x != u32::MAX) {
            cell_faces[cell as usize].push(i as u32);
        }
    }
    // each face's box and sorted vertices (its vertices lie on its plane)
    let face_box: Vec<([f64; 3], [f64; 3])> = out
        .faces
        .par_iter()
        .map(|f| {
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for &v in f.loops.iter().flatten() {
                for k in 0..3 {
                    lo[k] = lo[k].min(rlo[v as usize][k]);
                    hi[k] = hi[k].max(rhi[v as usize][k]);
                }
            }
            (lo, hi)
        })
        .collect();
    // a near pair fails when the rounded point is not strictly on the exact
    // side; `known` caches the exact side (2: not yet computed)
    let check = |x: &[[f64; 3]], r: &[f64], v: u32, fi: u32, known: &mut i8| -> Option<Bad> {
        let s = out.faces[fi as usize].support;
        let fp = planes[code(s, np)].as_ref().unwrap();
        if fp.box_sign(&x[v as usize], &[r[v as usize]; 3]).is_some() {
            return None;
        }
        if *known == 2 {
            *known = exact_side(c, defs[v as usize], s).as_i8();
        }
        let e = Sign::from_i8(*known);
        (e != Sign::Zero && float_side(c, &x[v as usize], s) != e).then_some((v, s, e))
    };
    if dbg {
        eprintln!("embed setup {:.4}", t0.elapsed().as_secs_f64());
    }
    let x = &out.vertices;
    // per cell: its vertices near each of its faces, by brute force on
    // small cells and through a grid of buckets on large ones; with the
    // pairs the float filter leaves undecided
    let per_cell: Vec<(Vec<NearPair>, Vec<u32>)> = cell_faces
        .par_iter()
        .map(|fs| {
            // an input vertex is written at its exact point and never
            // moved, so it is on its exact side of every plane: only
            // cut-vertices can fail
            let mut vs: Vec<u32> = fs
                .iter()
                .flat_map(|&i| out.faces[i as usize].loops.iter().flatten().copied())
                .filter(|&v| !pinned[v as usize])
                .collect();
            vs.sort_unstable();
            vs.dedup();
            let (items, wild): (Vec<GridItem>, Vec<GridItem>) =
                vs.iter().map(|&v| (v, rlo[v as usize], rhi[v as usize])).partition(|it| r[it.0 as usize].is_finite());
            let (mut pairs, mut open) = (Vec::new(), Vec::new());
            let mut near = |it: &GridItem, fi: u32| {
                let (flo, fhi) = &face_box[fi as usize];
                // a face's own vertices lie on its plane
                if overlap(&it.1, &it.2, flo, fhi) && !out.faces[fi as usize].loops.iter().flatten().any(|&u| u == it.0)
                {
                    let fp = planes[code(out.faces[fi as usize].support, np)].as_ref().unwrap();
                    if fp.box_sign(&x[it.0 as usize], &[r[it.0 as usize]; 3]).is_none() {
                        open.push(pairs.len() as u32);
                    }
                    pairs.push((it.0, fi, 2));
                }
            };
            if fs.len() * items.len() <= BRUTE {
                fs.iter().for_each(|&fi| items.iter().for_each(|it| near(it, fi)));
            } else {
                let mut ext: Vec<f64> = fs.iter().map(|&fi| extent(&face_box[fi as usize])).collect();
                let mid = ext.len() / 2;
                let h = 2.0 * *ext.select_nth_unstable_by(mid, f64::total_cmp).1;
                let grow = items.iter().map(|it| it.2[0] - it.1[0]).fold(0.0, f64::max);
                let grid = VertexGrid::new(items, h);
                for &fi in fs {
                    let (flo, fhi) = &face_box[fi as usize];
                    let (qlo, qhi) = (flo.map(|a| a - grow), fhi.map(|a| a + grow));
                    if !grid.query(&qlo, &qhi, |it| near(it, fi)) {
                        grid.items().iter().for_each(|it| near(it, fi));
                    }
                }
            }
            fs.iter().for_each(|&fi| wild.iter().for_each(|it| near(it, fi)));
            (pairs, open)
        })
        .collect();
    // the exact side of each undecided (vertex, supporting plane) once: a
    // vertex meets the same plane through both cells of a face and through
    // the several pieces of one input triangle
    let mut sides: Vec<(u32, usize, u32, i8)> = per_cell
        .iter()
        .flat_map(|(p, open)| open.iter().map(|&i| p[i as usize]))
        .map(|(v, fi, _)| (v, code(out.faces[fi as usize].support, np), fi, 2))
        .collect();
    sides.sort_unstable_by_key(|k| (k.0, k.1));
    sides.dedup_by_key(|k| (k.0, k.1));
    sides
        .par_iter_mut()
        .for_each(|(v, _, fi, e)| *e = exact_side(c, defs[*v as usize], out.faces[*fi as usize].support).as_i8());
    let side_of = |v: u32, fi: u32| {
        let k = (v, code(out.faces[fi as usize].support, np));
        sides[sides.binary_search_by_key(&k, |s| (s.0, s.1)).unwrap()].3
    };
    let per_cell: Vec<Vec<NearPair>> = per_cell
        .into_iter()
        .map(|(mut pairs, open)| {
            for &i in &open {
                let (v, fi, known) = &mut pairs[i as usize];
                *known = side_of(*v, *fi);
            }
            pairs
        })
        .collect();
    // a near pair fails when its rounded point is not strictly on the exact side
    let mut bad: Vec<Bad> = sides
        .iter()
        .filter_map(|&(v, _, fi, e)| {
            let (s, e) = (out.faces[fi as usize].support, Sign::from_i8(e));
            (e != Sign::Zero && float_side(c, &x[v as usize], s) != e).then_some((v, s, e))
        })
        .collect();
    if dbg {
        eprintln!("embed pairs {:.4} (exact sides {})", t0.elapsed().as_secs_f64(), sides.len());
    }
    let key = |b: &Bad| (b.0, code(b.1, np));
    bad.sort_unstable_by_key(key);
    bad.dedup_by_key(|b| key(b));
    st.sidedness_violations_rounded = bad.len();
    // 3. rounds on the moved vertices only: every other pair passed above
    // and neither its vertex nor the face boxes have moved
    let mut side_moved: Vec<u32> = Vec::new();
    let mut lines_of = Vec::new();
    let (mut start, mut flat) = (vec![0u32; nv + 1], Vec::new());
    if !bad.is_empty() {
        // the near faces of each vertex, compressed rows
        let all = || per_cell.iter().flatten();
        all().for_each(|&(v, _, _)| start[v as usize + 1] += 1);
        for i in 0..nv {
            start[i + 1] += start[i];
        }
        flat = vec![(0u32, 0i8); start[nv] as usize];
        let mut fill = start.clone();
        for &(v, fi, known) in all() {
            flat[fill[v as usize] as usize] = (fi, known);
            fill[v as usize] += 1;
        }
        lines_of = vec![Vec::new(); nv];
        for (k, l) in lines.iter().enumerate() {
            l.verts.iter().for_each(|&v| lines_of[v as usize].push(k as u32));
        }
    }

    for round in 0..MAX_ROUNDS {
        if bad.is_empty() {
            break;
        }
        let tried: Vec<u32> = bad.iter().map(|b| b.0).collect();
        // a round that leaves more violations than it found is undone
        let undo = (out.vertices.clone(), bad.clone(), side_moved.len(), line_moved.len());
        let mut now: Vec<u32> = Vec::new();
        for &(v, s, e) in &bad {
            let xv = out.vertices[v as usize];
            if float_side(c, &xv, s) == e {
                continue; // fixed by an earlier move of this round
            }
            let Some(u) = unit(planes[code(s, np)].as_ref().unwrap().n) else { continue };
            // along the face normal towards the exact side (Sec. 6.1)
            let sign = if e == Sign::Positive { 1.0 } else { -1.0 };
            if let Some(y) = push(xv, u, sign, ROUND_DOUBLINGS, |y| float_side(c, y, s) == e) {
                out.vertices[v as usize] = y;
                now.push(v);
                side_moved.push(v);
            }
        }
        // the moved vertices' line orders, then their radii
        let mut touched: Vec<u32> = now.iter().flat_map(|&v| lines_of[v as usize].iter().copied()).collect();
        touched.sort_unstable();
        touched.dedup();
        let mut repaired: Vec<u32> = Vec::new();
        for &k in &touched {
            enforce_line(c, &mut out.vertices, &pinned, &lines[k as usize], ROUND_DOUBLINGS, &mut repaired);
        }
        line_moved.extend(repaired.iter().copied());
        now.extend(repaired);
        let moved_now = now.len();
        now.extend(tried); // recounted even when no move helped
        now.sort_unstable();
        now.dedup();
        for &v in &now {
            r[v as usize] = radius(&out.vertices[v as usize], &boxes[v as usize]);
        }
        let x = &out.vertices;
        let before = bad.len();
        bad.clear();
        for &v in &now {
            for (fi, known) in &mut flat[start[v as usize] as usize..start[v as usize + 1] as usize] {
                bad.extend(check(x, &r, v, *fi, known));
            }
        }
        bad.sort_unstable_by_key(key);
        bad.dedup_by_key(|b| key(b));
        if dbg {
            eprintln!("embed round {round}: moved {moved_now}, violations {before} -> {}", bad.len());
        }
        if bad.len() > before {
            (out.vertices, bad) = (undo.0, undo.1);
            side_moved.truncate(undo.2);
            line_moved.truncate(undo.3);
            break;
        }
        if bad.len() == before {
            break; // no progress: the rest is beyond these local moves
        }
    }
    st.sidedness_violations = bad.len();
    if dbg {
        for b in bad.iter().take(6) {
            let fp = planes[code(b.1, np)].as_ref().unwrap();
            let n = unit(fp.n).unwrap_or([0.0; 3]);
            let p = out.vertices[b.0 as usize];
            let dist = (fp.n[0] * p[0] + fp.n[1] * p[1] + fp.n[2] * p[2] + fp.d)
                / (fp.n.iter().map(|a| a * a).sum::<f64>()).sqrt();
            eprintln!("bad {:?} {:?} {:?} at {:?} normal {:?} dist {dist:e}", b.0, defs[b.0 as usize], b.1, p, n);
        }
    }
    side_moved.sort_unstable();
    side_moved.dedup();
    line_moved.sort_unstable();
    line_moved.dedup();
    st.sidedness_moved = side_moved.len();
    st.line_moved = line_moved.len();
    // lines with no moved vertex passed every check in step 1
    if !line_moved.is_empty() || !side_moved.is_empty() {
        let mut m = vec![false; nv];
        line_moved.iter().chain(&side_moved).for_each(|&v| m[v as usize] = true);
        st.line_order_violations = lines
            .iter()
            .filter(|l| l.verts.iter().any(|&v| m[v as usize]))
            .map(|l| {
                let div = c.line_dir::<Interval>(l.dir);
                let x = &out.vertices;
                let ok = |w: &[u32]| step_sign(c, &x[w[0] as usize], &x[w[1] as usize], l.dir, &div) == Sign::Positive;
                l.verts.windows(2).filter(|w| !ok(w)).count()
            })
            .sum();
    }
    st
}
