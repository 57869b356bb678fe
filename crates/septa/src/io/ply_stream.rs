//! A [`StreamSink`] writing one binary little-endian PLY, block by block,
//! for networks larger than memory (issue 6; `septa ia|mi --stream`).
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
//! Vertices are written once: a block's inner vertices are its own, and a
//! vertex on a block boundary (shared by key, Du et al. Sec. 5.1) gets the
//! id it got in the first block that wrote it, through a map holding only
//! boundary keys. Blocks come in index order (x slabs outermost), so a key
//! whose grid element lies left of the current slab can never come again
//! and is dropped: the map holds about two slabs' boundary vertices, which
//! grow like the surface's section, not like the grid.
//!
//! Per face: `vertex_indices` (list uchar int), `label0`, `label1` (int:
//! IA the function, twice; MI the two materials) and `block` (int, the
//! block index), in the layout of `network.ply` (`network_out.rs`). Readers
//! that handle this: plyfile (tested), and any row-by-row PLY reader.
//! trimesh's binary reader needs one list length for all faces: with
//! [`PlyStreamSink::triangulated`] every polygon is written as a fan of
//! triangles (tested with trimesh). meshio misreads a face element with
//! more than one property either way.

use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use rustc_hash::FxHashMap;

use crate::grid::BoxGrid;
use crate::network::stream::{StreamBlock, StreamSink};
use crate::network::{Mode, VKey};

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
    /// Boundary vertex key -> vertex id, for keys that may still come.
    shared: FxHashMap<VKey, u32>,
    /// Cube x of the current slab; keys left of it are evicted.
    slab: usize,
    /// Grid vertices per x plane (to read x off a grid vertex id).
    plane: u64,
    remap: Vec<u32>,
    /// Most boundary keys held at once (for the memory claim).
    peak_shared: usize,
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
    /// Most boundary keys held at once by the vertex map.
    pub peak_shared_keys: usize,
}

const NONE: u32 = u32::MAX;

fn header(comment: &str, vertices: u64, faces: u64) -> String {
    format!(
        "ply\nformat binary_little_endian 1.0\ncomment {comment}\n\
         element vertex {vertices:020}\nproperty double x\nproperty double y\nproperty double z\n\
         element face {faces:020}\nproperty list uchar int vertex_indices\n\
         property int label0\nproperty int label1\nproperty int block\nend_header\n"
    )
}

/// Largest grid x index among a key's grid vertices (`plane`: grid
/// vertices per x plane).
fn max_x(plane: u64, k: &VKey) -> usize {
    k.grid.iter().filter(|&&v| v != u32::MAX).map(|&v| (v as u64 / plane) as usize).max().unwrap_or(0)
}

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
            shared: FxHashMap::default(),
            slab: 0,
            plane: (grid.res[1] as u64 + 1) * (grid.res[2] as u64 + 1),
            remap: Vec::new(),
            peak_shared: 0,
        };
        let mut main = BufWriter::with_capacity(1 << 20, File::create(&sink.tmp).map_err(|e| with_path(&sink.tmp, e))?);
        main.write_all(header(&sink.comment, 0, 0).as_bytes())?;
        sink.main = Some(main);
        let faces = File::create(&sink.tmp_faces).map_err(|e| with_path(&sink.tmp_faces, e))?;
        sink.faces = Some(BufWriter::with_capacity(1 << 20, faces));
        Ok(sink)
    }

    fn write_block(&mut self, b: &StreamBlock) -> std::io::Result<()> {
        if b.lo[0] > self.slab {
            // No later block reaches left of x = lo: those keys are done.
            self.slab = b.lo[0];
            let slab = self.slab;
            let plane = self.plane;
            self.shared.retain(|k, _| max_x(plane, k) >= slab);
        }
        let (Some(main), Some(faces)) = (self.main.as_mut(), self.faces.as_mut()) else {
            return Err(std::io::Error::other("the PLY stream is already finished"));
        };
        self.remap.clear();
        self.remap.resize(b.keys.len(), NONE);
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
                let v = v as usize;
                if self.remap[v] == NONE {
                    let next = self.vertices;
                    if next >= i32::MAX as u64 {
                        return Err(std::io::Error::other("more than 2^31 - 1 vertices: PLY int indices overflow"));
                    }
                    let id =
                        if b.shared[v] { *self.shared.entry(b.keys[v]).or_insert(next as u32) } else { next as u32 };
                    if id as u64 == next {
                        for x in b.points[v] {
                            main.write_all(&x.to_le_bytes())?;
                        }
                        self.vertices += 1;
                    }
                    self.remap[v] = id;
                }
                ids.push(self.remap[v] as i32);
            }
            let [l0, l1] = b.poly_label[p];
            let mut face = |vs: &[i32]| -> std::io::Result<()> {
                faces.write_all(&[vs.len() as u8])?;
                for v in vs {
                    faces.write_all(&v.to_le_bytes())?;
                }
                faces.write_all(&(l0 as i32).to_le_bytes())?;
                faces.write_all(&(l1 as i32).to_le_bytes())?;
                faces.write_all(&(b.index as i32).to_le_bytes())
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
        self.peak_shared = self.peak_shared.max(self.shared.len());
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
    pub fn finish(mut self) -> std::io::Result<PlyStreamStats> {
        let result = self.finish_inner();
        if result.is_err() {
            self.cleanup();
        }
        result
    }

    fn finish_inner(&mut self) -> std::io::Result<PlyStreamStats> {
        let (Some(main), Some(faces)) = (self.main.take(), self.faces.take()) else {
            return Err(std::io::Error::other("the PLY stream is already finished"));
        };
        let mut main = main.into_inner().map_err(|e| e.into_error())?;
        let faces = faces.into_inner().map_err(|e| e.into_error())?;
        drop(faces);
        let mut faces = File::open(&self.tmp_faces).map_err(|e| with_path(&self.tmp_faces, e))?;
        std::io::copy(&mut faces, &mut main).map_err(|e| with_path(&self.tmp, e))?;
        drop(faces);
        main.seek(SeekFrom::Start(0))?;
        main.write_all(header(&self.comment, self.vertices, self.faces_written).as_bytes())?;
        main.sync_all().map_err(|e| with_path(&self.tmp, e))?;
        drop(main);
        std::fs::rename(&self.tmp, &self.path).map_err(|e| with_path(&self.path, e))?;
        let _ = std::fs::remove_file(&self.tmp_faces);
        Ok(PlyStreamStats {
            vertices: self.vertices,
            faces: self.faces_written,
            polygons: self.polygons,
            peak_shared_keys: self.peak_shared,
        })
    }

    fn cleanup(&mut self) {
        self.main = None;
        self.faces = None;
        let _ = std::fs::remove_file(&self.tmp);
        let _ = std::fs::remove_file(&self.tmp_faces);
    }
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
