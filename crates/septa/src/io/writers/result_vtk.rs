//! VTK XML files of a [`ResultView`]: `.vtu` (the polygons with cell data
//! `patch`, `labels` (2 components), `cells` (2 components), `area`, `face`) and `.vtm`, a
//! MultiBlock of four `.vtu` pieces that ParaView opens as one tree:
//! `patches` (the polygons), `chains` (a line cell per chain edge with its `chain` and
//! the number of patches around that chain), `corners` (vertex cells with `corner`)
//! and `cells` (every cell's boundary, each polygon once per side and
//! oriented out of the cell, with `cell`, the cell's `label` and `volume`; shrink or
//! threshold by `cell` for an exploded view). Raw appended binary data,
//! UInt64 headers: readable by VTK >= 8 (ParaView, pyvista) and meshio.
//!
//! **Polygons by size.** Triangles are written as `VTK_TRIANGLE`, quads as
//! `VTK_QUAD`, larger polygons as `VTK_POLYGON`, in that order and the larger
//! ones by size (stable: by face id within a size). meshio starts a new cell
//! block wherever the cell type or a polygon's size changes, so in the
//! network's face order it read one block per run of one size (5,865 for the
//! Apollonius diagram of `builtin:apollonius-18`, 13,224 polygons of 3 to 6
//! vertices); grouped it reads one per size (4 there), as the cut writer's
//! polyhedra (`cut_vtu.rs`). A row is then not the face of that number in
//! `network.npz`/`.json`: the cell data `face` names it (in the `cells`
//! block too), and every per-face array is written in the rows' order.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::io::files::atomic::write_atomic_with;
use crate::io::files::outdir::OutputDir;
use crate::io::writers::result::ResultView;

/// VTK cell types used here.
const VTK_VERTEX: u8 = 1;
const VTK_LINE: u8 = 3;
const VTK_TRIANGLE: u8 = 5;
const VTK_POLYGON: u8 = 7;
const VTK_QUAD: u8 = 9;

/// The VTK cell type of a polygon of `n` vertices.
pub(crate) fn polygon_type(n: usize) -> u8 {
    match n {
        3 => VTK_TRIANGLE,
        4 => VTK_QUAD,
        _ => VTK_POLYGON,
    }
}

/// Where a polygon of `n` vertices goes in the file: triangles, quads, then
/// larger polygons by size (module doc).
pub(crate) fn size_class(n: usize) -> usize {
    match n {
        3 => 0,
        4 => 1,
        k => k,
    }
}

/// The faces of `r` in the order the VTK files write them (module doc).
pub fn vtk_face_order(r: &ResultView) -> Vec<u32> {
    let mut order: Vec<u32> = (0..r.num_faces() as u32).collect();
    // stable: by face id within a size
    order.sort_by_key(|&f| size_class(r.face(f as usize).len()));
    order
}

/// One unstructured piece: cells of one type over all of the result's points.
struct Piece<'a> {
    points: &'a [[f64; 3]],
    /// Cell `c` is `conn[offsets[c]..offsets[c + 1]]` (offsets start at 0).
    conn: Vec<u32>,
    offsets: Vec<u32>,
    /// Per cell its VTK type.
    types: Vec<u8>,
    /// Cell data: name, components, values (`components` per cell).
    data: Vec<(&'static str, usize, Values)>,
}

/// One cell-data array's values.
enum Values {
    I32(Vec<i32>),
    F64(Vec<f64>),
}

impl Values {
    fn bytes(&self) -> usize {
        match self {
            Values::I32(v) => v.len() * 4,
            Values::F64(v) => v.len() * 8,
        }
    }
    fn vtk_type(&self) -> &'static str {
        match self {
            Values::I32(_) => "Int32",
            Values::F64(_) => "Float64",
        }
    }
}

/// The XML of an unstructured grid with `np` points and `nc` cells whose
/// arrays (byte length, VTK type, name, components) follow in raw appended
/// data in this order: `Points`, then `connectivity`, `offsets`, `types`,
/// then the cell data (`scalars` the active one). Each appended array is
/// preceded by its UInt64 byte count; the text ends with the `_` that
/// starts the appended data.
pub(crate) fn vtu_header(np: usize, nc: usize, arrays: &[(usize, &str, &str, usize)], scalars: &str) -> String {
    let mut offset = 0usize;
    let mut xml = Vec::new();
    for (bytes, ty, name, comps) in arrays {
        xml.push(format!(
            "<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{comps}\" format=\"appended\" offset=\"{offset}\"/>\n"
        ));
        offset += 8 + bytes;
    }
    format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n\
         <UnstructuredGrid>\n<Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nc}\">\n<Points>\n{}</Points>\n\
         <Cells>\n{}{}{}</Cells>\n<CellData Scalars=\"{scalars}\">\n{}</CellData>\n</Piece>\n</UnstructuredGrid>\n\
         <AppendedData encoding=\"raw\">\n_",
        xml[0],
        xml[1],
        xml[2],
        xml[3],
        xml[4..].concat()
    )
}

fn write_piece(piece: &Piece, path: &Path) -> std::io::Result<()> {
    let nc = piece.offsets.len() - 1;
    let np = piece.points.len();
    // Appended arrays in order, each preceded by its UInt64 byte count.
    let mut arrays: Vec<(usize, &str, &str, usize)> = vec![
        (np * 24, "Float64", "Points", 3),
        (piece.conn.len() * 4, "Int32", "connectivity", 1),
        (nc * 4, "Int32", "offsets", 1),
        (nc, "UInt8", "types", 1),
    ];
    for (name, comps, values) in &piece.data {
        arrays.push((values.bytes(), values.vtk_type(), name, *comps));
    }
    let scalars = piece.data.first().map_or("", |d| d.0);
    let head = vtu_header(np, nc, &arrays, scalars);
    write_atomic_with(path, |w| {
        w.write_all(head.as_bytes())?;
        let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
        let flush = |w: &mut std::io::BufWriter<std::fs::File>, buf: &mut Vec<u8>, force: bool| {
            if force || buf.len() > 1 << 16 {
                w.write_all(buf)?;
                buf.clear();
            }
            Ok::<(), std::io::Error>(())
        };
        buf.extend_from_slice(&(arrays[0].0 as u64).to_le_bytes());
        for p in piece.points {
            for x in p {
                buf.extend_from_slice(&x.to_le_bytes());
            }
            flush(w, &mut buf, false)?;
        }
        let ints = |w: &mut std::io::BufWriter<std::fs::File>, buf: &mut Vec<u8>, xs: &mut dyn Iterator<Item = i32>| {
            for x in xs {
                buf.extend_from_slice(&x.to_le_bytes());
                if buf.len() > 1 << 16 {
                    w.write_all(buf)?;
                    buf.clear();
                }
            }
            Ok::<(), std::io::Error>(())
        };
        buf.extend_from_slice(&(arrays[1].0 as u64).to_le_bytes());
        ints(w, &mut buf, &mut piece.conn.iter().map(|&v| v as i32))?;
        buf.extend_from_slice(&(arrays[2].0 as u64).to_le_bytes());
        ints(w, &mut buf, &mut piece.offsets[1..].iter().map(|&v| v as i32))?;
        buf.extend_from_slice(&(arrays[3].0 as u64).to_le_bytes());
        buf.extend_from_slice(&piece.types);
        for (i, (_, _, values)) in piece.data.iter().enumerate() {
            buf.extend_from_slice(&(arrays[4 + i].0 as u64).to_le_bytes());
            match values {
                Values::I32(v) => ints(w, &mut buf, &mut v.iter().copied())?,
                Values::F64(v) => {
                    for x in v {
                        buf.extend_from_slice(&x.to_le_bytes());
                        flush(w, &mut buf, false)?;
                    }
                }
            }
        }
        flush(w, &mut buf, true)?;
        w.write_all(b"\n</AppendedData>\n</VTKFile>\n")
    })
}

fn polygons<'a>(r: &'a ResultView) -> Piece<'a> {
    let order = vtk_face_order(r);
    let mut conn = Vec::with_capacity(r.face_verts.len());
    let mut offsets = Vec::with_capacity(order.len() + 1);
    offsets.push(0u32);
    for &f in &order {
        conn.extend_from_slice(r.face(f as usize));
        offsets.push(conn.len() as u32);
    }
    let each = |f: &dyn Fn(usize) -> i32| order.iter().map(|&g| f(g as usize)).collect::<Vec<i32>>();
    let pairs = |a: &[[i32; 2]]| order.iter().flat_map(|&g| a[g as usize]).collect::<Vec<i32>>();
    Piece {
        points: &r.points,
        types: order.iter().map(|&f| polygon_type(r.face(f as usize).len())).collect(),
        conn,
        offsets,
        data: vec![
            ("patch", 1, Values::I32(each(&|f| r.patch[f] as i32))),
            ("labels", 2, Values::I32(pairs(&r.labels))),
            ("cells", 2, Values::I32(pairs(&r.cells))),
            ("area", 1, Values::F64(order.iter().map(|&f| r.face_area(f as usize)).collect())),
            ("face", 1, Values::I32(each(&|f| f as i32))),
        ],
    }
}

/// Writes the polygons of `r` as a `.vtu` (module doc).
pub fn write_vtu(r: &ResultView, path: &Path) -> std::io::Result<()> {
    write_piece(&polygons(r), path)
}

/// The chains as line cells, one per chain edge (meshio reads lines but
/// not polylines), with `chain` (its chain) and `patches` (how many
/// patches meet along that chain; 0 where unknown, e.g. region curves).
fn chains<'a>(r: &'a ResultView) -> Piece<'a> {
    let mut conn = Vec::new();
    let (mut chain, mut patches) = (Vec::new(), Vec::new());
    for (c, vs) in r.chains.iter().enumerate() {
        for e in vs.windows(2) {
            conn.extend_from_slice(e);
            chain.push(c as i32);
            patches.push(r.chain_patches.get(c).map_or(0, |p| p.len() as i32));
        }
    }
    Piece {
        points: &r.points,
        offsets: (0..=conn.len() as u32 / 2).map(|i| 2 * i).collect(),
        types: vec![VTK_LINE; conn.len() / 2],
        conn,
        data: measured(
            vec![("chain", 1, Values::I32(chain.clone())), ("patches", 1, Values::I32(patches))],
            "length",
            &r.measures.chain_length,
            &chain,
        ),
    }
}

fn corners<'a>(r: &'a ResultView) -> Piece<'a> {
    Piece {
        points: &r.points,
        conn: r.corners.to_vec(),
        offsets: (0..=r.corners.len() as u32).collect(),
        types: vec![VTK_VERTEX; r.corners.len()],
        data: vec![("corner", 1, Values::I32((0..r.corners.len() as i32).collect()))],
    }
}

/// Every cell's boundary: each polygon once per side it bounds, oriented out
/// of that cell (a polygon is counter-clockwise seen from its positive side,
/// so it is reversed for the cell on its positive side). Cell data `cell`,
/// `patch` and `label` (MI the cell's material, regions its region, IA its
/// sign vector as bits, function `f` positive in bit `f`, for `f < 31`)
/// and `face`. Rows by size as the polygons (module doc), then by cell.
fn cell_boundaries<'a>(r: &'a ResultView) -> Piece<'a> {
    let nf = r.num_faces();
    // (size class, cell, face, reversed)
    let mut side: Vec<(usize, i32, u32, bool)> = Vec::with_capacity(2 * nf);
    for f in 0..nf {
        let [cp, cn] = r.cells[f];
        let class = size_class(r.face(f).len());
        if cp >= 0 {
            side.push((class, cp, f as u32, true));
        }
        if cn >= 0 {
            side.push((class, cn, f as u32, false));
        }
    }
    side.sort_unstable();
    let side: Vec<(i32, u32, bool)> = side.into_iter().map(|(_, c, f, rev)| (c, f, rev)).collect();
    let mut conn = Vec::with_capacity(2 * r.face_verts.len());
    let mut offsets = vec![0u32];
    for &(_, f, reversed) in &side {
        let vs = r.face(f as usize);
        if reversed {
            conn.extend(vs.iter().rev());
        } else {
            conn.extend_from_slice(vs);
        }
        offsets.push(conn.len() as u32);
    }
    let label = |c: i32| -> i32 {
        let l = r.cell_labels.get(c as usize).map(|l| l.as_slice()).unwrap_or(&[]);
        if r.mode == "ia" {
            l.iter().take(31).enumerate().map(|(f, &b)| (b as i32) << f).sum()
        } else {
            l.first().copied().unwrap_or(-1) as i32
        }
    };
    Piece {
        points: &r.points,
        conn,
        offsets,
        types: side.iter().map(|s| polygon_type(r.face(s.1 as usize).len())).collect(),
        data: measured(
            vec![
                ("cell", 1, Values::I32(side.iter().map(|s| s.0).collect())),
                ("patch", 1, Values::I32(side.iter().map(|s| r.patch[s.1 as usize] as i32).collect())),
                ("label", 1, Values::I32(side.iter().map(|s| label(s.0)).collect())),
                ("face", 1, Values::I32(side.iter().map(|s| s.1 as i32).collect())),
            ],
            "volume",
            &r.measures.cell_volume,
            &side.iter().map(|s| s.0).collect::<Vec<_>>(),
        ),
    }
}

/// `data` and, when measured, `name`: `per_item[row_item[i]]` per row.
fn measured(
    mut data: Vec<(&'static str, usize, Values)>,
    name: &'static str,
    per_item: &[f64],
    row_item: &[i32],
) -> Vec<(&'static str, usize, Values)> {
    if !per_item.is_empty() {
        data.push((name, 1, Values::F64(row_item.iter().map(|&i| per_item[i as usize]).collect())));
    }
    data
}

/// The four block names of a `.vtm`, in order.
pub const VTM_BLOCKS: [&str; 4] = ["patches", "chains", "corners", "cells"];

/// The non-empty blocks of `r`'s multiblock, by name (meshio cannot read
/// an empty unstructured grid, so a block without cells, say no chains,
/// has no piece).
fn vtm_pieces<'a>(r: &'a ResultView) -> Vec<(&'static str, Piece<'a>)> {
    let pieces = [polygons(r), chains(r), corners(r), cell_boundaries(r)];
    VTM_BLOCKS.into_iter().zip(pieces).filter(|(_, p)| p.offsets.len() > 1).collect()
}

/// The `.vtm` text naming pieces `stem/<block>.vtu`.
fn vtm_xml(stem: &str, blocks: &[&str]) -> String {
    let mut xml = String::new();
    for (i, name) in blocks.iter().enumerate() {
        xml.push_str(&format!("<DataSet index=\"{i}\" name=\"{name}\" file=\"{stem}/{name}.vtu\"/>\n"));
    }
    format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n\
         <vtkMultiBlockDataSet>\n{xml}</vtkMultiBlockDataSet>\n</VTKFile>\n"
    )
}

/// Writes `path` (`NAME.vtm`) and its pieces `NAME/<block>.vtu` (module
/// doc); returns the pieces' paths. Empty blocks are left out (a stale
/// piece of that name is removed).
pub fn write_vtm(r: &ResultView, path: &Path) -> std::io::Result<Vec<PathBuf>> {
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "network".into());
    // the pieces' folder is a real folder beside the .vtm, never a link
    // leading elsewhere (safe_write.rs)
    let parent = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let dir = crate::io::files::safe_write::real_dir(parent, Path::new(&stem))?;
    let pieces = vtm_pieces(r);
    let mut paths = Vec::new();
    for name in VTM_BLOCKS {
        let p = dir.join(format!("{name}.vtu"));
        match pieces.iter().find(|(n, _)| *n == name) {
            Some((_, piece)) => {
                write_piece(piece, &p)?;
                paths.push(p);
            }
            None => {
                let _ = std::fs::remove_file(&p);
            }
        }
    }
    let names: Vec<&str> = pieces.iter().map(|(n, _)| *n).collect();
    write_atomic_with(path, |w| w.write_all(vtm_xml(&stem, &names).as_bytes()))?;
    Ok(paths)
}

/// Writes `STEM.vtm` and its pieces `STEM/<block>.vtu` into the output set
/// `out`: each piece is staged and listed in the manifest like every other
/// file, so a failed run leaves the old multiblock whole and a finished one
/// never mixes pieces of two runs (an old piece the new result has no cells
/// for goes with the old set).
pub fn write_vtm_into(r: &ResultView, out: &mut OutputDir, stem: &str) -> std::io::Result<()> {
    let pieces = vtm_pieces(r);
    for (name, piece) in &pieces {
        out.write_path(&format!("{stem}/{name}.vtu"), |p| write_piece(piece, p))?;
    }
    let names: Vec<&str> = pieces.iter().map(|(n, _)| *n).collect();
    out.write(&format!("{stem}.vtm"), vtm_xml(stem, &names).as_bytes())
}
