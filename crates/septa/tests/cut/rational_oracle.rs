//! An independent oracle for the written cut-cell embedding (issues 16 and
//! 18): big rationals from `num-rational`, not `septa-exact`. On small
//! reference cases it re-derives, from the written doubles of `cells.vtu`
//! alone, that every written polygon is exactly planar with three
//! non-collinear corners, every cell is closed and consistently oriented,
//! and every cell's exact volume is positive; and it must fail on the
//! unrepaired output (non-planar polygons written as such).

use crate::common;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use septa::cut::{cut_mesh, CutOptions};
use septa::io::{read_mesh, read_planes};

type Q = BigRational;
type P = [Q; 3];

fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}
fn sub(a: &P, b: &P) -> P {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}
fn cross(a: &P, b: &P) -> P {
    [&a[1] * &b[2] - &a[2] * &b[1], &a[2] * &b[0] - &a[0] * &b[2], &a[0] * &b[1] - &a[1] * &b[0]]
}
fn dot(a: &P, b: &P) -> Q {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

#[derive(Debug, Default, PartialEq)]
struct Oracle {
    nonplanar: usize,
    degenerate: usize,
    unbalanced: usize,
    nonpositive: usize,
}

fn oracle(points: &[[f64; 3]], cells: &[Vec<Vec<u32>>]) -> Oracle {
    let x: Vec<P> = points.iter().map(|p| [q(p[0]), q(p[1]), q(p[2])]).collect();
    let mut o = Oracle::default();
    for cell in cells {
        let mut vol = Q::zero();
        let origin = &x[cell[0][0] as usize];
        let mut edges: Vec<(u32, u32)> = Vec::new();
        for poly in cell {
            let p: Vec<&P> = poly.iter().map(|&v| &x[v as usize]).collect();
            // a normal from the first non-collinear corner triple
            let n = (2..p.len())
                .map(|k| cross(&sub(p[1], p[0]), &sub(p[k], p[0])))
                .find(|n| n.iter().any(|c| !c.is_zero()));
            match n {
                None => o.degenerate += 1,
                Some(n) => {
                    if p.iter().any(|v| !dot(&n, &sub(v, p[0])).is_zero()) {
                        o.nonplanar += 1;
                    }
                }
            }
            // divergence theorem: fan from the first corner (exact for a planar polygon)
            for k in 1..p.len().saturating_sub(1) {
                let (a, b, c) = (sub(p[0], origin), sub(p[k], origin), sub(p[k + 1], origin));
                vol += dot(&a, &cross(&b, &c));
            }
            for i in 0..poly.len() {
                edges.push((poly[i], poly[(i + 1) % poly.len()]));
            }
        }
        if !vol.is_positive() {
            o.nonpositive += 1;
        }
        let mut fwd: Vec<(u32, u32)> = edges.clone();
        let mut back: Vec<(u32, u32)> = edges.iter().map(|&(a, b)| (b, a)).collect();
        fwd.sort_unstable();
        back.sort_unstable();
        if fwd != back {
            o.unbalanced += 1;
        }
    }
    let _ = BigInt::zero();
    o
}

fn written(out: &septa::cut::CutCellMesh, tag: &str) -> (Vec<[f64; 3]>, Vec<Vec<Vec<u32>>>) {
    let dir = std::env::temp_dir().join(format!("septa-oracle-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cells.vtu");
    std::fs::write(&path, septa::io::cut_cells_vtu(out)).unwrap();
    let r = septa::io::read_polyhedra(&path).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    r
}

#[test]
fn written_embedding_passes_the_rational_oracle() {
    let data = common::shared_data();
    for (mesh, set) in [("cube", "A5"), ("cube", "R10"), ("knight", "R10"), ("staircase", "A5"), ("staircase", "R10")] {
        let m = read_mesh(&data.join(format!("meshes/{mesh}.obj"))).unwrap();
        let planes = read_planes(&data.join(format!("topocut/{mesh}.{set}.plane"))).unwrap();
        let out = cut_mesh(&m.vertices, &m.triangles, &planes, &CutOptions::default()).unwrap();
        let (pts, cells) = written(&out, &format!("{mesh}{set}"));
        assert_eq!(cells.len(), out.num_cells);
        let o = oracle(&pts, &cells);
        eprintln!("{mesh}.{set}: {o:?}");
        assert_eq!(o, Oracle::default(), "{mesh}.{set}");
        // the oracle agrees with septa's exact check on the same file
        let r = septa::cut::verify_cells(&pts, &cells);
        assert_eq!((r.nonplanar_faces, r.unbalanced_edges, r.nonpositive_cells), (0, 0, 0));
    }
}

/// Mutations the oracle must catch: the unsplit output (non-planar
/// polygons written as such), one polygon reversed, one cell inside out.
#[test]
fn rational_oracle_catches_broken_output() {
    let data = common::shared_data();
    let m = read_mesh(&data.join("meshes/knight.obj")).unwrap();
    let planes = read_planes(&data.join("topocut/knight.R10.plane")).unwrap();
    let mut out = cut_mesh(&m.vertices, &m.triangles, &planes, &CutOptions::default()).unwrap();
    let (pts, mut cells) = written(&out, "mut");
    cells[0][0].reverse();
    assert!(oracle(&pts, &cells).unbalanced >= 1);
    for p in cells[1].iter_mut() {
        p.reverse();
    }
    assert!(oracle(&pts, &cells).nonpositive >= 1);
    out.face_split.iter_mut().for_each(|s| *s = false);
    out.faces.iter_mut().for_each(|f| f.loops.truncate(1));
    let (pts, cells) = written(&out, "unsplit");
    let o = oracle(&pts, &cells);
    eprintln!("unsplit knight.R10: {o:?}");
    assert!(o.nonplanar > 100, "{o:?}");
}

/// `septa::cut::exact_coordinates` (the coordinates of
/// `vertices_exact.json`): each cut-vertex lies exactly on every plane its
/// triple names, an input vertex is itself, the written double is its exact
/// position up to rounding and the embedding's moves of a few hundred ulps,
/// and the fraction strings read back to the same rationals.
#[test]
fn exact_coordinates_lie_on_their_defining_planes() {
    use septa::cut::Def;
    use septa::cut::{exact_coordinates, fraction_string};
    let data = common::shared_data();
    let mut total = [0usize; 4];
    for (mesh, set) in [("cube", "A5"), ("knight", "R10"), ("staircase", "A5"), ("plate_genus9", "R10")] {
        let m = read_mesh(&data.join(format!("meshes/{mesh}.obj"))).unwrap();
        let planes = read_planes(&data.join(format!("topocut/{mesh}.{set}.plane"))).unwrap();
        let out = cut_mesh(&m.vertices, &m.triangles, &planes, &CutOptions::default()).unwrap();
        let ex = exact_coordinates(&m.vertices, &m.triangles, &out.planes, &out.vertex_defs).unwrap();
        assert_eq!(ex.len(), out.vertex_defs.len());
        let on = |p: u32, x: &P| {
            let pl = out.planes[p as usize];
            (q(pl[0]) * &x[0] + q(pl[1]) * &x[1] + q(pl[2]) * &x[2] + q(pl[3])).is_zero()
        };
        let mut checked = [0usize; 4];
        for (i, (d, x)) in out.vertex_defs.iter().zip(&ex).enumerate() {
            let ok = match *d {
                Def::V(v) => {
                    checked[0] += 1;
                    m.vertices[v as usize].iter().zip(x).all(|(a, b)| q(*a) == *b)
                }
                Def::EP(_, p) => {
                    checked[1] += 1;
                    on(p, x)
                }
                Def::TPP(_, p, r) => {
                    checked[2] += 1;
                    on(p, x) && on(r, x)
                }
                Def::PPP(p, r, s) => {
                    checked[3] += 1;
                    on(p, x) && on(r, x) && on(s, x)
                }
            };
            assert!(ok, "{mesh}.{set}: vertex {i} {d:?} off its elements");
            for k in 0..3 {
                let w = out.vertices[i][k];
                let err = (&q(w) - &x[k]).abs();
                let tol = q(w.abs().max(1.0) * 1e-12);
                assert!(err <= tol, "{mesh}.{set}: vertex {i} coordinate {k}: {w} vs {}", x[k]);
                let s = fraction_string(&x[k]);
                let back: Q = match s.split_once('/') {
                    Some((n, d)) => Q::new(n.parse::<BigInt>().unwrap(), d.parse::<BigInt>().unwrap()),
                    None => Q::from_integer(s.parse::<BigInt>().unwrap()),
                };
                assert_eq!(back, x[k]);
            }
        }
        eprintln!("{mesh}.{set}: V/EP/TPP/PPP checked {checked:?}");
        (0..4).for_each(|k| total[k] += checked[k]);
    }
    // every kind of triple was checked
    assert!(total.iter().all(|&n| n > 0), "{total:?}");
}
