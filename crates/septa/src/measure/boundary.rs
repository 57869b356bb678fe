//! The box-surface part of a cell's volume: `1/3 sum_F d_F A_c(F)` over the
//! three far faces `F` of the box (`d_F` the distance of `F` from the box's
//! first corner `O`, `A_c(F)` the area of the part of `F` in cell `c`).
//!
//! Which vertices lie on which box face is read from their exact keys (the
//! grid element they lie in), never from coordinates. The footprints are
//! never built: by Green's theorem in `F`, with the apex at `F`'s corner
//! `O_F = O + E_a`, `A_c(F) = 1/2 \oint (x - O_F) . nu dl` over the
//! footprint's boundary, made of
//! - the network's edges in `F` (*trace edges*): at such an edge every
//!   polygon through it separates its two cells, and the side of `F` each
//!   lies on is the sign of the polygon's normal projected into `F`; the
//!   cells whose wedge around the edge does not reach `F` get two opposite
//!   terms, so summing over all polygons at the edge leaves exactly the
//!   footprints' boundaries;
//! - the two far edges of `F`'s frame (the near ones pass through `O_F`
//!   and add nothing), each weighted by the length of its part in `c`:
//!   the same argument once more in one dimension, with the trace edges of
//!   `F` ending on that box edge as the points where the owner changes, and
//!   the owner of the box's far corner `Q` found from the sums themselves
//!   (every cell but the owner gets a non-negative sum).
//!
//! Network edges lying along a box edge (a function's zero set through a
//! box edge) are left out of the traces; the footprints next to them are
//! then off by the area they bound.

use super::geometry::{area_vector, cross, dot, norm, oriented, sub, BoxDomain};
use crate::complex::NONE;
use crate::network::Network;

/// Bit of the far face of axis `a` in a vertex's mask.
fn far(a: usize) -> u8 {
    1 << (2 * a + 1)
}

/// Per vertex, the box faces it lies on: bit `2a` the near face of axis
/// `a` (grid index 0), bit `2a + 1` the far one (index `res[a]`).
fn face_masks(net: &Network, res: [usize; 3]) -> Vec<u8> {
    let (ny, nz) = (res[1] + 1, res[2] + 1);
    net.keys
        .iter()
        .map(|k| {
            let mut mask = 0x3f;
            for &g in k.grid.iter().filter(|&&g| g != u32::MAX) {
                let g = g as usize;
                let ijk = [g / (ny * nz), (g / nz) % ny, g % nz];
                let mut m = 0;
                for a in 0..3 {
                    if ijk[a] == 0 {
                        m |= 1 << (2 * a);
                    }
                    if ijk[a] == res[a] {
                        m |= 1 << (2 * a + 1);
                    }
                }
                mask &= m;
            }
            if k.grid.iter().all(|&g| g == u32::MAX) {
                0
            } else {
                mask
            }
        })
        .collect()
}

/// One polygon's side of a trace edge in a far face: the edge's ends, the
/// unit direction in the face pointing into the polygon's positive cell,
/// and its two cells.
struct Trace {
    p: u32,
    q: u32,
    into_positive: [f64; 3],
    cells: [u32; 2],
}

/// Per cell, the box-surface part of its volume (module doc); `network_part`
/// is each cell's volume from its polygons alone (to find the owner of the
/// far corner when no trace reaches the far faces).
pub(crate) fn footprint_volumes(net: &Network, d: &BoxDomain, network_part: &[f64]) -> Vec<f64> {
    let nc = net.cells.len();
    let mask = face_masks(net, d.res);
    let points = &net.points;
    let e = d.edges;
    // Traces per far face.
    let mut traces: [Vec<Trace>; 3] = Default::default();
    let mirrored = d.mirrored();
    for f in 0..net.num_faces() {
        let [cp, cn] = oriented(net.face_cells[f], mirrored);
        if cp == NONE || cn == NONE {
            continue; // in the boundary: part of a footprint (mod.rs)
        }
        let poly = net.face(f);
        if poly.iter().all(|&v| mask[v as usize] & 0x2a == 0) {
            continue;
        }
        let normal = area_vector(points, poly);
        for k in 0..poly.len() {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            let both = mask[p as usize] & mask[q as usize];
            for a in 0..3 {
                // In far face a, and not along a box edge.
                if both & far(a) == 0 || both.count_ones() > 1 {
                    continue;
                }
                let n_f = face_normal(&e, a);
                let dir = sub(points[q as usize], points[p as usize]);
                let m = cross(n_f, dir);
                let len = norm(m);
                let s = dot(normal, m);
                if len == 0.0 || s == 0.0 {
                    continue;
                }
                let m = m.map(|x| x / len * s.signum());
                traces[a].push(Trace { p, q, into_positive: m, cells: [cp, cn] });
            }
        }
    }
    // Green's theorem in each far face: the traces' part of each footprint
    // area, and the one-dimensional sums along its two far frame edges.
    let mut trace_area: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; nc]);
    // Box edge where far faces a and b meet (parallel to axis c): per cell
    // the sum of its trace points' terms (`edge_sums[c]`), and whether any.
    let mut edge_sums: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; nc]);
    let mut edge_has_points = [false; 3];
    for a in 0..3 {
        let o_f = add(d.origin, e[a]);
        for t in &traces[a] {
            let (x, y) = (points[t.p as usize], points[t.q as usize]);
            let mid = [(x[0] + y[0]) / 2.0, (x[1] + y[1]) / 2.0, (x[2] + y[2]) / 2.0];
            // 1/2 int (x - O_F) . nu dl with nu = into_positive for the
            // negative cell (its outward side), minus that for the positive.
            let term = dot(sub(mid, o_f), t.into_positive) * norm(sub(y, x)) / 2.0;
            trace_area[a][t.cells[1] as usize] += term;
            trace_area[a][t.cells[0] as usize] -= term;
            // Ends on a far frame edge of this face: the edge shared with far
            // face b, running along axis c from O + E_a + E_b to the far corner.
            for v in [t.p, t.q] {
                for b in (0..3).filter(|&b| b != a) {
                    if mask[v as usize] & far(b) == 0 {
                        continue;
                    }
                    let c = 3 - a - b;
                    // Each box edge is summed from one of its two faces.
                    if a > b {
                        continue;
                    }
                    let w = e[c];
                    let lw = norm(w);
                    let g = dot(t.into_positive, w);
                    if g == 0.0 || lw == 0.0 {
                        continue;
                    }
                    let start = add(add(d.origin, e[a]), e[b]);
                    let along = dot(sub(points[v as usize], start), w) / lw;
                    // The positive cell lies towards +w when g > 0: its
                    // segment starts here (outward normal -w), the
                    // negative cell's ends here.
                    let sg = g.signum() * along;
                    edge_sums[c][t.cells[0] as usize] -= sg;
                    edge_sums[c][t.cells[1] as usize] += sg;
                    edge_has_points[c] = true;
                }
            }
        }
    }
    let owner = far_corner_owner(nc, &edge_sums, &edge_has_points, &trace_area, &traces, network_part);
    let mut out = vec![0.0; nc];
    for a in 0..3 {
        let n_f = face_normal(&e, a);
        let d_f = dot(e[a], n_f).abs();
        for (b, c) in [((a + 1) % 3, (a + 2) % 3), ((a + 2) % 3, (a + 1) % 3)] {
            // Frame edge of face a shared with far face b, along axis c:
            // its distance from O_F in the face, times 1/2 its length in
            // each cell.
            let h = norm(sub(e[b], scale(e[c], dot(e[b], e[c]) / dot(e[c], e[c]))));
            for (cell, o) in out.iter_mut().enumerate() {
                let mut length = edge_sums[c][cell];
                if Some(cell) == owner {
                    length += norm(e[c]);
                }
                *o += d_f / 3.0 * h * length / 2.0;
            }
        }
        for (cell, o) in out.iter_mut().enumerate() {
            *o += d_f / 3.0 * trace_area[a][cell];
        }
    }
    out
}

/// The cell at the box's far corner: the one whose sum along a far box edge
/// with trace points is negative (every other cell's is the length of its
/// part); else the one whose trace area of a far face with traces is
/// negative; else (no cell reaches the far faces but one) the one whose
/// polygons alone enclose a negative volume (it surrounds all others).
fn far_corner_owner(
    nc: usize,
    edge_sums: &[Vec<f64>; 3],
    edge_has_points: &[bool; 3],
    trace_area: &[Vec<f64>; 3],
    traces: &[Vec<Trace>; 3],
    network_part: &[f64],
) -> Option<usize> {
    let argmin =
        |xs: &[f64]| -> Option<usize> { xs.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).map(|(i, _)| i) };
    if nc == 0 {
        return None;
    }
    if let Some(c) = (0..3).find(|&c| edge_has_points[c]) {
        return argmin(&edge_sums[c]);
    }
    if let Some(a) = (0..3).find(|&a| !traces[a].is_empty()) {
        return argmin(&trace_area[a]);
    }
    argmin(network_part)
}

/// Unit normal of far face `a` (spanned by the other two edges), pointing
/// out of the box.
fn face_normal(e: &[[f64; 3]; 3], a: usize) -> [f64; 3] {
    let n = cross(e[(a + 1) % 3], e[(a + 2) % 3]);
    let l = norm(n);
    let n = n.map(|x| x / l);
    if dot(n, e[a]) < 0.0 {
        n.map(|x| -x)
    } else {
        n
    }
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    a.map(|x| x * s)
}
