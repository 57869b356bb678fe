//! A [`StreamSink`] writing one VTK `.vtu` (`septa ia|mi --stream OUT.vtu`),
//! for readers that cannot read the streamed PLY's per-face properties:
//! meshio reads a PLY face element with more than one property wrongly,
//! and VTK's PLY reader (ParaView, pyvista) drops them. The `.vtu` carries
//! the same polygons in the vocabulary of every other result file
//! (io/writers/result_vtk.rs): cell data `patch`, `labels` (2 components),
//! `cells` (2 components), plus `block` (the block index).
//!
//! A `.vtu` puts each array whole, one after another, while a stream
//! produces all of them together. So each array goes to its own temporary
//! spool file beside the output as blocks arrive (memory stays bounded by
//! the stream's window); [`VtuStreamSink::finish_with`] writes the header
//! (all sizes are known by then) and copies the spools in order, mapping
//! each polygon's patch piece to its patch and cells, then renames the file
//! over its destination. On error or drop every temporary file is removed.
//!
//! Vertices are written once, with the stream's ids, as in the PLY
//! (io/writers/ply_stream.rs).

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use crate::complex::Mode;
use crate::grid::BoxGrid;
use crate::io::writers::ply_stream::{PlyStreamSink, PlyStreamStats, StreamPly};
use crate::io::writers::result_vtk::vtu_header;
use crate::network::{NetworkSummary, StreamBlock, StreamSink};

/// VTK's polygon cell type.
const VTK_POLYGON: u8 = 7;

/// The spooled arrays, in the file's order (cell data `patch` and `cells`
/// come from the `piece` spool at the end).
const SPOOLS: [&str; 6] = ["points", "connectivity", "offsets", "labels", "block", "piece"];

/// Writes streamed blocks to one `.vtu` (module doc).
pub struct VtuStreamSink {
    path: PathBuf,
    dir: PathBuf,
    name: String,
    spools: Vec<Option<BufWriter<File>>>,
    vertices: u64,
    polygons: u64,
    corners: u64,
    /// With a grid, points are written where `network::embedding::snap_point`
    /// puts them (as the in-memory certified network has them).
    grid: Option<BoxGrid>,
}

fn with_path(path: &Path, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("{}: {e}", path.display()))
}

impl VtuStreamSink {
    /// Starts writing `path` (temporary files beside it).
    pub fn create(path: &Path) -> std::io::Result<VtuStreamSink> {
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new(".")).to_path_buf();
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let mut sink = VtuStreamSink {
            path: path.to_path_buf(),
            dir,
            name,
            spools: Vec::new(),
            vertices: 0,
            polygons: 0,
            corners: 0,
            grid: None,
        };
        for s in SPOOLS {
            let p = sink.temp(s);
            let f = crate::io::files::safe_write::create_temp(&p).map_err(|e| with_path(&p, e))?;
            sink.spools.push(Some(BufWriter::with_capacity(1 << 18, f)));
        }
        Ok(sink)
    }

    fn temp(&self, what: &str) -> PathBuf {
        self.dir.join(format!(".{}.{what}.tmp{}", self.name, std::process::id()))
    }

    fn write_block(&mut self, b: &StreamBlock) -> std::io::Result<()> {
        let [Some(points), Some(conn), Some(offsets), Some(labels), Some(block), Some(piece)] = &mut self.spools[..]
        else {
            return Err(std::io::Error::other("the VTU stream is already finished"));
        };
        for p in 0..b.num_polygons() {
            for &v in b.polygon(p) {
                let id = b.vertex_ids[v as usize] as u64;
                if id >= i32::MAX as u64 {
                    return Err(std::io::Error::other("more than 2^31 - 1 vertices: VTU Int32 indices overflow"));
                }
                if id == self.vertices {
                    let mut p = b.points[v as usize];
                    if let Some(g) = &self.grid {
                        p = crate::network::embedding::snap_point(p, &b.keys[v as usize], g);
                    }
                    for x in p {
                        points.write_all(&x.to_le_bytes())?;
                    }
                    self.vertices += 1;
                }
                conn.write_all(&(id as i32).to_le_bytes())?;
                self.corners += 1;
            }
            if self.corners >= i32::MAX as u64 {
                return Err(std::io::Error::other("more than 2^31 - 1 polygon corners: VTU Int32 offsets overflow"));
            }
            offsets.write_all(&(self.corners as i32).to_le_bytes())?;
            for l in b.poly_label[p] {
                labels.write_all(&(l as i32).to_le_bytes())?;
            }
            block.write_all(&(b.index as i32).to_le_bytes())?;
            piece.write_all(&b.poly_piece.get(p).copied().unwrap_or(u32::MAX).to_le_bytes())?;
            self.polygons += 1;
        }
        Ok(())
    }

    /// Finishes the file with each polygon's patch and cells from
    /// `topology` (the summary of the same stream; `-1` without one).
    pub fn finish_with(mut self, topology: Option<&NetworkSummary>) -> std::io::Result<PlyStreamStats> {
        let result = self.finish_inner(topology);
        self.cleanup();
        result
    }

    fn finish_inner(&mut self, topology: Option<&NetworkSummary>) -> std::io::Result<PlyStreamStats> {
        for s in &mut self.spools {
            let w = s.take().ok_or_else(|| std::io::Error::other("the VTU stream is already finished"))?;
            w.into_inner().map_err(|e| e.into_error())?;
        }
        let (nv, nc, nconn) = (self.vertices as usize, self.polygons as usize, self.corners as usize);
        let arrays = [
            (nv * 24, "Float64", "Points", 3),
            (nconn * 4, "Int32", "connectivity", 1),
            (nc * 4, "Int32", "offsets", 1),
            (nc, "UInt8", "types", 1),
            (nc * 4, "Int32", "patch", 1),
            (nc * 8, "Int32", "labels", 2),
            (nc * 8, "Int32", "cells", 2),
            (nc * 4, "Int32", "block", 1),
        ];
        let tmp = self.temp("vtu");
        let file = crate::io::files::safe_write::create_temp(&tmp).map_err(|e| with_path(&tmp, e))?;
        let mut w = BufWriter::with_capacity(1 << 20, file);
        w.write_all(vtu_header(nv, nc, &arrays, "patch").as_bytes())?;
        let size = |w: &mut BufWriter<File>, bytes: usize| w.write_all(&(bytes as u64).to_le_bytes());
        let copy = |w: &mut BufWriter<File>, what: &str| -> std::io::Result<()> {
            let p = self.temp(what);
            std::io::copy(&mut File::open(&p).map_err(|e| with_path(&p, e))?, w).map(|_| ())
        };
        for (what, array) in ["points", "connectivity", "offsets"].into_iter().zip(&arrays) {
            size(&mut w, array.0)?;
            copy(&mut w, what)?;
        }
        size(&mut w, nc)?;
        for _ in 0..nc {
            w.write_all(&[VTK_POLYGON])?;
        }
        // patch, then (after labels) cells: two passes over the pieces.
        let mapped = |w: &mut BufWriter<File>, cells: bool| -> std::io::Result<()> {
            let p = self.temp("piece");
            let mut r = BufReader::with_capacity(1 << 18, File::open(&p).map_err(|e| with_path(&p, e))?);
            let mut piece = [0u8; 4];
            for _ in 0..nc {
                r.read_exact(&mut piece)?;
                let piece = u32::from_le_bytes(piece) as usize;
                let known = topology.filter(|t| piece < t.piece_patch.len());
                let values = match (known, cells) {
                    (Some(t), false) => vec![t.piece_patch[piece] as i32],
                    (Some(t), true) => t.piece_cells[piece].iter().map(|&c| c as i32).collect(),
                    (None, false) => vec![-1],
                    (None, true) => vec![-1, -1],
                };
                for v in values {
                    w.write_all(&v.to_le_bytes())?;
                }
            }
            Ok(())
        };
        size(&mut w, arrays[4].0)?;
        mapped(&mut w, false)?;
        size(&mut w, arrays[5].0)?;
        copy(&mut w, "labels")?;
        size(&mut w, arrays[6].0)?;
        mapped(&mut w, true)?;
        size(&mut w, arrays[7].0)?;
        copy(&mut w, "block")?;
        w.write_all(b"\n</AppendedData>\n</VTKFile>\n")?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        crate::io::files::atomic::sync_if_durable(&file).map_err(|e| with_path(&tmp, e))?;
        drop(file);
        crate::io::files::safe_write::check_output_file(&self.path)?;
        std::fs::rename(&tmp, &self.path).map_err(|e| with_path(&self.path, e))?;
        Ok(PlyStreamStats { vertices: self.vertices, faces: self.polygons, polygons: self.polygons })
    }

    fn cleanup(&mut self) {
        self.spools.clear();
        for s in SPOOLS.iter().chain(&["vtu"]) {
            let _ = std::fs::remove_file(self.temp(s));
        }
    }
}

impl StreamSink for VtuStreamSink {
    fn block(&mut self, block: &StreamBlock) -> std::io::Result<()> {
        let r = self.write_block(block);
        r.map_err(|e| with_path(&self.path, e))
    }
}

impl Drop for VtuStreamSink {
    /// A sink dropped unfinished (an error, a cancelled run) leaves no file.
    fn drop(&mut self) {
        if !self.spools.is_empty() {
            self.cleanup();
        }
    }
}

/// The file a stream writes, by the extension of its path: `.vtu`
/// ([`VtuStreamSink`]) or a binary PLY ([`PlyStreamSink`], any other name).
pub enum StreamFile {
    /// A binary little-endian PLY.
    Ply(PlyStreamSink),
    /// A VTK unstructured grid.
    Vtu(VtuStreamSink),
}

impl StreamFile {
    /// Starts writing `path` for a run of `functions` functions in `mode` on
    /// `grid`; `triangles` (PLY only: every polygon as a fan of triangles)
    /// is refused for a `.vtu`, whose readers all take polygons.
    pub fn create(
        path: &Path,
        grid: &BoxGrid,
        mode: Mode,
        functions: usize,
        triangles: bool,
    ) -> std::io::Result<StreamFile> {
        // before any work: a link, FIFO or device at OUT is refused, never replaced
        crate::io::files::safe_write::check_output_file(path)?;
        if Self::is_vtu(path) {
            if triangles {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    format!("{}: triangle fans are for a PLY stream (a .vtu holds polygons)", path.display()),
                ));
            }
            let mut sink = VtuStreamSink::create(path)?;
            sink.grid = Some(grid.clone());
            return Ok(StreamFile::Vtu(sink));
        }
        Ok(StreamFile::Ply(PlyStreamSink::create(path, grid, mode, functions)?.triangulated(triangles)))
    }

    /// Whether `path` names a `.vtu` stream.
    pub fn is_vtu(path: &Path) -> bool {
        path.extension().is_some_and(|e| e.eq_ignore_ascii_case("vtu"))
    }

    /// Finishes the file (see [`PlyStreamSink::finish_with`] and [`VtuStreamSink::finish_with`]).
    pub fn finish_with(self, topology: Option<&NetworkSummary>) -> std::io::Result<PlyStreamStats> {
        match self {
            StreamFile::Ply(s) => s.finish_with(topology),
            StreamFile::Vtu(s) => s.finish_with(topology),
        }
    }
}

impl StreamSink for StreamFile {
    fn block(&mut self, block: &StreamBlock) -> std::io::Result<()> {
        match self {
            StreamFile::Ply(s) => s.block(block),
            StreamFile::Vtu(s) => s.block(block),
        }
    }
}

/// The arrays of a streamed `.vtu`, in file order.
const STREAM_VTU_ARRAYS: [&str; 8] =
    ["Points", "connectivity", "offsets", "types", "patch", "labels", "cells", "block"];

/// Reads a `.vtu` written by [`VtuStreamSink`] (for `septa view` on a
/// stream's folder) into the same arrays as the streamed PLY; errors name
/// the file and what is wrong.
pub fn read_stream_vtu(path: &Path) -> Result<StreamPly, String> {
    let name = path.display().to_string();
    let bytes = crate::io::files::input::read_input(path).map_err(|e| format!("{name}: cannot read: {e}"))?;
    const START: &[u8] = b"<AppendedData encoding=\"raw\">\n_";
    let end = bytes
        .windows(START.len())
        .position(|w| w == START)
        .ok_or_else(|| format!("{name}: not a streamed Septa .vtu (no raw appended data)"))?
        + START.len();
    let head = std::str::from_utf8(&bytes[..end]).map_err(|_| format!("{name}: the VTU header is not text"))?;
    let names: Vec<&str> = head.split("Name=\"").skip(1).filter_map(|s| s.split('"').next()).collect();
    if names != STREAM_VTU_ARRAYS {
        return Err(format!("{name}: not a streamed Septa .vtu (its arrays must be {})", STREAM_VTU_ARRAYS.join(", ")));
    }
    let attr = |key: &str| -> Result<usize, String> {
        head.split(&format!("{key}=\""))
            .nth(1)
            .and_then(|s| s.split('"').next())
            .and_then(|n| n.parse().ok())
            .ok_or_else(|| format!("{name}: the header has no {key}"))
    };
    let (nv, nc) = (attr("NumberOfPoints")?, attr("NumberOfCells")?);
    let mut at = end;
    let mut arrays: Vec<&[u8]> = Vec::new();
    for a in STREAM_VTU_ARRAYS {
        let short = || format!("{name}: the file ends inside array {a}");
        let size = bytes.get(at..at + 8).ok_or_else(short)?;
        let size = u64::from_le_bytes(size.try_into().unwrap()) as usize;
        arrays.push(bytes.get(at + 8..at + 8 + size).ok_or_else(short)?);
        at += 8 + size;
    }
    let ints =
        |b: &[u8]| -> Vec<i32> { b.chunks_exact(4).map(|c| i32::from_le_bytes(c.try_into().unwrap())).collect() };
    let (conn, offsets, patch, labels, cells) =
        (ints(arrays[1]), ints(arrays[2]), ints(arrays[4]), ints(arrays[5]), ints(arrays[6]));
    if arrays[0].len() != nv * 24 || [offsets.len(), patch.len(), labels.len() / 2, cells.len() / 2] != [nc; 4] {
        return Err(format!("{name}: array sizes do not match {nv} points and {nc} cells"));
    }
    let mut out = StreamPly {
        points: arrays[0]
            .chunks_exact(24)
            .map(|s| [0, 1, 2].map(|i| f64::from_le_bytes(s[8 * i..8 * i + 8].try_into().unwrap())))
            .collect(),
        patch,
        labels: labels.chunks_exact(2).map(|l| [l[0], l[1]]).collect(),
        cells: cells.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
        faces: Vec::with_capacity(nc),
    };
    let mut start = 0usize;
    for (f, &stop) in offsets.iter().enumerate() {
        let stop = usize::try_from(stop).ok().filter(|&s| s >= start + 3 && s <= conn.len());
        let stop = stop.ok_or_else(|| format!("{name}: polygon {f} has bad offsets"))?;
        let vs = &conn[start..stop];
        if let Some(v) = vs.iter().find(|&&v| v < 0 || v as usize >= nv) {
            return Err(format!("{name}: polygon {f} refers to point {v} of {nv}"));
        }
        out.faces.push(vs.iter().map(|&v| v as u32).collect());
        start = stop;
    }
    Ok(out)
}
