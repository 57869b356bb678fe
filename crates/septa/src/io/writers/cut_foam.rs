//! OpenFOAM `constant/polyMesh` of a cut-cell mesh (`points`, `faces`,
//! `owner`, `neighbour`, `boundary`, `faceZones`), ASCII.
//!
//! Cut-cell meshes are made for finite-volume solvers; OpenFOAM reads a mesh
//! as faces with an owner cell and, for internal faces, a neighbour cell.
//! Its rules, which this writer follows:
//! - internal faces first, in upper-triangular order: sorted by owner, then
//!   neighbour, with `owner < neighbour`;
//! - each face's normal (right-hand rule on its point order) points out of
//!   its owner;
//! - boundary faces after them, grouped by patch in the order of `boundary`.
//!
//! The faces are the polygons of `cells.vtu` ([`CutCellMesh::face_polygons`]:
//! a cut-face with holes or with rounded vertices off its plane becomes its
//! triangles), so the exact check of the written embedding holds for this
//! mesh too, and the points are the same doubles (printed in shortest
//! round-trip form). Every boundary face lies on the input surface (a
//! cut-face on a plane always separates two cells), so the input surface is
//! one `wall` patch, `surface`, less the parts the user names
//! ([`BoundaryPatches`], `septa cut --patch inlet=xmin`): each a `patch`
//! of the faces on the input triangles lying in one side of the bounding
//! box (all three corners exactly on it), listed before `surface`. Each plane family (planes with exactly
//! parallel normals, e.g. the x, y and z planes of `--grid`) gets a patch,
//! `planes<k>`, that is empty in the mesh as cut (there for boundary
//! conditions after splitting along it, e.g. by `createBaffles`), and a face
//! zone of the same name holding its internal faces, oriented by the
//! family's first plane normal (`flipMap` true where a face's normal is
//! opposite).

use crate::cut::CutCellMesh;
use crate::cut::Support;
use septa_exact::{det_sign, Sign};
use std::fmt::Write as _;
use std::path::Path;

/// A side of the input's bounding box: axis (0, 1, 2) and max (`true`) or min.
pub type BoxSide = (usize, bool);

/// Parses `xmin`, `xmax`, ..., `zmax`.
pub fn parse_box_side(s: &str) -> Option<BoxSide> {
    let axis = ["x", "y", "z"].iter().position(|a| s.starts_with(a))?;
    match &s[1..] {
        "min" => Some((axis, false)),
        "max" => Some((axis, true)),
        _ => None,
    }
}

/// Boundary patches named by the user: `names[k]` holds the faces on the
/// input triangles `t` with `of_triangle[t] == k`; the others are the wall
/// `surface`.
#[derive(Clone, Debug, Default)]
pub struct BoundaryPatches {
    /// Patch names, in the order of `boundary`.
    pub names: Vec<String>,
    /// Each input triangle's patch (`u32::MAX`: `surface`).
    pub of_triangle: Vec<u32>,
}

impl BoundaryPatches {
    /// Patches by bounding-box side: `(name, side)` takes the triangles whose
    /// three corners lie exactly on that side of the box of `vertices`.
    /// Errors: a name that is not an OpenFOAM word or is taken (`surface`,
    /// `planes<k>`, twice), a side named twice, a side no triangle lies on.
    pub fn by_side(
        vertices: &[[f64; 3]],
        triangles: &[[u32; 3]],
        sides: &[(String, BoxSide)],
    ) -> Result<BoundaryPatches, String> {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        let side_name = |(k, max): BoxSide| format!("{}{}", ["x", "y", "z"][k], if max { "max" } else { "min" });
        let mut out = BoundaryPatches { names: Vec::new(), of_triangle: vec![u32::MAX; triangles.len()] };
        for (i, (name, side)) in sides.iter().enumerate() {
            let word = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
            if !word {
                return Err(format!("patch name '{name}': use letters, digits and '_' (not first a digit)"));
            }
            let planes =
                name.strip_prefix("planes").is_some_and(|r| !r.is_empty() && r.bytes().all(|b| b.is_ascii_digit()));
            if name == "surface" || planes || out.names.contains(name) {
                return Err(format!(
                    "patch name '{name}' is taken (surface and planes<k> are septa's, each name once)"
                ));
            }
            if let Some(j) = sides[..i].iter().position(|s| s.1 == *side) {
                return Err(format!("side {} is named twice ({} and {name})", side_name(*side), sides[j].0));
            }
            let (k, max) = *side;
            let at = if max { hi[k] } else { lo[k] };
            let mut any = false;
            for (t, tri) in triangles.iter().enumerate() {
                if tri.iter().all(|&v| vertices[v as usize][k] == at) {
                    out.of_triangle[t] = i as u32;
                    any = true;
                }
            }
            if !any {
                return Err(format!(
                    "patch {name}={}: no triangle of the mesh lies on that side of its bounding box ({} = {at})",
                    side_name(*side),
                    ["x", "y", "z"][k]
                ));
            }
            out.names.push(name.clone());
        }
        Ok(out)
    }
}

/// The polyMesh arrays, in OpenFOAM's order.
#[derive(Clone, Debug, Default)]
pub struct PolyMesh {
    /// Point coordinates (the cut-cell mesh's points, unchanged).
    pub points: Vec<[f64; 3]>,
    /// Faces, each normal pointing out of its owner.
    pub faces: Vec<Vec<u32>>,
    /// Owner cell of each face.
    pub owner: Vec<u32>,
    /// Neighbour cell of each internal face (`owner < neighbour`).
    pub neighbour: Vec<u32>,
    /// Patches: name, OpenFOAM type, start face, number of faces.
    pub patches: Vec<(String, &'static str, usize, usize)>,
    /// Face zones: name, internal faces, flip of each.
    pub zones: Vec<(String, Vec<u32>, Vec<bool>)>,
    /// Number of cells.
    pub cells: usize,
    /// Two cut-cells whose numbers are traded in the polyMesh (see
    /// [`poly_mesh`]); every other polyMesh cell `i` is cut-cell `i`.
    pub swapped: Option<(u32, u32)>,
}

/// Plane families: planes whose normals are exactly parallel (all three
/// 2x2 minors of the two normals zero, decided exactly), numbered by first
/// plane; returns each plane's family and whether its normal opposes the
/// family's first plane normal.
pub fn plane_families(planes: &[[f64; 4]]) -> (Vec<u32>, Vec<bool>) {
    let mut reps: Vec<usize> = Vec::new();
    let (mut fam, mut opposite) = (Vec::with_capacity(planes.len()), Vec::with_capacity(planes.len()));
    for (p, n) in planes.iter().enumerate() {
        let parallel = |r: &[f64; 4]| {
            (0..3).all(|k| {
                let (i, j) = (k, (k + 1) % 3);
                det_sign(&[[n[i], n[j]], [r[i], r[j]]]) == Sign::Zero
            })
        };
        match reps.iter().position(|&r| parallel(&planes[r])) {
            Some(f) => {
                let r = &planes[reps[f]];
                // parallel normals: the sign of any component product where
                // the first plane's component is non-zero says the direction
                let k = (0..3).find(|&k| r[k] != 0.0).unwrap_or(0);
                fam.push(f as u32);
                opposite.push((n[k] > 0.0) != (r[k] > 0.0));
            }
            None => {
                fam.push(reps.len() as u32);
                opposite.push(false);
                reps.push(p);
            }
        }
    }
    (fam, opposite)
}

/// Builds the polyMesh of `m` (see the module documentation). Cell `i` is
/// cut-cell `i`, except when the last cut-cell has no face on the input
/// surface: with internal faces owned by their lower cell it would own no
/// face, and readers that count cells from the owner list alone (fluidfoam
/// does; OpenFOAM also reads the neighbour list) would miss it. It then
/// trades its number with the last cut-cell that has a surface face
/// ([`PolyMesh::swapped`]).
pub fn poly_mesh(m: &CutCellMesh) -> PolyMesh {
    poly_mesh_patched(m, &BoundaryPatches::default())
}

/// [`poly_mesh`] with the boundary faces on the triangles `patches` names
/// in patches of their own (before `surface`).
pub fn poly_mesh_patched(m: &CutCellMesh, patches: &BoundaryPatches) -> PolyMesh {
    let mut on_surface = vec![false; m.num_cells];
    for f in &m.faces {
        if let [c, u32::MAX] | [u32::MAX, c] = f.cells {
            if c != u32::MAX {
                on_surface[c as usize] = true;
            }
        }
    }
    let mut swapped = None;
    let mut cell: Vec<u32> = (0..m.num_cells as u32).collect();
    if let Some(last) = m.num_cells.checked_sub(1) {
        if !on_surface[last] {
            if let Some(b) = on_surface.iter().rposition(|&s| s) {
                cell.swap(last, b);
                swapped = Some((b as u32, last as u32));
            }
        }
    }
    let renumber = |c: u32| if c == u32::MAX { c } else { cell[c as usize] };
    let (family, opposite) = plane_families(&m.planes);
    let nfam = family.iter().map(|&f| f as usize + 1).max().unwrap_or(0);
    // (owner, neighbour or MAX, face polygon, zone entry)
    let mut internal: Vec<(u32, u32, Vec<u32>, Option<(u32, bool)>)> = Vec::new();
    // (patch, owner, face polygon): `surface` is patch `names.len()`
    let mut boundary: Vec<(u32, u32, Vec<u32>)> = Vec::new();
    let surface = patches.names.len() as u32;
    for (i, f) in m.faces.iter().enumerate() {
        let [c0, c1] = f.cells.map(renumber);
        let patch = match f.support {
            Support::Tri(t) => patches.of_triangle.get(t as usize).copied().filter(|&k| k < surface).unwrap_or(surface),
            Support::Plane(_) => surface,
        };
        for poly in m.face_polygons(i) {
            // the polygon is counter-clockwise about the support normal,
            // which points out of cells[0]
            let rev = || poly.iter().rev().copied().collect::<Vec<u32>>();
            match (c0 != u32::MAX, c1 != u32::MAX) {
                (true, true) => {
                    let flip = c1 < c0;
                    let zone = match f.support {
                        Support::Plane(p) => Some((family[p as usize], flip != opposite[p as usize])),
                        Support::Tri(_) => None,
                    };
                    let (o, n, face) = if flip { (c1, c0, rev()) } else { (c0, c1, poly.clone()) };
                    internal.push((o, n, face, zone));
                }
                (true, false) => boundary.push((patch, c0, poly.clone())),
                (false, true) => boundary.push((patch, c1, rev())),
                (false, false) => {}
            }
        }
    }
    internal.sort_by_key(|e| (e.0, e.1));
    boundary.sort_by_key(|e| (e.0, e.1));
    let mut pm = PolyMesh { points: m.vertices.clone(), cells: m.num_cells, swapped, ..Default::default() };
    pm.zones = (0..nfam).map(|k| (format!("planes{k}"), Vec::new(), Vec::new())).collect();
    for (k, (o, n, face, zone)) in internal.into_iter().enumerate() {
        pm.owner.push(o);
        pm.neighbour.push(n);
        pm.faces.push(face);
        if let Some((z, flip)) = zone {
            pm.zones[z as usize].1.push(k as u32);
            pm.zones[z as usize].2.push(flip);
        }
    }
    let names = patches.names.iter().map(|n| (n.clone(), "patch")).chain([("surface".to_string(), "wall")]);
    let mut rest = &boundary[..];
    for (k, (name, ty)) in names.enumerate() {
        let n = rest.iter().take_while(|e| e.0 == k as u32).count();
        pm.patches.push((name, ty, pm.faces.len(), n));
        for (_, o, face) in &rest[..n] {
            pm.owner.push(*o);
            pm.faces.push(face.clone());
        }
        rest = &rest[n..];
    }
    for k in 0..nfam {
        pm.patches.push((format!("planes{k}"), "patch", pm.faces.len(), 0));
    }
    pm
}

fn header(s: &mut String, class: &str, object: &str, note: Option<&str>) {
    s.push_str("FoamFile\n{\n    version     2.0;\n    format      ascii;\n");
    let _ = writeln!(s, "    class       {class};");
    if let Some(n) = note {
        let _ = writeln!(s, "    note        \"{n}\";");
    }
    let _ = writeln!(s, "    location    \"constant/polyMesh\";\n    object      {object};\n}}\n");
}

fn label_list(s: &mut String, v: &[u32]) {
    let _ = writeln!(s, "{}\n(", v.len());
    for x in v {
        let _ = writeln!(s, "{x}");
    }
    s.push_str(")\n");
}

impl PolyMesh {
    /// The files of `constant/polyMesh` as (name, text).
    pub fn files(&self) -> Vec<(&'static str, String)> {
        let note = format!(
            "nPoints:{} nCells:{} nFaces:{} nInternalFaces:{}",
            self.points.len(),
            self.cells,
            self.faces.len(),
            self.neighbour.len()
        );
        let mut points = String::new();
        header(&mut points, "vectorField", "points", None);
        let _ = writeln!(points, "{}\n(", self.points.len());
        for p in &self.points {
            let _ = writeln!(points, "({:?} {:?} {:?})", p[0], p[1], p[2]);
        }
        points.push_str(")\n");
        let mut faces = String::new();
        header(&mut faces, "faceList", "faces", None);
        let _ = writeln!(faces, "{}\n(", self.faces.len());
        for f in &self.faces {
            let _ = write!(faces, "{}(", f.len());
            for (k, v) in f.iter().enumerate() {
                let _ = write!(faces, "{}{v}", if k > 0 { " " } else { "" });
            }
            faces.push_str(")\n");
        }
        faces.push_str(")\n");
        let mut owner = String::new();
        header(&mut owner, "labelList", "owner", Some(&note));
        label_list(&mut owner, &self.owner);
        let mut neighbour = String::new();
        header(&mut neighbour, "labelList", "neighbour", Some(&note));
        label_list(&mut neighbour, &self.neighbour);
        let mut boundary = String::new();
        header(&mut boundary, "polyBoundaryMesh", "boundary", None);
        let _ = writeln!(boundary, "{}\n(", self.patches.len());
        for (name, ty, start, n) in &self.patches {
            let _ = writeln!(boundary, "    {name}\n    {{\n        type            {ty};");
            if *ty == "wall" {
                boundary.push_str("        inGroups        List<word> 1(wall);\n");
            }
            let _ = writeln!(boundary, "        nFaces          {n};\n        startFace       {start};\n    }}");
        }
        boundary.push_str(")\n");
        let mut zones = String::new();
        header(&mut zones, "regIOobject", "faceZones", None);
        let _ = writeln!(zones, "{}\n(", self.zones.len());
        for (name, faces, flip) in &self.zones {
            let _ = writeln!(zones, "{name}\n{{\n    type faceZone;\nfaceLabels List<label> {}\n(", faces.len());
            for f in faces {
                let _ = writeln!(zones, "{f}");
            }
            let _ = writeln!(zones, ")\n;\nflipMap List<bool> {}\n(", flip.len());
            for &b in flip {
                zones.push_str(if b { "1\n" } else { "0\n" });
            }
            zones.push_str(")\n;\n}\n");
        }
        zones.push_str(")\n");
        vec![
            ("points", points),
            ("faces", faces),
            ("owner", owner),
            ("neighbour", neighbour),
            ("boundary", boundary),
            ("faceZones", zones),
        ]
    }
}

/// Writes the polyMesh files of `m` into the folder `dir` (created if
/// needed; each file atomically). Errors name the file. Returns the cells
/// whose numbers were traded ([`PolyMesh::swapped`]).
pub fn write_poly_mesh(dir: &Path, m: &CutCellMesh) -> Result<Option<(u32, u32)>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let pm = poly_mesh(m);
    for (name, text) in pm.files() {
        let p = dir.join(name);
        crate::io::write_atomic(&p, text.as_bytes()).map_err(|e| format!("cannot write {}: {e}", p.display()))?;
    }
    Ok(pm.swapped)
}

#[cfg(test)]
mod tests {
    use super::plane_families;

    #[test]
    fn families_are_exactly_parallel_planes() {
        // x planes (one with the opposite normal), a z plane, and a plane
        // whose normal differs from x's by one ulp in y: its own family
        let tiny = f64::MIN_POSITIVE;
        let planes = [[1.0, 0.0, 0.0, -1.0], [0.0, 0.0, 3.0, 1.0], [-2.0, 0.0, 0.0, 5.0], [1.0, tiny, 0.0, 0.0]];
        let (fam, opp) = plane_families(&planes);
        assert_eq!(fam, vec![0, 1, 0, 2]);
        assert_eq!(opp, vec![false, false, true, false]);
    }
}
