//! Bounds enclose the *floating-point* values `eval` returns (docs/sparse.md):
//! sparse evaluation skips a block when a primitive's bound excludes zero
//! (IA) or proves one function larger than the others (MI), and the dense
//! path decides on the rounded samples, so sparse equals dense only if
//! every rounded sample in the box lies inside the bound. Random boxes
//! far from the surface rarely test this: here the boxes straddle or touch
//! the zero set, shrink to a few ulps around a sign change, sit far from
//! the origin (large coordinates, small values: rounding dominates), and
//! have grid vertices exactly on the surface.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::scene::{load_function_list, Primitive, TriMesh};
use serde_json::{json, Value};

/// One of every primitive type (and combinator), through the JSON reader.
const ALL: &str = include_str!("../common/all_primitives.json");

/// Extremes beyond the shared list: a torus whose tube is thinner than its
/// formula's rounding near the centre circle, and a nearly singular transform.
const EXTREME: &str = r#"[
 {"type": "torus", "center": [0, 0, 0.1], "axis_vector": [0.1, 0, 1], "major_radius": 0.5, "minor_radius": 0.0005},
 {"type": "torus", "center": [0, 0, 0.1], "axis_vector": [0.1, 0, 1], "major_radius": 0.5, "minor_radius": 0.0005, "squared": true},
 {"type": "transform", "matrix": [[1000, 999, 0], [0, 0.001, 0], [0, 0, 1]], "of": {"type": "sphere", "center": [0, 0, 0], "radius": 0.3}}
]"#;

/// The same primitive moved by `d` (its own points, not through a
/// transform, so large coordinates reach each shape's own formula).
fn shifted(p: &Value, d: [f64; 3]) -> Value {
    let add = |v: &Value| -> Value {
        let a: Vec<f64> = v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        json!([a[0] + d[0], a[1] + d[1], a[2] + d[2]])
    };
    let mut o = p.as_object().unwrap().clone();
    let ty = o["type"].as_str().unwrap().to_string();
    match ty.as_str() {
        "transform" => {
            let t = o.get("translate").cloned().unwrap_or(json!([0, 0, 0]));
            o.insert("translate".into(), add(&t));
        }
        "sum" | "min" | "max" => {
            let of: Vec<Value> = o["of"].as_array().unwrap().iter().map(|x| shifted(x, d)).collect();
            o.insert("of".into(), Value::Array(of));
        }
        "scale" | "neg" | "abs" => {
            let of = shifted(&o["of"], d);
            o.insert("of".into(), of);
        }
        "patch" => {
            let org = o["origin"].as_array().unwrap();
            let org = [org[0].as_f64().unwrap() + d[0], org[1].as_f64().unwrap() + d[1]];
            o.insert("origin".into(), json!(org));
            let h: Vec<Vec<f64>> = o["heights"]
                .as_array()
                .unwrap()
                .iter()
                .map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap() + d[2]).collect())
                .collect();
            o.insert("heights".into(), json!(h));
        }
        "points" | "mesh" => {
            let key = if ty == "points" { "points" } else { "vertices" };
            let pts: Vec<Value> = o[key].as_array().unwrap().iter().map(add).collect();
            o.insert(key.into(), Value::Array(pts));
        }
        _ => {
            for key in ["center", "point", "axis_point", "a", "b", "apex", "min", "max"] {
                if let Some(v) = o.get(key).cloned() {
                    o.insert(key.into(), add(&v));
                }
            }
        }
    }
    Value::Object(o)
}

/// Every primitive of [`ALL`], near the origin and moved far away.
fn primitives() -> Vec<(String, Primitive)> {
    let mut all: Value = serde_json::from_str(ALL).unwrap();
    let extreme: Value = serde_json::from_str(EXTREME).unwrap();
    all.as_array_mut().unwrap().extend(extreme.as_array().unwrap().iter().cloned());
    let mut out = vec![];
    for d in [[0.0; 3], [37.25, -11.5, 3.125], [1000.1, 999.7, -1000.3]] {
        let list: Vec<Value> = all.as_array().unwrap().iter().map(|p| shifted(p, d)).collect();
        let text = Value::Array(list.clone()).to_string();
        let prims = load_function_list(&text, "shifted.json", None).unwrap();
        for (j, (p, v)) in prims.into_iter().zip(&list).enumerate() {
            out.push((format!("#{j} {} moved by {d:?}", v["type"]), p));
        }
    }
    out
}

/// Checks `eval` at the corners, at vertices of an `n`-grid laid on the box
/// by the grid's own formula (`lo + (hi - lo) i / n`, `hi` at `n`) and at
/// random points. Returns whether the bound excludes zero.
pub(crate) fn check_box(name: &str, f: &Primitive, lo: [f64; 3], hi: [f64; 3], rng: &mut ChaCha8Rng) -> bool {
    let (blo, bhi) = f.bounds(lo, hi);
    assert!(!blo.is_nan() && !bhi.is_nan() && blo <= bhi, "{name}: bound [{blo}, {bhi}]");
    let at = |p: [f64; 3]| {
        let v = f.eval(p);
        assert!(
            blo <= v && v <= bhi,
            "{name}: eval {v:e} at {p:?} outside [{blo:e}, {bhi:e}] for the box {lo:?} .. {hi:?}"
        );
    };
    for c in 0..8 {
        at([0, 1, 2].map(|a| if c >> a & 1 == 1 { hi[a] } else { lo[a] }));
    }
    let n = 5;
    for i in 0..=n {
        for j in 0..=n {
            for k in 0..=n {
                let t = [i, j, k];
                at([0, 1, 2].map(|a| if t[a] == n { hi[a] } else { lo[a] + (hi[a] - lo[a]) * t[a] as f64 / n as f64 }));
            }
        }
    }
    for _ in 0..40 {
        at([0, 1, 2].map(|a| (lo[a] + (hi[a] - lo[a]) * rng.gen_range(0.0..=1.0)).clamp(lo[a], hi[a])));
    }
    blo > 0.0 || bhi < 0.0
}

/// A point where the computed `f` changes sign (or is exactly 0) between
/// two neighbouring floats of a random segment, by bisection; `None` when
/// the segment's ends have the same sign.
pub(crate) fn sign_change(f: &Primitive, mut a: [f64; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    let (fa, fb) = (f.eval(a), f.eval(b));
    if fa == 0.0 {
        return Some(a);
    }
    if (fa > 0.0) == (fb > 0.0) && fb != 0.0 {
        return None;
    }
    let pos_a = fa > 0.0;
    for _ in 0..200 {
        let m = [0, 1, 2].map(|i| 0.5 * (a[i] + b[i]));
        if m == a || m == b {
            break;
        }
        let fm = f.eval(m);
        if fm == 0.0 {
            return Some(m);
        }
        if (fm > 0.0) == pos_a {
            a = m;
        } else {
            b = m;
        }
    }
    Some(a)
}

#[test]
fn bounds_enclose_rounded_values_near_the_zero_set() {
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    for (name, f) in primitives() {
        // Where the shape is: sample its neighbourhood for a positive and
        // a negative value (shapes moved by d are searched around d).
        let d = match name.split("moved by ").nth(1) {
            Some(s) if s.starts_with("[0.0") => [0.0; 3],
            Some(s) if s.starts_with("[37") => [37.25, -11.5, 3.125],
            _ => [1000.1, 999.7, -1000.3],
        };
        // An inside point by random search (thin shapes are rarely hit).
        let mut best = d;
        let mut r = 1.0;
        for _ in 0..2000 {
            let q = [0, 1, 2].map(|i| best[i] + rng.gen_range(-r..r));
            if f.eval(q) > f.eval(best) {
                best = q;
            } else {
                r = (r * 0.995f64).max(1e-4);
            }
        }
        let mut zeros = vec![];
        for t in 0..400 {
            let a = if t % 2 == 0 { best } else { [0, 1, 2].map(|i| d[i] + rng.gen_range(-1.0..1.0)) };
            let b = [0, 1, 2].map(|i| d[i] + rng.gen_range(-1.0..1.0));
            if let Some(z) = sign_change(&f, a, b) {
                zeros.push(z);
            }
            if zeros.len() >= 25 {
                break;
            }
        }
        // Boxes of every size from a few ulps to 0.5 around, touching (a
        // corner exactly at the sign change) and beside each zero.
        for z in &zeros {
            let ulp = f64::EPSILON * (1.0 + z.iter().fold(0.0f64, |m, x| m.max(x.abs())));
            for h in [ulp, 4.0 * ulp, 1e-12, 1e-9, 1e-6, 1e-3, 0.05, 0.5] {
                let h = h.max(ulp);
                let s = [0, 1, 2].map(|_| rng.gen_range(0.3..1.0) * h);
                check_box(&name, &f, z.map(|x| x - h), z.map(|x| x + h), &mut rng);
                check_box(&name, &f, [0, 1, 2].map(|a| z[a] - s[a]), [0, 1, 2].map(|a| z[a] + h), &mut rng);
                check_box(&name, &f, *z, z.map(|x| x + h), &mut rng);
                check_box(&name, &f, z.map(|x| x - h), *z, &mut rng);
                let off = [0, 1, 2].map(|a| z[a] + rng.gen_range(-3.0..3.0) * h);
                check_box(&name, &f, off, [0, 1, 2].map(|a| off[a] + s[a]), &mut rng);
            }
        }
        // Random boxes elsewhere, for the useful side of the bound too.
        let mut excluded = 0;
        for _ in 0..60 {
            let c = [0, 1, 2].map(|i| d[i] + rng.gen_range(-1.5..1.5));
            let h = 10f64.powf(rng.gen_range(-4.0..-0.5));
            excluded += check_box(&name, &f, c.map(|x| x - h), c.map(|x| x + h), &mut rng) as usize;
        }
        // Only the constant and the non-positive distances (unsigned sphere,
        // line, segment, circle) have no sign change; their zeros on grid
        // vertices are checked below.
        let kind = name.split(' ').nth(1).unwrap_or("");
        let signless = ["\"constant\"", "\"neg\"", "\"line\"", "\"segment\"", "\"circle\""].contains(&kind)
            || name.starts_with("#2 ");
        assert!(signless || zeros.len() >= 5, "{name}: only {} sign changes found", zeros.len());
        // (A Wyvill bump is exactly 0 outside its support: nothing to exclude.)
        let flat = ["\"constant\"", "\"wyvill\""].contains(&kind);
        assert!(excluded > 0 || flat, "{name}: no random box excluded zero");
    }
}

#[test]
fn grid_vertices_exactly_on_the_surface() {
    // Grid vertices (the grid's own formula on [-1, 1] with 8 cubes) on
    // the zero set: x = 0.25 (plane), the sphere of radius 0.5 about the
    // origin at (0.5, 0, 0), the box face x = 0.75, the cylinder about the
    // z axis through (0.5, 0, z). Every block of cubes around them must be
    // bounded so that it is not skipped, and the samples must be inside.
    let fs = load_function_list(
        r#"[
        {"type": "plane", "point": [0.25, 0, 0], "normal": [1, 0, 0]},
        {"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
        {"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "squared": true},
        {"type": "box", "center": [0, 0, 0], "half_size": [0.75, 0.5, 0.5]},
        {"type": "cylinder", "axis_point": [0, 0, 0], "axis_vector": [0, 0, 1], "radius": 0.5},
        {"type": "sphere", "center": [0, 0, 0], "radius": -0.5},
        {"type": "line", "point": [0.5, 0.5, 0], "unit_vector": [0, 0, 1]},
        {"type": "circle", "center": [0, 0, 0], "axis_vector": [0, 0, 1], "radius": 0.5},
        {"type": "points", "points": [[0.5, 0.5, 0.5]], "weights": [0]},
        {"type": "torus", "center": [0, 0, 0], "axis_vector": [0, 0, 1], "major_radius": 0.5, "minor_radius": 0.25}
        ]"#,
        "on-grid.json",
        None,
    )
    .unwrap();
    let n = 8usize;
    let x = |i: usize| if i == n { 1.0 } else { -1.0 + 2.0 * i as f64 / n as f64 };
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for (fi, f) in fs.iter().enumerate() {
        let mut on = 0;
        for i in 0..=n {
            for j in 0..=n {
                for k in 0..=n {
                    let p = [x(i), x(j), x(k)];
                    if f.eval(p) != 0.0 {
                        continue;
                    }
                    on += 1;
                    // Every block of 1 or 2 cubes per side with p as a vertex.
                    for w in [1, 2] {
                        for c in 0..8 {
                            let lo = [i, j, k].map(|t| t as isize);
                            let l = [0, 1, 2].map(|a| if c >> a & 1 == 1 { lo[a] - w } else { lo[a] });
                            if l.iter().any(|&t| t < 0 || t + w > n as isize) {
                                continue;
                            }
                            let lo = l.map(|t| x(t as usize));
                            let hi = l.map(|t| x(t as usize + w as usize));
                            let name = format!("on-grid #{fi} at {p:?}");
                            assert!(!check_box(&name, f, lo, hi, &mut rng), "{name}: bound excludes 0");
                        }
                    }
                }
            }
        }
        assert!(on > 0, "function {fi}: no grid vertex on the surface");
    }
}

#[test]
fn open_meshes_get_no_bound_closed_ones_do() {
    // A tet with one triangle missing: its winding number is not 0 or 1
    // off the surface, so the sign of eval may flip anywhere: no bound.
    let v = vec![[-0.4, -0.4, -0.4], [0.4, -0.4, -0.4], [0.0, 0.4, -0.4], [0.0, 0.0, 0.4]];
    let closed = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    let m = |t: &[[u32; 3]]| Primitive::Mesh(std::sync::Arc::new(TriMesh::new(v.clone(), t.to_vec()).unwrap()));
    let (lo, hi) = ([2.0; 3], [2.5; 3]);
    let (l, h) = m(&closed).bounds(lo, hi);
    assert!(l.is_finite() && h < 0.0, "closed: [{l}, {h}]");
    let (l, h) = m(&closed[..3]).bounds(lo, hi);
    assert!(l == f64::NEG_INFINITY && h == f64::INFINITY, "open: [{l}, {h}]");
    assert!(septa::scene::block_may_be_active_ia(&[m(&closed[..3])], lo, hi));
    assert!(!septa::scene::block_may_be_active_ia(&[m(&closed)], lo, hi));
}

/// The network-level consequence: for every primitive kind alone (IA) and
/// with a sphere (MI), near the origin and moved far away, sparse equals
/// dense array by array (or both reject the same input).
#[test]
fn every_primitive_sparse_equals_dense() {
    use septa::complex::Mode;
    use septa::grid::{BoxGrid, Grid, Split};
    use septa::network::compute_sparse;
    use septa::network::{compute, NetworkOptions};
    use septa::scene::sample_grid;
    let mut skipped = 0;
    for (name, f) in primitives() {
        let d = if name.contains("[0.0, 0.0, 0.0]") {
            [0.0; 3]
        } else if name.contains("[37") {
            [37.25, -11.5, 3.125]
        } else {
            continue; // 1000 away: the same code, covered by the bounds test
        };
        let grid = BoxGrid::new([13; 3], [d.map(|x| x - 1.0), d.map(|x| x + 1.0)], Split::Five).unwrap();
        let g = Grid::Box(grid.clone());
        let sphere = Primitive::sphere([d[0] + 0.05, d[1] - 0.1, d[2] + 0.02], 0.37);
        for (mode, fs) in [(Mode::Ia, vec![f.clone()]), (Mode::Mi, vec![f.clone(), sphere])] {
            let mut o = NetworkOptions::new(mode);
            o.block = 4;
            let values = sample_grid(&fs, &g.vertices());
            let dense = compute(&g, &values, fs.len(), &o);
            let sparse = compute_sparse(&grid, &fs, &o);
            let what = format!("{name} {mode:?}");
            match (dense, sparse) {
                (Ok(a), Ok((b, stats))) => {
                    assert_eq!(a.counts(), b.counts(), "{what}");
                    assert_eq!(a.keys, b.keys, "{what}");
                    assert_eq!(a.face_verts, b.face_verts, "{what}");
                    assert_eq!(a.face_cells, b.face_cells, "{what}");
                    assert_eq!(a.chain_patches, b.chain_patches, "{what}");
                    skipped += stats.skipped;
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{what}"),
                (a, b) => panic!("{what}: dense {:?}, sparse {:?}", a.err(), b.err()),
            }
        }
    }
    assert!(skipped > 0);
}
