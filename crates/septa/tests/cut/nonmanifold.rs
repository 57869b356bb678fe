//! Closed meshes that are not manifolds (TopoCut App. C: two solids sharing
//! an edge or a vertex) and meshes that are truly invalid: each refusal
//! names its edge or vertex and says which of the two it is (issue 46).

use crate::shapes::{axis_planes, boxes_mesh, BoxShell};
use septa::cut::{cut_mesh, CutError, CutOptions};

fn unit(lo: [f64; 3]) -> BoxShell {
    BoxShell { lo, hi: lo.map(|x| x + 1.0), inward: false }
}

fn cut(v: &[[f64; 3]], t: &[[u32; 3]]) -> Result<(), CutError> {
    let planes = axis_planes(&[(2, 0.5)]);
    cut_mesh(v, t, &planes, &CutOptions::default()).map(|_| ())
}

#[test]
fn two_cubes_sharing_an_edge_or_a_vertex_are_named() {
    // sharing the edge x = y = 1: four triangles around it, two each way
    let (v, t) = boxes_mesh(&[unit([0.0; 3]), unit([1.0, 1.0, 0.0])]);
    let e = cut(&v, &t).unwrap_err();
    let msg = e.to_string();
    let CutError::NonManifoldEdge { a, b, count, ref triangles } = e else { panic!("{msg}") };
    assert_eq!(count, 4, "{msg}");
    assert_eq!(triangles.len(), 4);
    let ends = [v[a as usize], v[b as usize]];
    assert!(ends.iter().all(|p| p[0] == 1.0 && p[1] == 1.0), "{msg}");
    for tri in triangles {
        assert!(t[*tri].contains(&a) && t[*tri].contains(&b), "{msg}");
    }
    assert!(msg.contains(&format!("edge {a}-{b} is non-manifold")) && msg.contains("not cut it yet"), "{msg}");
    // sharing the corner (1, 1, 1): every edge has two triangles, the
    // corner two fans of six triangles each
    let (v, t) = boxes_mesh(&[unit([0.0; 3]), unit([1.0; 3])]);
    let e = cut(&v, &t).unwrap_err();
    let msg = e.to_string();
    let CutError::NonManifoldVertex { vertex, valence, fans, first_fan } = e else { panic!("{msg}") };
    assert_eq!(v[vertex], [1.0; 3], "{msg}");
    assert_eq!((valence, fans, first_fan), (12, 2, 6), "{msg}");
    assert!(msg.contains(&format!("vertex {vertex} is pinched")), "{msg}");
}

#[test]
fn open_and_inconsistent_meshes_are_refused_as_such() {
    let (v, t) = boxes_mesh(&[unit([0.0; 3])]);
    // one triangle flipped: its three edges run twice one way, never back
    let mut flipped = t.clone();
    flipped[3] = [t[3][0], t[3][2], t[3][1]];
    let e = cut(&v, &flipped).unwrap_err();
    let msg = e.to_string();
    let CutError::NonManifoldOrFlipped { a, b, forward, backward, triangle, other } = e else { panic!("{msg}") };
    assert_eq!((forward, backward), (2, 0), "{msg}");
    assert!(triangle == 3 || other == 3, "{msg}");
    assert!(msg.contains(&format!("edge {a}->{b}")) && msg.contains("inconsistent orientation"), "{msg}");
    // one triangle removed: open
    let open: Vec<[u32; 3]> = t.iter().copied().skip(1).collect();
    let e = cut(&v, &open).unwrap_err();
    assert!(matches!(e, CutError::NotWatertight { .. }), "{e}");
    assert!(e.to_string().contains("not watertight"), "{e}");
    // two cubes sharing an edge, one triangle at the edge flipped: refused
    // as inconsistent, not as the (valid) non-manifold edge
    let (v, mut t) = boxes_mesh(&[unit([0.0; 3]), unit([1.0, 1.0, 0.0])]);
    let k = (0..t.len()).find(|&k| t[k].iter().filter(|&&i| v[i as usize][..2] == [1.0, 1.0]).count() == 2).unwrap();
    t[k].swap(1, 2);
    let e = cut(&v, &t).unwrap_err();
    assert!(matches!(e, CutError::NonManifoldOrFlipped { .. }), "{e}");
}
