//! Triangulation of cut-faces without new vertices, for output (TopoCut
//! Sec. 6.3 "Trian"). Works on the floating-point embedding: holes are
//! joined to the outer boundary by a bridge edge (as in the paper's
//! multi-boundary post-processing), then ears are clipped with exact 2D
//! orientations of the projected doubles. This only shapes output files; no
//! combinatorial decision of the cut depends on it, and `verify` checks
//! the written result exactly.

use crate::cut::triangles::orient::orient2;
use septa_exact::Sign;

/// Triangles (vertex ids) covering a planar face given by its loops (outer
/// first, counter-clockwise about `normal`; holes clockwise).
pub fn triangulate(x: &[[f64; 3]], loops: &[Vec<u32>], normal: [f64; 3]) -> Vec<[u32; 3]> {
    if loops.len() == 1 && loops[0].len() == 3 {
        let l = &loops[0];
        return vec![[l[0], l[1], l[2]]];
    }
    let (k, poly) = bridged(x, loops, normal);
    ear_clip(x, k, normal[k] < 0.0, &poly)
}

/// Largest polygon (after bridging holes) given to [`triangulate_shaped`]:
/// its dynamic programme costs `O(n^3)` exact orientations.
pub const SHAPED_MAX: usize = 160;

/// Triangles covering a face like [`triangulate`], chosen among all
/// triangulations without new vertices to maximise the sum of the
/// logarithms of each triangle's smallest corner sine (dynamic programming
/// over the polygon's diagonals, each admitted by exact 2D orientations).
/// Ear clipping must cut some ear even where every ear is a sliver; along a
/// rounded chain of nearly collinear cut-vertices (a plane meeting a nearly
/// flat part of the surface) such a sliver's long side leaves the chain and
/// crosses the neighbouring face. The optimum fans the chain from a vertex
/// off it whenever one sees it. `None` when the polygon is larger than
/// [`SHAPED_MAX`] or has no triangulation in projection (not simple).
pub fn triangulate_shaped(x: &[[f64; 3]], loops: &[Vec<u32>], normal: [f64; 3]) -> Option<Vec<[u32; 3]>> {
    let (k, poly) = bridged(x, loops, normal);
    let n = poly.len();
    if !(3..=SHAPED_MAX).contains(&n) {
        return None;
    }
    let flip = normal[k] < 0.0;
    let o2 = |a: u32, b: u32, c: u32| {
        let s = orient2(x, k, a, b, c);
        if flip {
            s.flip()
        } else {
            s
        }
    };
    let (i2, j2) = ((k + 1) % 3, (k + 2) % 3);
    let between = |v: u32, a: u32, b: u32| {
        // v on the line a b (known): inside the closed segment, exactly
        let (pv, pa, pb) = (x[v as usize], x[a as usize], x[b as usize]);
        [i2, j2].iter().all(|&c| pv[c] >= pa[c].min(pb[c]) && pv[c] <= pa[c].max(pb[c]))
    };
    // closed segment intersection in projection
    let meets = |p: u32, q: u32, a: u32, b: u32| {
        // closed segments whose bounding boxes (in the projection) are
        // apart cannot meet: the exact test below would say so too, at the
        // price of four orientations (most boundary edges are far from a
        // candidate diagonal)
        let (pp, pq, pa, pb) = (x[p as usize], x[q as usize], x[a as usize], x[b as usize]);
        if [i2, j2].iter().any(|&c| pp[c].max(pq[c]) < pa[c].min(pb[c]) || pa[c].max(pb[c]) < pp[c].min(pq[c])) {
            return false;
        }
        let (s1, s2) = (o2(p, q, a), o2(p, q, b));
        let (s3, s4) = (o2(a, b, p), o2(a, b, q));
        if s1 != Sign::Zero && s1 == s2 || s3 != Sign::Zero && s3 == s4 {
            return false;
        }
        if s1 != Sign::Zero && s2 != Sign::Zero && s3 != Sign::Zero && s4 != Sign::Zero {
            return true;
        }
        (s1 == Sign::Zero && between(a, p, q))
            || (s2 == Sign::Zero && between(b, p, q))
            || (s3 == Sign::Zero && between(p, a, b))
            || (s4 == Sign::Zero && between(q, a, b))
    };
    // diagonal i-j strictly inside the polygon: in the cone of the corner
    // at i (O'Rourke, Computational Geometry in C, 1.6) and meeting no
    // boundary edge away from its own endpoints
    let diag = |i: usize, j: usize| -> bool {
        let (a, b) = (poly[i], poly[j]);
        if a == b {
            return false;
        }
        let (a0, a1) = (poly[(i + n - 1) % n], poly[(i + 1) % n]);
        let cone = if o2(a0, a, a1) != Sign::Negative {
            o2(a, b, a0) == Sign::Positive && o2(b, a, a1) == Sign::Positive
        } else {
            !(o2(a, b, a1) != Sign::Negative && o2(b, a, a0) != Sign::Negative)
        };
        cone && (0..n).all(|e| {
            let (c, d) = (poly[e], poly[(e + 1) % n]);
            c == a || c == b || d == a || d == b || !meets(a, b, c, d)
        })
    };
    let mut ok = vec![false; n * n];
    for i in 0..n {
        ok[i * n + (i + 1) % n] = true;
        ok[((i + 1) % n) * n + i] = true;
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let v = diag(i, j);
            ok[i * n + j] = v;
            ok[j * n + i] = v;
        }
    }
    let quality = |u: u32, v: u32, w: u32| {
        let p = [x[u as usize], x[v as usize], x[w as usize]];
        let e = |a: usize, b: usize| -> [f64; 3] { std::array::from_fn(|c| p[b][c] - p[a][c]) };
        let (ab, ac) = (e(0, 1), e(0, 2));
        let cr = [ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]];
        let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let twice_area = len(cr);
        let l = [len(ab), len(e(1, 2)), len(ac)];
        // smallest corner sine: 2A / (product of the two longest sides)
        let mut s = l;
        s.sort_by(f64::total_cmp);
        (twice_area / (s[1] * s[2]).max(f64::MIN_POSITIVE)).max(1e-300).ln()
    };
    // best[i][j]: best triangulation of the chain i..=j closed by i-j
    let mut best = vec![f64::NEG_INFINITY; n * n];
    let mut arg = vec![usize::MAX; n * n];
    for i in 0..n - 1 {
        best[i * n + i + 1] = 0.0;
    }
    for d in 2..n {
        for i in 0..n - d {
            let j = i + d;
            if !ok[i * n + j] {
                continue;
            }
            for m in i + 1..j {
                let (l, r) = (best[i * n + m], best[m * n + j]);
                if l == f64::NEG_INFINITY || r == f64::NEG_INFINITY {
                    continue;
                }
                if o2(poly[i], poly[m], poly[j]) != Sign::Positive {
                    continue;
                }
                let v = l + r + quality(poly[i], poly[m], poly[j]);
                if v > best[i * n + j] {
                    best[i * n + j] = v;
                    arg[i * n + j] = m;
                }
            }
        }
    }
    if best[n - 1] == f64::NEG_INFINITY {
        return None;
    }
    let mut out = Vec::with_capacity(n - 2);
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j - i < 2 {
            continue;
        }
        let m = arg[i * n + j];
        out.push([poly[i], poly[m], poly[j]]);
        stack.push((i, m));
        stack.push((m, j));
    }
    Some(out)
}

/// The projection axis (dropping the dominant normal component) and the
/// outer loop with every hole joined to it by a bridge edge.
fn bridged(x: &[[f64; 3]], loops: &[Vec<u32>], normal: [f64; 3]) -> (usize, Vec<u32>) {
    // project dropping the dominant normal axis, keeping orientation
    let k = (0..3).max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs())).unwrap();
    let (i, j) = if normal[k] >= 0.0 { ((k + 1) % 3, (k + 2) % 3) } else { ((k + 2) % 3, (k + 1) % 3) };
    let p = |v: u32| [x[v as usize][i], x[v as usize][j]];
    let mut poly: Vec<u32> = loops[0].clone();
    let mut holes: Vec<&Vec<u32>> = loops[1..].iter().collect();
    // bridge holes from the rightmost one inwards
    let maxx = |l: &Vec<u32>| l.iter().map(|&v| p(v)[0]).fold(f64::NEG_INFINITY, f64::max);
    holes.sort_by(|a, b| maxx(b).total_cmp(&maxx(a)));
    for (hi, h) in holes.iter().enumerate() {
        let (mi, &m) = h.iter().enumerate().max_by(|a, b| p(*a.1)[0].total_cmp(&p(*b.1)[0])).unwrap();
        let pm = p(m);
        // candidate outer vertices by distance; take the first visible one
        let mut cands: Vec<usize> = (0..poly.len()).collect();
        let d2 = |v: u32| {
            let q = p(v);
            (q[0] - pm[0]).powi(2) + (q[1] - pm[1]).powi(2)
        };
        cands.sort_by(|&a, &b| d2(poly[a]).total_cmp(&d2(poly[b])));
        // the bridge m -> c may cross no edge of the polygon so far, of this
        // hole or of a hole not yet bridged (two cavities cut by one plane
        // were bridged across each other), nor pass through a corner:
        // exact orientations of the projected doubles
        let rest = &holes[hi..];
        // a corner met twice (an earlier bridge ends there): the occurrence
        // whose interior angle holds the new bridge, or the bridges cross
        // at it (two holes bridged to one outer corner in the wrong order)
        let flip = normal[k] < 0.0;
        let o2 = |a: u32, b: u32, c: u32| if flip { orient2(x, k, a, b, c).flip() } else { orient2(x, k, a, b, c) };
        let in_cone = |c: usize| {
            let n = poly.len();
            let (a0, a, a1) = (poly[(c + n - 1) % n], poly[c], poly[(c + 1) % n]);
            if o2(a0, a, a1) != Sign::Negative {
                o2(a, m, a0) == Sign::Positive && o2(m, a, a1) == Sign::Positive
            } else {
                !(o2(a, m, a1) != Sign::Negative && o2(m, a, a0) != Sign::Negative)
            }
        };
        let visible = |c: usize| {
            let pc = poly[c];
            let edges = (0..poly.len())
                .map(|e| (poly[e], poly[(e + 1) % poly.len()]))
                .chain(rest.iter().flat_map(|l| (0..l.len()).map(move |e| (l[e], l[(e + 1) % l.len()]))));
            let corners = poly.iter().chain(rest.iter().copied().flatten());
            !edges.into_iter().any(|(a, b)| a != pc && b != pc && a != m && b != m && crosses(x, k, m, pc, a, b))
                && !corners.into_iter().any(|&v| v != pc && v != m && on_segment(x, k, m, pc, v))
                && (poly.iter().filter(|&&v| v == pc).count() == 1 || in_cone(c))
        };
        let c = cands.iter().copied().find(|&c| visible(c)).unwrap_or(cands[0]);
        let mut merged = Vec::with_capacity(poly.len() + h.len() + 2);
        merged.extend_from_slice(&poly[..=c]);
        for s in 0..=h.len() {
            merged.push(h[(mi + s) % h.len()]);
        }
        merged.extend_from_slice(&poly[c..]);
        poly = merged;
    }
    (k, poly)
}

/// Segments `p q` and `a b` (projected along axis `k`) cross at a point
/// inside both, exactly.
fn crosses(x: &[[f64; 3]], k: usize, p: u32, q: u32, a: u32, b: u32) -> bool {
    let o = |u: u32, v: u32, w: u32| orient2(x, k, u, v, w).as_i8();
    o(p, q, a) * o(p, q, b) < 0 && o(a, b, p) * o(a, b, q) < 0
}

/// Corner `v` lies on the closed segment `p q` (projected along axis `k`), exactly.
fn on_segment(x: &[[f64; 3]], k: usize, p: u32, q: u32, v: u32) -> bool {
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let (pp, pq, pv) = (x[p as usize], x[q as usize], x[v as usize]);
    orient2(x, k, p, q, v) == Sign::Zero
        && [i, j].iter().all(|&c| pv[c] >= pp[c].min(pq[c]) && pv[c] <= pp[c].max(pq[c]))
}

/// Ear clipping decided by exact 2D orientations of the projected doubles
/// (`tri_pair::orient2`, dropping axis `k`; `flip` when the projection reverses
/// the loop): an ear is strictly convex and holds no other corner in its
/// closed triangle, so on a simple projected polygon every triangle is
/// non-degenerate and none overlaps another (Meisters' two ears). Only a
/// polygon with no such ear (not simple in projection) falls back to the
/// least bad corner; the exact check (`verify`) then reports it.
///
/// The search for the next ear starts after the last one cut, not at the
/// polygon's first corner: on a convex polygon that cuts every other corner
/// in turn (a strip of compact triangles, then the same on what is left)
/// instead of a fan of slivers from one corner. A fan's triangles all share
/// that corner, so their boxes all overlap and every pair of them went
/// through the exact check's triangle-pair test: on nefertiti R20 the check
/// tested 2.59 M pairs with fans and 1.49 M with strips, and plate_genus9
/// R20's whole cut became 16% faster.
fn ear_clip(x: &[[f64; 3]], k: usize, flip: bool, poly: &[u32]) -> Vec<[u32; 3]> {
    let o2 = |a: u32, b: u32, c: u32| {
        let s = orient2(x, k, a, b, c);
        if flip {
            s.flip()
        } else {
            s
        }
    };
    // sine of the corner angle at v (floating point): among the exact ears
    // the first well-shaped one is cut, else the best. A rounded chain of
    // exactly collinear cut-vertices (along a plane-plane or mesh line) makes
    // ears of almost zero angle that would lie in a neighbouring face.
    let quality = |u: u32, v: u32, w: u32| {
        let (pu, pv, pw) = (x[u as usize], x[v as usize], x[w as usize]);
        let a: [f64; 3] = std::array::from_fn(|i| pu[i] - pv[i]);
        let b: [f64; 3] = std::array::from_fn(|i| pw[i] - pv[i]);
        let c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        let n = |p: [f64; 3]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        n(c) / (n(a) * n(b)).max(f64::MIN_POSITIVE)
    };
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let mut idx: Vec<u32> = poly.to_vec();
    let mut out = Vec::with_capacity(poly.len().saturating_sub(2));
    let mut start = 0;
    while idx.len() > 3 {
        let n = idx.len();
        let mut cut: Option<(usize, f64)> = None;
        let mut fallback = None;
        for a in (0..n).map(|i| (i + start) % n) {
            let (u, v, w) = (idx[(a + n - 1) % n], idx[a], idx[(a + 1) % n]);
            if o2(u, v, w) != Sign::Positive {
                continue;
            }
            fallback.get_or_insert(a);
            // a point outside the ear's box (in projection) is outside the
            // closed ear: compared before the orientations, the same answer
            let (pu, pv, pw) = (x[u as usize], x[v as usize], x[w as usize]);
            let lo = [pu[i].min(pv[i]).min(pw[i]), pu[j].min(pv[j]).min(pw[j])];
            let hi = [pu[i].max(pv[i]).max(pw[i]), pu[j].max(pv[j]).max(pw[j])];
            let blocked = idx.iter().any(|&q| {
                let pq = x[q as usize];
                pq[i] >= lo[0]
                    && pq[i] <= hi[0]
                    && pq[j] >= lo[1]
                    && pq[j] <= hi[1]
                    && q != u
                    && q != v
                    && q != w
                    && o2(u, v, q) != Sign::Negative
                    && o2(v, w, q) != Sign::Negative
                    && o2(w, u, q) != Sign::Negative
            });
            if !blocked {
                let qa = quality(u, v, w);
                if cut.is_none_or(|c| qa > c.1) {
                    cut = Some((a, qa));
                }
                if qa > 1e-3 {
                    break;
                }
            }
        }
        let cut = cut.map(|c| c.0);
        let a = cut.or(fallback).unwrap_or(0);
        out.push([idx[(a + n - 1) % n], idx[a], idx[(a + 1) % n]]);
        idx.remove(a);
        start = (a + 1) % (n - 1);
    }
    if idx.len() == 3 {
        out.push([idx[0], idx[1], idx[2]]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    }

    /// Two holes whose nearest outer corner is the same: the second bridge
    /// goes into the copy of the corner whose angle holds it, and the
    /// triangles cover the face once (every triangle counter-clockwise,
    /// their areas summing to the face's).
    #[test]
    fn two_holes_bridged_to_one_corner() {
        let x = [
            [0.0, 0.0, 0.0],
            [8.0, 0.0, 0.0],
            [8.0, 4.0, 0.0],
            [8.0, 8.0, 0.0],
            [0.0, 8.0, 0.0],
            // holes below and above y = 4, their rightmost corners (7, 3)
            // and (7, 5) both nearest to the outer corner (8, 4)
            [1.0, 1.0, 0.0],
            [1.0, 3.0, 0.0],
            [7.0, 3.0, 0.0],
            [6.0, 1.0, 0.0],
            [1.0, 5.0, 0.0],
            [1.0, 7.0, 0.0],
            [6.0, 7.0, 0.0],
            [7.0, 5.0, 0.0],
        ];
        let loops = [vec![0, 1, 2, 3, 4], vec![5, 6, 7, 8], vec![9, 10, 11, 12]];
        let t = triangulate(&x, &loops, [0.0, 0.0, 1.0]);
        let p = |v: u32| [x[v as usize][0], x[v as usize][1]];
        let area: f64 = t.iter().map(|f| cross(p(f[0]), p(f[1]), p(f[2])) / 2.0).sum();
        assert_eq!(area, 64.0 - 11.0 - 11.0);
        assert!(t.iter().all(|f| cross(p(f[0]), p(f[1]), p(f[2])) > 0.0), "{t:?}");
    }

    #[test]
    fn square_with_square_hole() {
        let x = [
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [4.0, 4.0, 0.0],
            [0.0, 4.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 3.0, 0.0],
            [3.0, 3.0, 0.0],
            [3.0, 1.0, 0.0],
        ];
        let t = triangulate(&x, &[vec![0, 1, 2, 3], vec![4, 5, 6, 7]], [0.0, 0.0, 1.0]);
        assert_eq!(t.len(), 8);
        let area: f64 = t
            .iter()
            .map(|f| {
                let p = |v: u32| [x[v as usize][0], x[v as usize][1]];
                cross(p(f[0]), p(f[1]), p(f[2])) / 2.0
            })
            .sum();
        assert!((area - 12.0).abs() < 1e-12, "{area}");
    }

    /// A nearly straight chain of five corners (bulging out by 1e-12) under
    /// one apex: every triangulation without slivers fans the chain from
    /// the apex, and the shaped one finds it (ear clipping cuts the apex
    /// first and must then clip slivers along the chain).
    #[test]
    fn shaped_fans_a_nearly_straight_chain() {
        let x = [
            [0.0, 0.0, 0.0],
            [1.0, -1e-12, 0.0],
            [2.0, -2e-12, 0.0],
            [3.0, -1e-12, 0.0],
            [4.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
        ];
        let loops = [vec![0, 1, 2, 3, 4, 5]];
        let t = triangulate_shaped(&x, &loops, [0.0, 0.0, 1.0]).unwrap();
        assert_eq!(t.len(), 4);
        assert!(t.iter().all(|f| f.contains(&5)), "{t:?}");
        let area: f64 = t
            .iter()
            .map(|f| {
                let p = |v: u32| [x[v as usize][0], x[v as usize][1]];
                cross(p(f[0]), p(f[1]), p(f[2])) / 2.0
            })
            .sum();
        assert!((area - 2.0).abs() < 1e-9, "{area}");
        // a polygon that is not simple in projection has no triangulation
        let bow = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(triangulate_shaped(&bow, &[vec![0, 1, 2, 3]], [0.0, 0.0, 1.0]).is_none());
    }
}
