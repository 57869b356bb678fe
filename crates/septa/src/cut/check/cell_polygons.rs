//! The check's input: cells as flat lists of outward polygons of vertex
//! ids (what `cells.vtu` holds, and what the writers take).

/// Cells as flat lists of polygons (what [`verify_cells`] and the writers
/// take, without a vector per polygon): polygon `p` is
/// `verts[poly_start[p]..poly_start[p + 1]]`, and cell `c` holds polygons
/// `cell_start[c]..cell_start[c + 1]`. The check runs once or twice on
/// every cut and the writers once; the nested form cost an allocation per
/// polygon to build and to drop.
///
/// ```
/// use septa::cut::CellPolygons;
/// let cells = CellPolygons::from_nested(&[vec![vec![0, 1, 2], vec![0, 2, 3]], vec![vec![4, 5, 6]]]);
/// assert_eq!(cells.num_cells(), 2);
/// assert_eq!(cells.cell(0).collect::<Vec<_>>(), [&[0, 1, 2][..], &[0, 2, 3][..]]);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CellPolygons {
    pub(crate) cell_start: Vec<u32>,
    pub(crate) poly_start: Vec<u32>,
    pub(crate) verts: Vec<u32>,
}

impl CellPolygons {
    /// The same cells from their nested form (each cell a list of
    /// polygons, each polygon a list of vertex ids).
    pub fn from_nested(cells: &[Vec<Vec<u32>>]) -> CellPolygons {
        let mut f = CellPolygons { cell_start: vec![0], poly_start: vec![0], verts: Vec::new() };
        for cell in cells {
            for poly in cell {
                f.verts.extend_from_slice(poly);
                f.poly_start.push(f.verts.len() as u32);
            }
            f.cell_start.push(f.poly_start.len() as u32 - 1);
        }
        f
    }

    /// Number of cells.
    pub fn num_cells(&self) -> usize {
        self.cell_start.len() - 1
    }

    /// The polygons of cell `c`, in order.
    pub fn cell(&self, c: usize) -> impl Iterator<Item = &[u32]> + '_ {
        (self.cell_start[c] as usize..self.cell_start[c + 1] as usize)
            .map(move |p| &self.verts[self.poly_start[p] as usize..self.poly_start[p + 1] as usize])
    }
}
