//! Flipping edges inside a patch: an edge held by two triangles of one
//! patch (never a constraint) is replaced by the other diagonal of their
//! quadrilateral when that lowers the valence excess (Botsch & Kobbelt 2004:
//! target 6 at a free vertex; constraint vertices, shared by patches, do not count) or, at equal valence, makes
//! the pair locally Delaunay (the angles opposite the edge sum to more than
//! 180 degrees), provided the new edge does not exist yet, the pair is
//! nearly flat (normals within 30 degrees, unless one is a sliver under 10
//! degrees), neither new triangle turns over, and a valence flip makes no
//! new angle under 25 degrees. A flip keeps every count of the patch.

use super::soup::{dot, ekey, min_angle, norm, sub, unit, Kind, Soup};

fn angle_at(s: &Soup, c: u32, a: u32, b: u32) -> f64 {
    let (u, v) = (sub(s.x[a as usize], s.x[c as usize]), sub(s.x[b as usize], s.x[c as usize]));
    let d = dot(u, v) / (norm(u) * norm(v));
    if d.is_finite() {
        d.clamp(-1.0, 1.0).acos()
    } else {
        0.0
    }
}

/// The valence excess of `v` with `dv` more edges: free vertices only
/// (a constraint vertex's valence counts every patch around it).
fn excess(s: &Soup, v: u32, dv: i64) -> i64 {
    if matches!(s.kind[v as usize], Kind::Free(_)) {
        (s.neighbours(v).len() as i64 + dv - 6).abs()
    } else {
        0
    }
}

/// Flips edges as the module doc says; how many.
pub(super) fn flip_all(s: &mut Soup, delaunay_only: bool) -> usize {
    let mut n = 0;
    for _pass in 0..4 {
        let mut k = 0;
        for (a, b) in s.edges() {
            if s.feat.contains_key(&ekey(a, b)) {
                continue;
            }
            let ts = s.edge_tris(a, b);
            if ts.len() != 2 || s.patch[ts[0] as usize] != s.patch[ts[1] as usize] {
                continue;
            }
            // t1 = (a, b, c) in its orientation, t2 = (b, a, d)
            let (t1, t2) = (ts[0], ts[1]);
            let tri = s.tris[t1 as usize];
            let i = (0..3).find(|&i| tri[i] == a && tri[(i + 1) % 3] == b);
            let (t1, t2) = if i.is_some() { (t1, t2) } else { (t2, t1) };
            let c = s.apex(t1, a, b);
            let d = s.apex(t2, a, b);
            if c == d || s.neighbours(c).contains(&d) {
                continue;
            }
            let before: i64 = [a, b, c, d].iter().map(|&v| excess(s, v, 0)).sum();
            let after = excess(s, a, -1) + excess(s, b, -1) + excess(s, c, 1) + excess(s, d, 1);
            let delaunay = angle_at(s, c, a, b) + angle_at(s, d, a, b) > std::f64::consts::PI + 1e-9;
            let want = if delaunay_only { delaunay } else { after < before || (after == before && delaunay) };
            if !want {
                continue;
            }
            let (n1, n2) = (Soup::normal_of(&s.x, &[a, b, c]), Soup::normal_of(&s.x, &[b, a, d]));
            // nearly flat, unless one is a sliver (whose normal means little)
            let shape = |t: [u32; 3]| min_angle(t.map(|v| s.x[v as usize]));
            if shape([a, b, c]) > 10.0 && shape([b, a, d]) > 10.0 && dot(unit(n1), unit(n2)) < 0.866 {
                continue;
            }
            let (m1, m2) = (Soup::normal_of(&s.x, &[a, d, c]), Soup::normal_of(&s.x, &[d, b, c]));
            let ref_n = unit(super::soup::add(n1, n2));
            if norm(m1) == 0.0 || norm(m2) == 0.0 || dot(unit(m1), ref_n) < 0.5 || dot(unit(m2), ref_n) < 0.5 {
                continue;
            }
            // a valence flip makes no new small angle
            let old_min = shape([a, b, c]).min(shape([b, a, d]));
            let new_min = shape([a, d, c]).min(shape([d, b, c]));
            if !delaunay && new_min < old_min.min(super::collapse::MIN_ANGLE) {
                continue;
            }
            s.set_tri(t1, [a, d, c]);
            s.set_tri(t2, [d, b, c]);
            k += 1;
        }
        n += k;
        if k == 0 {
            break;
        }
    }
    n
}
