//! Void shells (TopoCut Sec. 6.1): a mesh component that lies inside one
//! open cell of the plane arrangement is bounded by triangle pieces only,
//! forms its own shell of negative volume, and belongs to the cut-cell of
//! the same arrangement cell that encloses it. The arrangement cell is
//! identified exactly by the side of each plane; when one positive cell
//! has that signature the void is attached to it, otherwise (nested shells:
//! an island in the cavity, voids in islands, ...) an exact ray from the
//! void finds the enclosing cell (`void_rays.rs`).

use crate::cut::base::geom::{Ctx, Def};
use crate::cut::cells::void_rays::{enclosing_cell, Enclosing};
use crate::cut::{CutCellMesh, Support};
use septa_exact::{Interval, Sign};

/// Attaches voids; returns `(attached, left unresolved)`.
pub fn attach_voids(c: &Ctx, out: &mut CutCellMesh, boxes: &[Option<[Interval; 3]>]) -> (usize, usize) {
    let n = out.num_cells;
    let mut only_tri = vec![true; n];
    let mut faces_of: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, f) in out.faces.iter().enumerate() {
        for &cell in f.cells.iter().filter(|&&x| x != u32::MAX) {
            faces_of[cell as usize].push(i);
            if matches!(f.support, Support::Plane(_)) {
                only_tri[cell as usize] = false;
            }
        }
    }
    // A shell bounded by triangle pieces only is a void when its signed
    // volume is negative: decided exactly on the input coordinates.
    let voids: Vec<usize> =
        (0..n).filter(|&k| only_tri[k] && volume_sign(c, out, &faces_of[k], k) == Sign::Negative).collect();
    if voids.is_empty() {
        return (0, 0);
    }
    // The cells a void may belong to: positive volume, decided exactly (a
    // legitimate cell can be too small for its floating-point volume).
    let positive: Vec<bool> = (0..n)
        .map(|k| {
            !voids.contains(&k)
                && crate::cut::cells::volume::cell_volume_sign(c, out, &faces_of[k], k as u32) == Sign::Positive
        })
        .collect();
    let np = c.planes.len();
    let signature = |cell: usize| -> Vec<Sign> {
        let mut sig = vec![Sign::Zero; np];
        for &fi in &faces_of[cell] {
            let f = &out.faces[fi];
            if let Support::Plane(p) = f.support {
                sig[p as usize] = if f.cells[0] == cell as u32 { Sign::Negative } else { Sign::Positive };
            }
        }
        for (q, s) in sig.iter_mut().enumerate() {
            if *s != Sign::Zero {
                continue;
            }
            'find: for &fi in &faces_of[cell] {
                for l in &out.faces[fi].loops {
                    for &v in l {
                        let d: Def = out.vertex_defs[v as usize];
                        let side = c.side(d, q as u32);
                        if side != Sign::Zero {
                            *s = side;
                            break 'find;
                        }
                    }
                }
            }
        }
        sig
    };
    let sigs: Vec<Option<Vec<Sign>>> =
        (0..n).map(|k| if positive[k] || voids.contains(&k) { Some(signature(k)) } else { None }).collect();
    let mut is_void = vec![false; n];
    for &v in &voids {
        is_void[v] = true;
    }
    let mut target: Vec<u32> = (0..n as u32).collect();
    let (mut attached, mut unresolved) = (0, 0);
    for &v in &voids {
        let sv = sigs[v].as_ref().unwrap();
        let cands: Vec<usize> = (0..n)
            .filter(|&k| positive[k])
            .filter(|&k| {
                sigs[k]
                    .as_ref()
                    .is_some_and(|s| s.iter().zip(sv).all(|(a, b)| *a == Sign::Zero || *b == Sign::Zero || a == b))
            })
            .collect();
        if cands.len() == 1 {
            target[v] = cands[0] as u32;
            attached += 1;
            continue;
        }
        match enclosing_cell(c, out, &faces_of[v], v as u32, &is_void, boxes) {
            Enclosing::Cell(k) => {
                target[v] = k;
                attached += 1;
            }
            Enclosing::Unknown => unresolved += 1,
        }
    }
    if attached == 0 {
        return (0, unresolved);
    }
    // compact cell ids
    let mut new_id = vec![u32::MAX; n];
    let mut next = 0u32;
    for k in 0..n {
        if target[k] == k as u32 {
            new_id[k] = next;
            next += 1;
        }
    }
    let map = |k: u32| {
        if k == u32::MAX {
            k
        } else {
            new_id[target[k as usize] as usize]
        }
    };
    let mut vols = vec![0.0; next as usize];
    for k in 0..n {
        vols[map(k as u32) as usize] += out.cell_volumes[k];
    }
    for f in &mut out.faces {
        f.cells = [map(f.cells[0]), map(f.cells[1])];
    }
    out.cell_volumes = vols;
    out.num_cells = next as usize;
    (attached, unresolved)
}

/// Exact sign of the signed volume of cell `cell` from its faces: on the
/// exact cut-vertices (`volume.rs`), whatever their kind.
fn volume_sign(c: &Ctx, out: &CutCellMesh, faces: &[usize], cell: usize) -> Sign {
    crate::cut::cells::volume::cell_volume_sign(c, out, faces, cell as u32)
}
