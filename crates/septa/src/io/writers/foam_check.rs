//! `septa cut --check-mesh`: the quantities OpenFOAM's `checkMesh` reports
//! for a polyMesh, computed as it computes them (v1912, the Debian
//! package's; `primitiveMeshCheck`, `primitiveMeshTools`), so a user sees
//! before running a solver what `checkMesh` will say, and a test compares
//! both on the same files.
//!
//! Face centres and area vectors: a triangle directly; a larger face by
//! the triangles from each edge to the average of its points, the centre
//! weighted by their areas. Cell centres and volumes: pyramids from each
//! face to the average of the cell's face centres. Then, per internal face
//! with `d` from owner to neighbour centre and area vector `S`:
//! non-orthogonality `acos(d.S / |d||S|)` (the average is `acos` of the
//! mean cosine), skewness `|sv| / fd` (`sv`: the face centre's offset from
//! where `d` crosses the face, `fd`: the face's extent along `sv`, at least
//! `0.2 |d|`; at boundary faces `d` is the normal part of the owner's
//! offset and at least `0.4 |d|`), face pyramids (each face's pyramid to
//! its owner and neighbour centres positive: a cell centre on the wrong
//! side of a face, as in a strongly concave cell, fails), and the volume
//! ratio `min(V_o, V_n) / max(V_o, V_n)`. Failed checks, as `checkMesh`
//! counts them: non-positive volumes or face areas, a non-orthogonality
//! past 90 degrees, a face pyramid below `-1e-15`, a skewness above 4, a
//! cell openness above `1e-6`.

use super::cut_foam::PolyMesh;

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: V, s: f64) -> V {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V, b: V) -> V {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn mag(a: V) -> f64 {
    dot(a, a).sqrt()
}

// OpenFOAM's constants (double precision)
const VSMALL: f64 = 1e-300;
const ROOTVSMALL: f64 = 1e-150;
const SMALL: f64 = 1e-15;
const NON_ORTH_THRESHOLD_DEG: f64 = 70.0;
const SKEW_THRESHOLD: f64 = 4.0;
const CLOSED_THRESHOLD: f64 = 1e-6;
const VOL_RATIO_WARN: f64 = 0.01;

/// What `checkMesh` reports (its default checks and the volume ratio of
/// `-allGeometry`).
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct FoamCheck {
    /// Cells.
    pub cells: usize,
    /// Faces (internal and boundary).
    pub faces: usize,
    /// Internal faces.
    pub internal_faces: usize,
    /// Total cell volume.
    pub total_volume: f64,
    /// Smallest and largest cell volume.
    pub min_volume: f64,
    /// Largest cell volume.
    pub max_volume: f64,
    /// Cells of volume below `1e-300` (a failed check).
    pub nonpositive_volumes: usize,
    /// Smallest face area.
    pub min_face_area: f64,
    /// Largest face area.
    pub max_face_area: f64,
    /// Faces of area below `1e-300` (a failed check).
    pub zero_area_faces: usize,
    /// Largest cell openness `|sum S| / sum |S|` per component.
    pub max_cell_openness: f64,
    /// Largest cell aspect ratio.
    pub max_aspect_ratio: f64,
    /// Largest non-orthogonality (degrees) over internal faces.
    pub max_non_orthogonality: f64,
    /// `acos` of the mean cosine (degrees), as `checkMesh` prints.
    pub average_non_orthogonality: f64,
    /// Internal faces above 70 degrees (a warning).
    pub severely_non_orthogonal: usize,
    /// Internal faces at 90 degrees or more (a failed check).
    pub non_orthogonal_errors: usize,
    /// Largest skewness over all faces.
    pub max_skewness: f64,
    /// Faces of skewness above 4 (a failed check).
    pub highly_skew_faces: usize,
    /// Faces with an owner or neighbour pyramid below `-1e-15` (a failed
    /// check: "incorrectly oriented").
    pub wrong_pyramids: usize,
    /// Smallest `min(V_o, V_n) / max(V_o, V_n)` over internal faces.
    pub min_volume_ratio: f64,
    /// Internal faces whose volume ratio is below 0.01 (a warning).
    pub small_volume_ratio_faces: usize,
    /// The failed checks, by `checkMesh`'s names (empty: "Mesh OK").
    pub failed: Vec<&'static str>,
}

/// Face centres and area vectors as `primitiveMesh` makes them.
pub fn face_centres_and_areas(points: &[V], faces: &[Vec<u32>]) -> (Vec<V>, Vec<V>) {
    let p = |i: u32| points[i as usize];
    faces
        .iter()
        .map(|f| {
            let n = f.len();
            if n == 3 {
                let c = scale(add(add(p(f[0]), p(f[1])), p(f[2])), 1.0 / 3.0);
                return (c, scale(cross(sub(p(f[1]), p(f[0])), sub(p(f[2]), p(f[0]))), 0.5));
            }
            let avg = scale(f.iter().fold([0.0; 3], |s, &i| add(s, p(i))), 1.0 / n as f64);
            let (mut sum_n, mut sum_a, mut sum_ac) = ([0.0; 3], 0.0, [0.0; 3]);
            for i in 0..n {
                let (a, b) = (p(f[i]), p(f[(i + 1) % n]));
                let c = add(add(a, b), avg);
                let nn = cross(sub(b, a), sub(avg, a));
                let m = mag(nn);
                sum_n = add(sum_n, nn);
                sum_a += m;
                sum_ac = add(sum_ac, scale(c, m));
            }
            let centre = if sum_a < ROOTVSMALL { avg } else { scale(sum_ac, 1.0 / (3.0 * sum_a)) };
            (centre, scale(sum_n, 0.5))
        })
        .unzip()
}

/// `checkMesh`'s quantities for `pm`.
pub fn check_poly_mesh(pm: &PolyMesh) -> FoamCheck {
    let nc = pm.cells;
    let nf = pm.faces.len();
    let ni = pm.neighbour.len();
    let (fc, fa) = face_centres_and_areas(&pm.points, &pm.faces);
    // cell centres and volumes
    let mut est = vec![[0.0; 3]; nc];
    let mut count = vec![0usize; nc];
    for f in 0..nf {
        let o = pm.owner[f] as usize;
        est[o] = add(est[o], fc[f]);
        count[o] += 1;
    }
    for f in 0..ni {
        let n = pm.neighbour[f] as usize;
        est[n] = add(est[n], fc[f]);
        count[n] += 1;
    }
    for c in 0..nc {
        est[c] = scale(est[c], 1.0 / count[c].max(1) as f64);
    }
    let mut cc = vec![[0.0; 3]; nc];
    let mut vol = vec![0.0; nc];
    let mut pyramid = |c: usize, f: usize, v3: f64| {
        let pc = add(scale(fc[f], 0.75), scale(est[c], 0.25));
        cc[c] = add(cc[c], scale(pc, v3));
        vol[c] += v3;
    };
    for f in 0..nf {
        let o = pm.owner[f] as usize;
        pyramid(o, f, dot(fa[f], sub(fc[f], est[o])));
    }
    for f in 0..ni {
        let n = pm.neighbour[f] as usize;
        pyramid(n, f, dot(fa[f], sub(est[n], fc[f])));
    }
    for c in 0..nc {
        cc[c] = if vol[c].abs() > VSMALL { scale(cc[c], 1.0 / vol[c]) } else { est[c] };
        vol[c] /= 3.0;
    }
    let mut r = FoamCheck { cells: nc, faces: nf, internal_faces: ni, ..Default::default() };
    r.total_volume = vol.iter().sum();
    r.min_volume = vol.iter().copied().fold(f64::INFINITY, f64::min);
    r.max_volume = vol.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    r.nonpositive_volumes = vol.iter().filter(|&&v| v < VSMALL).count();
    let areas: Vec<f64> = fa.iter().map(|&a| mag(a)).collect();
    r.min_face_area = areas.iter().copied().fold(f64::INFINITY, f64::min);
    r.max_face_area = areas.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    r.zero_area_faces = areas.iter().filter(|&&a| a < VSMALL).count();
    // closedness: the area vectors of each cell sum to zero
    let mut closed = vec![[0.0; 3]; nc];
    let mut closed_mag = vec![[0.0; 3]; nc];
    for f in 0..nf {
        let o = pm.owner[f] as usize;
        closed[o] = add(closed[o], fa[f]);
        closed_mag[o] = add(closed_mag[o], fa[f].map(f64::abs));
        if f < ni {
            let n = pm.neighbour[f] as usize;
            closed[n] = sub(closed[n], fa[f]);
            closed_mag[n] = add(closed_mag[n], fa[f].map(f64::abs));
        }
    }
    for c in 0..nc {
        let open = (0..3).map(|k| closed[c][k].abs() / (closed_mag[c][k] + ROOTVSMALL)).fold(0.0, f64::max);
        r.max_cell_openness = r.max_cell_openness.max(open);
        let lo = closed_mag[c].iter().copied().fold(f64::INFINITY, f64::min);
        let hi = closed_mag[c].iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let v = vol[c].max(ROOTVSMALL);
        let aspect = (hi / (lo + ROOTVSMALL)).max(closed_mag[c].iter().sum::<f64>() / 6.0 / v.powf(2.0 / 3.0));
        r.max_aspect_ratio = r.max_aspect_ratio.max(aspect);
    }
    // non-orthogonality
    let severe = NON_ORTH_THRESHOLD_DEG.to_radians().cos();
    let (mut min_cos, mut sum_cos) = (1.0f64, 0.0);
    for f in 0..ni {
        let d = sub(cc[pm.neighbour[f] as usize], cc[pm.owner[f] as usize]);
        let cos = dot(d, fa[f]) / (mag(d) * areas[f] + ROOTVSMALL);
        min_cos = min_cos.min(cos);
        sum_cos += cos;
        if cos < severe {
            if cos > SMALL {
                r.severely_non_orthogonal += 1;
            } else {
                r.non_orthogonal_errors += 1;
            }
        }
    }
    let deg = |c: f64| c.clamp(-1.0, 1.0).acos().to_degrees();
    r.max_non_orthogonality = if ni > 0 { deg(min_cos) } else { 0.0 };
    r.average_non_orthogonality = if ni > 0 { deg(sum_cos / ni as f64) } else { 0.0 };
    // skewness
    for f in 0..nf {
        let o = cc[pm.owner[f] as usize];
        let cpf = sub(fc[f], o);
        let (d, floor) = if f < ni {
            (sub(cc[pm.neighbour[f] as usize], o), 0.2)
        } else {
            let n = scale(fa[f], 1.0 / (areas[f] + ROOTVSMALL));
            (scale(n, dot(n, cpf)), 0.4)
        };
        let sv = sub(cpf, scale(d, dot(fa[f], cpf) / (dot(fa[f], d) + ROOTVSMALL)));
        let sv_hat = scale(sv, 1.0 / (mag(sv) + ROOTVSMALL));
        let mut fd = floor * mag(d) + ROOTVSMALL;
        for &p in &pm.faces[f] {
            fd = fd.max(dot(sv_hat, sub(pm.points[p as usize], fc[f])).abs());
        }
        let skew = mag(sv) / fd;
        r.max_skewness = r.max_skewness.max(skew);
        if skew > SKEW_THRESHOLD {
            r.highly_skew_faces += 1;
        }
    }
    // face pyramids: a third of S . (centre of face - apex), with the face's
    // own centre and area vector, positive for the owner; for the
    // neighbour the same with the sign turned
    for f in 0..nf {
        let own = dot(fa[f], sub(fc[f], cc[pm.owner[f] as usize])) / 3.0;
        let nei = if f < ni { dot(fa[f], sub(cc[pm.neighbour[f] as usize], fc[f])) / 3.0 } else { 1.0 };
        if own < -SMALL || nei < -SMALL {
            r.wrong_pyramids += 1;
        }
    }
    // volume ratio
    r.min_volume_ratio = 1.0;
    for f in 0..ni {
        let (a, b) = (vol[pm.owner[f] as usize], vol[pm.neighbour[f] as usize]);
        let ratio = a.min(b) / a.max(b).max(VSMALL);
        r.min_volume_ratio = r.min_volume_ratio.min(ratio);
        if ratio < VOL_RATIO_WARN {
            r.small_volume_ratio_faces += 1;
        }
    }
    if r.max_cell_openness > CLOSED_THRESHOLD {
        r.failed.push("cell openness");
    }
    if r.zero_area_faces > 0 {
        r.failed.push("face areas");
    }
    if r.nonpositive_volumes > 0 {
        r.failed.push("cell volumes");
    }
    if r.non_orthogonal_errors > 0 {
        r.failed.push("non-orthogonality");
    }
    if r.wrong_pyramids > 0 {
        r.failed.push("face pyramids");
    }
    if r.highly_skew_faces > 0 {
        r.failed.push("skewness");
    }
    r
}
