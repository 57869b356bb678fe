//! The adaptive grid as a VTK unstructured grid (`grid.vtu`): tets with
//! cell data `stop` (why each leaf stopped: 0 empty, 1 certified, 2
//! min-edge, 3 budget; `Stop::name`) and `miss` (the test an uncertified
//! leaf failed last, -1 for certified ones). Appended raw binary with
//! 64-bit headers, read by VTK, ParaView, meshio and pyvista.

use super::{AdaptiveGrid, Miss};

/// The `miss` code of a leaf (`-1`: certified or empty).
pub fn miss_code(m: Option<Miss>) -> i8 {
    match m {
        None => -1,
        Some(Miss::NoBound) => 0,
        Some(Miss::Cone) => 1,
        Some(Miss::Boundary) => 2,
        Some(Miss::Distance) => 3,
        Some(Miss::Pair) => 4,
        Some(Miss::Triple) => 5,
        Some(Miss::Many) => 6,
    }
}

/// The names of the `miss` codes 0.. (for adaptive.json's legend).
pub const MISS_NAMES: [&str; 7] = ["no-bound", "cone", "boundary", "distance", "pair", "triple", "many"];

/// The grid as the bytes of a `.vtu` file.
pub fn grid_vtu(g: &AdaptiveGrid) -> Vec<u8> {
    let mut arrays: Vec<(&str, &str, usize, Vec<u8>)> = Vec::new();
    let points: Vec<u8> = g.vertices.iter().flat_map(|p| p.iter().flat_map(|x| x.to_le_bytes())).collect();
    let conn: Vec<u8> = g.tets.iter().flat_map(|t| t.iter().flat_map(|&v| (v as i64).to_le_bytes())).collect();
    let offs: Vec<u8> = (1..=g.tets.len()).flat_map(|i| (4 * i as i64).to_le_bytes()).collect();
    let types: Vec<u8> = vec![10u8; g.tets.len()]; // VTK_TETRA
    let stop: Vec<u8> = g.stop.iter().map(|&s| s as u8).collect();
    let miss: Vec<u8> = g.miss.iter().map(|&m| miss_code(m) as u8).collect();
    arrays.push(("Points", "Float64", 3, points));
    arrays.push(("connectivity", "Int64", 1, conn));
    arrays.push(("offsets", "Int64", 1, offs));
    arrays.push(("types", "UInt8", 1, types));
    arrays.push(("stop", "UInt8", 1, stop));
    arrays.push(("miss", "Int8", 1, miss));
    let mut offset = 0usize;
    let mut tags = Vec::new();
    for (name, ty, comps, data) in &arrays {
        tags.push(format!(
            "<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{comps}\" format=\"appended\" offset=\"{offset}\"/>"
        ));
        offset += 8 + data.len();
    }
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n");
    s.push_str(&format!("<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", g.vertices.len(), g.tets.len()));
    s.push_str(&format!("<Points>\n{}\n</Points>\n", tags[0]));
    s.push_str(&format!("<Cells>\n{}\n{}\n{}\n</Cells>\n", tags[1], tags[2], tags[3]));
    s.push_str(&format!("<CellData Scalars=\"stop\">\n{}\n{}\n</CellData>\n", tags[4], tags[5]));
    s.push_str("</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_");
    let mut out = s.into_bytes();
    for (_, _, _, data) in &arrays {
        out.extend_from_slice(&(data.len() as u64).to_le_bytes());
        out.extend_from_slice(data);
    }
    out.extend_from_slice(b"\n</AppendedData>\n</VTKFile>\n");
    out
}

/// `adaptive.json`: the settings, the counts of leaves by reason, the
/// edge range and quality, and the places left uncertified.
pub fn adaptive_json(g: &AdaptiveGrid, seconds: f64) -> serde_json::Value {
    use super::Stop;
    let (short, long) = g.edge_range();
    let places = g.uncertified_places();
    serde_json::json!({
        "tets": g.tets.len(),
        "vertices": g.vertices.len(),
        "rounds": g.rounds,
        "seconds": seconds,
        "tolerance": g.options.tolerance,
        "min_edge": g.options.min_edge,
        "max_tets": g.options.max_tets,
        "start_cubes": g.options.start,
        "leaves": {
            "empty": g.count(Stop::Empty),
            "certified": g.count(Stop::Certified),
            "min-edge": g.count(Stop::MinEdge),
            "budget": g.count(Stop::Budget),
        },
        "misses": MISS_NAMES.iter().enumerate().map(|(i, n)| (n.to_string(), g.miss.iter().filter(|&&m| miss_code(m) == i as i8).count().into())).collect::<serde_json::Map<String, serde_json::Value>>(),
        "certified": g.count(Stop::MinEdge) + g.count(Stop::Budget) == 0,
        "shortest_edge": short,
        "longest_edge": long,
        "worst_radius_ratio": g.worst_radius_ratio(),
        "stop_legend": ["empty", "certified", "min-edge", "budget"],
        "miss_legend": MISS_NAMES,
        "uncertified_places": places.iter().take(1000).collect::<Vec<_>>(),
    })
}
