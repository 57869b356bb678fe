//! # Scenes: what users write
//!
//! Shapes as functions, not sampled arrays (issue 7): **primitives**
//! ([`Primitive`]: plane, half-space, sphere, ellipsoid, box, cylinder,
//! capped cylinder, cone, torus, capsule, line, segment, circle, point
//! sets, triangle meshes, bicubic patches, blends, affine transforms and
//! function combinators), each with a value, an analytic gradient (for
//! vertex normals) and a guaranteed bound over a box (for skipping empty
//! blocks, issue 6); **sampling** on grid vertices ([`sample_grid`]);
//! **region rules** in Bloomenthal's non-manifold model ([`RegionRule`],
//! [`Interest`]); and **scene files** ([`Scene`]) with errors that name the
//! file, line and field ([`SceneError`]). The reference implementation's
//! primitive JSON loads unchanged ([`load_function_list`]) and samples to
//! bit-identical values.
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

pub mod builtin;
mod composite;
mod error;
mod gradbound;
mod interval;
mod mesh;
mod mesh_bvh;
mod normals;
mod patch;
mod primitive;
mod regions;
mod sample;
#[allow(clippy::module_inception)]
mod scene;
mod shapes;
mod spec;
mod vec3;

pub use composite::{rotation, wyvill, Mat3, Transform, Wyvill};
pub use error::{JsonPath, SceneError, Seg};
pub use mesh::{parse_obj, parse_stl, MeshFileError, TriMesh};
pub use patch::BicubicPatch;
pub use primitive::Primitive;
pub use regions::{must_flip, Expr, Interest, RegionId, RegionRule, Rule};
pub use sample::{block_may_be_active_ia, block_may_be_active_mi, sample_grid};
pub use scene::{load_function_list, GridSpec, Mode, Scene};
pub use shapes::{
    BoxShape, CappedCylinder, Capsule, Cone, Cylinder, Ellipsoid, Plane, PointSet, Sphere, SphereKind, Torus,
};
pub use spec::PRIMITIVE_TYPES;
