//! # Scenes: what users write
//!
//! Shapes as functions, not sampled arrays: **primitives**
//! ([`Primitive`]: plane, half-space, sphere, ellipsoid, box, cylinder,
//! capped cylinder, cone, torus, capsule, line, segment, circle, point
//! sets, triangle meshes, bicubic patches, blends, affine transforms and
//! function combinators), each with a value, an analytic gradient (for
//! vertex normals) and a guaranteed bound over a box (for skipping empty
//! blocks, docs/sparse.md); **sampling** on grid vertices ([`sample_grid`]);
//! **region rules** in Bloomenthal's non-manifold model ([`RegionRule`],
//! [`Interest`]); and **scene files** ([`Scene`]) with errors that name the
//! file, line and field ([`SceneError`]). The reference implementation's
//! primitive JSON loads unchanged ([`load_function_list`]) and samples to
//! bit-identical values.
//!
//! ## Primitive JSON
//!
//! Every primitive is an object with a `"type"` (hyphens may replace
//! underscores) and, inside a scene, an optional `"name"`. Positive inside.
//! The first eight are the reference implementation's, with its field names.
//!
//! | type | fields | value |
//! |---|---|---|
//! | `sphere` | `center`, `radius`, `squared`?, `unsigned`? | `r - \|p-c\|` (`r^2 - \|p-c\|^2`; `-\|r - \|p-c\|\|`) |
//! | `plane` | `point`, `normal` | `n . (p - point)`, `n` normalized |
//! | `line` | `point`, `unit_vector` (or `direction`), `squared`? | minus the distance to the line |
//! | `cylinder` | `axis_point` + `axis_vector` or `axis_point1` + `axis_point2`, `radius`, `squared`? | `r -` distance to the axis |
//! | `torus` | `center`, `axis_vector`, `major_radius`, `minor_radius`, `squared`? | `r - sqrt((rho - R)^2 + h^2)` (`r^2 - (rho - R)^2 - h^2`) |
//! | `circle` | `center`, `axis_vector`, `radius` | minus the distance to the circle |
//! | `cone` | `apex`, `axis_vector`, `apex_angle` (radians) | `u . (p - apex) - cos(angle) \|p - apex\|` |
//! | `zero` | | 0 |
//! | `constant` | `value` | the value |
//! | `half_space` | `point`, `normal` (outward) | `-n . (p - point)` |
//! | `ellipsoid` | `center`, `radii` | `min(radii) (1 - \|(p - c) / radii\|)` |
//! | `box` | `center` + `half_size` or `size`, or `min` + `max` | exact signed distance |
//! | `capped_cylinder` | `a`, `b`, `radius` | exact signed distance |
//! | `capsule` | `a`, `b`, `radius` | `r -` distance to the segment |
//! | `segment` | `a`, `b` | minus the distance to the segment |
//! | `points` | `points`, `weights`? | `max_i (w_i - \|p - x_i\|)` |
//! | `mesh` | `path` (`.obj .off .ply .stl`, relative to the scene) or `vertices` + `triangles` | signed distance to a closed mesh |
//! | `patch` | `origin` `[x0, y0]`, `size` `[sx, sy]`, `heights` (4 x 4) | signed offset from a bicubic height patch |
//! | `wyvill` | `center`, `axis`?, `radius`, `height` | `height W(dist / radius)` (Bloomenthal's `Sigmoid`) |
//! | `transform` | `of`, `scale`? (number or 3), `rotate`? (`{axis, degrees}`), `matrix`? (3 x 3), `translate`? | `of` moved by `p -> T R S p` |
//! | `sum`, `min`, `max` | `of`: list | sum, minimum, maximum |
//! | `scale`, `neg`, `abs` | `of`, (`factor`) | `factor f`, `-f`, `\|f\|` |
//!
//! `?` marks optional fields. Scene files, region rules and CSG: [`Scene`]
//! and [`Expr::parse`]; built-in scenes: [`builtin`].
//!
//! What is exact here: nothing needs to be. Sampled values are *input
//! data*; every topological decision is taken later, exactly, on them.
//! Bounds are conservative (outward-rounded), so a skipped block provably
//! holds no part of the network.
//!
//! ```
//! use septa::scene::{sample_grid, Scene};
//! let scene = Scene::load("builtin:sphere-with-hole").unwrap();
//! let points = scene.grid.vertices();
//! let values = sample_grid(&scene.functions, &points);
//! assert_eq!(values.len(), points.len() * scene.functions.len());
//! // The region of an IA cell from its sign vector (small, large):
//! assert_eq!(scene.regions.region_ia(&[false, true]), 2);
//! assert!(scene.interest.surface(2, 0) && !scene.interest.surface(1, 2));
//! ```

mod arith;
pub mod builtin;
mod closed_form;
mod composite;
mod csg_tree;
mod error;
mod field;
mod gradbound;
mod gradbound_composite;
mod gradbound_shapes;
mod grid_spec;
mod interval;
mod interval_vec;
mod mesh;
mod mesh_bvh;
mod normals;
mod patch;
mod primitive;
mod print;
mod rbf;
mod rbf_bounds;
mod region_rule;
mod rounding;
mod sample;
#[allow(clippy::module_inception)]
mod scene;
mod shapes;
mod spec;
mod strict_json;
mod torus;
pub(crate) mod vec3;

pub use closed_form::ClosedForm;
pub use composite::{rotation, wyvill, Mat3, Transform, Wyvill};
pub use csg_tree::load_csg_tree;
pub use error::{JsonPath, SceneError, Seg};
pub use field::Primitives;
pub use grid_spec::GridSpec;
pub use interval::Interval;
pub use mesh::{read_tri_mesh, TriMesh};
pub use patch::BicubicPatch;
pub use primitive::Primitive;
pub use print::{primitive_json, scene_json, scene_text};
pub use rbf::{read_hermite_rbf, HermiteRbf};
pub use region_rule::{must_flip, Expr, Interest, RegionId, RegionRule, Rule, MAX_DEPTH, MAX_RULE_LEN};
pub use sample::{block_may_be_active_ia, block_may_be_active_mi, sample_grid};
pub use scene::{load_function_list, load_function_list_warnings, Mode, Scene};
pub use shapes::{
    BoxShape, CappedCylinder, Capsule, Cone, Cylinder, Ellipsoid, PlaneShape, PointSet, Sphere, SphereKind,
};
pub use spec::PRIMITIVE_TYPES;
pub use strict_json::parse as parse_json_strict;
pub use torus::Torus;
