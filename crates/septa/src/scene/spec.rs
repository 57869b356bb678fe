//! Primitive JSON: the reference implementation's function format
//! (`sphere`, `plane`, `line`, `cylinder`, `torus`, `circle`, `cone`,
//! `zero`, with its exact field names and its `squared` flag) loads
//! unchanged; Septa adds more types. Every error carries the JSON path of
//! the offending field.

use std::path::Path;
use std::sync::Arc;

use serde_json::{Map, Value};

use super::closed_form::ClosedForm;
use super::composite::{rotation, Mat3, Transform, Wyvill};
use super::error::{err, JsonPath, Located};
use super::mesh::{read_tri_mesh, TriMesh};
use super::patch::BicubicPatch;
use super::primitive::Primitive;
use super::rbf::{read_hermite_rbf, HermiteRbf};
use super::shapes::*;
use super::torus::Torus;
use super::vec3::{normalize, sub, V3};

/// Every primitive `type` name accepted (hyphens may replace underscores).
pub const PRIMITIVE_TYPES: &[&str] = &[
    "sphere",
    "plane",
    "line",
    "cylinder",
    "torus",
    "circle",
    "cone",
    "zero",
    "constant",
    "half_space",
    "ellipsoid",
    "box",
    "capped_cylinder",
    "capsule",
    "segment",
    "points",
    "mesh",
    "patch",
    "wyvill",
    "Gaussian",
    "smile",
    "cyclide",
    "wave",
    "teardrop",
    "rbf",
    "transform",
    "sum",
    "scale",
    "neg",
    "abs",
    "min",
    "max",
];

/// Options of the reader.
pub(crate) struct Ctx<'a> {
    /// Folder that relative mesh paths are resolved against.
    pub base_dir: Option<&'a Path>,
    /// Reference compatibility: a negative sphere radius means the
    /// reference's unsigned sphere distance instead of an error, and a key
    /// the reader does not use is a warning (the reference program ignores
    /// it too), not an error.
    pub compat: bool,
    /// The warnings of the compatible reading (keys not used), in order.
    pub warnings: std::cell::RefCell<Vec<Located>>,
}

impl<'a> Ctx<'a> {
    /// A reader of scene fields (strict) or of the reference's function
    /// format (`compat`).
    pub fn new(base_dir: Option<&'a Path>, compat: bool) -> Ctx<'a> {
        Ctx { base_dir, compat, warnings: Default::default() }
    }
}

/// An object being read: its members, and which of them were asked for,
/// so that a member nobody reads (a misspelt `radiuss`) is reported
/// ([`Obj::finish`]) instead of silently running a default.
pub(crate) struct Obj<'a> {
    pub map: &'a Map<String, Value>,
    pub path: JsonPath,
    used: std::cell::RefCell<Vec<String>>,
}

impl<'a> Obj<'a> {
    pub fn new(v: &'a Value, path: &JsonPath) -> Result<Obj<'a>, Located> {
        match v.as_object() {
            Some(map) => Ok(Obj { map, path: path.clone(), used: Default::default() }),
            None => err(path, "expected an object"),
        }
    }
    fn mark(&self, k: &str) {
        let mut u = self.used.borrow_mut();
        if !u.iter().any(|x| x == k) {
            u.push(k.to_string());
        }
    }
    /// Member `k`, if given (marked as read).
    pub fn opt(&self, k: &str) -> Option<&'a Value> {
        self.mark(k);
        self.map.get(k)
    }
    pub fn get(&self, k: &str) -> Result<&'a Value, Located> {
        match self.opt(k) {
            Some(v) => Ok(v),
            None => err(&self.path, format!("missing parameter `{k}`")),
        }
    }
    pub fn has(&self, k: &str) -> bool {
        self.mark(k);
        self.map.contains_key(k)
    }
    /// The first member not read (in the file's order), as an error naming
    /// it and the members that are read here.
    pub fn unknown(&self) -> Option<Located> {
        let used = self.used.borrow();
        let k = self.map.keys().find(|k| !used.iter().any(|u| u == *k))?;
        let mut known: Vec<&str> = used.iter().map(String::as_str).collect();
        known.sort_unstable();
        Some(Located {
            path: self.path.key(k),
            message: format!("unknown or unused key `{k}` (read here: {})", known.join(", ")),
        })
    }
    /// Marks the members `keys` as read (the keys an object may have, when
    /// they are read later or conditionally).
    pub fn mark_all(&self, keys: &[&str]) {
        keys.iter().for_each(|k| self.mark(k));
    }
    /// Every member must have been read: an error naming the first that was not.
    pub fn finish(&self) -> Result<(), Located> {
        self.unknown().map_or(Ok(()), Err)
    }
    pub fn f64(&self, k: &str) -> Result<f64, Located> {
        num(self.get(k)?, &self.path.key(k))
    }
    pub fn nonneg(&self, k: &str) -> Result<f64, Located> {
        let r = self.f64(k)?;
        if r < 0.0 {
            return err(&self.path.key(k), format!("negative {} {r}", k.replace('_', " ")));
        }
        Ok(r)
    }
    pub fn positive(&self, k: &str) -> Result<f64, Located> {
        let r = self.f64(k)?;
        if r <= 0.0 {
            return err(&self.path.key(k), format!("`{k}` must be positive, got {r}"));
        }
        Ok(r)
    }
    pub fn vec3(&self, k: &str) -> Result<V3, Located> {
        vec3(self.get(k)?, &self.path.key(k))
    }
    pub fn dir(&self, k: &str) -> Result<V3, Located> {
        let v = self.vec3(k)?;
        if v == [0.0; 3] {
            return err(&self.path.key(k), "zero vector (a direction is needed)");
        }
        Ok(normalize(v))
    }
    pub fn flag(&self, k: &str) -> Result<bool, Located> {
        match self.opt(k) {
            None => Ok(false),
            Some(Value::Bool(b)) => Ok(*b),
            Some(_) => err(&self.path.key(k), "expected true or false"),
        }
    }
    pub fn str(&self, k: &str) -> Result<&'a str, Located> {
        match self.get(k)? {
            Value::String(s) => Ok(s),
            _ => err(&self.path.key(k), "expected a string"),
        }
    }
}

pub(crate) fn num(v: &Value, path: &JsonPath) -> Result<f64, Located> {
    match v.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => err(path, "expected a finite number"),
    }
}

pub(crate) fn array<'a>(v: &'a Value, path: &JsonPath) -> Result<&'a Vec<Value>, Located> {
    match v.as_array() {
        Some(a) => Ok(a),
        None => err(path, "expected an array"),
    }
}

pub(crate) fn vec3(v: &Value, path: &JsonPath) -> Result<V3, Located> {
    let a = array(v, path)?;
    if a.len() != 3 {
        return err(path, format!("expected 3 numbers, got {}", a.len()));
    }
    Ok([num(&a[0], &path.index(0))?, num(&a[1], &path.index(1))?, num(&a[2], &path.index(2))?])
}

fn list_of<'a>(o: &Obj<'a>, k: &str, ctx: &Ctx) -> Result<Vec<Primitive>, Located> {
    let p = o.path.key(k);
    let a = array(o.get(k)?, &p)?;
    if a.is_empty() {
        return err(&p, "needs at least one primitive");
    }
    a.iter().enumerate().map(|(i, v)| primitive(v, &p.index(i), ctx)).collect()
}

/// Read one primitive object (any `name` member is ignored here). A member
/// the type does not read is an error naming it, or in the reference's
/// format (`ctx.compat`) a warning.
pub(crate) fn primitive(v: &Value, path: &JsonPath, ctx: &Ctx) -> Result<Primitive, Located> {
    let o = Obj::new(v, path)?;
    o.mark("name");
    let p = primitive_of(&o, path, ctx)?;
    if let Some(unknown) = o.unknown() {
        if !ctx.compat {
            return Err(unknown);
        }
        ctx.warnings.borrow_mut().push(unknown);
    }
    Ok(p)
}

fn primitive_of(o: &Obj, path: &JsonPath, ctx: &Ctx) -> Result<Primitive, Located> {
    let ty = o.str("type")?.replace('-', "_");
    // read only by the types it changes (elsewhere it is an unused key)
    let squared = || o.flag("squared");
    Ok(match ty.as_str() {
        "sphere" => {
            // the reference's display option (a flat-shaded sphere): the
            // function is the same
            o.mark("flat");
            let center = o.vec3("center")?;
            let r = o.f64("radius")?;
            let kind = if squared()? {
                SphereKind::Squared
            } else if r < 0.0 && (ctx.compat || o.flag("unsigned")?) {
                SphereKind::Unsigned
            } else if r < 0.0 {
                return err(
                    &path.key("radius"),
                    format!("negative radius {r} (the reference's unsigned sphere distance is `\"unsigned\": true` with a positive radius)"),
                );
            } else if o.flag("unsigned")? {
                SphereKind::Unsigned
            } else {
                SphereKind::Signed
            };
            Primitive::Sphere(Sphere { center, radius: r.abs(), kind })
        }
        "plane" => Primitive::Plane(PlaneShape { point: o.vec3("point")?, normal: o.dir("normal")? }),
        "half_space" | "halfspace" => {
            Primitive::HalfSpace(PlaneShape { point: o.vec3("point")?, normal: o.dir("normal")? })
        }
        "line" => Primitive::Cylinder(Cylinder {
            point: o.vec3("point")?,
            axis: o.dir(if o.has("unit_vector") { "unit_vector" } else { "direction" })?,
            radius: 0.0,
            squared: squared()?,
        }),
        "cylinder" => {
            let (point, axis) = if o.has("axis_point1") && o.has("axis_point2") {
                let a = o.vec3("axis_point1")?;
                let d = sub(o.vec3("axis_point2")?, a);
                if d == [0.0; 3] {
                    return err(&path.key("axis_point2"), "axis points coincide");
                }
                (a, normalize(d))
            } else {
                (o.vec3("axis_point")?, o.dir("axis_vector")?)
            };
            let radius = o.nonneg("radius")?;
            Primitive::Cylinder(Cylinder { point, axis, radius, squared: squared()? })
        }
        "torus" => Primitive::Torus(Torus {
            center: o.vec3("center")?,
            axis: o.dir("axis_vector")?,
            major: o.nonneg("major_radius")?,
            minor: o.nonneg("minor_radius")?,
            squared: squared()?,
        }),
        "circle" => Primitive::Torus(Torus {
            center: o.vec3("center")?,
            axis: o.dir("axis_vector")?,
            major: o.nonneg("radius")?,
            minor: 0.0,
            squared: squared()?,
        }),
        "cone" => Primitive::Cone(Cone {
            apex: o.vec3("apex")?,
            axis: o.dir("axis_vector")?,
            cos_angle: o.f64("apex_angle")?.cos(),
        }),
        "zero" => Primitive::Constant(0.0),
        "constant" => Primitive::Constant(o.f64("value")?),
        "ellipsoid" => {
            let radii = o.vec3("radii")?;
            if radii.iter().any(|r| *r <= 0.0) {
                return err(&path.key("radii"), "radii must be positive");
            }
            Primitive::Ellipsoid(Ellipsoid { center: o.vec3("center")?, radii })
        }
        "box" => {
            let (center, half) = if o.has("min") || o.has("max") {
                let (a, b) = (o.vec3("min")?, o.vec3("max")?);
                ([0, 1, 2].map(|i| 0.5 * (a[i] + b[i])), [0, 1, 2].map(|i| 0.5 * (b[i] - a[i])))
            } else if o.has("size") {
                (o.vec3("center")?, o.vec3("size")?.map(|s| 0.5 * s))
            } else {
                (o.vec3("center")?, o.vec3("half_size")?)
            };
            if half.iter().any(|h| *h <= 0.0) {
                return err(path, "box sides must be positive");
            }
            Primitive::Box(BoxShape { center, half })
        }
        "capped_cylinder" | "capsule" | "segment" => {
            let (a, b) = (o.vec3("a")?, o.vec3("b")?);
            let radius = if ty == "segment" { 0.0 } else { o.nonneg("radius")? };
            if ty == "capped_cylinder" {
                if a == b {
                    return err(&path.key("b"), "cap centres coincide");
                }
                Primitive::CappedCylinder(CappedCylinder { a, b, radius })
            } else {
                Primitive::Capsule(Capsule { a, b, radius })
            }
        }
        "points" => {
            let pp = path.key("points");
            let pts = array(o.get("points")?, &pp)?;
            if pts.is_empty() {
                return err(&pp, "needs at least one point");
            }
            let points: Vec<V3> =
                pts.iter().enumerate().map(|(i, v)| vec3(v, &pp.index(i))).collect::<Result<_, _>>()?;
            let weights = if o.has("weights") {
                let wp = path.key("weights");
                let w = array(o.get("weights")?, &wp)?;
                if w.len() != points.len() {
                    return err(&wp, format!("{} weights for {} points", w.len(), points.len()));
                }
                w.iter().enumerate().map(|(i, v)| num(v, &wp.index(i))).collect::<Result<_, _>>()?
            } else {
                vec![0.0; points.len()]
            };
            Primitive::Points(PointSet { points, weights })
        }
        "mesh" => Primitive::Mesh(Arc::new(mesh(o, ctx)?)),
        "patch" => {
            let orig = o.path.key("origin");
            let size = o.path.key("size");
            let g2 = |k: &str, p: &JsonPath| -> Result<[f64; 2], Located> {
                let a = array(o.get(k)?, p)?;
                if a.len() != 2 {
                    return err(p, "expected 2 numbers");
                }
                Ok([num(&a[0], &p.index(0))?, num(&a[1], &p.index(1))?])
            };
            let origin = g2("origin", &orig)?;
            let sz = g2("size", &size)?;
            if sz[0] <= 0.0 || sz[1] <= 0.0 {
                return err(&size, "sizes must be positive");
            }
            let hp = path.key("heights");
            let rows = array(o.get("heights")?, &hp)?;
            if rows.len() != 4 {
                return err(&hp, "expected 4 rows of 4 control heights");
            }
            let mut heights = [[0.0; 4]; 4];
            for (i, r) in rows.iter().enumerate() {
                let r = array(r, &hp.index(i))?;
                if r.len() != 4 {
                    return err(&hp.index(i), "expected 4 control heights");
                }
                for j in 0..4 {
                    heights[i][j] = num(&r[j], &hp.index(i).index(j))?;
                }
            }
            Primitive::Patch(Box::new(BicubicPatch { origin, size: sz, heights }))
        }
        "Gaussian" | "gaussian" | "smile" | "cyclide" | "wave" | "teardrop" => {
            Primitive::ClosedForm(ClosedForm::from_name(if ty == "gaussian" { "Gaussian" } else { &ty }).unwrap())
        }
        "rbf" => Primitive::Rbf(Arc::new(rbf(&o, ctx)?)),
        "wyvill" => Primitive::Wyvill(Wyvill {
            center: o.vec3("center")?,
            axis: if o.has("axis") { Some(o.dir("axis")?) } else { None },
            radius: o.positive("radius")?,
            height: o.f64("height")?,
        }),
        "transform" => transform(o, ctx)?,
        "sum" => Primitive::Sum(list_of(o, "of", ctx)?),
        "min" => Primitive::Min(list_of(o, "of", ctx)?),
        "max" => Primitive::Max(list_of(o, "of", ctx)?),
        "scale" | "neg" | "abs" => {
            let inner = Box::new(primitive(o.get("of")?, &path.key("of"), ctx)?);
            match ty.as_str() {
                "scale" => Primitive::Scale(o.f64("factor")?, inner),
                "neg" => Primitive::Scale(-1.0, inner),
                _ => Primitive::Abs(inner),
            }
        }
        other => {
            return err(
                &path.key("type"),
                format!("unknown primitive `{other}` (known: {})", PRIMITIVE_TYPES.join(", ")),
            )
        }
    })
}

/// A Hermite RBF: the reference's `points` (`.xyz`) and `rbf_coeffs`
/// files, relative to the function file, or inline `centers`,
/// `coefficients` (4N) and `polynomial` (4). The reference's display
/// fields `color` and `samples` are not used.
fn rbf(o: &Obj, ctx: &Ctx) -> Result<HermiteRbf, Located> {
    o.mark_all(&["color", "samples"]);
    if o.has("points") || o.has("rbf_coeffs") {
        let full = |k: &str| -> Result<std::path::PathBuf, Located> {
            let rel = o.str(k)?;
            Ok(ctx.base_dir.map_or_else(|| Path::new(rel).to_path_buf(), |d| d.join(rel)))
        };
        let (points, coeffs) = (full("points")?, full("rbf_coeffs")?);
        return read_hermite_rbf(&points, &coeffs).or_else(|e| err(&o.path.key("points"), e));
    }
    let cp = o.path.key("centers");
    let cs = array(o.get("centers")?, &cp)?;
    let centers: Vec<V3> = cs.iter().enumerate().map(|(i, v)| vec3(v, &cp.index(i))).collect::<Result<_, _>>()?;
    let kp = o.path.key("coefficients");
    let ks = array(o.get("coefficients")?, &kp)?;
    let coeffs: Vec<f64> = ks.iter().enumerate().map(|(i, v)| num(v, &kp.index(i))).collect::<Result<_, _>>()?;
    let pp = o.path.key("polynomial");
    let ps = array(o.get("polynomial")?, &pp)?;
    if ps.len() != 4 {
        return err(&pp, "the polynomial needs 4 numbers (c0, cx, cy, cz)");
    }
    let poly = [
        num(&ps[0], &pp.index(0))?,
        num(&ps[1], &pp.index(1))?,
        num(&ps[2], &pp.index(2))?,
        num(&ps[3], &pp.index(3))?,
    ];
    HermiteRbf::new(centers, &coeffs, poly).or_else(|e| err(&kp, e))
}

fn mesh(o: &Obj, ctx: &Ctx) -> Result<TriMesh, Located> {
    if o.has("path") {
        let rel = o.str("path")?;
        let full = match ctx.base_dir {
            Some(d) => d.join(rel),
            None => Path::new(rel).to_path_buf(),
        };
        return read_tri_mesh(&full).or_else(|e| err(&o.path.key("path"), e));
    }
    let vp = o.path.key("vertices");
    let tp = o.path.key("triangles");
    let vs = array(o.get("vertices")?, &vp)?;
    let vertices: Vec<V3> = vs.iter().enumerate().map(|(i, v)| vec3(v, &vp.index(i))).collect::<Result<_, _>>()?;
    let ts = array(o.get("triangles")?, &tp)?;
    let mut triangles = Vec::with_capacity(ts.len());
    for (i, t) in ts.iter().enumerate() {
        let p = tp.index(i);
        let a = array(t, &p)?;
        let idx: Vec<u32> =
            a.iter().filter_map(|x| x.as_u64()).filter(|&x| (x as usize) < vertices.len()).map(|x| x as u32).collect();
        if a.len() != 3 || idx.len() != 3 {
            return err(&p, format!("a triangle needs 3 vertex indices below {}", vertices.len()));
        }
        triangles.push([idx[0], idx[1], idx[2]]);
    }
    if triangles.is_empty() {
        return err(&tp, "no triangles");
    }
    match TriMesh::new(vertices, triangles) {
        Some(m) => Ok(m),
        None => err(&tp, "bad triangles"),
    }
}

fn transform(o: &Obj, ctx: &Ctx) -> Result<Primitive, Located> {
    let inner = primitive(o.get("of")?, &o.path.key("of"), ctx)?;
    // p -> T (R (S p)): scale, then rotate (or a general matrix), then move.
    let mut m: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    if o.has("scale") {
        let sp = o.path.key("scale");
        let s = match o.get("scale")? {
            Value::Array(_) => vec3(o.get("scale")?, &sp)?,
            v => [num(v, &sp)?; 3],
        };
        for i in 0..3 {
            m[i][i] = s[i];
        }
    }
    let mul =
        |a: &Mat3, b: &Mat3| -> Mat3 { [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum())) };
    if o.has("rotate") {
        let r = Obj::new(o.get("rotate")?, &o.path.key("rotate"))?;
        let angle = r.f64("degrees")?.to_radians();
        m = mul(&rotation(r.dir("axis")?, angle), &m);
        r.finish()?;
    }
    if o.has("matrix") {
        let mp = o.path.key("matrix");
        let rows = array(o.get("matrix")?, &mp)?;
        if rows.len() != 3 {
            return err(&mp, "expected 3 rows");
        }
        let mut a = [[0.0; 3]; 3];
        for i in 0..3 {
            a[i] = vec3(&rows[i], &mp.index(i))?;
        }
        m = mul(&a, &m);
    }
    let t = if o.has("translate") { o.vec3("translate")? } else { [0.0; 3] };
    match Transform::new(m, t, inner) {
        Some(t) => Ok(Primitive::Transform(Box::new(t))),
        None => err(&o.path, "the transform's linear part is singular"),
    }
}
