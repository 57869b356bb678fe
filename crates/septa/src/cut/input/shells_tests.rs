//! Shell nesting: exact crossings through faces, edges and vertices; nested
//! shells must alternate orientation.
use super::*;
use crate::cut::input::input::check_mesh_nm;

/// An axis-aligned cube `[lo, lo + size]^3`, 12 triangles facing outwards
/// (or inwards), appended to `v`, `t`.
fn cube(v: &mut Vec<[f64; 3]>, t: &mut Vec<[u32; 3]>, lo: [f64; 3], size: f64, outwards: bool) {
    let base = v.len() as u32;
    for i in 0..8 {
        v.push([0, 1, 2].map(|k| lo[k] + size * ((i >> k) & 1) as f64));
    }
    // Two triangles per face, from the corner ids (bit k = axis k).
    let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    for q in quads {
        for tri in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            let mut tri = tri.map(|c| base + c);
            if !outwards {
                tri.swap(1, 2);
            }
            t.push(tri);
        }
    }
}

fn check(v: &[[f64; 3]], t: &[[u32; 3]]) -> Result<(), CutError> {
    let ((_, tri_edges, edge_tris), nm) = check_mesh_nm(v, t)?;
    check_shells(v, t, &edge_tris, &tri_edges, &nm)
}

#[test]
fn nested_shells_must_alternate() {
    let (mut v, mut t) = (Vec::new(), Vec::new());
    cube(&mut v, &mut t, [0.0; 3], 3.0, true);
    let outer = (v.clone(), t.clone());
    // A cavity (inner cube facing inwards): accepted.
    cube(&mut v, &mut t, [1.0; 3], 1.0, false);
    check(&v, &t).unwrap();
    // A solid inside the cavity, facing outwards: accepted.
    cube(&mut v, &mut t, [1.25; 3], 0.5, true);
    check(&v, &t).unwrap();
    // The same three with the innermost facing inwards: winding -1 there.
    let (mut v2, mut t2) = (v[..16].to_vec(), t[..24].to_vec());
    cube(&mut v2, &mut t2, [1.25; 3], 0.5, false);
    let e = check(&v2, &t2).unwrap_err();
    assert!(matches!(&e, CutError::ShellWinding { shell: 2, around, winding: -1, .. } if around == &[0, 1]), "{e}");
    // Two nested cubes facing the same way (was cut into overlapping cells).
    let (mut v, mut t) = outer;
    cube(&mut v, &mut t, [1.0; 3], 1.0, true);
    let e = check(&v, &t).unwrap_err();
    assert!(matches!(&e, CutError::ShellWinding { shell: 1, winding: 2, .. }), "{e}");
    assert!(e.to_string().contains("shell 1") && e.to_string().contains("inside shells [0]"), "{e}");
    // Side by side, both outwards: accepted; one inwards beside: refused.
    let (mut v, mut t) = (Vec::new(), Vec::new());
    cube(&mut v, &mut t, [0.0; 3], 1.0, true);
    cube(&mut v, &mut t, [2.0, 0.0, 0.0], 1.0, true);
    check(&v, &t).unwrap();
    let (mut v, mut t) = (Vec::new(), Vec::new());
    cube(&mut v, &mut t, [0.0; 3], 2.0, true);
    cube(&mut v, &mut t, [3.0, 0.0, 0.0], 1.0, false);
    assert!(matches!(check(&v, &t), Err(CutError::ShellWinding { shell: 1, winding: -1, .. })));
}

/// The octahedron `|x| + |y| + |z| = 4`, outwards, as one shell.
fn octahedron() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let v =
        vec![[4.0, 0.0, 0.0], [-4.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, -4.0, 0.0], [0.0, 0.0, 4.0], [0.0, 0.0, -4.0]];
    let mut t = Vec::new();
    for x in [0, 1] {
        for y in [2, 3] {
            for z in [4, 5] {
                // Outwards iff the corner signs multiply to +1.
                t.push(if (x + y + z) % 2 == 0 { [x, y, z] } else { [x, z, y] });
            }
        }
    }
    (v, t)
}

#[test]
fn rays_through_edges_and_vertices_count_once() {
    let (v, t) = octahedron();
    let shell: Vec<u32> = (0..t.len() as u32).collect();
    assert_eq!(orientation(&v, &t, &shell), Sign::Positive);
    // Start points whose ray along +x meets the octahedron inside a face,
    // on an edge, at a vertex, or passes through two vertices / two edges.
    for (q, expect) in [
        ([0.0, 1.0, 1.0], 1),
        ([0.0, 2.0, 0.0], 1),
        ([0.0, 0.0, 0.0], 1),
        ([0.0, 0.0, -3.0], 1),
        ([-5.0, 0.0, 0.0], 0),
        ([-5.0, 1.0, 0.0], 0),
        ([-5.0, 0.0, 4.0], 0),
        ([5.0, 0.0, 0.0], 0),
        ([0.0, 4.5, 0.0], 0),
    ] {
        let mut w = v.clone();
        w.push(q);
        match winding(&w, &t, &shell, Query::Vertex(6)) {
            Crossings::Winding(n) => assert_eq!(n, expect, "{q:?}"),
            Crossings::OnTriangle(tri) => panic!("{q:?} is not on triangle {tri}"),
        }
    }
    // A point of the surface is found on it.
    let mut w = v.clone();
    w.push([1.0, 1.0, 2.0]);
    assert!(matches!(winding(&w, &t, &shell, Query::Vertex(6)), Crossings::OnTriangle(_)));
}

/// The start point of a shell with no vertex of its own: the centroid of
/// one of its triangles, exactly (the cube's inner cube, and outside it).
#[test]
fn winding_at_a_centroid() {
    let (mut v, mut t) = (Vec::new(), Vec::new());
    cube(&mut v, &mut t, [0.0; 3], 3.0, true);
    cube(&mut v, &mut t, [1.0; 3], 1.0, false);
    cube(&mut v, &mut t, [4.0, 0.0, 0.0], 1.0, true);
    let outer: Vec<u32> = (0..12).collect();
    for (tri, expect) in [(12, 1), (23, 1), (24, 0), (30, 0)] {
        match winding(&v, &t, &outer, Query::Centroid(tri)) {
            Crossings::Winding(n) => assert_eq!(n, expect, "triangle {tri}"),
            Crossings::OnTriangle(x) => panic!("triangle {tri}: on {x}"),
        }
    }
    // a centroid on the shell (on the face x = 0, across the ray): found on it
    assert!(matches!(winding(&v, &t, &outer, Query::Centroid(8)), Crossings::OnTriangle(8)));
}
