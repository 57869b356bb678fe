//! A scene as the JSON a user edits (`septa regions --print builtin:NAME`):
//! the inverse of the scene reader (`spec.rs`, `scene.rs`), field names as
//! in docs/scenes.md. Reading the printed text gives the same scene (up to
//! the rounding of a re-normalized direction or a cone's angle); printing
//! that again gives the same text (a test checks every built-in scene).

use serde_json::{json, Map, Value};

use super::primitive::Primitive;
use super::region_rule::{Expr, RegionRule};
use super::scene::{Mode, Scene};
use super::shapes::SphereKind;

/// The scene as scene-file JSON; an error names a primitive that has no
/// JSON form here (a triangle mesh given by its arrays).
pub fn scene_json(s: &Scene) -> Result<Value, String> {
    let mut doc = Map::new();
    doc.insert("grid".into(), json!({"resolution": s.grid.resolution, "bounds": s.grid.bounds, "split": s.grid.split}));
    doc.insert("mode".into(), json!(if s.mode == Mode::Mi { "mi" } else { "ia" }));
    let mut functions = Vec::new();
    for (i, f) in s.functions.iter().enumerate() {
        let mut p = primitive_json(f).map_err(|e| format!("function {i}: {e}"))?;
        if let (Some(name), Some(o)) = (s.names.get(i), p.as_object_mut()) {
            let mut named = Map::new();
            named.insert("name".into(), json!(name));
            named.extend(std::mem::take(o));
            p = Value::Object(named);
        }
        functions.push(p);
    }
    doc.insert("functions".into(), Value::Array(functions));
    if let RegionRule::Rules { rules, otherwise } = &s.regions {
        let mut list: Vec<Value> = rules
            .iter()
            .map(|r| match &r.when {
                Expr::True => json!({"region": r.region}),
                e => json!({"when": expr_text(e, &s.names), "region": r.region}),
            })
            .collect();
        list.push(json!({"region": otherwise}));
        doc.insert("regions".into(), Value::Array(list));
    }
    if let Some(pairs) = &s.interest.surfaces {
        doc.insert("surfaces".into(), json!(pairs.iter().map(|&(a, b)| [a, b]).collect::<Vec<_>>()));
    }
    if let Some(triples) = &s.interest.curves {
        doc.insert("curves".into(), json!(triples));
    }
    if !s.region_names.is_empty() {
        let m: Map<String, Value> = s.region_names.iter().map(|(k, v)| (k.to_string(), json!(v))).collect();
        doc.insert("region_names".into(), Value::Object(m));
    }
    if !s.interest.features {
        doc.insert("features".into(), json!(false));
    }
    Ok(Value::Object(doc))
}

/// A function's name in a condition: its name when the condition reader
/// takes it as one (letters, digits, `_`, `.`), else its index.
fn name(i: usize, names: &[String]) -> String {
    match names.get(i) {
        Some(n) if !n.is_empty() && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.') => n.clone(),
        _ => i.to_string(),
    }
}

/// A condition as text, every compound operand in parentheses (so the
/// operators' precedence never matters).
fn expr_text(e: &Expr, names: &[String]) -> String {
    let operand = |e: &Expr| match e {
        Expr::Func(_) | Expr::Not(_) => expr_text(e, names),
        _ => format!("({})", expr_text(e, names)),
    };
    match e {
        Expr::True => "true".into(),
        Expr::Func(i) => name(*i, names),
        Expr::Not(a) => format!("!{}", operand(a)),
        Expr::And(xs) => xs.iter().map(operand).collect::<Vec<_>>().join(" & "),
        Expr::Or(xs) => xs.iter().map(operand).collect::<Vec<_>>().join(" | "),
        Expr::Diff(a, b) => format!("{} - {}", operand(a), operand(b)),
    }
}

fn list(xs: &[Primitive]) -> Result<Vec<Value>, String> {
    xs.iter().map(primitive_json).collect()
}

/// One primitive in the scene reader's form.
pub fn primitive_json(p: &Primitive) -> Result<Value, String> {
    Ok(match p {
        Primitive::Constant(v) => json!({"type": "constant", "value": v}),
        Primitive::Plane(q) => json!({"type": "plane", "point": q.point, "normal": q.normal}),
        Primitive::HalfSpace(q) => json!({"type": "half_space", "point": q.point, "normal": q.normal}),
        Primitive::Sphere(s) => match s.kind {
            SphereKind::Signed => json!({"type": "sphere", "center": s.center, "radius": s.radius}),
            SphereKind::Squared => json!({"type": "sphere", "center": s.center, "radius": s.radius, "squared": true}),
            SphereKind::Unsigned => json!({"type": "sphere", "center": s.center, "radius": s.radius, "unsigned": true}),
        },
        Primitive::Ellipsoid(e) => json!({"type": "ellipsoid", "center": e.center, "radii": e.radii}),
        Primitive::Box(b) => json!({"type": "box", "center": b.center, "half_size": b.half}),
        Primitive::Cylinder(c) if c.radius == 0.0 => {
            json!({"type": "line", "point": c.point, "direction": c.axis, "squared": c.squared})
        }
        Primitive::Cylinder(c) => json!({"type": "cylinder", "axis_point": c.point, "axis_vector": c.axis,
            "radius": c.radius, "squared": c.squared}),
        Primitive::CappedCylinder(c) => json!({"type": "capped_cylinder", "a": c.a, "b": c.b, "radius": c.radius}),
        Primitive::Cone(c) => {
            json!({"type": "cone", "apex": c.apex, "axis_vector": c.axis, "apex_angle": c.cos_angle.acos()})
        }
        Primitive::Torus(t) if t.minor == 0.0 && !t.squared => {
            json!({"type": "circle", "center": t.center, "axis_vector": t.axis, "radius": t.major})
        }
        Primitive::Torus(t) if t.squared => json!({"type": "torus", "center": t.center, "axis_vector": t.axis,
            "major_radius": t.major, "minor_radius": t.minor, "squared": true}),
        Primitive::Torus(t) => json!({"type": "torus", "center": t.center, "axis_vector": t.axis,
            "major_radius": t.major, "minor_radius": t.minor}),
        Primitive::Capsule(c) if c.radius == 0.0 => json!({"type": "segment", "a": c.a, "b": c.b}),
        Primitive::Capsule(c) => json!({"type": "capsule", "a": c.a, "b": c.b, "radius": c.radius}),
        Primitive::Points(s) => json!({"type": "points", "points": s.points, "weights": s.weights}),
        Primitive::Mesh(_) => return Err("a triangle mesh has no printed form; give it as a file (`path`)".into()),
        Primitive::Patch(p) => json!({"type": "patch", "origin": p.origin, "size": p.size, "heights": p.heights}),
        Primitive::ClosedForm(c) => json!({"type": c.name()}),
        Primitive::Rbf(r) => {
            let n = r.len();
            let mut coeffs = r.a.clone();
            for j in 0..3 {
                coeffs.extend((0..n).map(|i| r.b[i][j]));
            }
            json!({"type": "rbf", "centers": r.centers, "coefficients": coeffs, "polynomial": r.poly})
        }
        Primitive::Wyvill(w) => {
            let mut v = json!({"type": "wyvill", "center": w.center, "radius": w.radius, "height": w.height});
            if let Some(a) = w.axis {
                v["axis"] = json!(a);
            }
            v
        }
        Primitive::Transform(t) => json!({"type": "transform", "of": primitive_json(&t.inner)?,
            "matrix": t.linear, "translate": t.translation}),
        Primitive::Sum(xs) => json!({"type": "sum", "of": list(xs)?}),
        Primitive::Min(xs) => json!({"type": "min", "of": list(xs)?}),
        Primitive::Max(xs) => json!({"type": "max", "of": list(xs)?}),
        Primitive::Scale(f, x) => json!({"type": "scale", "factor": f, "of": primitive_json(x)?}),
        Primitive::Abs(x) => json!({"type": "abs", "of": primitive_json(x)?}),
    })
}

/// [`scene_json`] as text to edit: one line per field, per function and per
/// region rule, in the order of docs/scenes.md.
pub fn scene_text(s: &Scene) -> Result<String, String> {
    let doc = scene_json(s)?;
    let mut out = String::from("{\n");
    let keys = ["grid", "mode", "functions", "regions", "region_names", "surfaces", "curves", "features"];
    let present: Vec<&str> = keys.iter().copied().filter(|k| doc.get(*k).is_some()).collect();
    for (i, k) in present.iter().enumerate() {
        let v = &doc[*k];
        out.push_str(&format!("  \"{k}\": "));
        match v {
            Value::Array(items) if matches!(*k, "functions" | "regions") => {
                out.push_str("[\n");
                for (j, item) in items.iter().enumerate() {
                    let sep = if j + 1 < items.len() { "," } else { "" };
                    out.push_str(&format!("    {item}{sep}\n"));
                }
                out.push_str("  ]");
            }
            v => out.push_str(&v.to_string()),
        }
        out.push_str(if i + 1 < present.len() { ",\n" } else { "\n" });
    }
    out.push_str("}\n");
    Ok(out)
}
