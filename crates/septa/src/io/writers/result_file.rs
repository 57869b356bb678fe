//! One file of a result in a chosen format: the dispatch from [`Format`] to
//! the writer of that format (the writers read the result through
//! [`ResultView`]; this file sits above them).

use crate::io::writers::result::{Format, ResultView};
use crate::io::writers::{result_mesh, result_npz, result_vtk, solids_out};

/// Writes one file of `r` in `format` (JSON is refused: its document
/// depends on the kind of result); for a solid format (`stl`, `solid.obj`,
/// `solid.ply`) `path` is the folder of the per-cell files.
pub fn write_file(
    r: &ResultView,
    path: &std::path::Path,
    format: Format,
    meta: &serde_json::Value,
) -> std::io::Result<()> {
    match format {
        Format::Json => Err(std::io::Error::other("JSON is written by the result's own writer")),
        Format::Npz => result_npz::write_npz(r, path, meta),
        Format::Ply => result_mesh::write_ply(r, path, result_mesh::PlyLayout::Full),
        Format::PlyPlain => result_mesh::write_ply(r, path, result_mesh::PlyLayout::Plain),
        Format::Obj => result_mesh::write_obj(r, path),
        Format::Vtu => result_vtk::write_vtu(r, path),
        Format::Vtm => result_vtk::write_vtm(r, path).map(|_| ()),
        Format::Stl | Format::SolidObj | Format::SolidPly => {
            solids_out::write_solids(r, path, format.solid().unwrap()).map(|_| ())
        }
    }
}
