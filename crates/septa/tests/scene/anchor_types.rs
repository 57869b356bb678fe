//! The function types of the 2024 adaptive-grid paper's data
//! (shared/data/adaptive): every function file of its figures loads; the
//! closed forms and the Hermite RBFs give the values and gradients its own
//! program gives (recorded below from a run of it, built in a temporary
//! folder from its public repository); value and gradient enclosures hold
//! and tighten; sparse equals dense; bad RBF files are named.

use std::path::PathBuf;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::scene::{load_function_list, primitive_json, HermiteRbf, Primitive};

use super::bounds_float::{check_box, sign_change};
use super::gradients::{enclosures_hold, enclosures_tighten};

fn adaptive() -> PathBuf {
    crate::common::shared_data().join("adaptive")
}

fn load(rel: &str) -> Result<Vec<Primitive>, septa::scene::SceneError> {
    let path = adaptive().join(rel);
    let text = std::fs::read_to_string(&path).unwrap();
    load_function_list(&text, &path.display().to_string(), path.parent())
}

/// `(file, point, value, gradient)` printed by the anchor's program
/// (values to full precision, gradients to its 6 printed digits).
#[rustfmt::skip]
const ANCHOR_VALUES: &[(&str, [f64; 3], f64, [f64; 3])] = &[
    ("function_examples/1-Gaussian.json", [0.03, 0.11, 0.07], 4.784463113015796, [2.31227, -6.93106, -2.30939]),
    ("function_examples/1-Gaussian.json", [0.03, 0.54, 1.01], -0.18475157947509357, [-2.30939, -2.3094, -2.30941]),
    ("function_examples/1-Gaussian.json", [0.48, 0.54, 0.54], 1.713586322450494, [2.43215, -4.6801, -4.6801]),
    ("function_examples/1-Gaussian.json", [0.93, 0.97, 1.01], -1.4509168869842464, [2.31235, -2.30931, -6.93098]),
    ("function_examples/1-smile.json", [0.03, 0.11, 0.07], 32.21486146536081, [-234.573, -215.672, -179.482]),
    ("function_examples/1-smile.json", [0.03, 0.54, 1.01], 12.737694379231284, [-109.564, 6.86737, 114.169]),
    ("function_examples/1-smile.json", [0.48, 0.54, 0.54], 0.22852361746475514, [1.12023, 8.21505, 1.20932e-06]),
    ("function_examples/1-smile.json", [0.93, 0.97, 1.01], 41.433653051392, [222.709, 244.318, 265.927]),
    ("function_examples/1-cyclide.json", [0.03, 0.11, 0.07], 221029.81209999998, [-666402.0, -570178.0, -925874.0]),
    ("function_examples/1-cyclide.json", [0.03, 0.54, 1.01], 196567.55560000002, [-551735.0, 48721.0, 973704.0]),
    ("function_examples/1-cyclide.json", [0.48, 0.54, 0.54], 7775.6176, [14454.7, -13357.4, 14290.6]),
    ("function_examples/1-cyclide.json", [0.93, 0.97, 1.01], 342412.9561, [773940.0, 851601.0, 1276590.0]),
    ("function_examples/1-wave.json", [0.03, 0.11, 0.07], 1.7861847134654627, [0.973861, -2.48544, -4.0]),
    ("function_examples/1-wave.json", [0.03, 0.54, 1.01], -2.2237471351457865, [4.26779, -5.68905, -4.0]),
    ("function_examples/1-wave.json", [0.48, 0.54, 0.54], 0.20616032538867907, [-10.2057, 0.121731, -4.0]),
    ("function_examples/1-wave.json", [0.93, 0.97, 1.01], -1.6615362251700687, [3.29355, 2.92473, -4.0]),
    ("function_examples/1-teardrop.json", [0.03, 0.11, 0.07], -1.3245775312, [0.581409, 3.12, 3.44]),
    ("function_examples/1-teardrop.json", [0.03, 0.54, 1.01], -1.0233775312, [0.581409, -0.32, -4.08]),
    ("function_examples/1-teardrop.json", [0.48, 0.54, 0.54], -0.012798771200000024, [-0.0002432, -0.32, -0.32]),
    ("function_examples/1-teardrop.json", [0.93, 0.97, 1.01], -1.4152824111999998, [5.27926, -3.76, -4.08]),
    ("Figure18/config.json", [-0.9, -1.1, -0.8], -1.288215407751351, [1.09351, 0.242583, 0.82306]),
    ("Figure18/config.json", [-0.9, 0.9499999999999997, 1.0], -0.2620275057364658, [1.04106, -0.526635, 0.067012]),
    ("Figure18/config.json", [1.0500000000000003, -1.1, 1.0], -0.3090768953145657, [-1.27784, 0.169504, -0.070372]),
    ("Figure18/config.json", [1.0500000000000003, 0.9499999999999997, 1.0], -0.05496995220885603, [-0.804529, -0.691689, 0.0248746]),
    ("Figure22/config.json", [-0.9, -1.1, -0.8], -0.995361698309158, [0.683571, 1.14938, 0.42902]),
    ("Figure22/config.json", [-0.9, 0.9499999999999997, 1.0], -1.4893498177443436, [1.09733, -1.65475, -0.978469]),
    ("Figure22/config.json", [1.0500000000000003, -1.1, 1.0], -1.6076596249885244, [-0.670241, 0.913989, -0.905195]),
    ("Figure22/config.json", [1.0500000000000003, 0.9499999999999997, 1.0], -1.907650593514436, [-0.759477, -1.29075, -0.994015]),
];

#[test]
fn every_anchor_function_file_loads() {
    let cases: &[(&str, usize)] = &[
        ("Figure1/10-wikiBall.json", 10),
        ("10-wikiBall_planes_perturbed_1e-6.json", 10),
        ("Figure10/2-cylSphere.json", 2),
        ("Figure11/3-cylinder.json", 3),
        ("Figure13/figure13.json", 3),
        ("Figure14/figure14.json", 8),
        ("Figure15/figure15.json", 1),
        ("Figure18/config.json", 1),
        ("Figure20/csg_examples_1.json", 4),
        ("Figure21/csg_examples_3.json", 20),
        ("Figure22/config.json", 1),
        ("csg_sign_test/two_spheres.json", 2),
    ];
    for (rel, n) in cases {
        let f = load(rel).unwrap_or_else(|e| panic!("{rel}: {e}"));
        assert_eq!(f.len(), *n, "{rel}");
    }
    for e in std::fs::read_dir(adaptive().join("function_examples")).unwrap() {
        let rel = format!("function_examples/{}", e.unwrap().file_name().to_string_lossy());
        assert!(!load(&rel).unwrap_or_else(|e| panic!("{rel}: {e}")).is_empty(), "{rel}");
    }
    match &load("Figure18/config.json").unwrap()[0] {
        Primitive::Rbf(r) => assert_eq!(r.len(), 1011),
        other => panic!("not an RBF: {other:?}"),
    }
    // What exists nowhere (figure2) or is a GPU shader names the type.
    let e = load("Figure2/figure2.json").unwrap_err();
    assert!(e.message.contains("figure2") && e.path.to_string() == "[0].type", "{e}");
    let e = load("Figure19/key.json").unwrap_err();
    assert!(e.message.contains("shader"), "{e}");
}

#[test]
fn values_and_gradients_equal_the_anchors() {
    for (rel, p, v, g) in ANCHOR_VALUES {
        let f = &load(rel).unwrap()[0];
        let got = f.eval(*p);
        // The closed forms are the same formulas (the Gaussian without its
        // source's 1e-14-sized round-off terms); the RBF sums in another order.
        // The RBF's terms are 1e5 times its value: summed in another order
        // (and compensated here), the last 5 digits differ.
        let tol = if rel.contains("config") { 1e-10 } else { 1e-12 };
        assert!((got - v).abs() <= tol * (1.0 + v.abs()), "{rel} at {p:?}: {got} vs the anchor's {v}");
        let d = f.gradient(*p);
        for a in 0..3 {
            // The anchor rounds the Gaussian's gradient constants (85.3333 =
            // 4 x 21.3333 + 1e-4): its gradient is not quite its value's.
            let tol = if rel.contains("Gaussian") { 1e-4 } else { 1e-5 };
            assert!((d[a] - g[a]).abs() <= tol * (1.0 + g[a].abs()), "{rel} at {p:?}: gradient {d:?} vs {g:?}");
        }
    }
}

#[test]
fn hermite_rbfs_vanish_at_their_centres() {
    // The Hermite fit interpolates 0 at every centre with the normal as
    // gradient: a check of the file layout (a wrong block order fails).
    for rel in ["Figure18/config.json", "Figure22/config.json"] {
        let Primitive::Rbf(r) = &load(rel).unwrap()[0] else { panic!() };
        let f = Primitive::Rbf(r.clone());
        for c in &r.centers {
            assert!(f.eval(*c).abs() < 1e-6, "{rel}: {} at centre {c:?}", f.eval(*c));
            let g = f.gradient(*c);
            let n = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
            assert!((n - 1.0).abs() < 1e-3, "{rel}: |grad| {n} at {c:?}");
        }
    }
}

/// A small random Hermite RBF whose zero set crosses `[0.2, 0.8]^3`.
fn small_rbf(seed: u64) -> Primitive {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = 12;
    let centers: Vec<[f64; 3]> = (0..n).map(|_| [0, 1, 2].map(|_| rng.gen_range(0.2..0.8))).collect();
    let coeffs: Vec<f64> = (0..4 * n).map(|_| rng.gen_range(-1.0..1.0)).collect();
    let r = HermiteRbf::new(centers.clone(), &coeffs, [0.0, 0.3, -0.2, 0.1]).unwrap();
    let c0 = -Primitive::Rbf(r.into()).eval([0.5; 3]);
    Primitive::Rbf(HermiteRbf::new(centers, &coeffs, [c0, 0.3, -0.2, 0.1]).unwrap().into())
}

/// The anchor's types with the region to test them in.
fn anchor_primitives() -> Vec<(String, Primitive, ([f64; 3], f64))> {
    let unit = ([0.5; 3], 0.55);
    let mut out = vec![];
    for t in ["Gaussian", "smile", "cyclide", "wave", "teardrop"] {
        let f = load_function_list(&format!("[{{\"type\": \"{t}\"}}]"), "t.json", None).unwrap().remove(0);
        out.push((t.to_string(), f, unit));
    }
    for rel in ["Figure18/config.json", "Figure22/config.json"] {
        out.push((rel.to_string(), load(rel).unwrap().remove(0), ([0.0; 3], 1.0)));
    }
    out.push(("small rbf".into(), small_rbf(5), unit));
    for (rel, i) in
        [("Figure1/10-wikiBall.json", 6), ("Figure14/figure14.json", 6), ("Figure20/csg_examples_1.json", 0)]
    {
        out.push((format!("{rel}#{i}"), load(rel).unwrap().remove(i), unit));
    }
    out
}

#[test]
fn anchor_types_bounds_enclose_rounded_values() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for (name, f, (mid, r)) in anchor_primitives() {
        let heavy = name.ends_with("config.json");
        let mut zeros = vec![];
        for _ in 0..300 {
            let a = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            let b = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            if let Some(z) = sign_change(&f, a, b) {
                zeros.push(z);
            }
            if zeros.len() >= if heavy { 6 } else { 20 } {
                break;
            }
        }
        assert!(zeros.len() >= 5, "{name}: {} zeros", zeros.len());
        for z in &zeros {
            for h in [1e-15, 1e-12, 1e-9, 1e-6, 1e-3, 0.05, 0.5] {
                check_box(&name, &f, z.map(|x| x - h), z.map(|x| x + h), &mut rng);
                check_box(&name, &f, *z, z.map(|x| x + h), &mut rng);
            }
        }
        let mut excluded = 0;
        for _ in 0..if heavy { 15 } else { 60 } {
            let c = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            let h = 10f64.powf(rng.gen_range(-4.0..-1.0));
            excluded += check_box(&name, &f, c.map(|x| x - h), c.map(|x| x + h), &mut rng) as usize;
        }
        assert!(excluded > 0, "{name}: no box excluded zero");
    }
}

#[test]
fn anchor_types_value_enclosures_tighten() {
    // Around a zero, a box of half side h gets a value enclosure of width
    // about 2 |grad| h: the mean value form, not the terms' sizes.
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    for (name, f, (mid, r)) in anchor_primitives() {
        let mut checked = 0;
        for _ in 0..200 {
            let a = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            let b = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            let Some(z) = sign_change(&f, a, b) else { continue };
            let g = f.gradient(z);
            let gn = g[0].abs() + g[1].abs() + g[2].abs();
            if gn < 1e-3 {
                continue;
            }
            // (An RBF's Hessian enclosure is the sum of its terms' third
            // derivatives' sizes times the box: 1e5 for the data's, so its
            // boxes of 1e-4 are within 20x of that, not yet 4x; 4 > 2
            // sqrt(3): the Lipschitz bounds of distances use the ball
            // around the box.)
            for (h, k) in [(1e-4, 20.0), (1e-7, 4.0)] {
                let (lo, hi) = f.bounds(z.map(|x| x - h), z.map(|x| x + h));
                assert!(
                    hi - lo <= k * gn * h + 1e-9 * (1.0 + f.eval(z).abs()),
                    "{name} at {z:?}, h {h}: [{lo}, {hi}], gradient {g:?}"
                );
            }
            checked += 1;
            if checked == 10 {
                break;
            }
        }
        assert!(checked >= 5, "{name}: {checked}");
    }
}

#[test]
fn anchor_types_gradient_enclosures() {
    for (name, f, span) in anchor_primitives() {
        let one = vec![(name.clone(), f.clone())];
        let n = if name.ends_with("config.json") { 8 } else { 40 };
        enclosures_hold(&one, span, 11, n);
        enclosures_tighten(&one, span, 12, n);
        // The analytic gradient against central differences.
        let mut rng = ChaCha8Rng::seed_from_u64(13);
        let (mid, r) = span;
        for _ in 0..100 {
            let p = [0, 1, 2].map(|i| mid[i] + rng.gen_range(-r..r));
            let g = f.gradient(p);
            let h = 1e-6;
            for a in 0..3 {
                let (mut pp, mut pm) = (p, p);
                pp[a] += h;
                pm[a] -= h;
                let fd = (f.eval(pp) - f.eval(pm)) / (2.0 * h);
                let scale = 1.0 + g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                assert!((g[a] - fd).abs() < 1e-5 * scale, "{name} at {p:?}: {g:?} vs {fd} ({a})");
            }
        }
    }
}

#[test]
fn anchor_types_sparse_equals_dense() {
    use septa::complex::Mode;
    use septa::grid::{BoxGrid, Grid, Split};
    use septa::network::{compute, compute_sparse, NetworkOptions};
    use septa::scene::sample_grid;
    let mut skipped = 0;
    for (name, f, (mid, r)) in anchor_primitives() {
        let grid = BoxGrid::new([13; 3], [mid.map(|x| x - r), mid.map(|x| x + r)], Split::Six).unwrap();
        let g = Grid::Box(grid.clone());
        let mut o = NetworkOptions::new(Mode::Ia);
        o.block = 4;
        let fs = vec![f];
        let values = sample_grid(&fs, &g.vertices());
        let dense = compute(&g, &values, 1, &o).unwrap();
        let (sparse, stats) = compute_sparse(&grid, &fs, &o).unwrap();
        assert_eq!(dense.counts(), sparse.counts(), "{name}");
        assert_eq!(dense.face_verts, sparse.face_verts, "{name}");
        assert!(!dense.face_verts.is_empty(), "{name}: no surface in the grid");
        skipped += stats.skipped;
    }
    assert!(skipped > 0);
}

#[test]
fn anchor_types_print_and_read_back() {
    for (name, f, (mid, _)) in anchor_primitives() {
        let text = serde_json::Value::Array(vec![primitive_json(&f).unwrap()]).to_string();
        let back = load_function_list(&text, "printed.json", None).unwrap_or_else(|e| panic!("{name}: {e}"));
        for d in [[0.0; 3], [0.1, -0.2, 0.05], [0.3, 0.2, -0.1]] {
            let p = [0, 1, 2].map(|i| mid[i] + d[i]);
            assert_eq!(back[0].eval(p), f.eval(p), "{name}");
        }
    }
}

#[test]
fn bad_rbf_files_are_named() {
    let dir = std::env::temp_dir().join(format!("septa_rbf_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let list = r#"[{"type": "rbf", "points": "p.xyz", "rbf_coeffs": "p_coeff"}]"#;
    let run = |xyz: &str, coeff: &str| {
        std::fs::write(dir.join("p.xyz"), xyz).unwrap();
        std::fs::write(dir.join("p_coeff"), coeff).unwrap();
        load_function_list(list, "f.json", Some(&dir)).map(|_| ()).map_err(|e| e.to_string())
    };
    assert!(run("3\n0 0 0\n1 0 0\n", "1 2 0 0 0 0 0 0\n0 0 0 1\n").is_ok());
    let e = run("3\n0 0 0\n1 0 0\n", "1 2 0 0 0 0 0\n0 0 0 1\n").unwrap_err();
    assert!(e.contains("7 coefficients for 2 centres") && e.contains("[0].points"), "{e}");
    let e = run("3\n0 0 x\n", "1 0 0 0\n0 0 0 1\n").unwrap_err();
    assert!(e.contains("p.xyz:2") && e.contains("`x`"), "{e}");
    let e = run("2\n0 0\n", "1 0 0 0\n0 0 0 1\n").unwrap_err();
    assert!(e.contains("dimension 2"), "{e}");
    let e = run("3\n0 0 0\n", "1 0 0 0\n0 0 1\n").unwrap_err();
    assert!(e.contains("p_coeff:2") && e.contains("4 numbers"), "{e}");
    std::fs::remove_file(dir.join("p_coeff")).unwrap();
    let e = load_function_list(list, "f.json", Some(&dir)).unwrap_err().to_string();
    assert!(e.contains("cannot read") && e.contains("p_coeff"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}
