//! The in-order half of a stream (docs/sparse.md): block results, in the plan's
//! order, get their vertices' streamed ids (`numbering.rs`), go to the sink,
//! and, for topology, their summaries to the assembly (`assembly.rs`);
//! [`StreamFeeder::finish`] shoots the rays (`rerun.rs`).
//!
//! [`stream_sparse`](crate::network::stream_sparse) and
//! [`stream_topology`](crate::network::stream_topology) compute the blocks on
//! this machine and feed them here; a caller whose blocks were computed
//! elsewhere (on a Dask cluster, as bytes: [`BlockResult::from_bytes`])
//! feeds them the same way, so the stream and its topology are the same
//! wherever the blocks ran.

use super::assembly::Assembler;
use super::halves::{pair, OpenHalf};
use super::numbering::VertexNumbering;
use super::prepare::{prepare, Prepared};
use super::sink::{StreamBlock, StreamError, StreamSink, StreamStats};
use super::summary_result::NetworkSummary;
use crate::complex::{Mode, NONE};
use crate::grid::{BoxGrid, Grid};
use crate::network::block::{FaceKey, Label, PointValues};
use crate::network::field::BoundedField;
use crate::network::sparse::{block_at, check_functions, ctx, cubes, BlockResult, JobKey, SparsePlan};
use crate::network::topology::{contact_links, ray_cells};
use crate::network::{NetworkError, NetworkOptions, VKey};
use rustc_hash::FxHashMap;
use smallvec::SmallVec;

/// Feeds block results to a sink in plan order (module doc).
pub struct StreamFeeder<'a> {
    grid: BoxGrid,
    functions: Box<dyn BoundedField + Send + 'a>,
    options: NetworkOptions,
    job: JobKey,
    kept: Vec<usize>,
    next: usize,
    numbering: VertexNumbering,
    assembler: Option<Assembler>,
    ids: Vec<u32>,
    pieces: Vec<u32>,
    stats: StreamStats,
    /// Halves waiting for the block across their tet face, and the slab
    /// (x index) left of which none can come any more.
    halves: FxHashMap<HalfKey, StoredHalf>,
    half_slab: usize,
}

/// A half kept until the block across its tet face comes (`halves.rs`).
struct StoredHalf {
    /// Region label on its side.
    label: Label,
    /// Its shell node in the assembly (topology only).
    node: u32,
    /// Its slot in the assembly's `half_piece` (topology only).
    slot: u32,
}

/// Sorted vertex keys of a half: with its tet face, what pairs it.
type HalfKey = (FaceKey, SmallVec<[VKey; 4]>);

/// The block's open halves paired with earlier ones (`pair_across`).
struct AcrossPairs {
    /// Faces, in the block's order of open halves.
    faces: Vec<Across>,
    /// Two halves of one material (MI): no face, one shell.
    same: Vec<(usize, StoredHalf)>,
    /// Per open half of the block: paired now.
    paired: Vec<bool>,
}

/// The key pairing half `h` (block vertex keys `keys`).
fn half_key(h: &OpenHalf, keys: &[VKey]) -> HalfKey {
    let mut k: SmallVec<[VKey; 4]> = h.verts.iter().map(|&v| keys[v as usize]).collect();
    k.sort_unstable();
    (h.face, k)
}

/// A face paired across a block boundary, streamed with the later block.
struct Across {
    /// Open half of the later block.
    j: usize,
    /// Vertices (later block's ids), counter-clockwise seen from side 0.
    verts: SmallVec<[u32; 8]>,
    label: [u16; 2],
    side_label: [Label; 2],
    /// Side of the later block's half.
    side: usize,
    earlier: StoredHalf,
}

impl<'a> StreamFeeder<'a> {
    /// A feeder for the blocks `plan.kept` of a sparse job
    /// ([`plan_sparse`](crate::network::plan_sparse) on the same grid, functions and
    /// options); with `topology`, the assembly runs too.
    pub fn new<F: BoundedField + Send + 'a>(
        grid: &BoxGrid,
        functions: F,
        options: &NetworkOptions,
        plan: &SparsePlan,
        topology: bool,
    ) -> Result<StreamFeeder<'a>, NetworkError> {
        let k = functions.functions();
        check_functions(k)?;
        if plan.dense {
            return Err(NetworkError::DensePlanStreamed);
        }
        let numbering = VertexNumbering::new(grid);
        let assembler = topology.then(|| Assembler::new(options.mode, k, numbering.plane(), grid.clone()));
        let stats = StreamStats {
            blocks: plan.blocks,
            sampled: plan.kept.len(),
            skipped: plan.blocks - plan.kept.len(),
            ..StreamStats::default()
        };
        Ok(StreamFeeder {
            grid: grid.clone(),
            functions: Box::new(functions),
            options: options.clone(),
            job: JobKey::of(grid, k, options),
            kept: plan.kept.clone(),
            next: 0,
            numbering,
            assembler,
            ids: Vec::new(),
            pieces: Vec::new(),
            stats,
            halves: FxHashMap::default(),
            half_slab: 0,
        })
    }

    /// Feeds the next block's result (it must be block `plan.kept[i]` for
    /// the `i`-th call, of this job) to `sink`, then drops it.
    pub fn feed<S: StreamSink + ?Sized>(&mut self, mut result: BlockResult, sink: &mut S) -> Result<(), StreamError> {
        let prepared = prepare(&self.grid, &self.options, &mut result, self.assembler.is_some())?;
        self.feed_with(result, prepared, sink)
    }

    /// Feeds several consecutive block results, making their summaries in
    /// parallel on the current rayon pool first (the assembly itself is in
    /// order): what a client receiving batches from many workers should call.
    pub fn feed_all<S: StreamSink + ?Sized>(
        &mut self,
        mut results: Vec<BlockResult>,
        sink: &mut S,
    ) -> Result<(), StreamError> {
        use rayon::prelude::*;
        let topology = self.assembler.is_some();
        let (grid, options) = (&self.grid, &self.options);
        let prepared: Vec<Prepared> =
            results.par_iter_mut().map(|r| prepare(grid, options, r, topology)).collect::<Result<_, _>>()?;
        for (r, p) in results.into_iter().zip(prepared) {
            self.feed_with(r, p, sink)?;
        }
        Ok(())
    }

    /// [`StreamFeeder::feed`] with the block's summary already made (in parallel).
    pub(crate) fn feed_with<S: StreamSink + ?Sized>(
        &mut self,
        r: BlockResult,
        prepared: Prepared,
        sink: &mut S,
    ) -> Result<(), StreamError> {
        if !r.job.same(&self.job) {
            return Err(NetworkError::ForeignBlock {
                index: r.index,
                job: format!("{:?}", r.job),
                expected: format!("{:?}", self.job),
            }
            .into());
        }
        match self.kept.get(self.next) {
            Some(&i) if i == r.index => self.next += 1,
            want => return Err(NetworkError::BlockOutOfOrder { index: r.index, expected: want.copied() }.into()),
        }
        let b = block_at(&self.grid, self.options.block, r.index).expect("a planned block exists");
        let (lo, hi) = cubes(&b);
        let Prepared { open, summary } = prepared;
        let out = &r.out;
        let AcrossPairs { faces: across, same, paired } = self.pair_across(lo[0], &r, &open)?;
        let stats = &mut self.stats;
        stats.sampled_vertices += r.sampled_vertices;
        stats.active += (out.active_tets > 0) as usize;
        stats.active_tets += out.active_tets;
        stats.faces += out.poly_label.len() + across.len();
        stats.block_vertices += out.keys.len();
        // Faces paired across blocks are streamed after the block's own.
        let extended = (!across.is_empty()).then(|| {
            let (mut start, mut verts, mut label) =
                (out.poly_start.clone(), out.poly_verts.clone(), out.poly_label.clone());
            for a in &across {
                verts.extend_from_slice(&a.verts);
                start.push(verts.len() as u32);
                label.push(a.label);
            }
            (start, verts, label)
        });
        let (poly_start, poly_verts, poly_label) = match &extended {
            Some((s, v, l)) => (&s[..], &v[..], &l[..]),
            None => (&out.poly_start[..], &out.poly_verts[..], &out.poly_label[..]),
        };
        let base = self.assembler.as_ref().map_or(0, |a| a.pieces());
        let block_pieces = summary.as_ref().map_or(0, |s| s.piece_label.len() as u32);
        let vertex_piece: &[u32] = summary.as_ref().map_or(&[], |s| &s.vertex_piece);
        // A vertex on no polygon of the block but on a face paired across
        // takes that face's piece (the i-th such face is piece `base + block_pieces + i`).
        let mut across_piece: FxHashMap<u32, u32> = FxHashMap::default();
        for (i, a) in across.iter().enumerate() {
            for &v in &a.verts {
                if vertex_piece.get(v as usize) == Some(&NONE) {
                    across_piece.entry(v).or_insert(base + block_pieces + i as u32);
                }
            }
        }
        let piece_of = |v: u32| match vertex_piece.get(v as usize) {
            Some(&NONE) => across_piece[&v],
            Some(p) => base + p,
            None => 0,
        };
        // Shared vertices seen before join components, once the block's
        // pieces exist in the assembly.
        let mut repeats: Vec<(u32, u32)> = Vec::new();
        self.numbering.block(lo[0], &out.keys, &out.shared, poly_verts, &mut self.ids, piece_of, |first, v| {
            if !vertex_piece.is_empty() {
                repeats.push((first, piece_of(v)));
            }
        })?;
        self.pieces.clear();
        let mut placed = None;
        if let (Some(asm), Some(s)) = (self.assembler.as_mut(), &summary) {
            let nodes = asm.add(r.index, lo[0], out, s, &self.ids)?;
            let first_slot = asm.half_piece.len() as u32;
            if !open.is_empty() {
                asm.block_halves.push((r.index, first_slot));
                asm.half_piece.resize(asm.half_piece.len() + open.len(), NONE);
            }
            for a in across {
                let mine = nodes.node(s.open_half_node[a.j]);
                let ids: SmallVec<[u32; 8]> = a.verts.iter().map(|&v| self.ids[v as usize]).collect();
                let keys: SmallVec<[VKey; 8]> = a.verts.iter().map(|&v| out.keys[v as usize]).collect();
                let nodes2 = if a.side == 0 { [mine, a.earlier.node] } else { [a.earlier.node, mine] };
                let piece = asm.add_face_across(&ids, &keys, a.label, a.side_label, nodes2)?;
                asm.half_piece[a.earlier.slot as usize] = piece;
                asm.half_piece[(first_slot as usize) + a.j] = piece;
                for &v in &a.verts {
                    asm.same_vertex(piece, piece_of(v));
                }
            }
            for (j, earlier) in same {
                asm.same_shell(nodes.node(s.open_half_node[j]), earlier.node);
            }
            for (x, y) in repeats {
                asm.same_vertex(x, y);
            }
            self.pieces.extend(s.poly_piece.iter().map(|&p| base + p));
            self.pieces.extend((0..(poly_label.len() - out.poly_label.len()) as u32).map(|i| base + block_pieces + i));
            placed = Some((nodes, first_slot));
        }
        for (j, h) in open.iter().enumerate() {
            if paired[j] {
                continue;
            }
            let (node, slot) = match (&placed, &summary) {
                (Some((nodes, first)), Some(s)) => (nodes.node(s.open_half_node[j]), first + j as u32),
                _ => (NONE, NONE),
            };
            let label = out.comp_label[h.cell as usize].clone();
            self.halves.insert(half_key(h, &out.keys), StoredHalf { label, node, slot });
        }
        sink.block(&StreamBlock {
            index: r.index,
            lo,
            hi,
            keys: &out.keys,
            shared: &out.shared,
            points: &out.points,
            poly_start,
            poly_verts,
            poly_label,
            vertex_ids: &self.ids,
            poly_piece: &self.pieces,
            active_tets: out.active_tets,
        })?;
        Ok(())
    }

    /// Pairs the open halves of block result `r` (cubes from x index `lo_x`)
    /// with the halves kept from earlier blocks (`halves.rs`), after dropping
    /// those no block from `lo_x` on can pair: an IA face found from one
    /// side only is an error (the in-memory merge would keep it one-sided).
    fn pair_across(&mut self, lo_x: usize, r: &BlockResult, open: &[OpenHalf]) -> Result<AcrossPairs, NetworkError> {
        if lo_x > self.half_slab {
            self.half_slab = lo_x;
            self.drop_halves(lo_x)?;
        }
        let mut pairs = AcrossPairs { faces: Vec::new(), same: Vec::new(), paired: vec![false; open.len()] };
        if self.halves.is_empty() {
            return Ok(pairs);
        }
        for (j, h) in open.iter().enumerate() {
            let Some(earlier) = self.halves.remove(&half_key(h, &r.out.keys)) else { continue };
            pairs.paired[j] = true;
            let mine = &r.out.comp_label[h.cell as usize];
            match pair(self.options.mode, h.zero, &earlier.label, mine) {
                Some(p) => {
                    // The earlier half is given first: side 0 unless `second_first`.
                    let side = if p.second_first { 0 } else { 1 };
                    let verts = if side == 0 { h.verts.clone() } else { h.verts.iter().rev().copied().collect() };
                    let side_label = if side == 0 {
                        [mine.clone(), earlier.label.clone()]
                    } else {
                        [earlier.label.clone(), mine.clone()]
                    };
                    pairs.faces.push(Across { j, verts, label: p.label, side_label, side, earlier });
                }
                None => pairs.same.push((j, earlier)),
            }
        }
        Ok(pairs)
    }

    /// Drops the kept halves whose tet face lies left of x index `slab`.
    fn drop_halves(&mut self, slab: usize) -> Result<(), NetworkError> {
        let plane = self.numbering.plane();
        let mut lost: Option<FaceKey> = None;
        self.halves.retain(|k, _| {
            let keep = k.0.iter().map(|&v| (v as u64 / plane) as usize).max().unwrap_or(0) >= slab;
            if !keep && lost.is_none() {
                lost = Some(k.0);
            }
            keep
        });
        match (lost, self.options.mode) {
            (Some(face), Mode::Ia) => Err(NetworkError::FaceFromOneSide { face }),
            _ => Ok(()),
        }
    }

    /// After the last block: the stream's statistics and, with topology,
    /// the network's topology (cells by ray shooting, running the few
    /// blocks a ray looks at again on the current rayon pool's thread).
    pub fn finish(mut self) -> Result<(StreamStats, Option<NetworkSummary>), StreamError> {
        if self.next != self.kept.len() {
            return Err(NetworkError::BlocksMissing { fed: self.next, planned: self.kept.len() }.into());
        }
        self.drop_halves(usize::MAX)?;
        let mut stats = self.stats;
        stats.vertices = self.numbering.count();
        stats.peak_shared_keys = self.numbering.peak();
        let Some(mut asm) = self.assembler else { return Ok((stats, None)) };
        stats.peak_open = asm.peak_open;
        let (grid, functions, options) = (&self.grid, &*self.functions as &dyn BoundedField, &self.options);
        let g = Grid::Box(grid.clone());
        let pv = PointValues { grid, functions };
        let ctx = ctx(&g, functions.functions(), options, &pv);
        let row0: Vec<f64> = (0..functions.functions()).map(|f| functions.value(f, grid.vertex(0))).collect();
        let block_pieces = std::mem::take(&mut asm.block_pieces);
        let halves = super::rerun::HalfPieces {
            blocks: std::mem::take(&mut asm.block_halves),
            piece: std::mem::take(&mut asm.half_piece),
        };
        let mut reruns = 0;
        let summary = asm.finish(
            stats.vertices as usize,
            |a, piece_sheet, several| {
                let mut index = super::rerun::RerunIndex::new(grid, &g, functions, options, &block_pieces, &halves, a);
                let mut links = Vec::new();
                if several.iter().any(|&x| x) {
                    for key in index.contact_keys(piece_sheet, several)? {
                        links.extend(contact_links(&ctx, &mut index, &key)?);
                    }
                }
                let r = ray_cells(&ctx, &mut index, &a.starts, a.num_shells, &links);
                reruns = index.reruns;
                r
            },
            |a, piece_sheet, s1, s2| {
                super::rerun::RerunIndex::new(grid, &g, functions, options, &block_pieces, &halves, a).contact(
                    piece_sheet,
                    s1,
                    s2,
                )
            },
            &row0,
        )?;
        stats.reruns = reruns;
        Ok((stats, Some(summary)))
    }
}
