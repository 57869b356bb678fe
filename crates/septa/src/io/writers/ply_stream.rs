//! A [`StreamSink`] writing one binary little-endian PLY, block by block,
//! for networks larger than memory (docs/sparse.md; `septa ia|mi --stream`).
//!
//! PLY puts the element counts in the header and all vertices before all
//! faces, while a stream learns both counts last and produces vertices and
//! faces together. So vertices go straight into the output's temporary
//! file after a header whose counts are zero-padded to a fixed width
//! (`element vertex 00000000000001234567`: a valid integer for every PLY
//! reader), faces into a second temporary file; [`PlyStreamSink::finish`]
//! appends the faces, rewrites the header in place with the real counts
//! and renames the file over its destination (a reader never sees half a
//! file; on error or drop both temporary files are removed).
//!
//! Vertices are written once, with the stream's ids
//! ([`StreamBlock::vertex_ids`]: a vertex on a block boundary keeps the id
//! of the first block that used it), so a vertex is written when its id is
//! the next one.
//!
//! Per face: `vertex_indices` (list uchar int), `labels_0`, `labels_1` (int:
//! IA the function, twice; MI the two materials), `block` (int, the block
//! index), `patch`, `cells_0`, `cells_1` (int: the patch and the cells on the
//! positive and negative side, from the topology given to
//! [`PlyStreamSink::finish_with`]; -1 without one). The faces' temporary
//! file holds each polygon's patch piece, mapped while it is appended. Readers
//! that handle this: plyfile (tested), and any row-by-row PLY reader.
//! trimesh's binary reader needs one list length for all faces: with
//! [`PlyStreamSink::triangulated`] every polygon is written as a fan of
//! triangles (tested with trimesh). meshio misreads a face element with
//! more than one property either way.

use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use std::io::{BufReader, Read};

use crate::complex::Mode;
use crate::grid::BoxGrid;
use crate::network::NetworkSummary;
use crate::network::{StreamBlock, StreamSink};

/// Writes streamed blocks to one PLY (module doc).
pub struct PlyStreamSink {
    path: PathBuf,
    tmp: PathBuf,
    tmp_faces: PathBuf,
    main: Option<BufWriter<File>>,
    faces: Option<BufWriter<File>>,
    comment: String,
    vertices: u64,
    faces_written: u64,
    polygons: u64,
    /// Write each polygon as a fan of triangles (for readers that need one
    /// polygon size, such as trimesh).
    triangles: bool,
    /// Points are written on the grid's lines and planes where the exact
    /// vertex is (`network::embedding::snap_point`), as the in-memory
    /// certified network has them.
    grid: BoxGrid,
}

/// What a finished PLY holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlyStreamStats {
    /// Vertices written (each once).
    pub vertices: u64,
    /// Faces written (triangles with [`PlyStreamSink::triangulated`]).
    pub faces: u64,
    /// Network polygons written (as themselves or as triangle fans).
    pub polygons: u64,
}

fn header(comment: &str, vertices: u64, faces: u64) -> String {
    format!(
        "ply\nformat binary_little_endian 1.0\ncomment {comment}\n\
         element vertex {vertices:020}\nproperty double x\nproperty double y\nproperty double z\n\
         element face {faces:020}\nproperty list uchar int vertex_indices\n\
         property int labels_0\nproperty int labels_1\nproperty int block\n\
         property int patch\nproperty int cells_0\nproperty int cells_1\nend_header\n"
    )
}

/// Largest grid x index among a key's grid vertices (`plane`: grid
/// vertices per x plane).
fn with_path(path: &Path, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("{}: {e}", path.display()))
}

impl PlyStreamSink {
    /// Starts writing `path` (temporary files beside it) for a run of
    /// `functions` functions in `mode` on `grid`.
    pub fn create(path: &Path, grid: &BoxGrid, mode: Mode, functions: usize) -> std::io::Result<PlyStreamSink> {
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let pid = std::process::id();
        let tmp = dir.join(format!(".{name}.tmp{pid}"));
        let tmp_faces = dir.join(format!(".{name}.faces.tmp{pid}"));
        let comment = format!(
            "septa streamed surface network: {} of {functions} functions, grid {:?} (vertices on block boundaries written once)",
            match mode {
                Mode::Ia => "IA",
                Mode::Mi => "MI",
            },
            grid.res
        );
        let mut sink = PlyStreamSink {
            path: path.to_path_buf(),
            tmp,
            tmp_faces,
            main: None,
            faces: None,
            comment,
            vertices: 0,
            faces_written: 0,
            polygons: 0,
            triangles: false,
            grid: grid.clone(),
        };
        let mut main = BufWriter::with_capacity(
            1 << 20,
            crate::io::files::safe_write::create_temp(&sink.tmp).map_err(|e| with_path(&sink.tmp, e))?,
        );
        main.write_all(header(&sink.comment, 0, 0).as_bytes())?;
        sink.main = Some(main);
        let faces =
            crate::io::files::safe_write::create_temp(&sink.tmp_faces).map_err(|e| with_path(&sink.tmp_faces, e))?;
        sink.faces = Some(BufWriter::with_capacity(1 << 20, faces));
        Ok(sink)
    }

    fn write_block(&mut self, b: &StreamBlock) -> std::io::Result<()> {
        let (Some(main), Some(faces)) = (self.main.as_mut(), self.faces.as_mut()) else {
            return Err(std::io::Error::other("the PLY stream is already finished"));
        };
        let mut ids: Vec<i32> = Vec::with_capacity(16);
        for p in 0..b.num_polygons() {
            let vs = b.polygon(p);
            if vs.len() > 255 {
                return Err(std::io::Error::other(format!(
                    "block {}: a polygon has {} vertices; PLY lists hold 255",
                    b.index,
                    vs.len()
                )));
            }
            ids.clear();
            for &v in vs {
                let id = b.vertex_ids[v as usize] as u64;
                if id >= i32::MAX as u64 {
                    return Err(std::io::Error::other("more than 2^31 - 1 vertices: PLY int indices overflow"));
                }
                if id == self.vertices {
                    let p =
                        crate::network::embedding::snap_point(b.points[v as usize], &b.keys[v as usize], &self.grid);
                    for x in p {
                        main.write_all(&x.to_le_bytes())?;
                    }
                    self.vertices += 1;
                }
                ids.push(id as i32);
            }
            let [l0, l1] = b.poly_label[p];
            let piece = b.poly_piece.get(p).copied().unwrap_or(u32::MAX);
            let mut face = |vs: &[i32]| -> std::io::Result<()> {
                faces.write_all(&[vs.len() as u8])?;
                for v in vs {
                    faces.write_all(&v.to_le_bytes())?;
                }
                faces.write_all(&(l0 as i32).to_le_bytes())?;
                faces.write_all(&(l1 as i32).to_le_bytes())?;
                faces.write_all(&(b.index as i32).to_le_bytes())?;
                faces.write_all(&piece.to_le_bytes())
            };
            if self.triangles {
                // A network polygon is convex (a plane section of a convex
                // cell of the tet): a fan from its first vertex triangulates it.
                for i in 1..ids.len() - 1 {
                    face(&[ids[0], ids[i], ids[i + 1]])?;
                    self.faces_written += 1;
                }
            } else {
                face(&ids)?;
                self.faces_written += 1;
            }
            self.polygons += 1;
        }
        Ok(())
    }

    /// Writes every polygon as a fan of triangles (each keeps the polygon's
    /// labels and block): trimesh's binary PLY reader needs one list length.
    pub fn triangulated(mut self, yes: bool) -> PlyStreamSink {
        self.triangles = yes;
        self
    }

    /// Appends the faces, writes the real counts into the header and
    /// renames the file over its destination.
    pub fn finish(self) -> std::io::Result<PlyStreamStats> {
        self.finish_with(None)
    }

    /// Finishes the file with each face's patch and cells from `topology`
    /// (the summary of the same stream, [`stream_topology`](crate::network::stream_topology)).
    pub fn finish_with(mut self, topology: Option<&NetworkSummary>) -> std::io::Result<PlyStreamStats> {
        let result = self.finish_inner(topology);
        if result.is_err() {
            self.cleanup();
        }
        result
    }

    fn finish_inner(&mut self, topology: Option<&NetworkSummary>) -> std::io::Result<PlyStreamStats> {
        let (Some(main), Some(faces)) = (self.main.take(), self.faces.take()) else {
            return Err(std::io::Error::other("the PLY stream is already finished"));
        };
        let mut main = main.into_inner().map_err(|e| e.into_error())?;
        let faces = faces.into_inner().map_err(|e| e.into_error())?;
        drop(faces);
        let faces = File::open(&self.tmp_faces).map_err(|e| with_path(&self.tmp_faces, e))?;
        append_faces(faces, &mut main, self.faces_written, topology).map_err(|e| with_path(&self.tmp, e))?;
        main.seek(SeekFrom::Start(0))?;
        main.write_all(header(&self.comment, self.vertices, self.faces_written).as_bytes())?;
        crate::io::files::atomic::sync_if_durable(&main).map_err(|e| with_path(&self.tmp, e))?;
        drop(main);
        crate::io::files::safe_write::check_output_file(&self.path)?;
        std::fs::rename(&self.tmp, &self.path).map_err(|e| with_path(&self.path, e))?;
        let _ = std::fs::remove_file(&self.tmp_faces);
        Ok(PlyStreamStats { vertices: self.vertices, faces: self.faces_written, polygons: self.polygons })
    }

    fn cleanup(&mut self) {
        self.main = None;
        self.faces = None;
        let _ = std::fs::remove_file(&self.tmp);
        let _ = std::fs::remove_file(&self.tmp_faces);
    }
}

/// Copies `n` spooled faces into `out`, mapping each one's patch piece to
/// its patch and cells (`-1` without a topology).
fn append_faces(spool: File, out: &mut File, n: u64, topology: Option<&NetworkSummary>) -> std::io::Result<()> {
    let mut r = BufReader::with_capacity(1 << 20, spool);
    let mut w = BufWriter::with_capacity(1 << 20, out);
    let mut buf = [0u8; 1 + 255 * 4 + 12];
    for _ in 0..n {
        r.read_exact(&mut buf[..1])?;
        let len = 1 + 4 * buf[0] as usize + 12;
        r.read_exact(&mut buf[1..len])?;
        w.write_all(&buf[..len])?;
        let mut piece = [0u8; 4];
        r.read_exact(&mut piece)?;
        let piece = u32::from_le_bytes(piece) as usize;
        let cols = match topology {
            Some(t) if piece < t.piece_patch.len() => {
                let [c0, c1] = t.piece_cells[piece];
                [t.piece_patch[piece] as i32, c0 as i32, c1 as i32]
            }
            _ => [-1; 3],
        };
        for c in cols {
            w.write_all(&c.to_le_bytes())?;
        }
    }
    let mut rest = [0u8; 1];
    if r.read(&mut rest)? != 0 {
        return Err(std::io::Error::other("the faces' temporary file is longer than its faces"));
    }
    w.flush()
}

impl StreamSink for PlyStreamSink {
    fn block(&mut self, block: &StreamBlock) -> std::io::Result<()> {
        let r = self.write_block(block);
        r.map_err(|e| with_path(&self.path, e))
    }
}

impl Drop for PlyStreamSink {
    /// A sink dropped unfinished (an error, a cancelled run) leaves no file.
    fn drop(&mut self) {
        if self.main.is_some() || self.faces.is_some() {
            self.cleanup();
        }
    }
}

/// A streamed PLY read back: points and polygons with each face's
/// `labels_0/1`, `patch` and `cells_0/1` (triangle fans stay triangles).
#[derive(Clone, Debug, Default)]
pub struct StreamPly {
    /// Vertex positions.
    pub points: Vec<[f64; 3]>,
    /// Polygons (vertex ids).
    pub faces: Vec<Vec<u32>>,
    /// Per face: `labels_0`, `labels_1`.
    pub labels: Vec<[i32; 2]>,
    /// Per face: `patch` (-1 without topology).
    pub patch: Vec<i32>,
    /// Per face: `cells_0`, `cells_1` (-1: none).
    pub cells: Vec<[i32; 2]>,
}

/// Reads a PLY written by [`PlyStreamSink`] (for `septa view` on a stream's
/// folder); errors name the file and what is wrong.
pub fn read_stream_ply(path: &Path) -> Result<StreamPly, String> {
    let name = path.display().to_string();
    let bytes = crate::io::files::input::read_input(path).map_err(|e| format!("{name}: cannot read: {e}"))?;
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .ok_or_else(|| format!("{name}: not a PLY file (no end_header)"))?
        + 11;
    let head = std::str::from_utf8(&bytes[..end]).map_err(|_| format!("{name}: the PLY header is not text"))?;
    let expected = header("", 0, 0);
    let props = |h: &str| -> Vec<String> {
        h.lines().filter(|l| l.starts_with("property") || l.starts_with("format")).map(str::to_string).collect()
    };
    if props(head) != props(&expected) {
        return Err(format!("{name}: not a streamed Septa PLY (its faces need vertex_indices, labels_0, labels_1, block, patch, cells_0, cells_1)"));
    }
    let count = |el: &str| -> Result<usize, String> {
        head.lines()
            .find_map(|l| l.strip_prefix(&format!("element {el} ")))
            .and_then(|n| n.trim().parse().ok())
            .ok_or_else(|| format!("{name}: the header has no element {el} count"))
    };
    let (nv, nf) = (count("vertex")?, count("face")?);
    let short = || format!("{name}: the file ends before its {nv} vertices and {nf} faces");
    let mut at = end;
    let mut take = |n: usize| -> Result<&[u8], String> {
        let s = bytes.get(at..at + n).ok_or_else(short)?;
        at += n;
        Ok(s)
    };
    let mut out = StreamPly::default();
    for _ in 0..nv {
        let s = take(24)?;
        out.points.push([0, 1, 2].map(|i| f64::from_le_bytes(s[8 * i..8 * i + 8].try_into().unwrap())));
    }
    let int = |s: &[u8], i: usize| i32::from_le_bytes(s[4 * i..4 * i + 4].try_into().unwrap());
    for f in 0..nf {
        let n = take(1)?[0] as usize;
        let s = take(4 * n + 24)?;
        let vs: Vec<u32> = (0..n).map(|i| int(s, i) as u32).collect();
        if let Some(v) = vs.iter().find(|&&v| v as usize >= nv) {
            return Err(format!("{name}: face {f} refers to vertex {v} of {nv}"));
        }
        out.faces.push(vs);
        out.labels.push([int(s, n), int(s, n + 1)]);
        out.patch.push(int(s, n + 3));
        out.cells.push([int(s, n + 4), int(s, n + 5)]);
    }
    Ok(out)
}
