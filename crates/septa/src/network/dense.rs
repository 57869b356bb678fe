//! The in-memory job on sampled values (any tet grid): blocks in parallel,
//! merged by global keys, numbered canonically, then the topology
//! (Du et al. Sec. 6-7).

use std::time::Instant;

use rayon::prelude::*;
use smallvec::SmallVec;

use super::block::{BlockOut, Ctx, Worker};
use super::topology::{canonicalize_merged, canonicalize_topology, topology, Merged, Merger, Topology};
use super::{CellInfo, CellMethod, Mode, Network, NetworkError, NetworkOptions};
use crate::complex::Options;
use crate::grid::Grid;

/// Whether ray shooting is sure to apply: a box grid and no network vertex
/// at a grid vertex (IA: no value is exactly 0; MI: no tie for the maximum).
fn ray_applies(grid: &Grid, values: &[f64], k: usize, mode: Mode) -> bool {
    if !matches!(grid, Grid::Box(_)) {
        return false;
    }
    match mode {
        Mode::Ia => values.iter().all(|&x| x != 0.0),
        Mode::Mi => values.chunks_exact(k).all(|r| {
            // One pass: the running maximum and whether it is tied.
            let (mut m, mut tied) = (r[0], false);
            for &x in &r[1..] {
                if x > m {
                    (m, tied) = (x, false);
                } else if x == m {
                    tied = true;
                }
            }
            !tied
        }),
    }
}

/// Computes the IA or MI network of `k` functions given by their values at
/// the grid vertices (`values[v * k + f]`), on the current rayon pool.
pub fn compute(grid: &Grid, values: &[f64], k: usize, options: &NetworkOptions) -> Result<Network, NetworkError> {
    let t0 = Instant::now();
    let n = grid.num_vertices();
    if k == 0 {
        return Err(NetworkError::NoFunctions);
    }
    if k > u16::MAX as usize - 1 {
        return Err(NetworkError::TooManyFunctions(k));
    }
    if values.len() != n * k {
        return Err(NetworkError::ValueCount { expected: n * k, vertices: n, functions: k, got: values.len() });
    }
    // One branch-free pass (it vectorises) for NaN/inf and IA zeros; the
    // position of a bad value is searched only when there is one.
    let (mut nonfinite, mut zero) = (false, false);
    for chunk in values.chunks(4096) {
        for &x in chunk {
            nonfinite |= !x.is_finite();
            zero |= x == 0.0;
        }
    }
    if nonfinite {
        let i = values.iter().position(|x| !x.is_finite()).unwrap_or(0);
        return Err(NetworkError::NonFinite { vertex: i / k, function: i % k, value: values[i] });
    }
    let ray = options.raytrace
        && !options.volumes
        && match options.mode {
            Mode::Ia => !zero && matches!(grid, Grid::Box(_)),
            Mode::Mi => ray_applies(grid, values, k, options.mode),
        };
    let t_check = Instant::now();
    let ctx = Ctx {
        grid,
        values,
        k,
        mode: options.mode,
        options: {
            let mut o = Options::with_float(options.float);
            o.lookup = options.lookup;
            o
        },
        average_domination: options.mi_average_domination,
        volumes: options.volumes,
        grouping: !ray,
        sparse: None,
        block_rows: None,
        lookup: Ctx::lookup_of(grid),
    };
    let blocks = grid.blocks(options.block);
    let done = std::sync::atomic::AtomicUsize::new(0);
    // Blocks run in windows and merge in block order as each window
    // completes: only a window's block outputs live beside the merged network.
    let window = 16 * rayon::current_num_threads().max(1);
    let mut merger = Merger::new(options.mode);
    let mut merge_time = std::time::Duration::ZERO;
    for chunk in blocks.chunks(window) {
        let outs: Vec<BlockOut> = chunk
            .par_iter()
            .map_init(Worker::default, |w, b| {
                if options.cancelled() {
                    return Err(NetworkError::Cancelled);
                }
                let out = w.run(&ctx, b);
                if let Some(p) = &options.progress {
                    p.tick(&done, blocks.len());
                }
                out
            })
            .collect::<Result<_, _>>()?;
        let t = Instant::now();
        for out in outs {
            merger.add(out);
        }
        merge_time += t.elapsed();
    }
    crate::heap::release_free_memory();
    let t = Instant::now();
    let mut m = merger.finish();
    merge_time += t.elapsed();
    let t1 = Instant::now() - merge_time;
    let t_merged = Instant::now();
    canonicalize_merged(&mut m);
    let t2 = Instant::now();
    let mut topo = topology(&mut m, (options.raytrace && !options.volumes).then_some(&ctx));
    canonicalize_topology(&mut topo);
    label_free_cells(&mut topo.cells, options.mode, &values[..k]);
    let t3 = Instant::now();
    if !ctx.grouping && topo.cells_method != CellMethod::Raytrace {
        // Cannot happen when the preconditions hold; never answer without cells.
        let mut o = options.clone();
        o.raytrace = false;
        return compute(grid, values, k, &o);
    }
    let mut net = assemble(options.mode, k, m, topo, [t1 - t_check, t_merged - t1, t3 - t2]);
    // Input checks and canonical numbering are neither extraction nor
    // topology: report them apart (`septa bench grid` sums tets + merge).
    net.seconds.insert(0, ("check", (t_check - t0).as_secs_f64()));
    net.seconds.insert(3, ("canon", (t2 - t_merged).as_secs_f64()));
    Ok(net)
}

/// A cell bounded by no face (no network at all) takes the label of the
/// values `row` of one grid vertex (IA sign bits; MI argmax).
pub(crate) fn label_free_cells(cells: &mut [CellInfo], mode: Mode, row: &[f64]) {
    let k = row.len();
    for cell in cells.iter_mut().filter(|c| c.label.is_empty()) {
        cell.label = match mode {
            Mode::Ia => {
                let mut l: SmallVec<[u64; 2]> = SmallVec::from_elem(0, k.div_ceil(64));
                for (f, &x) in row.iter().enumerate() {
                    if x > 0.0 {
                        l[f / 64] |= 1 << (f % 64);
                    }
                }
                l
            }
            Mode::Mi => {
                let m = (0..k).fold(0, |b, f| if row[f] > row[b] { f } else { b });
                SmallVec::from_elem(m as u64, 1)
            }
        };
    }
}

/// The network from merged polygons and their topology; `stages` are the
/// durations of the tets, merge and topology stages.
pub(crate) fn assemble(mode: Mode, k: usize, m: Merged, topo: Topology, stages: [std::time::Duration; 3]) -> Network {
    Network {
        mode,
        functions: k,
        points: m.points,
        keys: m.keys,
        face_start: m.face_start,
        face_verts: m.face_verts,
        face_label: m.face_label,
        face_cells: topo.face_cells,
        face_patch: topo.face_patch,
        edges: topo.edges,
        patches: topo.patches,
        chains: topo.chains,
        chain_patches: topo.chain_patches,
        corners: topo.corners,
        shells: topo.shells,
        cells: topo.cells,
        components: topo.components,
        active_tets: m.active_tets,
        cells_method: topo.cells_method,
        seconds: vec![
            ("tets", stages[0].as_secs_f64()),
            ("merge", stages[1].as_secs_f64()),
            ("topology", stages[2].as_secs_f64()),
        ],
        embedding: None,
    }
}
