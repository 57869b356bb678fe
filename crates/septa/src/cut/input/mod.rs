//! Stages 1 to 3 (`check_mesh`, `self_intersection`, `input`), input conditions
//! (TopoCut Sec. 2.1, App. A), checked before any cutting: a scale the doubles
//! can cut at (`scale`), a closed, consistently oriented mesh with distinct
//! vertices, its non-manifold edges paired into wedges (`input`, `wedges`;
//! App. C), no self-intersection (`input::check_self_intersections`),
//! shells (meeting only at non-manifold edges and vertices) oriented outward
//! (`shells`), and distinct planes.
//!
//! Enters: the caller's vertices, triangles and planes. Leaves: the mesh's
//! edge topology (edges, per-triangle edges, per-edge triangles) and the
//! planes kept, or a [`CutError`] naming the offending element.
//!
//! [`CutError`]: crate::cut::CutError

pub(crate) mod input;
pub(crate) mod scale;
pub(crate) mod shells;
pub(crate) mod wedges;
