//! `<stream>.topology.json`: the topology of a streamed network (docs/sparse.md),
//! in `network.json`'s names and layout for what it has (patches, chains,
//! chain_patches, corners, shells, cells, counts; written by the same code)
//! plus the map from each polygon's patch piece to its patch and cells; the
//! polygons themselves are in the streamed PLY (whose faces already carry
//! patch and cells). Vertex ids in chains and corners are the PLY's.

use std::io::Write;
use std::path::Path;

use crate::complex::Mode;
use crate::complex::NONE;
use crate::io::files::atomic::write_atomic_with;
use crate::io::writers::network_out::{list, write_counts_seconds, write_topology, TopologyJson};
use crate::network::NetworkSummary;

/// Writes the summary's JSON atomically.
pub fn write_summary_json(s: &NetworkSummary, path: &Path, seconds: &[(&str, f64)]) -> std::io::Result<()> {
    write_atomic_with(path, |w| {
        let mode = match s.mode {
            Mode::Ia => "ia",
            Mode::Mi => "mi",
        };
        writeln!(w, "{{\"mode\":\"{mode}\",\"functions\":{},", s.functions)?;
        write_topology(
            w,
            &TopologyJson {
                mode: s.mode,
                functions: s.functions,
                patches: &s.patches,
                chains: &s.chains,
                chain_patches: &s.chain_patches,
                corners: &s.corners,
                shells: &s.shells,
                cells: &s.cells,
            },
        )?;
        w.write_all(b",\n\"piece_patch\":")?;
        list(w, s.piece_patch.iter())?;
        w.write_all(b",\n\"piece_cells\":[")?;
        for (i, c) in s.piece_cells.iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            let id = |x: u32| if x == NONE { -1 } else { x as i64 };
            write!(w, "[{},{}]", id(c[0]), id(c[1]))?;
        }
        w.write_all(b"]")?;
        write_counts_seconds(w, &s.counts(), seconds)
    })
}
