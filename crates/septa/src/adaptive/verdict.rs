//! The verdict on one tet: which terms matter (IA: every function; MI: the
//! differences of the functions that can win there) and whether every
//! sheet, pair and triple of them is certified (`certify.rs`).

use crate::complex::Mode;
use crate::scene::{Interval, Primitive};

use super::certify::{pair, sheet, triple, Miss, Sheet};
use super::term::{primitive_parts, Local, Term, Tet};

/// The outcome of the criterion on a tet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// No zero set of a relevant term meets the tet.
    Empty,
    /// Every sheet, pair and triple is certified.
    Certified,
    /// Not certified yet, with the first reason found.
    Refine(Miss),
}

/// One function's parts on the tet's box.
struct Parts {
    vals: [f64; 4],
    bound: Interval,
    g: [Interval; 3],
    centre: Interval,
    err: f64,
}

fn parts(f: &Primitive, tet: &Tet, vals: [f64; 4]) -> Option<Parts> {
    let (bound, g, err) = primitive_parts(f, tet.lo, tet.hi)?;
    let c = tet.centre();
    let fc = f.eval(c);
    Some(Parts { vals, bound, g, centre: Interval::new(fc - err, fc + err), err })
}

/// The criterion on a tet with corner values `vals[corner][function]`.
pub fn judge(functions: &[Primitive], mode: Mode, tet: &Tet, vals: [&[f64]; 4], tolerance: f64) -> Verdict {
    match mode {
        Mode::Ia => judge_ia(functions, tet, vals, tolerance),
        Mode::Mi => judge_mi(functions, tet, vals, tolerance),
    }
}

fn corner_vals(vals: &[&[f64]; 4], i: usize) -> [f64; 4] {
    [vals[0][i], vals[1][i], vals[2][i], vals[3][i]]
}

fn judge_ia(fs: &[Primitive], tet: &Tet, vals: [&[f64]; 4], tolerance: f64) -> Verdict {
    let mut crossing: Vec<usize> = Vec::new();
    for (i, f) in fs.iter().enumerate() {
        if f.bounds_interval(tet.lo, tet.hi).contains(0.0) {
            crossing.push(i);
        }
    }
    if crossing.is_empty() {
        return Verdict::Empty;
    }
    let mut terms = Vec::with_capacity(crossing.len());
    for &i in &crossing {
        let Some(p) = parts(&fs[i], tet, corner_vals(&vals, i)) else { return Verdict::Refine(Miss::NoBound) };
        let Some(t) = Term::new(tet, p.vals, p.bound, p.g, p.centre, p.err, Local::One(&fs[i]).affine()) else {
            return Verdict::Refine(Miss::NoBound);
        };
        terms.push(t);
    }
    let subs: Vec<Local<'_>> = crossing.iter().map(|&i| Local::One(&fs[i])).collect();
    let all: Vec<usize> = (0..terms.len()).collect();
    let pairs: Vec<(usize, usize)> = all.iter().flat_map(|&a| ((a + 1)..terms.len()).map(move |b| (a, b))).collect();
    let triples: Vec<[usize; 3]> = combos3(terms.len());
    if terms.len() >= 4 && !terms.iter().all(|t| t.affine) {
        return Verdict::Refine(Miss::Many);
    }
    check(tet, &terms, &subs, &pairs, &triples, tolerance)
}

fn combos3(n: usize) -> Vec<[usize; 3]> {
    let mut out = vec![];
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                out.push([a, b, c]);
            }
        }
    }
    out
}

fn check(
    tet: &Tet,
    terms: &[Term],
    subs: &[Local<'_>],
    pairs: &[(usize, usize)],
    triples: &[[usize; 3]],
    tolerance: f64,
) -> Verdict {
    let mut sheets: Vec<Option<Sheet>> = Vec::with_capacity(terms.len());
    for (t, s) in terms.iter().zip(subs) {
        if !t.crosses() {
            sheets.push(None);
            continue;
        }
        match sheet(tet, t, tolerance, *s) {
            Ok(sh) => sheets.push(Some(sh)),
            Err(m) => return Verdict::Refine(m),
        }
    }
    if sheets.iter().all(|s| s.is_none()) {
        return Verdict::Empty;
    }
    for &(a, b) in pairs {
        let (Some(sa), Some(sb)) = (sheets[a], sheets[b]) else { continue };
        if let Err(m) = pair(tet, (&terms[a], sa), (&terms[b], sb), tolerance, subs[a], subs[b]) {
            return Verdict::Refine(m);
        }
    }
    for tr in triples {
        if tr.iter().any(|&i| sheets[i].is_none()) {
            continue;
        }
        if let Err(m) = triple(tet, [&terms[tr[0]], &terms[tr[1]], &terms[tr[2]]], tolerance) {
            return Verdict::Refine(m);
        }
    }
    Verdict::Certified
}

/// MI: a function can win on the tet unless another one provably exceeds
/// it there (plain bounds, then the centred form of the difference).
fn judge_mi(fs: &[Primitive], tet: &Tet, vals: [&[f64]; 4], tolerance: f64) -> Verdict {
    let bounds: Vec<Interval> = fs.iter().map(|f| f.bounds_interval(tet.lo, tet.hi)).collect();
    let best_lo = bounds.iter().map(|b| b.lo).fold(f64::NEG_INFINITY, f64::max);
    let mut cand: Vec<usize> = (0..fs.len()).filter(|&i| bounds[i].hi >= best_lo).collect();
    if cand.len() <= 1 {
        return Verdict::Empty;
    }
    let mut ps: Vec<Parts> = Vec::with_capacity(cand.len());
    for &i in &cand {
        match parts(&fs[i], tet, corner_vals(&vals, i)) {
            Some(p) => ps.push(p),
            None => return Verdict::Refine(Miss::NoBound),
        }
    }
    let h: [f64; 3] = [0, 1, 2].map(|k| 0.5 * (tet.hi[k] - tet.lo[k]) * (1.0 + 1e-15));
    // Lower bound of f_a - f_b on the box.
    let lower = |a: &Parts, b: &Parts| -> f64 {
        let plain = a.bound.sub(b.bound).lo;
        let mut var = Interval::point(0.0);
        for k in 0..3 {
            var = var.add(a.g[k].sub(b.g[k]).abs().scale(h[k]));
        }
        let mv = a.centre.sub(b.centre).lo - var.hi;
        if mv.is_finite() {
            plain.max(mv)
        } else {
            plain
        }
    };
    let keep: Vec<bool> =
        (0..cand.len()).map(|i| !(0..cand.len()).any(|j| j != i && lower(&ps[j], &ps[i]) > 0.0)).collect();
    let mut kept = vec![];
    let mut kept_parts = vec![];
    for ((c, p), k) in cand.iter().zip(ps).zip(&keep) {
        if *k {
            kept.push(*c);
            kept_parts.push(p);
        }
    }
    cand = kept;
    let ps = kept_parts;
    if cand.len() <= 1 {
        return Verdict::Empty;
    }
    if cand.len() >= 5 {
        return Verdict::Refine(Miss::Many);
    }
    // Terms f_a - f_b for a < b among the candidates, in lexicographic order.
    let n = cand.len();
    let mut index = vec![vec![usize::MAX; n]; n];
    let mut terms = vec![];
    let mut subs: Vec<Local<'_>> = vec![];
    for a in 0..n {
        for b in a + 1..n {
            let (pa, pb) = (&ps[a], &ps[b]);
            let vals = [0, 1, 2, 3].map(|c| pa.vals[c] - pb.vals[c]);
            let bound = Interval::new(lower(pa, pb), -lower(pb, pa));
            let g = [0, 1, 2].map(|k| pa.g[k].sub(pb.g[k]));
            let local = Local::Diff(&fs[cand[a]], &fs[cand[b]]);
            let Some(t) = Term::new(tet, vals, bound, g, pa.centre.sub(pb.centre), pa.err + pb.err, local.affine())
            else {
                return Verdict::Refine(Miss::NoBound);
            };
            index[a][b] = terms.len();
            terms.push(t);
            subs.push(Local::Diff(&fs[cand[a]], &fs[cand[b]]));
        }
    }
    // Curves where three are equal: (f_a - f_b, f_a - f_c); points where four are.
    let mut pairs = vec![];
    let mut triples = vec![];
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                pairs.push((index[a][b], index[a][c]));
                for d in c + 1..n {
                    triples.push([index[a][b], index[a][c], index[a][d]]);
                }
            }
        }
    }
    check(tet, &terms, &subs, &pairs, &triples, tolerance)
}
