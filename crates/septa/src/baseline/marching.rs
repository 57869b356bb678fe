//! Marching tetrahedra of each function separately.

use rustc_hash::FxHashMap;

use super::Soup;

/// Zero sets of the `k` functions (values row-major `(#V, k)`), each
/// extracted separately by marching tetrahedra; points shared along grid
/// edges per function.
pub fn marching_tets(points: &[[f64; 3]], tets: &[[u32; 4]], values: &[f64], k: usize) -> Soup {
    let mut soup = Soup::new();
    let mut edge_point: FxHashMap<(u32, u32, u32), u32> = FxHashMap::default();
    for f in 0..k {
        let val = |v: u32| values[v as usize * k + f];
        for tet in tets {
            let inside: Vec<bool> = tet.iter().map(|&v| val(v) > 0.0).collect();
            let n_in = inside.iter().filter(|&&b| b).count();
            if n_in == 0 || n_in == 4 {
                continue;
            }
            let mut point = |a: u32, b: u32, soup: &mut Soup| -> u32 {
                let key = (a.min(b), a.max(b), f as u32);
                *edge_point.entry(key).or_insert_with(|| {
                    let (fa, fb) = (val(a), val(b));
                    let t = fa / (fa - fb);
                    let (pa, pb) = (points[a as usize], points[b as usize]);
                    soup.points.push([0, 1, 2].map(|i| pa[i] + t * (pb[i] - pa[i])));
                    soup.points.len() as u32 - 1
                })
            };
            let ins: Vec<u32> = (0..4).filter(|&i| inside[i]).map(|i| tet[i]).collect();
            let outs: Vec<u32> = (0..4).filter(|&i| !inside[i]).map(|i| tet[i]).collect();
            if ins.len() == 2 {
                let q = [
                    point(ins[0], outs[0], &mut soup),
                    point(ins[0], outs[1], &mut soup),
                    point(ins[1], outs[1], &mut soup),
                    point(ins[1], outs[0], &mut soup),
                ];
                soup.push_polygon(&q);
            } else {
                let (apex, others) = if ins.len() == 1 { (ins[0], outs) } else { (outs[0], ins) };
                let t = [
                    point(apex, others[0], &mut soup),
                    point(apex, others[1], &mut soup),
                    point(apex, others[2], &mut soup),
                ];
                soup.push_polygon(&t);
            }
        }
    }
    soup
}
