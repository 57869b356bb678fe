//! One cell of a result (a region, a label, an arrangement or material
//! cell) as a closed, outward-oriented triangle surface holding only its
//! own vertices: what an STL file, a volume mesher or a solid modeller
//! takes. The same rule as Python's `Network.region` (python/septa/_solids.py)
//! and as the `cells` block of `network.vtm`: a polygon is counter-clockwise
//! seen from its positive side (`cells[f][0]`), so it faces out of the cell
//! on its negative side as it is and out of the cell on its positive side
//! reversed. The triangles are the polygons' fans, the triangulation every
//! writer uses and the certified embedding checks (Du et al. Sec. 4: each
//! polygon is convex).
//!
//! In float32 (an STL) the vertices that the certified embedding kept apart
//! by a few ulps round to one point. They are merged (equal float32 values,
//! no tolerance: a reader merging an STL's corners does the same), the
//! triangles that become degenerate dropped, and so are pairs of coincident
//! opposite triangles (a fin of no volume); closedness is checked after.

use super::geometry::{cross, dot, sub};

/// A closed, outward-oriented triangle surface (module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Solid {
    /// Vertex positions (float32 values when built `float32`), in the order
    /// of the result's point ids.
    pub points: Vec<[f64; 3]>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// The volume it encloses (divergence theorem over the triangles).
    pub volume: f64,
}

/// Why a cell has no solid.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolidError {
    /// No polygon bounds the cell.
    #[error("no polygon bounds it")]
    Empty,
    /// Some directed edge has no opposite twin: the cell reaches the
    /// domain's box, whose faces the network does not hold.
    #[error("its surface is open ({0} edges without their opposite twin): it reaches the domain's box")]
    Open(usize),
    /// Closed, but around the other cells (the cell holding the whole box
    /// boundary): its outward side is their inside.
    #[error("it reaches the domain's box (its closed surface encloses {0:.6}: the other regions, not itself)")]
    Outside(f64),
}

/// The surface of cell `cell` of the polygons `face_start`/`face_verts`
/// over `points` with per polygon the cells on its positive and negative
/// side (`-1`: none). `float32`: vertices rounded to float32 and merged
/// (module doc). `volume`: the cell's measured volume, if known; a closed
/// surface enclosing minus that volume is the cell in a mirrored domain (a
/// voxel-to-world map of negative determinant, `BoxDomain::mirrored`) and is
/// turned around.
pub fn cell_solid(
    points: &[[f64; 3]],
    face_start: &[u32],
    face_verts: &[u32],
    cells: &[[i32; 2]],
    cell: i32,
    float32: bool,
    volume: Option<f64>,
) -> Result<Solid, SolidError> {
    let mut tris: Vec<[u32; 3]> = Vec::new();
    // The positive sides first, then the negative ones (Python's order).
    for positive in [true, false] {
        for (f, c) in cells.iter().enumerate() {
            // a polygon with the cell on both sides is inside it
            let mine = if positive { c[0] == cell && c[1] != cell } else { c[1] == cell && c[0] != cell };
            if !mine {
                continue;
            }
            let p = &face_verts[face_start[f] as usize..face_start[f + 1] as usize];
            for k in 1..p.len() - 1 {
                let t = [p[0], p[k], p[k + 1]];
                tris.push(if positive { [t[2], t[1], t[0]] } else { t });
            }
        }
    }
    if tris.is_empty() {
        return Err(SolidError::Empty);
    }
    // Only its own vertices, in the order of the result's point ids.
    let mut used: Vec<u32> = tris.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    let local = |v: u32| used.binary_search(&v).unwrap() as u32;
    let mut tris: Vec<[u32; 3]> = tris.iter().map(|t| t.map(local)).collect();
    let mut pts: Vec<[f64; 3]> = used.iter().map(|&v| points[v as usize]).collect();
    if float32 {
        (pts, tris) = float32_merged(&pts, &tris);
    }
    let open = open_edges(&tris);
    if open > 0 {
        return Err(SolidError::Open(open));
    }
    let mut enclosed = enclosed_volume(&pts, &tris);
    if !(enclosed > 0.0) {
        let mirrored = volume.is_some_and(|v| v > 0.0 && ((-enclosed - v).abs() <= 1e-6 * v));
        if !mirrored {
            return Err(SolidError::Outside(enclosed));
        }
        for t in &mut tris {
            t.swap(0, 2);
        }
        enclosed = -enclosed;
    }
    Ok(Solid { points: pts, triangles: tris, volume: enclosed })
}

/// The volume a closed triangle surface encloses (positive when its
/// triangles face out).
pub fn enclosed_volume(points: &[[f64; 3]], tris: &[[u32; 3]]) -> f64 {
    let o = points.first().copied().unwrap_or([0.0; 3]);
    let six: f64 = tris
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| sub(points[v as usize], o));
            dot(a, cross(b, c))
        })
        .sum();
    six / 6.0
}

/// The float32 surface: vertices rounded, equal ones merged (kept in the
/// order of their first vertex), degenerate triangles and pairs of
/// coincident triangles dropped, unused vertices removed.
fn float32_merged(pts: &[[f64; 3]], tris: &[[u32; 3]]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    // -0.0 and 0.0 are one point
    let key = |p: &[f64; 3]| p.map(|x| ((x as f32) + 0.0).to_bits());
    let mut order: Vec<u32> = (0..pts.len() as u32).collect();
    order.sort_by_key(|&i| (key(&pts[i as usize]), i));
    let mut rep = vec![0u32; pts.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j < order.len() && key(&pts[order[j] as usize]) == key(&pts[order[i] as usize]) {
            rep[order[j] as usize] = order[i];
            j += 1;
        }
        i = j;
    }
    let mut merged: Vec<[u32; 3]> = tris
        .iter()
        .map(|t| t.map(|v| rep[v as usize]))
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    let mut keys: Vec<[u32; 3]> = merged
        .iter()
        .map(|t| {
            let mut k = *t;
            k.sort_unstable();
            k
        })
        .collect();
    let count = {
        let mut sorted = keys.clone();
        sorted.sort_unstable();
        move |k: &[u32; 3]| sorted.partition_point(|x| x <= k) - sorted.partition_point(|x| x < k)
    };
    let single: Vec<bool> = keys.iter().map(|k| count(k) == 1).collect();
    keys.clear();
    let mut s = single.iter();
    merged.retain(|_| *s.next().unwrap());
    let mut used: Vec<u32> = merged.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    let local = |v: u32| used.binary_search(&v).unwrap() as u32;
    let tris = merged.iter().map(|t| t.map(local)).collect();
    let pts = used.iter().map(|&v| pts[v as usize].map(|x| x as f32 as f64)).collect();
    (pts, tris)
}

/// Directed edges whose reverse is not used as often (0 for a closed,
/// consistently oriented surface).
fn open_edges(tris: &[[u32; 3]]) -> usize {
    let mut fwd: Vec<(u32, u32)> = Vec::with_capacity(3 * tris.len());
    for t in tris {
        for k in 0..3 {
            fwd.push((t[k], t[(k + 1) % 3]));
        }
    }
    let mut rev: Vec<(u32, u32)> = fwd.iter().map(|&(a, b)| (b, a)).collect();
    fwd.sort_unstable();
    rev.sort_unstable();
    // matched = size of the multiset intersection
    let (mut i, mut j, mut matched) = (0, 0, 0);
    while i < fwd.len() && j < rev.len() {
        match fwd[i].cmp(&rev[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                matched += 1;
                i += 1;
                j += 1;
            }
        }
    }
    fwd.len() - matched
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube as 6 quads, CCW from outside, as the negative side of
    /// cell 0 (outside: cell 1).
    fn cube() -> (Vec<[f64; 3]>, Vec<u32>, Vec<u32>, Vec<[i32; 2]>) {
        let pts: Vec<[f64; 3]> =
            (0..8).map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]).collect();
        let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let verts: Vec<u32> = quads.iter().flatten().copied().collect();
        let start: Vec<u32> = (0..=6).map(|i| 4 * i).collect();
        (pts, start, verts, vec![[1, 0]; 6])
    }

    #[test]
    fn cube_is_closed_with_volume_one() {
        let (p, s, v, c) = cube();
        let solid = cell_solid(&p, &s, &v, &c, 0, false, None).unwrap();
        assert_eq!((solid.points.len(), solid.triangles.len()), (8, 12));
        assert_eq!(solid.volume, 1.0);
        // the other side encloses minus it: refused, unless measured as mirrored
        assert_eq!(cell_solid(&p, &s, &v, &c, 1, false, None), Err(SolidError::Outside(-1.0)));
        assert_eq!(cell_solid(&p, &s, &v, &c, 1, false, Some(1.0)).unwrap().volume, 1.0);
        assert_eq!(cell_solid(&p, &s, &v, &c, 2, false, None), Err(SolidError::Empty));
        // one face gone: 4 open edges
        assert_eq!(cell_solid(&p, &s[..6], &v[..20], &c[..5], 0, false, None), Err(SolidError::Open(4)));
    }

    #[test]
    fn float32_merges_points_an_ulp_apart() {
        let (mut p, s, mut v, c) = cube();
        // a copy of vertex 7 nudged by one double ulp, used by the last quad
        p.push([1.0 + f64::EPSILON, 1.0, 1.0]);
        *v.iter_mut().rev().nth(1).unwrap() = 8;
        assert!(matches!(cell_solid(&p, &s, &v, &c, 0, false, None), Err(SolidError::Open(_))));
        let solid = cell_solid(&p, &s, &v, &c, 0, true, None).unwrap();
        assert_eq!((solid.points.len(), solid.triangles.len(), solid.volume), (8, 12, 1.0));
    }
}
