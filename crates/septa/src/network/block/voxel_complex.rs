//! The complexes of label-volume tets (indicator values, `voxels.rs`),
//! built once per distinct set of corner values and copied after; called
//! by the per-tet worker, below the voxel fast path that calls the worker.

use rustc_hash::FxHashMap;

use super::values::Ctx;
use crate::complex::{BuildError, Complex, Mode};

/// `complex.build(ctx.mode, vals, ..)`, for label indicators taken from
/// `built` when the same corner values were met before: the values of a
/// tet with 3 or 4 labels are indicators (0 or 1), so only a few hundred
/// distinct value sets occur, and `Complex::build` depends on nothing else
/// (a 128^3 volume has over a thousand such tets, each a full incremental
/// construction before).
pub(super) fn build_complex(
    complex: &mut Complex,
    built: &mut FxHashMap<Vec<u64>, Complex>,
    ctx: &Ctx,
    tet: &[u32; 4],
    vals: &[[f64; 4]],
) -> Result<(), BuildError> {
    if !(ctx.mode == Mode::Mi && ctx.label(tet[0]).is_some()) {
        return complex.build(ctx.mode, vals, &ctx.options);
    }
    let key: Vec<u64> = vals.iter().flat_map(|r| r.map(f64::to_bits)).collect();
    match built.get(&key) {
        Some(c) => complex.clone_from(c),
        None => {
            complex.build(ctx.mode, vals, &ctx.options)?;
            built.insert(key, complex.clone());
        }
    }
    Ok(())
}
