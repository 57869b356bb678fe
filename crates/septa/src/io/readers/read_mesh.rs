//! Reading a triangle mesh of any supported format: the format chosen by
//! the file's extension, the bytes read once (bounded, regular files only)
//! and handed to that format's parser.

use crate::io::readers::mesh::{IndexedMesh, ReadError};
use std::path::Path;

/// Reads a triangle mesh, choosing the format by extension
/// (`.obj`, `.off`, `.ply`, `.stl`).
pub fn read_mesh(path: &Path) -> Result<IndexedMesh, ReadError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let bytes =
        crate::io::files::input::read_input(path).map_err(|e| ReadError::new(path, 0, format!("cannot read: {e}")))?;
    let mesh = match ext.as_str() {
        "obj" => crate::io::readers::mesh_obj::parse_obj(path, &bytes),
        "off" => crate::io::readers::mesh_off::parse_off(path, &bytes),
        "stl" => crate::io::readers::mesh_stl::parse_stl(path, &bytes),
        "ply" => crate::io::readers::mesh_ply::parse_ply(path, &bytes),
        _ => Err(ReadError::new(path, 0, format!("unknown mesh extension '{ext}' (use .obj, .off, .ply or .stl)"))),
    }?;
    if mesh.triangles.is_empty() {
        // Said here, where the file is known (an all-zero STL read as 0 triangles).
        return Err(ReadError::new(path, 0, format!("no triangles ({} vertices)", mesh.vertices.len())));
    }
    Ok(mesh)
}
