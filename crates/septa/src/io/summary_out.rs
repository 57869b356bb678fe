//! `<stream>.topology.json`: the topology of a streamed network (issue 6),
//! in `network.json`'s names for what it has (patches, chains,
//! chain_patches, corners, shells, cells, counts) plus the map from each
//! polygon's patch piece to its patch and cells; the polygons themselves
//! are in the streamed PLY (whose faces already carry patch and cells).
//! Vertex ids in chains and corners are the PLY's.

use std::io::Write;
use std::path::Path;

use super::atomic::write_atomic_with;
use super::network_out::{label_json, list};
use crate::complex::NONE;
use crate::network::{Mode, NetworkSummary};

/// Writes the summary's JSON atomically.
pub fn write_summary_json(s: &NetworkSummary, path: &Path, seconds: &[(&str, f64)]) -> std::io::Result<()> {
    write_atomic_with(path, |w| {
        let mode = match s.mode {
            Mode::Ia => "ia",
            Mode::Mi => "mi",
        };
        write!(w, "{{\"mode\":\"{mode}\",\"functions\":{},\n\"patches\":[", s.functions)?;
        for (i, p) in s.patches.iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            write!(w, "{{\"label\":[{},{}],\"faces\":{}}}", p.label[0], p.label[1], p.faces)?;
        }
        let lists = |w: &mut dyn Write, name: &str, xs: &[Vec<u32>]| -> std::io::Result<()> {
            write!(w, "],\n\"{name}\":[")?;
            for (i, c) in xs.iter().enumerate() {
                if i > 0 {
                    w.write_all(b",")?;
                }
                list(w, c.iter())?;
            }
            Ok(())
        };
        lists(w, "chains", &s.chains)?;
        lists(w, "chain_patches", &s.chain_patches)?;
        w.write_all(b"],\n\"corners\":")?;
        list(w, s.corners.iter())?;
        w.write_all(b",\n\"shells\":[")?;
        for (i, sh) in s.shells.iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            list(w, sh.iter())?;
        }
        w.write_all(b"],\n\"cells\":[")?;
        for (i, c) in s.cells.iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            w.write_all(b"{\"shells\":")?;
            list(w, c.shells.iter())?;
            write!(w, ",\"label\":{}}}", label_json(s.mode, s.functions, &c.label))?;
        }
        w.write_all(b"],\n\"piece_patch\":")?;
        list(w, s.piece_patch.iter())?;
        w.write_all(b",\n\"piece_cells\":[")?;
        for (i, c) in s.piece_cells.iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            let id = |x: u32| if x == NONE { -1 } else { x as i64 };
            write!(w, "[{},{}]", id(c[0]), id(c[1]))?;
        }
        w.write_all(b"],\n\"counts\":{")?;
        for (i, (k, v)) in s.counts().iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            write!(w, "\"{k}\":{v}")?;
        }
        w.write_all(b"},\n\"seconds\":{")?;
        for (i, (k, v)) in seconds.iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            write!(w, "\"{k}\":{v}")?;
        }
        w.write_all(b"}}\n")
    })
}
