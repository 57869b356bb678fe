//! Tangential smoothing (Botsch & Kobbelt 2004): a free vertex moves in
//! its tangent plane towards the area-weighted centroid of its triangles,
//! a curve vertex along its trace towards the middle of its two trace
//! neighbours; then each goes back onto the surface (`Surface::place`).
//! A move that would turn a triangle over (normal beyond 60 degrees of its
//! patch's area-weighted normal there) or make it degenerate is halved, then refused.

use super::soup::{add, dot, norm, scale, sub, unit, Kind, Soup, V};
use super::surface::Surface;

fn star_ok(s: &Soup, v: u32, p: V) -> bool {
    s.faces_ok(&[v], |_| false, |w| if w == v { p } else { s.x[w as usize] })
}

/// Where `v` would like to go (before being put back on the surface).
fn aim(s: &Soup, v: u32) -> Option<V> {
    let p = s.x[v as usize];
    match s.kind[v as usize] {
        Kind::Fixed => None,
        Kind::Curve(_) => {
            let nb = s.curve_neighbours(v);
            if nb.len() != 2 {
                return None;
            }
            let (a, b) = (s.x[nb[0] as usize], s.x[nb[1] as usize]);
            let d = unit(sub(b, a));
            let m = scale(add(a, b), 0.5);
            Some(add(p, scale(d, dot(sub(m, p), d))))
        }
        Kind::Free(_) => {
            let (mut c, mut area, mut n) = ([0.0; 3], 0.0, [0.0; 3]);
            for &t in &s.vt[v as usize] {
                let tri = s.tris[t as usize];
                let nt = Soup::normal_of(&s.x, &tri);
                let a = norm(nt);
                let g = scale(add(add(s.x[tri[0] as usize], s.x[tri[1] as usize]), s.x[tri[2] as usize]), 1.0 / 3.0);
                c = add(c, scale(g, a));
                area += a;
                n = add(n, nt);
            }
            if !(area > 0.0) {
                return None;
            }
            let c = scale(c, 1.0 / area);
            let n = unit(n);
            let d = sub(c, p);
            Some(add(p, sub(d, scale(n, dot(d, n)))))
        }
    }
}

/// One round of smoothing over every movable vertex; how many moved.
pub(super) fn smooth_all(s: &mut Soup, surf: &Surface) -> usize {
    let mut n = 0;
    for v in 0..s.x.len() as u32 {
        if s.vt[v as usize].is_empty() {
            continue;
        }
        let Some(q) = aim(s, v) else { continue };
        let p = s.x[v as usize];
        let mut step = sub(q, p);
        for _ in 0..3 {
            let cand = surf.place(s.kind[v as usize], add(p, step));
            if star_ok(s, v, cand) {
                s.x[v as usize] = cand;
                n += 1;
                break;
            }
            step = scale(step, 0.5);
        }
    }
    n
}
