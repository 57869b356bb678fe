//! The [`Primitive`] enum: every function a scene can sample, with its
//! value, analytic gradient and a guaranteed bound over a box.

use std::sync::Arc;

use super::closed_form::ClosedForm;
use super::composite::{self, Mat3, Transform, Wyvill};
use super::interval::Interval;
use super::mesh::TriMesh;
use super::patch::BicubicPatch;
use super::rbf::HermiteRbf;
use super::shapes::*;
use super::torus::Torus;
use super::vec3::{normalize, V3};

/// A real function of a point in space.
///
/// Sign convention (the reference implementation's): **positive inside**.
/// Distance-like primitives without an inside (`line`, `segment`, `circle`,
/// `points`) are negated distances.
///
/// ```
/// use septa::scene::Primitive;
/// let s = Primitive::sphere([0.0, 0.0, 0.0], 1.0);
/// assert_eq!(s.eval([0.5, 0.0, 0.0]), 0.5);
/// assert_eq!(s.gradient([0.5, 0.0, 0.0]), [-1.0, 0.0, 0.0]);
/// let (lo, hi) = s.bounds([2.0, 2.0, 2.0], [3.0, 3.0, 3.0]);
/// assert!(hi < 0.0 && lo <= 1.0 - 27f64.sqrt());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Primitive {
    /// A constant (reference `zero` is 0).
    Constant(f64),
    /// Signed distance to a plane, growing along the normal.
    Plane(PlaneShape),
    /// Half-space behind an outward normal: positive inside
    /// (the negated plane).
    HalfSpace(PlaneShape),
    /// Sphere.
    Sphere(Sphere),
    /// Ellipsoid.
    Ellipsoid(Ellipsoid),
    /// Axis-aligned box, exact signed distance.
    Box(BoxShape),
    /// Infinite cylinder, or a line with radius 0.
    Cylinder(Cylinder),
    /// Capped cylinder, exact signed distance.
    CappedCylinder(CappedCylinder),
    /// Cone.
    Cone(Cone),
    /// Torus, or a circle with minor radius 0.
    Torus(Torus),
    /// Capsule, or a segment with radius 0.
    Capsule(Capsule),
    /// Weighted point set (Voronoi / Apollonius sites).
    Points(PointSet),
    /// Signed distance to a closed triangle mesh.
    Mesh(Arc<TriMesh>),
    /// Bicubic height-field patch.
    Patch(Box<BicubicPatch>),
    /// Wyvill blend bump.
    Wyvill(Wyvill),
    /// A closed-form test function of the adaptive-grid paper.
    ClosedForm(ClosedForm),
    /// Hermite RBF with the cubic kernel (shared: large).
    Rbf(Arc<HermiteRbf>),
    /// Affine transform of another primitive.
    Transform(Box<Transform>),
    /// Sum of primitives.
    Sum(Vec<Primitive>),
    /// Constant multiple.
    Scale(f64, Box<Primitive>),
    /// Absolute value.
    Abs(Box<Primitive>),
    /// Pointwise minimum (non-empty).
    Min(Vec<Primitive>),
    /// Pointwise maximum (non-empty).
    Max(Vec<Primitive>),
}

impl Primitive {
    /// Sphere `r - |p - c|`.
    pub fn sphere(center: V3, radius: f64) -> Primitive {
        Primitive::Sphere(Sphere { center, radius, kind: SphereKind::Signed })
    }
    /// Plane `n . (p - point)` (normal normalized here).
    pub fn plane(point: V3, normal: V3) -> Primitive {
        Primitive::Plane(PlaneShape { point, normal: normalize(normal) })
    }
    /// Half-space `-n . (p - point)`, positive on the side opposite the
    /// outward normal.
    pub fn half_space(point: V3, outward: V3) -> Primitive {
        Primitive::HalfSpace(PlaneShape { point, normal: normalize(outward) })
    }
    /// Axis-aligned box from centre and half sizes.
    pub fn cuboid(center: V3, half: V3) -> Primitive {
        Primitive::Box(BoxShape { center, half })
    }
    /// Infinite cylinder `r - dist(p, axis)`.
    pub fn cylinder(point: V3, axis: V3, radius: f64) -> Primitive {
        Primitive::Cylinder(Cylinder { point, axis: normalize(axis), radius, squared: false })
    }
    /// Capped cylinder between `a` and `b`.
    pub fn capped_cylinder(a: V3, b: V3, radius: f64) -> Primitive {
        Primitive::CappedCylinder(CappedCylinder { a, b, radius })
    }
    /// Negated distance to a line.
    pub fn line(point: V3, direction: V3) -> Primitive {
        Primitive::cylinder(point, direction, 0.0)
    }
    /// Torus.
    pub fn torus(center: V3, axis: V3, major: f64, minor: f64) -> Primitive {
        Primitive::Torus(Torus { center, axis: normalize(axis), major, minor, squared: false })
    }
    /// Affine transform `p -> A p + t` of `inner`; `None` if `A` is singular.
    pub fn transform(linear: Mat3, translation: V3, inner: Primitive) -> Option<Primitive> {
        Transform::new(linear, translation, inner).map(|t| Primitive::Transform(Box::new(t)))
    }

    /// Values at `points` into `out` (same length): the same bits as
    /// [`Primitive::eval`] per point, with the choice of primitive made once
    /// for the run of points instead of once per value (sampling a block is
    /// mostly this loop for spheres and planes).
    pub(crate) fn eval_into(&self, points: &[V3], out: &mut [f64]) {
        debug_assert_eq!(points.len(), out.len());
        match self {
            Primitive::Sphere(s) => out.iter_mut().zip(points).for_each(|(o, p)| *o = s.eval(*p)),
            Primitive::Plane(s) => out.iter_mut().zip(points).for_each(|(o, p)| *o = s.eval(*p)),
            _ => out.iter_mut().zip(points).for_each(|(o, p)| *o = self.eval(*p)),
        }
    }

    /// Value at `p`.
    pub fn eval(&self, p: V3) -> f64 {
        use Primitive::*;
        match self {
            Constant(v) => *v,
            Plane(s) => s.eval(p),
            HalfSpace(s) => -s.eval(p),
            Sphere(s) => s.eval(p),
            Ellipsoid(s) => s.eval(p),
            Box(s) => s.eval(p),
            Cylinder(s) => s.eval(p),
            CappedCylinder(s) => s.eval(p),
            Cone(s) => s.eval(p),
            Torus(s) => s.eval(p),
            Capsule(s) => s.eval(p),
            Points(s) => s.eval(p),
            Mesh(s) => s.eval(p),
            Patch(s) => s.eval(p),
            Wyvill(s) => s.eval(p),
            ClosedForm(s) => s.eval(p),
            Rbf(s) => s.eval(p),
            Transform(s) => s.eval(p),
            Sum(t) => composite::sum_eval(t, p),
            Scale(k, t) => k * t.eval(p),
            Abs(t) => t.eval(p).abs(),
            Min(t) => composite::extreme(t, p, false).0,
            Max(t) => composite::extreme(t, p, true).0,
        }
    }

    /// Analytic gradient at `p` (a one-sided or zero gradient where the
    /// function has a kink, e.g. at a sphere's centre).
    pub fn gradient(&self, p: V3) -> V3 {
        use Primitive::*;
        match self {
            Constant(_) => [0.0; 3],
            Plane(s) => s.gradient(p),
            HalfSpace(s) => s.gradient(p).map(|x| -x),
            Sphere(s) => s.gradient(p),
            Ellipsoid(s) => s.gradient(p),
            Box(s) => s.gradient(p),
            Cylinder(s) => s.gradient(p),
            CappedCylinder(s) => s.gradient(p),
            Cone(s) => s.gradient(p),
            Torus(s) => s.gradient(p),
            Capsule(s) => s.gradient(p),
            Points(s) => s.gradient(p),
            Mesh(s) => s.gradient(p),
            Patch(s) => s.gradient(p),
            Wyvill(s) => s.gradient(p),
            ClosedForm(s) => s.gradient(p),
            Rbf(s) => s.gradient(p),
            Transform(s) => s.gradient(p),
            Sum(t) => composite::sum_gradient(t, p),
            Scale(k, t) => t.gradient(p).map(|x| k * x),
            Abs(t) => {
                let k = if t.eval(p) < 0.0 { -1.0 } else { 1.0 };
                t.gradient(p).map(|x| k * x)
            }
            Min(t) => t[composite::extreme(t, p, false).1].gradient(p),
            Max(t) => t[composite::extreme(t, p, true).1].gradient(p),
        }
    }

    /// A guaranteed enclosure `(lo, hi)` of the values [`Primitive::eval`]
    /// returns at any point of the box `[min, max]` (corners included),
    /// float rounding included: interval arithmetic on eval's own
    /// expression (monotone rounding), or an enclosure of the exact value
    /// padded by a stated bound on eval's rounding error (`rounding.rs`
    /// says which and why). Used to skip empty blocks (docs/sparse.md): sparse
    /// evaluation is identical to dense because of this. May be infinite,
    /// never NaN.
    pub fn bounds(&self, min: V3, max: V3) -> (f64, f64) {
        let i = self.bounds_interval(min, max);
        (i.lo, i.hi)
    }

    pub(crate) fn bounds_interval(&self, lo: V3, hi: V3) -> Interval {
        use Primitive::*;
        // Each arm encloses eval's computed values (rounding.rs).
        match self {
            Constant(v) => Interval::point(*v),
            Plane(s) => s.bounds(lo, hi),
            HalfSpace(s) => s.bounds(lo, hi).neg(),
            Sphere(s) => s.bounds(lo, hi),
            Ellipsoid(s) => s.bounds(lo, hi),
            Box(s) => s.bounds(lo, hi),
            Cylinder(s) => s.bounds(lo, hi),
            CappedCylinder(s) => s.bounds(lo, hi),
            Cone(s) => s.bounds(lo, hi),
            Torus(s) => s.bounds(lo, hi),
            Capsule(s) => s.bounds(lo, hi),
            Points(s) => s.bounds(lo, hi),
            Mesh(s) => s.bounds(lo, hi),
            Patch(s) => s.bounds(lo, hi),
            Wyvill(s) => s.bounds(lo, hi),
            ClosedForm(s) => s.bounds(lo, hi),
            Rbf(s) => s.bounds(lo, hi),
            Transform(s) => s.bounds(lo, hi),
            Sum(t) => composite::sum_bounds(t, lo, hi),
            Scale(k, t) => t.bounds_interval(lo, hi).scale(*k),
            Abs(t) => t.bounds_interval(lo, hi).abs(),
            Min(t) => composite::extreme_bounds(t, lo, hi, false),
            Max(t) => composite::extreme_bounds(t, lo, hi, true),
        }
    }
}
