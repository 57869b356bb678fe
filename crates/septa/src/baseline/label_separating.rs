//! The label-separating extractor: a surface between grid vertices of
//! different labels, through edge midpoints, face centres and tet centres.

use rustc_hash::FxHashMap;

use super::Soup;

/// Label of each grid vertex: IA the sign vector (as bits), MI the argmax.
fn labels(values: &[f64], k: usize, mi: bool) -> Vec<u64> {
    values
        .chunks_exact(k)
        .map(|row| {
            if mi {
                let mut best = 0;
                for (i, &x) in row.iter().enumerate() {
                    if x > row[best] {
                        best = i;
                    }
                }
                best as u64
            } else {
                row.iter().enumerate().fold(0u64, |acc, (i, &x)| acc | (((x > 0.0) as u64) << (i % 64)))
            }
        })
        .collect()
}

/// For every tet edge joining vertices of different labels, the quad
/// (edge midpoint, face centre, tet centre, face centre) over its two
/// faces in the tet; together they separate every pair of labels.
pub fn label_separating(points: &[[f64; 3]], tets: &[[u32; 4]], values: &[f64], k: usize, mi: bool) -> Soup {
    let label = labels(values, k, mi);
    let mut soup = Soup::new();
    let mut shared: FxHashMap<(u32, u32, u32), u32> = FxHashMap::default();
    let centre = |ids: &[u32]| {
        let mut c = [0.0; 3];
        for &v in ids {
            for i in 0..3 {
                c[i] += points[v as usize][i] / ids.len() as f64;
            }
        }
        c
    };
    const EDGES: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];
    for tet in tets {
        let l = tet.map(|v| label[v as usize]);
        if l.iter().all(|&x| x == l[0]) {
            continue;
        }
        soup.points.push(centre(tet));
        let tc = soup.points.len() as u32 - 1;
        for [a, b] in EDGES {
            if l[a] == l[b] {
                continue;
            }
            let (va, vb) = (tet[a], tet[b]);
            let mut get = |key: (u32, u32, u32), ids: &[u32], soup: &mut Soup| {
                *shared.entry(key).or_insert_with(|| {
                    soup.points.push(centre(ids));
                    soup.points.len() as u32 - 1
                })
            };
            let m = get((va.min(vb), va.max(vb), u32::MAX), &[va, vb], &mut soup);
            let others: Vec<u32> = (0..4).filter(|&i| i != a && i != b).map(|i| tet[i]).collect();
            let mut face = |c: u32, soup: &mut Soup| {
                let mut f = [va, vb, c];
                f.sort_unstable();
                get((f[0], f[1], f[2]), &f, soup)
            };
            let f1 = face(others[0], &mut soup);
            let f2 = face(others[1], &mut soup);
            soup.push_polygon(&[m, f1, tc, f2]);
        }
    }
    soup
}
