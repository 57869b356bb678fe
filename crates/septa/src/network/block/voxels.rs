//! Label volumes on their voxels: when the functions are a label volume's
//! indicators (1 for a vertex's label, 0 for every other one; every value
//! exact), a tet's complex is decided by the labels at its 4 corners, so
//! the per-tet work the general path does on `k` values per corner is
//! skipped:
//! - one label at the 4 corners: the tet is empty (that label strictly
//!   dominates every other one at all 4 corners, Du et al. Sec. 3);
//! - two labels `a < b`: the active functions are exactly `[a, b]` (each is
//!   1 at some corner, so neither is dominated; any other label is 0 at all
//!   4 corners, below the average of the corner winners, which is 1/2
//!   there: `complex::average_dominates`), never tied at a corner, so the
//!   tet is one polygon from the two-function template (`simple.rs`), with
//!   the same rows of values the general path would read;
//! - three or four labels: the general path (active functions, tables or
//!   the incremental construction).
//!
//! The output is the general path's, byte for byte: the same emission
//! functions run on the same values in the same tet order; debug builds
//! check the active functions against `active_functions` per tet.

use super::simple::{indicator_pair_tet, CubeCorners};
use super::state::State;
use super::values::Ctx;
use super::worker::Worker;
use crate::complex::Mode;
use crate::network::NetworkError;

/// Whether the run's values are label indicators that the rules above apply
/// to (MI with the average domination rule, or two labels in all).
pub(super) fn applies(ctx: &Ctx, some_vertex: u32) -> bool {
    ctx.mode == Mode::Mi && (ctx.average_domination || ctx.k == 2) && ctx.label(some_vertex).is_some()
}

/// Tet `t` with grid vertices `tet` and the labels `corners` at them (in
/// tet order), placed by `geometry`: emits it and returns true, or returns
/// false (3+ labels: the caller runs the general path, with `w.pair_hint`
/// left empty).
pub(super) fn indicator_tet(
    w: &mut Worker,
    ctx: &Ctx,
    st: &mut State,
    t: usize,
    tet: &[u32; 4],
    corners: [u64; 4],
    geometry: &CubeCorners,
) -> Result<bool, NetworkError> {
    let mut sorted = corners;
    sorted.sort_unstable();
    if sorted[0] == sorted[3] {
        if st.grouping {
            w.process_tet(ctx, st, t)?; // its region joins its neighbours
        }
        return Ok(true);
    }
    let distinct = 1 + (1..4).filter(|&c| sorted[c] != sorted[c - 1]).count();
    if distinct != 2 {
        return Ok(false);
    }
    let pair = [sorted[0] as u16, sorted[3] as u16];
    // The values are the indicators of the pair: decided by which corners
    // carry the lesser label (the two-function template's sign pattern).
    let pattern = (0..4).fold(0, |p, i| p | ((corners[i] == sorted[0]) as usize) << i);
    #[cfg(debug_assertions)]
    {
        let mut check = Vec::new();
        super::active::active_functions(ctx, t, tet, &mut check)?;
        debug_assert_eq!(check, pair, "active functions of tet {t}");
        debug_assert_eq!(*tet, ctx.grid.tet(t), "grid vertices of tet {t}");
    }
    st.out.active_tets += 1;
    if indicator_pair_tet(ctx, st, tet, &pair, pattern, geometry) {
        return Ok(true);
    }
    // Grouping, volumes or no tables: the general path, told the pair.
    st.out.active_tets -= 1;
    w.pair_hint = Some(pair);
    w.process_tet(ctx, st, t)?;
    w.pair_hint = None;
    Ok(true)
}
