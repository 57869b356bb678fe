//! What `septa regions` and `septa labels` print: the surfaces and curves in
//! words, regions and functions by their names (the `--json` object has the
//! same facts as numbers).
use std::fmt::Write as _;

use septa::regions::{CurveKind, RegionSurfaces};

/// Lines listed per kind before the rest is counted ("... and 40 more").
const MAX_LINES: usize = 12;

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The text block of a region result (ends with a newline).
pub fn regions_text(input: &str, r: &RegionSurfaces) -> String {
    let names = &r.names;
    let mut out = String::new();
    let features = r.curves.iter().filter(|c| c.kind == CurveKind::Feature).count();
    let curves = match (features, r.curves.len() - features) {
        (0, _) => plural(r.curves.len(), "curve", "curves"),
        (f, 0) => format!("{} (sharp edges)", plural(f, "feature curve", "feature curves")),
        (f, j) => format!(
            "{} and {}",
            plural(j, "junction curve", "junction curves"),
            plural(f, "feature curve", "feature curves")
        ),
    };
    writeln!(
        out,
        "{input}: {} in {}, {curves}",
        plural(r.faces.len(), "polygon", "polygons"),
        plural(r.surfaces.len(), "surface", "surfaces")
    )
    .unwrap();
    let regions = r.region_ids();
    for (i, &g) in regions.iter().enumerate() {
        if i == MAX_LINES {
            writeln!(out, "  ... and {} more regions (all in --json)", regions.len() - i).unwrap();
            break;
        }
        match r.measures.cell_volume.get(i) {
            Some(v) if v.is_finite() => writeln!(out, "  region {}: volume {v:.6}", names.region_text(g)).unwrap(),
            _ => writeln!(out, "  region {}", names.region_text(g)).unwrap(),
        }
    }
    for (i, s) in r.surfaces.iter().enumerate() {
        if i == MAX_LINES {
            writeln!(out, "  ... and {} more surfaces (all in --json)", r.surfaces.len() - i).unwrap();
            break;
        }
        let [a, b] = s.regions;
        // A surface is one connected piece: closed, it is a sphere with
        // (2 - Euler) / 2 handles.
        let closed = if s.boundary_loops == 0 && s.euler % 2 == 0 && s.euler <= 2 {
            format!("closed, genus {}", (2 - s.euler) / 2)
        } else if s.boundary_loops == 0 {
            "closed".to_string()
        } else {
            plural(s.boundary_loops, "boundary loop", "boundary loops")
        };
        let area = r.measures.patch_area.get(i).map(|a| format!(", area {a:.6}")).unwrap_or_default();
        writeln!(
            out,
            "  surface between regions {} and {}: {}, Euler characteristic {}, {closed}{area}",
            names.region_text(a),
            names.region_text(b),
            plural(s.faces, "polygon", "polygons"),
            s.euler
        )
        .unwrap();
    }
    for (i, c) in r.curves.iter().enumerate() {
        if i == MAX_LINES {
            writeln!(out, "  ... and {} more curves (all in --json)", r.curves.len() - i).unwrap();
            break;
        }
        let regions: Vec<String> = c.regions.iter().map(|&x| names.region_text(x)).collect();
        let what = match c.kind {
            CurveKind::Junction => format!("where regions {} meet", regions.join(", ")),
            CurveKind::Feature => {
                let fs: Vec<String> = c.functions.iter().map(|&f| names.function(f as usize)).collect();
                format!("sharp edge where {}", fs.join(" meets "))
            }
        };
        writeln!(
            out,
            "  curve {i}, {what}: {}, {}, length {:.6}",
            if c.closed { "closed" } else { "open" },
            plural(c.vertices.len(), "vertex", "vertices"),
            c.length
        )
        .unwrap();
    }
    out
}

/// The measures of a grid network in words: the cells' volumes (the
/// largest few), the total patch area and chain length.
pub fn network_text(net: &septa::network::Network, notes: &septa::io::Annotations) -> String {
    let m = &notes.measures;
    let mut out = String::new();
    let known: Vec<(usize, f64)> = m.cell_volume.iter().copied().enumerate().filter(|(_, v)| v.is_finite()).collect();
    if !known.is_empty() {
        let total: f64 = known.iter().map(|x| x.1).sum();
        let mut order = known.clone();
        order.sort_by(|a, b| b.1.total_cmp(&a.1));
        let shown: Vec<String> = order.iter().take(5).map(|(c, v)| format!("cell {c}: {v:.6}")).collect();
        let rest = if order.len() > 5 { format!(", ... ({} more)", order.len() - 5) } else { String::new() };
        writeln!(out, "volumes: {} in all; largest {}{rest}", fmt(total), shown.join(", ")).unwrap();
        if known.len() < m.cell_volume.len() {
            writeln!(
                out,
                "  {} of {} cells reach the tet mesh's boundary: no volume",
                m.cell_volume.len() - known.len(),
                m.cell_volume.len()
            )
            .unwrap();
        }
    }
    let _ = net;
    if !m.patch_area.is_empty() {
        let area: f64 = m.patch_area.iter().sum();
        let length: f64 = m.chain_length.iter().sum();
        writeln!(out, "patch area {} in all, chain length {} in all", fmt(area), fmt(length)).unwrap();
    }
    out
}

fn fmt(x: f64) -> String {
    format!("{x:.6}")
}
