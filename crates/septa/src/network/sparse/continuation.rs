//! Continuation for functions without bounds (docs/sparse.md; Bloomenthal,
//! *Non-Manifold Surfaces*, Sec. 4.5.1 "Cell Propagation"): start from seed
//! blocks and grow across the block faces the network touches, so only the
//! blocks the network's reached components meet are ever sampled.
//!
//! **The rule for "touches".** The network is built from the linear
//! interpolation of the samples on each tet, so on a triangle of the grid
//! (a tet face) it is exactly decided by the 3 vertex values: IA, the zero
//! set of `f` meets a closed triangle iff `f`'s values there are not all of
//! one strict sign; MI, the triangle holds no interface iff one function is
//! the unique maximum at its 3 vertices (then it is the maximum on the whole
//! triangle, by convexity). A block face is touched iff one of its
//! triangles is. Because the face's squares are chained by shared vertices,
//! this equals a test on the face's vertices alone: IA, some function is
//! not of one strict sign over them; MI, no single function is the unique
//! maximum at all of them. Only signs and argmax of the samples decide it:
//! no tolerance.
//!
//! **Why every block of a reached component is visited.** A connected
//! component of the network is a connected set; if it meets closed blocks
//! `A` and `B`, a path inside it from `A` to `B` leaves each block through a
//! point of its boundary, which lies on a block face (an edge or corner is
//! on a face too), and that face is then touched. So the closed blocks a
//! component meets are connected through touched faces, and the search from
//! any seed block the component meets visits all of them. A component that
//! meets no seed block is **missed by design** (as in Bloomenthal's
//! polygonizer): seeds come from given points or from a coarse scan of the
//! block corners (a block whose 8 corners show a sign change, IA, or a
//! change of the maximum, MI), and a component inside one block's corners
//! shows neither.
//!
//! Everything after the search is the sparse path's (`sparse.rs`): blocks
//! merged in block order, topology by ray shooting with values computed on
//! demand in unvisited blocks, the same dense fallback; when every component
//! is reached the output equals the dense network (tests).

use std::sync::Mutex;

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::run::{
    block_at, block_count, check_functions, ctx, cubes, finish_with, BlockResult, JobKey, SparsePlan, SparseStats,
};
use crate::complex::Mode;
use crate::grid::{BoxGrid, Grid};
use crate::network::block::{BlockValues, Values, Worker};
use crate::network::field::Field;
use crate::network::{Network, NetworkError, NetworkOptions};

/// Where continuation starts.
#[derive(Clone, Debug)]
pub enum Seeds<'a> {
    /// The blocks holding these points (each must lie in the grid's box).
    Points(&'a [[f64; 3]]),
    /// Blocks whose 8 corners show a sign change (IA) or a change of the
    /// maximum function (MI), from one sampling of the block-corner lattice.
    CoarseScan,
}

/// What continuation did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ContinuationStats {
    /// Blocks: `sampled` visited, `skipped` never visited.
    pub blocks: SparseStats,
    /// Seed blocks.
    pub seeds: usize,
    /// Rounds of the search (its depth plus one).
    pub rounds: usize,
}

/// Evaluates `field` at `points` (grid vertices `ids`) and checks the
/// values: as many as asked, finite; returns them and whether ray
/// shooting's precondition holds there (as `sparse::sample_block`).
fn eval_checked(
    field: &dyn Field,
    mode: Mode,
    points: &[[f64; 3]],
    ids: &[u32],
) -> Result<(Vec<f64>, bool), NetworkError> {
    let k = field.functions();
    let mut data = Vec::with_capacity(points.len() * k);
    field.eval(points, &mut data).map_err(NetworkError::FieldFailed)?;
    if data.len() != points.len() * k {
        return Err(NetworkError::FieldValues { values: data.len(), points: points.len(), functions: k });
    }
    if let Some(i) = data.iter().position(|x| !x.is_finite()) {
        return Err(NetworkError::NonFinite { vertex: ids[i / k] as usize, function: i % k, value: data[i] });
    }
    let clean = data.chunks_exact(k).all(|row| match mode {
        Mode::Ia => row.iter().all(|&x| x != 0.0),
        Mode::Mi => unique_max(row).is_some(),
    });
    Ok((data, clean))
}

/// The function that is the unique maximum of `row`, if any.
fn unique_max(row: &[f64]) -> Option<usize> {
    let m = row.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mut it = row.iter().enumerate().filter(|(_, &x)| x == m);
    let first = it.next()?.0;
    it.next().is_none().then_some(first)
}

/// Whether the network touches the closed set whose sample rows are
/// `rows` (one block face's vertices, or a block's corners): see the
/// module doc.
fn touches<'r>(mode: Mode, k: usize, rows: impl Iterator<Item = &'r [f64]> + Clone) -> bool {
    match mode {
        Mode::Ia => (0..k).any(|f| {
            let (mut le, mut ge) = (false, false);
            for r in rows.clone() {
                le |= r[f] <= 0.0;
                ge |= r[f] >= 0.0;
                if le && ge {
                    return true;
                }
            }
            false
        }),
        Mode::Mi => {
            let mut owner = None;
            for r in rows {
                match (unique_max(r), owner) {
                    (None, _) => return true,
                    (Some(g), None) => owner = Some(g),
                    (Some(g), Some(o)) if g != o => return true,
                    _ => {}
                }
            }
            false
        }
    }
}

/// Blocks per axis.
fn block_counts(grid: &BoxGrid, size: usize) -> [usize; 3] {
    grid.res.map(|r| r.div_ceil(size))
}

/// The face neighbours of block `index` across the faces the network
/// touches, from the block's samples.
fn touched_neighbours(grid: &BoxGrid, size: usize, index: usize, bv: &BlockValues, mode: Mode, k: usize) -> Vec<usize> {
    let n = block_counts(grid, size);
    let b = [index / (n[1] * n[2]), index / n[2] % n[1], index % n[2]];
    let lo = [0, 1, 2].map(|a| b[a] * size);
    let hi = [0, 1, 2].map(|a| (lo[a] + size).min(grid.res[a]));
    let vn = [0, 1, 2].map(|a| hi[a] - lo[a] + 1);
    let mut out = Vec::new();
    for a in 0..3 {
        for (side, fixed) in [(0usize, lo[a]), (1, hi[a])] {
            let exists = if side == 0 { b[a] > 0 } else { b[a] + 1 < n[a] };
            if !exists {
                continue;
            }
            let (u, w) = ((a + 1) % 3, (a + 2) % 3);
            let row = |(p, q): (usize, usize)| {
                let mut c = [0; 3];
                c[a] = fixed - lo[a];
                c[u] = p;
                c[w] = q;
                let local = (c[0] * vn[1] + c[1]) * vn[2] + c[2];
                &bv.data[local * k..(local + 1) * k]
            };
            let rows = (0..vn[u]).flat_map(move |p| (0..vn[w]).map(move |q| (p, q))).map(row);
            if touches(mode, k, rows) {
                let mut nb = b;
                nb[a] = if side == 0 { b[a] - 1 } else { b[a] + 1 };
                out.push((nb[0] * n[1] + nb[1]) * n[2] + nb[2]);
            }
        }
    }
    out
}

/// Seed blocks, ascending and without repeats.
fn seed_blocks(
    grid: &BoxGrid,
    field: &dyn Field,
    mode: Mode,
    size: usize,
    seeds: &Seeds,
) -> Result<Vec<usize>, NetworkError> {
    let n = block_counts(grid, size);
    let mut out = match seeds {
        Seeds::Points(points) => {
            let mut out = Vec::with_capacity(points.len());
            for (i, p) in points.iter().enumerate() {
                let mut b = [0; 3];
                for a in 0..3 {
                    let (lo, hi) = (grid.bounds[0][a], grid.bounds[1][a]);
                    if !(lo..=hi).contains(&p[a]) {
                        return Err(NetworkError::SeedOutside { seed: i, point: *p });
                    }
                    // Floating point only picks where to start, never a topological answer.
                    let cube = (((p[a] - lo) / (hi - lo) * grid.res[a] as f64) as usize).min(grid.res[a] - 1);
                    b[a] = cube / size;
                }
                out.push((b[0] * n[1] + b[1]) * n[2] + b[2]);
            }
            out
        }
        Seeds::CoarseScan => {
            let k = field.functions();
            let coord = |a: usize, c: usize| (c * size).min(grid.res[a]);
            let m = n.map(|x| x + 1);
            let mut ids = Vec::with_capacity(m[0] * m[1] * m[2]);
            for i in 0..m[0] {
                for j in 0..m[1] {
                    for l in 0..m[2] {
                        ids.push(grid.vertex_index([coord(0, i), coord(1, j), coord(2, l)]));
                    }
                }
            }
            let points: Vec<[f64; 3]> = ids.iter().map(|&v| grid.vertex(v)).collect();
            let (data, _) = eval_checked(field, mode, &points, &ids)?;
            let row = |i: usize, j: usize, l: usize| {
                let c = (i * m[1] + j) * m[2] + l;
                &data[c * k..(c + 1) * k]
            };
            let mut out = Vec::new();
            for i in 0..n[0] {
                for j in 0..n[1] {
                    for l in 0..n[2] {
                        let corners = (0..8).map(|c| row(i + (c >> 2), j + (c >> 1 & 1), l + (c & 1)));
                        if touches(mode, k, corners) {
                            out.push((i * n[1] + j) * n[2] + l);
                        }
                    }
                }
            }
            out
        }
    };
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

/// Values computed on demand (ray shooting through unvisited blocks), one
/// row per vertex, cached; the first evaluation error is kept and reported.
struct FieldValues<'a> {
    grid: &'a BoxGrid,
    field: &'a dyn Field,
    cache: Mutex<FxHashMap<u32, Box<[f64]>>>,
    error: Mutex<Option<NetworkError>>,
}

impl Values for FieldValues<'_> {
    fn val(&self, v: u32, f: usize) -> f64 {
        if let Some(r) = self.cache.lock().unwrap().get(&v) {
            return r[f];
        }
        match eval_checked(self.field, Mode::Ia, &[self.grid.vertex(v)], &[v]) {
            Ok((row, _)) => {
                let x = row[f];
                self.cache.lock().unwrap().insert(v, row.into_boxed_slice());
                x
            }
            Err(e) => {
                self.error.lock().unwrap().get_or_insert(e);
                // Never used: the run returns the error.
                1.0
            }
        }
    }
}

/// The dense path on a field: every vertex sampled (in chunks).
fn dense(grid: &BoxGrid, field: &dyn Field, options: &NetworkOptions) -> Result<Network, NetworkError> {
    let g = Grid::Box(grid.clone());
    let ids: Vec<u32> = (0..grid.num_vertices() as u32).collect();
    let mut values = Vec::with_capacity(ids.len() * field.functions());
    for chunk in ids.chunks(1 << 16) {
        let points: Vec<[f64; 3]> = chunk.iter().map(|&v| grid.vertex(v)).collect();
        values.extend(eval_checked(field, options.mode, &points, chunk)?.0);
    }
    crate::network::compute(&g, &values, field.functions(), options)
}

/// Seed blocks of a continuation job (indices into `grid.blocks(options.block)`,
/// ascending), from points or the coarse scan.
pub fn continuation_seeds(
    grid: &BoxGrid,
    field: &dyn Field,
    seeds: &Seeds,
    options: &NetworkOptions,
) -> Result<Vec<usize>, NetworkError> {
    check_functions(field.functions())?;
    seed_blocks(grid, field, options.mode, options.block.max(1), seeds)
}

fn continuation_block_with(
    w: &mut Worker,
    g: &Grid,
    grid: &BoxGrid,
    field: &dyn Field,
    options: &NetworkOptions,
    index: usize,
) -> Result<(BlockResult, Vec<usize>), NetworkError> {
    let k = field.functions();
    let size = options.block.max(1);
    let b = block_at(grid, size, index)
        .ok_or_else(|| NetworkError::NoSuchBlock { index, blocks: block_count(grid, size) })?;
    let (lo, hi) = cubes(&b);
    let mut ids = Vec::new();
    for i in lo[0]..=hi[0] {
        for j in lo[1]..=hi[1] {
            for l in lo[2]..=hi[2] {
                ids.push(grid.vertex_index([i, j, l]));
            }
        }
    }
    let points: Vec<[f64; 3]> = ids.iter().map(|&v| grid.vertex(v)).collect();
    let (data, clean) = eval_checked(field, options.mode, &points, &ids)?;
    let vn = [0, 1, 2].map(|a| hi[a] - lo[a] + 1);
    let bv = BlockValues::new(grid, lo, vn, k, data);
    let next = touched_neighbours(grid, size, index, &bv, options.mode, k);
    let c = ctx(g, k, options, &bv);
    let out = w.run(&c, &b)?;
    let job = JobKey::of(grid, k, options);
    Ok((BlockResult { job, index, out, clean, sampled_vertices: ids.len() }, next))
}

/// One step of the search: samples block `index`, builds its part of the
/// network and lists the face neighbours across the faces the network
/// touches (the blocks to visit next). Independent of every other block.
pub fn continuation_block(
    grid: &BoxGrid,
    field: &dyn Field,
    options: &NetworkOptions,
    index: usize,
) -> Result<(BlockResult, Vec<usize>), NetworkError> {
    check_functions(field.functions())?;
    let g = Grid::Box(grid.clone());
    continuation_block_with(&mut Worker::default(), &g, grid, field, options, index)
}

/// The end of the search: the visited blocks' results merged in block order,
/// topology by ray shooting (values in unvisited blocks computed on demand
/// from `field`), with the sparse path's dense fallback.
pub fn finish_continuation(
    grid: &BoxGrid,
    field: &dyn Field,
    options: &NetworkOptions,
    results: Vec<BlockResult>,
) -> Result<(Network, SparseStats), NetworkError> {
    let k = field.functions();
    check_functions(k)?;
    let n = block_counts(grid, options.block.max(1));
    let mut kept: Vec<usize> = results.iter().map(|r| r.index).collect();
    kept.sort_unstable();
    let plan = SparsePlan { blocks: n[0] * n[1] * n[2], kept, dense: options.volumes || !options.raytrace };
    let pv = FieldValues { grid, field, cache: Mutex::default(), error: Mutex::default() };
    let out = finish_with(grid, k, options, &plan, results, &pv, || dense(grid, field, options));
    if let Some(e) = pv.error.lock().unwrap().take() {
        return Err(e);
    }
    out
}

/// Computes the IA or MI network of `field` on `grid` by continuation from
/// `seeds` (see the module doc): the network of the components the seeds
/// reach, equal to [`compute`](crate::network::compute) when they reach them all.
/// It is [`continuation_seeds`], rounds of [`continuation_block`] over each
/// frontier (in parallel on the current rayon pool) and
/// [`finish_continuation`].
pub fn compute_continuation(
    grid: &BoxGrid,
    field: &dyn Field,
    seeds: Seeds,
    options: &NetworkOptions,
) -> Result<(Network, ContinuationStats), NetworkError> {
    check_functions(field.functions())?;
    let n = block_counts(grid, options.block.max(1));
    let mut stats = ContinuationStats::default();
    let mut results: Vec<BlockResult> = Vec::new();
    if !(options.volumes || !options.raytrace) {
        let mut frontier = continuation_seeds(grid, field, &seeds, options)?;
        stats.seeds = frontier.len();
        let mut visited = vec![false; n[0] * n[1] * n[2]];
        frontier.iter().for_each(|&b| visited[b] = true);
        let g = Grid::Box(grid.clone());
        // Breadth-first, one frontier at a time; the blocks of a frontier in parallel.
        while !frontier.is_empty() {
            stats.rounds += 1;
            let outs: Vec<(BlockResult, Vec<usize>)> = frontier
                .par_iter()
                .map_init(Worker::default, |w, &index| {
                    if options.cancelled() {
                        return Err(NetworkError::Cancelled);
                    }
                    continuation_block_with(w, &g, grid, field, options, index)
                })
                .collect::<Result<_, NetworkError>>()?;
            let mut next = Vec::new();
            for (r, nbs) in outs {
                for nb in nbs {
                    if !visited[nb] {
                        visited[nb] = true;
                        next.push(nb);
                    }
                }
                results.push(r);
            }
            next.sort_unstable();
            frontier = next;
        }
    }
    let (net, s) = finish_continuation(grid, field, options, results)?;
    stats.blocks = s;
    Ok((net, stats))
}
