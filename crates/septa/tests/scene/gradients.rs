//! Gradient enclosures (`Primitive::gradient_bounds`, used by the adaptive
//! criterion and by vertex projection): for every primitive type, the
//! analytic gradient at points of random boxes of every size from 1e-10 to
//! 1 lies inside the enclosure (the Clarke hull at kinks), the analytic
//! gradient itself matches finite differences, and away from kinks the
//! enclosure's width shrinks linearly with the box.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::scene::{load_function_list, Primitive};

/// One of every primitive type (and combinator), through the JSON reader.
const ALL: &str = include_str!("../common/all_primitives.json");

/// Kinds beyond the shared list whose gradient has its own code path.
const MORE: &str = r#"[
 {"type": "torus", "center": [0, 0, 0.1], "axis_vector": [0.1, 0, 1], "major_radius": 0.5, "minor_radius": 0.15, "squared": true},
 {"type": "torus", "center": [0.1, 0, 0], "axis_vector": [1, 0, 0.2], "major_radius": 0.3, "minor_radius": 0.4},
 {"type": "sphere", "center": [0.1, -0.2, 0.05], "radius": 0.5, "unsigned": true},
 {"type": "line", "point": [0, 0.2, 0], "unit_vector": [1, 1, 0], "squared": true},
 {"type": "capsule", "a": [0, 0, 0], "b": [0, 0, 0], "radius": 0.3},
 {"type": "abs", "of": {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}},
 {"type": "transform", "scale": [2, 0.5, 1], "of": {"type": "cylinder", "axis_point": [0, 0, 0], "axis_vector": [0, 0, 1], "radius": 0.2}}
]"#;

fn primitives() -> Vec<(String, Primitive)> {
    let mut out = vec![];
    for (file, text) in [("all.json", ALL), ("more.json", MORE)] {
        let v: serde_json::Value = serde_json::from_str(text).unwrap();
        let fs = load_function_list(text, file, None).unwrap();
        for (i, f) in fs.into_iter().enumerate() {
            out.push((format!("{file}#{i} {}", v[i]["type"]), f));
        }
    }
    out
}

fn random_box(rng: &mut ChaCha8Rng, c: [f64; 3], h: f64) -> ([f64; 3], [f64; 3]) {
    let lo = [0, 1, 2].map(|a| c[a] - h * rng.gen_range(0.2..1.0));
    let hi = [0, 1, 2].map(|a| c[a] + h * rng.gen_range(0.2..1.0));
    (lo, hi)
}

/// The analytic gradient at the corners and at random points of the box
/// lies in the enclosure.
fn check_contains(name: &str, f: &Primitive, lo: [f64; 3], hi: [f64; 3], rng: &mut ChaCha8Rng) {
    let g = f.gradient_bounds(lo, hi).unwrap_or_else(|| panic!("{name}: no gradient enclosure"));
    let at = |p: [f64; 3]| {
        let d = f.gradient(p);
        for a in 0..3 {
            assert!(
                g[a].contains(d[a]),
                "{name}: gradient {d:?} at {p:?} outside {g:?} (component {a}) for the box {lo:?} .. {hi:?}"
            );
        }
    };
    for c in 0..8 {
        at([0, 1, 2].map(|a| if c >> a & 1 == 1 { hi[a] } else { lo[a] }));
    }
    for _ in 0..24 {
        at([0, 1, 2].map(|a| (lo[a] + (hi[a] - lo[a]) * rng.gen_range(0.0..=1.0)).clamp(lo[a], hi[a])));
    }
}

/// A point where `f` changes sign along a random segment (bisection), so
/// boxes are also laid across the zero set, where the criterion looks.
fn zero_near(f: &Primitive, mut a: [f64; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    let (fa, fb) = (f.eval(a), f.eval(b));
    if (fa > 0.0) == (fb > 0.0) {
        return None;
    }
    for _ in 0..80 {
        let m = [0, 1, 2].map(|i| 0.5 * (a[i] + b[i]));
        if (f.eval(m) > 0.0) == (fa > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    Some(a)
}

pub(crate) fn enclosures_hold(prims: &[(String, Primitive)], span: ([f64; 3], f64), seed: u64, n: usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mid, r) = span;
    for (name, f) in prims {
        let mut centres = vec![];
        for _ in 0..300 {
            let a = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            let b = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            if let Some(z) = zero_near(f, a, b) {
                centres.push(z);
            }
            if centres.len() >= n {
                break;
            }
        }
        for _ in 0..n {
            centres.push([0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r)));
        }
        for c in &centres {
            for e in [-10.0, -8.0, -6.0, -4.0, -2.0, -1.0, 0.0] {
                let h = r * 10f64.powf(e + rng.gen_range(-0.5..0.0));
                let (lo, hi) = random_box(&mut rng, *c, h);
                check_contains(name, f, lo, hi, &mut rng);
            }
        }
    }
}

/// Finite differences agree with the analytic gradient at points where
/// the one-sided slopes agree (not at a kink); returns whether `p` is such
/// a point at step `h`.
fn smooth_at(f: &Primitive, p: [f64; 3], h: f64) -> bool {
    (0..3).all(|a| {
        let (mut pp, mut pm) = (p, p);
        pp[a] += h;
        pm[a] -= h;
        let (fp, f0, fm) = (f.eval(pp), f.eval(p), f.eval(pm));
        let (right, left) = ((fp - f0) / h, (f0 - fm) / h);
        (right - left).abs() <= 1e-3 * (1.0 + right.abs())
    })
}

/// Width of the widest component of the enclosure over the cube of half
/// side `h` around `p`.
fn width(f: &Primitive, p: [f64; 3], h: f64) -> f64 {
    let g = f.gradient_bounds(p.map(|x| x - h), p.map(|x| x + h)).unwrap();
    g.iter().map(|x| x.hi - x.lo).fold(0.0, f64::max)
}

pub(crate) fn enclosures_tighten(prims: &[(String, Primitive)], span: ([f64; 3], f64), seed: u64, n: usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mid, r) = span;
    for (name, f) in prims {
        if name.contains("\"mesh\"") {
            continue; // the unit ball only (documented): no tightening claimed
        }
        let mut checked = 0;
        for _ in 0..5 * n {
            let p = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            if !(smooth_at(f, p, 1e-5 * r) && smooth_at(f, p, 1e-7 * r)) {
                continue;
            }
            checked += 1;
            let scale = 1.0 + f.gradient(p).iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let w3 = width(f, p, 1e-3 * r);
            let w6 = width(f, p, 1e-6 * r);
            let w9 = width(f, p, 1e-9 * r);
            // Linear: a thousand times smaller box, (at least about) a
            // thousand times narrower, down to the rounding pad.
            let pad = 1e-10 * scale;
            assert!(w6 <= 1e-2 * w3 + pad, "{name} at {p:?}: widths {w3:e} (1e-3) {w6:e} (1e-6)");
            assert!(w9 <= 1e-2 * w6 + pad, "{name} at {p:?}: widths {w6:e} (1e-6) {w9:e} (1e-9)");
            assert!(w9 <= 1e-5 * scale, "{name} at {p:?}: width {w9:e} at 1e-9");
        }
        assert!(checked >= n / 4, "{name}: only {checked} smooth points");
    }
}

#[test]
fn every_primitive_encloses_its_gradients() {
    enclosures_hold(&primitives(), ([0.0; 3], 1.0), 41, 40);
}

#[test]
fn every_primitive_enclosure_tightens_linearly() {
    enclosures_tighten(&primitives(), ([0.0; 3], 1.0), 42, 40);
}

#[test]
fn kinks_give_the_clarke_hull() {
    // At a sphere's centre every unit vector is a Clarke gradient; on a
    // max of two planes' crossing, both normals; on a box edge, both faces'.
    let s = Primitive::sphere([0.0; 3], 1.0);
    let g = s.gradient_bounds([-1e-9; 3], [1e-9; 3]).unwrap();
    assert!(g.iter().all(|x| x.lo <= -1.0 && x.hi >= 1.0), "{g:?}");
    let m =
        Primitive::Max(vec![Primitive::plane([0.0; 3], [1.0, 0.0, 0.0]), Primitive::plane([0.0; 3], [0.0, 1.0, 0.0])]);
    let g = m.gradient_bounds([-1e-6; 3], [1e-6; 3]).unwrap();
    assert!(g[0].contains(0.0) && g[0].contains(1.0) && g[1].contains(0.0) && g[1].contains(1.0), "{g:?}");
    assert!(g[2].hi - g[2].lo < 1e-9, "{g:?}");
    // Away from the crossing only one plane is active: exact.
    let g = m.gradient_bounds([0.5, -0.1, -0.1], [0.6, 0.1, 0.1]).unwrap();
    assert!(g[0].lo > 0.999 && g[1].hi < 1e-9, "{g:?}");
    // The box's face is smooth: exact normal on it, both sides.
    let b = Primitive::cuboid([0.0; 3], [0.5; 3]);
    let g = b.gradient_bounds([0.5 - 1e-7, -0.1, -0.1], [0.5 + 1e-7, 0.1, 0.1]).unwrap();
    assert!(g[0].hi < -0.999 && g[1].mag() < 1e-9 && g[2].mag() < 1e-9, "{g:?}");
    // Its edge: the hull of both faces' normals.
    let g = b.gradient_bounds([0.5 - 1e-7, 0.5 - 1e-7, -0.1], [0.5 + 1e-7, 0.5 + 1e-7, 0.1]).unwrap();
    assert!(g[0].contains(-1.0) && g[0].contains(0.0) && g[1].contains(-1.0) && g[1].contains(0.0), "{g:?}");
    // An open mesh has no trustworthy gradient bound.
    let v = vec![[-0.4, -0.4, -0.4], [0.4, -0.4, -0.4], [0.0, 0.4, -0.4], [0.0, 0.0, 0.4]];
    let open = septa::scene::TriMesh::new(v, vec![[0, 2, 1], [0, 1, 3], [1, 2, 3]]).unwrap();
    assert!(Primitive::Mesh(std::sync::Arc::new(open)).gradient_bounds([0.0; 3], [0.1; 3]).is_none());
}

#[test]
fn analytic_gradients_of_the_extra_kinds_match_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(43);
    for (name, f) in primitives().iter().filter(|(n, _)| n.starts_with("more")) {
        let mut checked = 0;
        for _ in 0..300 {
            let p = [0, 1, 2].map(|_| rng.gen_range(-0.9..0.9));
            if !smooth_at(f, p, 1e-6) {
                continue;
            }
            checked += 1;
            let g = f.gradient(p);
            for a in 0..3 {
                let (mut pp, mut pm) = (p, p);
                pp[a] += 1e-6;
                pm[a] -= 1e-6;
                let fd = (f.eval(pp) - f.eval(pm)) / 2e-6;
                assert!((g[a] - fd).abs() < 1e-5 * (1.0 + fd.abs()), "{name} at {p:?}: {g:?} vs {fd} ({a})");
            }
        }
        assert!(checked > 200, "{name}: {checked}");
    }
}
