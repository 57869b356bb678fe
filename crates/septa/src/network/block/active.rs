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
    active_functions_with(ctx, t, tet, None, out)
}

/// [`active_functions`], given (MI) the unique strict maximum at each corner
/// when known (`boxfast.rs` labels every vertex of a block first).
pub(crate) fn active_functions_with(
    ctx: &Ctx,
    t: usize,
    tet: &[u32; 4],
    corner_winners: Option<[u64; 4]>,
    out: &mut Vec<u16>,
) -> Result<(), NetworkError> {
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
        Mode::Mi => mi_active(tet, ctx, corner_winners, out),
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
///
/// `corner_winners`: the unique strict maximum at each corner, if known;
/// then the functions maximal at some corner are exactly these.
fn mi_active(tet: &[u32; 4], ctx: &Ctx, corner_winners: Option<[u64; 4]>, out: &mut Vec<u16>) {
    let k = ctx.k;
    // The 4 corner rows, read once as slices (no copy from a block's
    // samples): the tests below compare every function at every corner.
    let mut bufs: [Vec<f64>; 4] = Default::default();
    let [b0, b1, b2, b3] = &mut bufs;
    let rows: [&[f64]; 4] = [ctx.row(tet[0], b0), ctx.row(tet[1], b1), ctx.row(tet[2], b2), ctx.row(tet[3], b3)];
    let at = |f: usize| [rows[0][f], rows[1][f], rows[2][f], rows[3][f]];
    let dominates = |g: usize, f: usize| (0..4).all(|i| rows[i][g] > rows[i][f]);
    if ctx.average_domination && k >= 3 {
        // The functions maximal at some corner, ascending (the order of the
        // sums below, so both ways give the same bits).
        let mut winners: SmallVec<[u16; 8]> = match corner_winners {
            Some(l) => l.iter().map(|&f| f as u16).collect(),
            None => {
                // Values are finite (checked when sampled).
                let max = rows.map(|r| r.iter().copied().fold(f64::NEG_INFINITY, |m, x| if x > m { x } else { m }));
                (0..k).filter(|&f| (0..4).any(|i| rows[i][f] == max[i])).map(|f| f as u16).collect()
            }
        };
        winners.sort_unstable();
        winners.dedup();
        if winners.len() >= 2 {
            let w_rows: SmallVec<[[f64; 4]; 8]> = winners.iter().map(|&w| at(w as usize)).collect();
            let sums = crate::complex::WinnerSums::new(&w_rows);
            // Below every winner at every corner: dominated by any winner
            // alone (exact comparisons), so the tests below would drop it too.
            let below = std::array::from_fn::<f64, 4, _>(|i| w_rows.iter().fold(f64::INFINITY, |m, w| m.min(w[i])));
            for f in 0..k {
                let r = at(f);
                if r[0] < below[0] && r[1] < below[1] && r[2] < below[2] && r[3] < below[3] {
                    continue;
                }
                // A winner is never dominated; the others may be by the
                // winners' average or by a single function.
                if winners.contains(&(f as u16)) || !(sums.dominates(&r) || (0..k).any(|g| g != f && dominates(g, f))) {
                    out.push(f as u16);
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
