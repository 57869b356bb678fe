//! The measures of region surfaces (`crate::measure`): each region's volume
//! (the sum of its network cells'), each surface's area, each curve's length.

use super::RegionSurfaces;
use crate::measure::{area_vector_len, network_measures, path_length};

impl RegionSurfaces {
    /// The regions of the result, ascending (the `cells` of every output).
    pub fn region_ids(&self) -> Vec<crate::scene::RegionId> {
        let set: std::collections::BTreeSet<_> = self.cell_region.iter().copied().collect();
        set.into_iter().collect()
    }

    /// Recomputes [`RegionSurfaces::measures`] from the network, the kept
    /// polygons and [`RegionSurfaces::domain`] (after the points moved, say).
    pub fn measure(&mut self) {
        let cells = network_measures(&self.network, self.domain.as_ref()).cell_volume;
        let regions = self.region_ids();
        let mut cell_volume = vec![0.0; regions.len()];
        for (c, &g) in self.cell_region.iter().enumerate() {
            if let Ok(i) = regions.binary_search(&g) {
                cell_volume[i] += cells[c];
            }
        }
        self.measures.cell_volume = cell_volume;
        self.measure_surfaces();
    }

    /// Recomputes the surfaces' areas and the curves' lengths (their own
    /// and in [`RegionSurfaces::measures`]) from the points, leaving the
    /// volumes (an affine map scales those by its determinant: `io::place_surfaces`).
    pub fn measure_surfaces(&mut self) {
        let points = &self.network.points;
        let mut patch_area = vec![0.0; self.surfaces.len()];
        for i in 0..self.faces.len() {
            let poly = &self.loops[self.loop_start[i] as usize..self.loop_start[i + 1] as usize];
            if let Some(a) = patch_area.get_mut(self.face_surface[i] as usize) {
                *a += area_vector_len(points, poly) / 2.0;
            }
        }
        for c in &mut self.curves {
            c.length = path_length(points, &c.vertices);
        }
        self.measures.patch_area = patch_area;
        self.measures.chain_length = self.curves.iter().map(|c| c.length).collect();
    }
}
