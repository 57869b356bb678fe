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
        writeln!(
            out,
            "  surface between regions {} and {}: {}, Euler characteristic {}, {closed}",
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
            "  curve {i}, {what}: {}, {}, length {:.4}",
            if c.closed { "closed" } else { "open" },
            plural(c.vertices.len(), "vertex", "vertices"),
            c.length
        )
        .unwrap();
    }
    out
}
