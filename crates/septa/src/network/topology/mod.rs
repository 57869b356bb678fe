//! From merged polygons to the network's topology (Du et al. Sec. 7):
//! blocks merged by global keys (`merge`), a canonical numbering
//! independent of thread count and function order (`canon`), patches,
//! chains, corners, shells and cells (`build`), cells by topological ray
//! shooting (`raytrace`, Sec. 7.1, on the questions of `ray_index`) or by
//! grouping.

mod build;
mod canon;
mod contact;
mod merge;
mod ray_index;
mod raytrace;

pub(crate) use build::{cell_cycle, chains, topology, wedge_cycle, Topology};
pub(crate) use canon::{canonicalize_merged, canonicalize_topology, min_rotation};
pub(crate) use contact::{contact_links, edge_on_grid_boundary};
pub(crate) use merge::{merge, Merged, Merger};
pub(crate) use ray_index::{faces_at_vertices, ray_start, FaceSide, RayIndex};
pub(crate) use raytrace::ray_cells;
