//! A [`StreamSink`] writing one VTK `.vtu` (`septa ia|mi --stream OUT.vtu`),
//! for readers that cannot read the streamed PLY's per-face properties:
//! meshio reads a PLY face element with more than one property wrongly,
//! and VTK's PLY reader (ParaView, pyvista) drops them. The `.vtu` carries
//! the same polygons in the vocabulary of every other result file
//! (io/writers/result_vtk.rs): cell data `patch`, `labels` (2 components),
//! `cells` (2 components), plus `block` (the block index) and `face` (the
//! polygon's place in the stream: its row in the streamed PLY).
//!
//! As every Septa VTU (io/writers/result_vtk.rs), triangles are `VTK_TRIANGLE`,
//! quads `VTK_QUAD`, larger polygons `VTK_POLYGON`, grouped by size so that
//! meshio reads one block per size; within a size in stream order.
//!
//! A `.vtu` puts each array whole, one after another, while a stream
//! produces all of them together. So the points go to a temporary spool
//! file and each polygon to the spool of its size (a fixed-length record:
//! its vertices, labels, block, patch piece and place) beside the output as
//! blocks arrive (memory stays bounded by the stream's window);
//! [`VtuStreamSink::finish_with`] writes the header (all sizes are known by
//! then) and, per array, reads the size spools in order, mapping each
//! polygon's patch piece to its patch and cells, then renames the file over
//! its destination. On error or drop every temporary file is removed.
//!
//! Vertices are written once, with the stream's ids, as in the PLY
//! (io/writers/ply_stream.rs).

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use crate::complex::Mode;
use crate::grid::BoxGrid;
use crate::io::writers::ply_stream::{PlyStreamSink, PlyStreamStats, StreamPly};
use crate::io::writers::result_vtk::vtu_header;
use crate::io::writers::result_vtk::{polygon_type, size_class};
use crate::network::{NetworkSummary, StreamBlock, StreamSink};

/// The polygons of one size: their spool of records (`n` vertex ids, 2
/// labels, block, patch piece, place: `n + 5` little-endian 4-byte words)
/// and how many.
struct SizeSpool {
    file: Option<BufWriter<File>>,
    count: u64,
}

/// Writes streamed blocks to one `.vtu` (module doc).
pub struct VtuStreamSink {
    path: PathBuf,
    dir: PathBuf,
    name: String,
    /// The points' spool (`None` once finished).
    points: Option<BufWriter<File>>,
    /// Polygons by size (vertex count).
    sizes: BTreeMap<usize, SizeSpool>,
    finished: bool,
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
            points: None,
            sizes: BTreeMap::new(),
            finished: false,
            vertices: 0,
            polygons: 0,
            corners: 0,
            grid: None,
        };
        let p = sink.temp("points");
        let f = crate::io::files::safe_write::create_temp(&p).map_err(|e| with_path(&p, e))?;
        sink.points = Some(BufWriter::with_capacity(1 << 18, f));
        Ok(sink)
    }

    fn temp(&self, what: &str) -> PathBuf {
        self.dir.join(format!(".{}.{what}.tmp{}", self.name, std::process::id()))
    }

    fn write_block(&mut self, b: &StreamBlock) -> std::io::Result<()> {
        let finished = || std::io::Error::other("the VTU stream is already finished");
        if self.finished {
            return Err(finished());
        }
        let mut record: Vec<u8> = Vec::with_capacity(64);
        for p in 0..b.num_polygons() {
            let poly = b.polygon(p);
            record.clear();
            for &v in poly {
                let id = b.vertex_ids[v as usize] as u64;
                if id >= i32::MAX as u64 {
                    return Err(std::io::Error::other("more than 2^31 - 1 vertices: VTU Int32 indices overflow"));
                }
                if id == self.vertices {
                    let mut x = b.points[v as usize];
                    if let Some(g) = &self.grid {
                        x = crate::network::embedding::snap_point(x, &b.keys[v as usize], g);
                    }
                    let points = self.points.as_mut().ok_or_else(finished)?;
                    for c in x {
                        points.write_all(&c.to_le_bytes())?;
                    }
                    self.vertices += 1;
                }
                record.extend_from_slice(&(id as i32).to_le_bytes());
            }
            self.corners += poly.len() as u64;
            if self.corners >= i32::MAX as u64 || self.polygons >= i32::MAX as u64 {
                return Err(std::io::Error::other(
                    "more than 2^31 - 1 polygons or polygon corners: VTU Int32 offsets overflow",
                ));
            }
            for l in b.poly_label[p] {
                record.extend_from_slice(&(l as i32).to_le_bytes());
            }
            record.extend_from_slice(&(b.index as i32).to_le_bytes());
            record.extend_from_slice(&b.poly_piece.get(p).copied().unwrap_or(u32::MAX).to_le_bytes());
            record.extend_from_slice(&(self.polygons as i32).to_le_bytes());
            let spool = match self.sizes.entry(poly.len()) {
                std::collections::btree_map::Entry::Occupied(e) => e.into_mut(),
                std::collections::btree_map::Entry::Vacant(e) => {
                    let path = self.dir.join(format!(".{}.size{}.tmp{}", self.name, poly.len(), std::process::id()));
                    let f = crate::io::files::safe_write::create_temp(&path).map_err(|e| with_path(&path, e))?;
                    e.insert(SizeSpool { file: Some(BufWriter::with_capacity(1 << 16, f)), count: 0 })
                }
            };
            spool.file.as_mut().ok_or_else(finished)?.write_all(&record)?;
            spool.count += 1;
            self.polygons += 1;
        }
        Ok(())
    }

    /// The polygon sizes in the file's order (triangles, quads, larger).
    fn size_order(&self) -> Vec<usize> {
        let mut sizes: Vec<usize> = self.sizes.keys().copied().collect();
        sizes.sort_by_key(|&n| size_class(n));
        sizes
    }

    /// Streams, for every polygon in file order, `words` 4-byte words
    /// starting at word `from(n)` of its record (`n` its size) into `out`.
    fn each_record(
        &self,
        w: &mut BufWriter<File>,
        mut out: impl FnMut(&mut BufWriter<File>, &[u8]) -> std::io::Result<()>,
        field: impl Fn(usize) -> std::ops::Range<usize>,
    ) -> std::io::Result<()> {
        for n in self.size_order() {
            let path = self.temp(&format!("size{n}"));
            let mut r = BufReader::with_capacity(1 << 18, File::open(&path).map_err(|e| with_path(&path, e))?);
            let mut record = vec![0u8; 4 * (n + 5)];
            let range = field(n);
            for _ in 0..self.sizes[&n].count {
                r.read_exact(&mut record)?;
                out(w, &record[4 * range.start..4 * range.end])?;
            }
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
        self.finished = true;
        let finished = || std::io::Error::other("the VTU stream is already finished");
        let points = self.points.take().ok_or_else(finished)?;
        points.into_inner().map_err(|e| e.into_error())?;
        for s in self.sizes.values_mut() {
            let w = s.file.take().ok_or_else(finished)?;
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
            (nc * 4, "Int32", "face", 1),
        ];
        let tmp = self.temp("vtu");
        let file = crate::io::files::safe_write::create_temp(&tmp).map_err(|e| with_path(&tmp, e))?;
        let mut w = BufWriter::with_capacity(1 << 20, file);
        w.write_all(vtu_header(nv, nc, &arrays, "patch").as_bytes())?;
        let size = |w: &mut BufWriter<File>, bytes: usize| w.write_all(&(bytes as u64).to_le_bytes());
        size(&mut w, arrays[0].0)?;
        let p = self.temp("points");
        std::io::copy(&mut File::open(&p).map_err(|e| with_path(&p, e))?, &mut w)?;
        let copy = |w: &mut BufWriter<File>, b: &[u8]| w.write_all(b);
        size(&mut w, arrays[1].0)?;
        self.each_record(&mut w, copy, |n| 0..n)?;
        size(&mut w, arrays[2].0)?;
        let mut end = 0i32;
        for n in self.size_order() {
            for _ in 0..self.sizes[&n].count {
                end += n as i32;
                w.write_all(&end.to_le_bytes())?;
            }
        }
        size(&mut w, arrays[3].0)?;
        for n in self.size_order() {
            for _ in 0..self.sizes[&n].count {
                w.write_all(&[polygon_type(n)])?;
            }
        }
        // patch and cells: each polygon's patch piece mapped by the topology
        let mapped = |cells: bool| {
            move |w: &mut BufWriter<File>, b: &[u8]| -> std::io::Result<()> {
                let piece = u32::from_le_bytes(b.try_into().unwrap()) as usize;
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
                Ok(())
            }
        };
        size(&mut w, arrays[4].0)?;
        self.each_record(&mut w, mapped(false), |n| n + 3..n + 4)?;
        size(&mut w, arrays[5].0)?;
        self.each_record(&mut w, copy, |n| n..n + 2)?;
        size(&mut w, arrays[6].0)?;
        self.each_record(&mut w, mapped(true), |n| n + 3..n + 4)?;
        size(&mut w, arrays[7].0)?;
        self.each_record(&mut w, copy, |n| n + 2..n + 3)?;
        size(&mut w, arrays[8].0)?;
        self.each_record(&mut w, copy, |n| n + 4..n + 5)?;
        w.write_all(b"\n</AppendedData>\n</VTKFile>\n")?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        crate::io::files::atomic::sync_if_durable(&file).map_err(|e| with_path(&tmp, e))?;
        drop(file);
        crate::io::files::safe_write::check_output_file(&self.path)?;
        std::fs::rename(&tmp, &self.path).map_err(|e| with_path(&self.path, e))?;
        Ok(PlyStreamStats { vertices: self.vertices, faces: self.polygons, polygons: self.polygons })
    }

    fn cleanup(&mut self) {
        self.points = None;
        let sizes: Vec<usize> = self.sizes.keys().copied().collect();
        self.sizes.clear();
        self.finished = true;
        for what in sizes.iter().map(|n| format!("size{n}")).chain(["points".into(), "vtu".into()]) {
            let _ = std::fs::remove_file(self.temp(&what));
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
        if self.points.is_some() || !self.sizes.is_empty() {
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

/// The arrays of a streamed `.vtu`, in file order (`face` since polygons
/// are grouped by size; a file without it is in stream order).
const STREAM_VTU_ARRAYS: [&str; 9] =
    ["Points", "connectivity", "offsets", "types", "patch", "labels", "cells", "block", "face"];

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
    let has_face = names == STREAM_VTU_ARRAYS;
    if !has_face && names != STREAM_VTU_ARRAYS[..8] {
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
    for a in &STREAM_VTU_ARRAYS[..names.len()] {
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
    if has_face {
        // rows grouped by size: back to the stream's order
        let face = ints(arrays[8]);
        if face.len() != nc {
            return Err(format!("{name}: array sizes do not match {nv} points and {nc} cells"));
        }
        let mut row_of = vec![usize::MAX; nc];
        for (row, &f) in face.iter().enumerate() {
            match usize::try_from(f).ok().filter(|&f| f < nc && row_of[f] == usize::MAX) {
                Some(f) => row_of[f] = row,
                None => return Err(format!("{name}: row {row} names face {f}, not a face of 0..{nc} given once")),
            }
        }
        out.patch = row_of.iter().map(|&r| out.patch[r]).collect();
        out.labels = row_of.iter().map(|&r| out.labels[r]).collect();
        out.cells = row_of.iter().map(|&r| out.cells[r]).collect();
        let mut faces = std::mem::take(&mut out.faces);
        out.faces = row_of.iter().map(|&r| std::mem::take(&mut faces[r])).collect();
    }
    Ok(out)
}
