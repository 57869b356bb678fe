//! Active functions of a tet (Du et al. Sec. 3): the functions whose
//! zero set (IA) or maximum boundary (MI) can meet the tet, decided exactly
//! from the values at its four corners.

use smallvec::SmallVec;

use super::types::Label;
use super::values::Ctx;
use crate::complex::Mode;
use crate::network::NetworkError;

/// The active functions of tet `t` (ascending): IA, those with a sign change
/// or a zero at its vertices; MI, those not strictly dominated at all 4.
pub(crate) fn active_functions(ctx: &Ctx, t: usize, tet: &[u32; 4], out: &mut Vec<u16>) -> Result<(), NetworkError> {
    out.clear();
    let k = ctx.k;
    match ctx.mode {
        Mode::Ia => {
            for f in 0..k {
                let r = tet.map(|v| ctx.val(v, f));
                if !(r.iter().all(|&x| x > 0.0) || r.iter().all(|&x| x < 0.0)) {
                    if r.iter().all(|&x| x == 0.0) {
                        return Err(NetworkError::VanishesOnTet { tet: t, function: f });
                    }
                    out.push(f as u16);
                }
            }
        }
        Mode::Mi => mi_active(tet, ctx, out),
    }
    Ok(())
}

/// IA sign bits at tet vertex 0 (every inactive function has one sign on the tet).
pub(crate) fn ia_base_label(tet: &[u32; 4], ctx: &Ctx) -> Label {
    let k = ctx.k;
    let mut l: Label = SmallVec::from_elem(0, k.div_ceil(64).max(1));
    for f in 0..k {
        if ctx.val(tet[0], f) > 0.0 {
            l[f / 64] |= 1 << (f % 64);
        }
    }
    l
}

/// MI active functions: those not strictly dominated at all 4 tet vertices,
/// by one function or (with `ctx.average_domination`) by the average of
/// the functions maximal at some vertex (complex/dominated.rs).
fn mi_active(tet: &[u32; 4], ctx: &Ctx, out: &mut Vec<u16>) {
    let k = ctx.k;
    // The 4 corner rows, read once as slices (no copy from a block's
    // samples): the tests below compare every function at every corner.
    let mut bufs: [Vec<f64>; 4] = Default::default();
    let [b0, b1, b2, b3] = &mut bufs;
    let rows: [&[f64]; 4] = [ctx.row(tet[0], b0), ctx.row(tet[1], b1), ctx.row(tet[2], b2), ctx.row(tet[3], b3)];
    let at = |f: usize| [rows[0][f], rows[1][f], rows[2][f], rows[3][f]];
    let dominates = |g: usize, f: usize| (0..4).all(|i| rows[i][g] > rows[i][f]);
    if ctx.average_domination && k >= 3 {
        let max = rows.map(|r| r.iter().copied().fold(f64::NEG_INFINITY, f64::max));
        let is_winner = |f: usize| (0..4).any(|i| rows[i][f] == max[i]);
        let winners: SmallVec<[[f64; 4]; 8]> = (0..k).filter(|&f| is_winner(f)).map(at).collect();
        if winners.len() >= 2 {
            let sums = crate::complex::WinnerSums::new(&winners);
            // Below every winner at every corner: dominated by any winner
            // alone (exact comparisons), so the tests below would drop it too.
            let below = std::array::from_fn::<f64, 4, _>(|i| winners.iter().fold(f64::INFINITY, |m, w| m.min(w[i])));
            for f in 0..k {
                let r = at(f);
                if (0..4).all(|i| r[i] < below[i]) {
                    continue;
                }
                let winner = is_winner(f);
                if winner || !sums.dominates(&r) {
                    // A winner is never dominated; the others still may be
                    // by a single function, as below.
                    if winner || !(0..k).any(|g| g != f && dominates(g, f)) {
                        out.push(f as u16);
                    }
                }
            }
            return;
        }
    }
    // A likely dominator: the maximum at vertex 0.
    let g0 = (0..k).fold(0, |b, f| if rows[0][f] > rows[0][b] { f } else { b });
    for f in 0..k {
        if f != g0 && dominates(g0, f) {
            continue;
        }
        if (0..k).any(|g| g != f && dominates(g, f)) {
            continue;
        }
        out.push(f as u16);
    }
}
