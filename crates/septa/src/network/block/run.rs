//! A block's run: the box fast path (`boxfast`) when it applies, else the
//! general per-tet step (`worker`) on every tet of the block; the worker's
//! maps are handed to the next block of the same thread.

use super::state::{finish, Lengths, State};
use super::types::BlockOut;
use super::values::Ctx;
use super::worker::Worker;
use crate::grid::{Block, Grid};
use crate::network::NetworkError;

impl Worker {
    /// Processes one block.
    pub fn run(&mut self, ctx: &Ctx, block: &Block) -> Result<BlockOut, NetworkError> {
        let mut st = State {
            grouping: ctx.grouping,
            block_box: match block {
                Block::Cubes { lo, hi } => Some((*lo, *hi)),
                Block::Tets(_) => None,
            },
            vmap: std::mem::take(&mut self.vmap),
            emap: std::mem::take(&mut self.emap),
            ..State::default()
        };
        self.last.reserve(&mut st);
        if let (Grid::Box(g), Block::Cubes { lo, hi }) = (ctx.grid, block) {
            if super::boxfast::applies(ctx) {
                super::boxfast::run_box(self, ctx, &mut st, g, *lo, *hi)?;
                st.out.tets = (0..3).map(|a| hi[a] - lo[a]).product::<usize>() * g.split.tets_per_cube();
                return Ok(self.finish(st));
            }
        }
        let mut tets = std::mem::take(&mut self.tets);
        ctx.grid.block_tets(block, &mut tets);
        for &t in &tets {
            self.process_tet(ctx, &mut st, t)?;
        }
        st.out.tets = tets.len();
        self.tets = tets;
        Ok(self.finish(st))
    }

    /// Hands the block's vertex map back for the next block and compresses
    /// the block's output.
    fn finish(&mut self, mut st: State) -> BlockOut {
        self.last = Lengths::of(&st);
        let mut vmap = std::mem::take(&mut st.vmap);
        vmap.clear();
        self.vmap = vmap;
        let mut emap = std::mem::take(&mut st.emap);
        emap.clear();
        self.emap = emap;
        finish(st)
    }
}
